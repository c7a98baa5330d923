// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The input of fuzz_engine: fuzz bytes decoded into the tool's options (a
/// preset, then overrides, as `streamclust cluster` would parse them) and a
/// script of engine calls over a point stream. Every byte string decodes
/// (missing bytes read as 0), so the fuzzer never wastes an input.
///
/// Layout: 8 header bytes (configuration, preset, window, grid, mask and
/// cap, ground and mount, linkage, connectivity stress), then operations:
///
/// | first byte | operation                                   | then          |
/// |------------|---------------------------------------------|---------------|
/// | 0-149      | insert one point                             | x y z time    |
/// | 150-189    | insert_batch of 1-48 points                  | n, points     |
/// | 190-214    | retrieve, compare                            | -             |
/// | 215-229    | advance_to(clock + dt), retrieve, compare    | time          |
/// | 230-239    | complete_calibration                         | -             |
/// | 240-255    | insert copies of the last point              | n, time       |
///
/// Coordinates come from a small alphabet (16 values, a few jitters, and
/// NaN, infinities, huge, tiny and sub-minimum-range values), so duplicate
/// points, near-duplicates and crowded cells are common. Times step from a
/// clock: small steps, no step, steps back, jumps ahead (past the jump
/// guard), and one-off absurd values (NaN, +-inf, beyond +-9e9 s).

#include "cli/options.hpp"

#include <streamclust/io/record.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace streamclust::fuzz {

/// Bounds that keep one input's work small (an execution in milliseconds).
inline constexpr std::size_t kMaxPoints = 2048;      ///< points offered per input
inline constexpr std::size_t kMaxRetrievals = 64;    ///< compared retrievals per input
inline constexpr std::size_t kMaxPacket = 48;        ///< points per insert_batch
inline constexpr std::size_t kMaxCopies = 32;        ///< copies of the last point per operation

/// One engine call of the script.
struct Operation {
  enum Kind : std::uint8_t { insert, insert_batch, retrieve, advance_and_retrieve, complete_calibration };
  Kind kind = insert;
  std::size_t first = 0;  ///< insert, insert_batch: the first point of `Scenario::stream`
  std::size_t count = 0;  ///< insert_batch: points offered (insert: 1)
  double time = 0.0;      ///< advance_and_retrieve: the time advanced to [s]
};

/// The engine's connectivity parameters that the tool leaves at their
/// defaults, set to extremes on some inputs (folds between retrievals,
/// pruned edges) so that their paths run too.
struct ForestStress {
  std::uint32_t min_fold_edges = 65536;
  std::uint32_t fold_edges_per_point = 2;
  std::uint32_t prune_witnesses = 0;
};

/// A decoded input.
struct Scenario {
  std::size_t config = 0;       ///< index into the configuration table (engine_configs.hpp)
  std::size_t preset = 0;       ///< which of the configuration's presets (0-2)
  cli::ClusterOptions options;  ///< everything but the policy slots, which the configuration sets
  ForestStress forest;
  std::vector<io::Record> stream;  ///< every point offered, in order, sensor frame
  std::vector<Operation> script;
};

/// Reads bytes front to back; 0 once they run out.
class ByteCursor {
 public:
  ByteCursor(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t next() { return at_ < size_ ? data_[at_++] : 0; }
  bool done() const { return at_ >= size_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

/// A coordinate [m] from one byte.
inline float coordinate(std::uint8_t b) {
  static constexpr float base[16] = {0.0f, 0.25f, 0.5f, 1.0f, 1.5f, 2.0f, 3.0f, 5.0f,
                                     10.0f, 30.0f, -0.25f, -0.5f, -1.0f, -2.0f, -5.0f, -30.0f};
  static constexpr float jitter[14] = {0.0f, 0.0f, 0.0f, 0.0f, 1e-7f, -1e-7f, 1e-5f,
                                       -1e-5f, 0.01f, -0.01f, 0.05f, 0.1f, 0.33f, -0.33f};
  constexpr float inf = std::numeric_limits<float>::infinity();
  static constexpr float special[32] = {
      std::numeric_limits<float>::quiet_NaN(), inf, -inf, std::numeric_limits<float>::max(),
      -std::numeric_limits<float>::max(), 1e30f, -1e30f, 1e-30f, 1e-40f /* subnormal */, -0.0f, 1e6f, -1e6f,
      1e-3f, 0.1f /* the default minimum range */, 0.0999f, 0.1001f, 100.0f, 250.0f, -100.0f, 0.7071f,
      -0.7071f, 1.2f, -1.2f, 2.5f, -2.5f, 0.03f, -0.03f, 0.2f, -0.2f, 4.0f, 7.0f, -7.0f};
  if (b >= 224) return special[b - 224];
  return base[b & 15] + jitter[b >> 4];
}

/// The scenario's stream clock: times of the points and of advance_to.
class Clock {
 public:
  explicit Clock(double origin) : origin_(origin), now_(origin) {}

  /// The next time from one byte [s]; most bytes move the clock, a few
  /// give a one-off absurd value and leave it.
  double next(std::uint8_t b) {
    static constexpr double step[16] = {0.0, 1e-6, 1e-5, 5e-5, 1e-4, 5e-4, 1e-3, 4e-3,
                                        0.01, 0.03, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0};
    static constexpr double jump[8] = {59.9, 60.0, 60.0001, 61.0, 100.0, 3600.0, 1e6, 1e9};
    constexpr double inf = std::numeric_limits<double>::infinity();
    static constexpr double absurd[16] = {std::numeric_limits<double>::quiet_NaN(), inf, -inf, 9e9, 9.000001e9,
                                          -9e9, 1e300, -1e300, 1.7e9, 0.0, -1.0, 1e-310, 1e-300, -0.0, 2e9, 0.5};
    if (b < 128) return now_ += step[b % 16];
    if (b < 160) return now_ -= step[b % 16];
    if (b < 192) return now_;
    if (b < 224) return now_ += jump[b % 8];
    if (b < 240) return absurd[b % 16];
    return now_ = origin_ + step[b % 16];
  }
  double now() const { return now_; }

 private:
  double origin_;
  double now_;
};

/// The header's choices, applied to options that already hold a preset.
inline void apply_header(const std::array<std::uint8_t, 8>& h, Scenario& s) {
  cli::ClusterOptions& o = s.options;
  o.quiet = true;
  static constexpr double durations[8] = {0.1, 0.05, 0.01, 0.002, 0.0, 0.5, 1e-4, 0.02};
  static constexpr std::size_t counts[8] = {1, 2, 3, 7, 20, 100, 500, 20000};
  if ((h[2] & 0x80) == 0) o.window_seconds = durations[h[2] & 7];  // else the preset's
  o.window_count = counts[(h[2] >> 3) & 7];
  static constexpr std::uint32_t grids[16][2] = {{1, 1}, {1, 2}, {2, 1}, {1, 7}, {3, 5},   {4, 16},  {8, 32},  {16, 64},
                                                 {2, 360}, {64, 4}, {5, 5}, {9, 3}, {32, 1800}, {1, 1024}, {7, 1}, {12, 12}};
  if (h[3] >= 96) o.grid = std::make_pair(grids[h[3] % 16][0], grids[h[3] % 16][1]);
  static constexpr int masks[8] = {5, 1, 3, 5, 7, 9, 15, 31};
  static constexpr std::uint32_t caps[4] = {4, 1, 2, 32};  // K x cells stays a few MB
  if ((h[4] & 0x80) == 0) o.mask = masks[h[4] & 7];  // else the preset's
  o.params.get<CappedGrid>().capacity = caps[(h[4] >> 3) & 3];
  static constexpr float multiplicities[4] = {2.0f, 1.25f, 4.0f, 10.0f};
  if ((h[4] & 0x40) != 0) o.max_multiplicity = multiplicities[(h[4] >> 5) & 1 ? 3 : 1];
  // Ground and mount: --ground / --no-ground, --sensor-height, --mount, --no-ceiling, --max-time-jump.
  if ((h[5] & 3) == 1) o.ground = true;
  if ((h[5] & 3) == 2) o.ground = false;
  static constexpr float heights[4] = {0.0f, 0.5f, 1.2f, 2.5f};
  if (((h[5] >> 2) & 3) != 0) o.sensor_height = heights[(h[5] >> 2) & 3];
  static constexpr std::array<double, 3> mounts[4] = {{0, 0, 0}, {0, 15, 0}, {180, 0, 0}, {10, -20, 90}};
  if (((h[5] >> 4) & 3) != 0) o.mount_deg = mounts[(h[5] >> 4) & 3];
  if ((h[5] & 0x40) != 0) o.ceiling = false;
  static constexpr double jumps[4] = {60.0, 0.5, 0.01, 1e9};
  if ((h[5] & 0x80) != 0) o.max_time_jump = jumps[h[6] >> 6];
  // Linkage and projection.
  static constexpr float thetas[4] = {1.0f, 45.0f, 89.9f, 10.0f};
  if ((h[6] & 3) != 0) o.params.get<AngularLinkage>().theta_deg = thetas[h[6] & 3];
  static constexpr float ray_floor[4] = {0.2f, 0.0f, 5.0f, 0.2f};
  o.params.get<AngularLinkage>().min_ray_angle_deg = ray_floor[(h[6] >> 2) & 3];
  static constexpr float distances[4] = {0.5f, 0.05f, 3.0f, 0.5f};
  o.params.get<EuclideanLinkage>().max_distance = distances[(h[6] >> 4) & 3];
  o.params.get<RangeAdaptiveLinkage>().min_distance = distances[(h[6] >> 4) & 3] * 0.4f;
  static constexpr float factors[4] = {0.05f, 0.0f, 1.0f, 0.05f};
  o.params.get<RangeAdaptiveLinkage>().range_factor = factors[(h[7] >> 6) & 3];
  static constexpr float min_ranges[4] = {0.1f, 0.0f, 2.0f, 0.1f};
  o.min_range = min_ranges[(h[7] >> 4) & 3];
  // The spanning forest's own parameters (not options of the tool).
  static constexpr std::uint32_t folds[4] = {65536, 1, 7, 100};
  s.forest.min_fold_edges = folds[h[7] & 3];
  s.forest.fold_edges_per_point = (h[7] & 4) != 0 ? 1 : 2;
  s.forest.prune_witnesses = (h[7] >> 3) & 1 ? 2 : 0;
}

/// The point from 4 bytes (x, y, z, time) at the clock.
inline io::Record point(ByteCursor& in, Clock& clock) {
  io::Record r;
  r.x = coordinate(in.next());
  r.y = coordinate(in.next());
  r.z = coordinate(in.next());
  r.t = clock.next(in.next());
  return r;
}

/// The script and stream of the bytes after the header.
inline void decode_script(ByteCursor& in, Scenario& s, Clock& clock) {
  std::size_t retrievals = 0;
  auto room = [&] { return kMaxPoints - s.stream.size(); };
  while (!in.done() && room() > 0) {
    const std::uint8_t op = in.next();
    if (op < 150) {
      s.script.push_back({Operation::insert, s.stream.size(), 1, 0.0});
      s.stream.push_back(point(in, clock));
    } else if (op < 190) {
      const std::size_t n = std::min<std::size_t>(1 + in.next() % kMaxPacket, room());
      s.script.push_back({Operation::insert_batch, s.stream.size(), n, 0.0});
      for (std::size_t k = 0; k < n; ++k) s.stream.push_back(point(in, clock));
    } else if (op < 215) {
      if (retrievals++ < kMaxRetrievals) s.script.push_back({Operation::retrieve, 0, 0, 0.0});
    } else if (op < 230) {
      const double t = clock.next(in.next());
      if (retrievals++ < kMaxRetrievals) s.script.push_back({Operation::advance_and_retrieve, 0, 0, t});
    } else if (op < 240) {
      s.script.push_back({Operation::complete_calibration, 0, 0, 0.0});
    } else {
      const std::size_t n = std::min<std::size_t>(1 + in.next() % kMaxCopies, room());
      io::Record copy = s.stream.empty() ? io::Record{1.0f, 1.0f, 1.0f, 0.0f, clock.now(), -1} : s.stream.back();
      copy.t = clock.next(in.next());
      s.script.push_back({Operation::insert_batch, s.stream.size(), n, 0.0});
      for (std::size_t k = 0; k < n; ++k) s.stream.push_back(copy);
    }
  }
}

}  // namespace streamclust::fuzz
