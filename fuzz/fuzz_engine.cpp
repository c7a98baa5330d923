// SPDX-License-Identifier: MIT
// Fuzz target: the continuous engine against the batch clusterer, a
// differential target. An input is a scenario (engine/scenario.hpp): one of
// the tool's compiled configurations (engine/engine_configs.hpp), one of its
// presets with overrides, and a script of inserts, packets, advances,
// retrievals and calibration ends over a stream of at most 2048 points with
// duplicates, crowded cells, NaN and infinite coordinates, and times that
// stall, go backwards and jump. At every retrieval the continuous partition
// must equal the batch partition of the same window (engine/run_scenario.hpp
// lists the checks); a mismatch aborts.

#include "engine/engine_configs.hpp"
#include "engine/scenario.hpp"

#include "cli/options.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace {

namespace fz = streamclust::fuzz;

/// The scenario of an input: configuration and preset from the first two
/// header bytes, then the header's overrides and the script.
fz::Scenario decode(const std::uint8_t* data, std::size_t size) {
  fz::ByteCursor in(data, size);
  std::array<std::uint8_t, 8> header{};
  for (std::uint8_t& b : header) b = in.next();
  fz::Scenario s;
  s.config = header[0] % fz::kEngineConfigCount;
  s.preset = header[1] % 3;
  streamclust::cli::apply_preset(fz::kEngineConfigs[s.config].presets[s.preset], s.options);
  fz::apply_header(header, s);
  static constexpr double origins[4] = {0.0, 1.7e9, -5.0, 0.25};  // [s] where the clock starts
  fz::Clock clock(origins[(header[1] >> 2) & 3]);
  fz::decode_script(in, s, clock);
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fz::Scenario s = decode(data, size);
  fz::kEngineConfigs[s.config].run(s);
  return 0;
}
