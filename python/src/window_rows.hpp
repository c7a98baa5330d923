// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// StreamSession: an ErasedClusterer plus the bookkeeping that turns a
/// retrieval into the rows of the CLI's labels file (`--labels`): every
/// window point by stream index, labelled with its component, -2 ground,
/// -3 ceiling, and -1 for a rejected record inside the window's span of
/// stream indices. The same rows as tools/cli/cluster_driver.hpp, so a
/// Python retrieval and a CLI cycle compare row by row.

#include "erased_clusterer.hpp"

#include <cstdint>
#include <deque>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::python {

/// Row labels of structure and rejected records (docs/cli.md, `--labels`).
inline constexpr std::int32_t kUnlabelled = -1;
inline constexpr std::int32_t kGroundRow = -2;
inline constexpr std::int32_t kCeilingRow = -3;
inline constexpr std::int32_t kWallRow = -4;

/// One retrieval as rows, in ascending stream index. Scratch reused by the
/// next retrieval.
struct WindowRows {
  std::vector<std::int64_t> index;
  std::vector<std::int32_t> label;
};

/// The engine with the stream bookkeeping of the CLI's driver. Not
/// thread-safe (the binding serialises calls).
class StreamSession {
 public:
  explicit StreamSession(std::unique_ptr<ErasedClusterer> engine) : engine_(std::move(engine)) {}

  /// Offers `points`; books rejected stream indices for the rows and the
  /// newest accepted time. Writes the reason codes to `reasons_out` when not
  /// null (points.size bytes). Returns the points accepted. O(points).
  std::size_t insert(const PointBuffers& points, std::uint8_t* reasons_out) {
    reasons_.resize(points.size);
    const std::uint64_t first_index = engine_->offered();
    const std::size_t accepted = engine_->insert(points, reasons_.data());
    for (std::size_t i = 0; i < points.size; ++i) {
      const RejectReason r = reasons_[i];
      if (reasons_out) reasons_out[i] = static_cast<std::uint8_t>(r);
      if (r == RejectReason::accepted) {
        last_accepted_time_ = points.t[i];
      } else {
        rejected_.push_back(first_index + i);
      }
    }
    return accepted;
  }

  void advance_to(double time) { engine_->advance_to(time); }
  bool calibrating() const { return engine_->calibrating(); }
  void complete_calibration() { engine_->complete_calibration(); }
  ErasedClusterer& engine() { return *engine_; }
  const ErasedClusterer& engine() const { return *engine_; }
  /// Stream time of the newest accepted point [s] (0 before any).
  double last_accepted_time() const { return last_accepted_time_; }

  /// Retrieves and merges the result into `rows` (cleared first). Returns
  /// the engine's result (valid until the next call). O(window + rejected
  /// records since the last retrieval). Throws std::overflow_error when a
  /// component id no longer fits the int32 labels (after 2^31 components).
  const Clustering& retrieve(WindowRows& rows) {
    const Clustering& result = engine_->retrieve();
    rows.index.clear();
    rows.label.clear();
    const auto& points = result.points;
    std::size_t k = 0;
    auto take_objects_before = [&](std::uint64_t limit) {
      for (; k < points.size() && points[k].stream_index < limit; ++k) {
        rows.index.push_back(static_cast<std::int64_t>(points[k].stream_index));
        rows.label.push_back(to_label(points[k].label));
      }
    };
    for (const StructurePoint& s : result.structure) {
      take_objects_before(s.stream_index);
      rows.index.push_back(static_cast<std::int64_t>(s.stream_index));
      rows.label.push_back(s.surface == SurfaceClass::ceiling ? kCeilingRow
                           : s.surface == SurfaceClass::wall  ? kWallRow
                                                               : kGroundRow);
    }
    take_objects_before(std::numeric_limits<std::uint64_t>::max());
    // Rejected records inside the window's span: merged in as -1 (the CLI's rule).
    const std::uint64_t oldest =
        rows.index.empty() ? engine_->offered() : static_cast<std::uint64_t>(rows.index.front());
    while (!rejected_.empty() && rejected_.front() < oldest) rejected_.pop_front();
    if (!rejected_.empty()) {
      merged_index_.clear();
      merged_label_.clear();
      std::size_t i = 0, j = 0;
      while (i < rows.index.size() || j < rejected_.size()) {
        if (j == rejected_.size() ||
            (i < rows.index.size() && static_cast<std::uint64_t>(rows.index[i]) < rejected_[j])) {
          merged_index_.push_back(rows.index[i]);
          merged_label_.push_back(rows.label[i]);
          ++i;
        } else {
          merged_index_.push_back(static_cast<std::int64_t>(rejected_[j]));
          merged_label_.push_back(kUnlabelled);
          ++j;
        }
      }
      rows.index.swap(merged_index_);
      rows.label.swap(merged_label_);
    }
    return result;
  }

 private:
  static std::int32_t to_label(ComponentId id) {
    if (id == kNoComponent) return kUnlabelled;
    if (id > static_cast<ComponentId>(std::numeric_limits<std::int32_t>::max())) {
      throw std::overflow_error("component id " + std::to_string(id) + " does not fit the int32 labels");
    }
    return static_cast<std::int32_t>(id);
  }

  std::unique_ptr<ErasedClusterer> engine_;
  std::vector<RejectReason> reasons_;  // scratch of one insert
  std::deque<std::uint64_t> rejected_;  // stream indices of rejected records, ascending
  std::vector<std::int64_t> merged_index_;
  std::vector<std::int32_t> merged_label_;
  double last_accepted_time_ = 0.0;
};

}  // namespace streamclust::python
