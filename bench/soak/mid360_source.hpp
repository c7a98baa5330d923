// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Livox Mid-360 of the soak: its real firing table replayed when the
/// Livox data is present (patterns/mid360_u16le.bin), else the analytic
/// scan model; one sensor type either way, so the engine and the simulator
/// are compiled once. Models the simulator's sensor concept (sim/ray.hpp).
/// Not thread-safe (a sensor is a stream).

#include <streamclust/sim/ray.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/sensors/table_replay.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <system_error>

namespace streamclust::bench {

class Mid360Source {
 public:
  /// The table under `livox_data` (a folder holding patterns/), if it is a
  /// file there; else the analytic model. Throws what TableReplay throws
  /// for an unreadable table.
  explicit Mid360Source(const std::string& livox_data) {
    const std::filesystem::path table = std::filesystem::path(livox_data) / "patterns" / "mid360_u16le.bin";
    std::error_code ec;
    if (!livox_data.empty() && std::filesystem::is_regular_file(table, ec)) {
      table_.emplace(sim::TableReplay::mid360(table.string()));
      description_ = "Livox Mid-360, its real firing table (" + table.string() + ")";
    } else {
      model_.emplace();
      description_ = "Livox Mid-360, analytic scan model (no firing table under '" + livox_data + "')";
    }
  }

  /// The next firing. O(1).
  sim::Ray next() { return table_ ? table_->next() : model_->next(); }
  /// Firings per second [Hz].
  double point_rate() const { return table_ ? table_->point_rate() : model_->point_rate(); }
  /// Which model fires, for the report.
  const std::string& description() const { return description_; }

 private:
  std::optional<sim::TableReplay> table_;
  std::optional<sim::Mid360Model> model_;
  std::string description_;
};

}  // namespace streamclust::bench
