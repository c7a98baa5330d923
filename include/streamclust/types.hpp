// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Vocabulary types shared by the engine, the batch clusterer and every policy:
/// handles, grid geometry, the stored per-point sample and rejection reasons.

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace streamclust {

/// Handle of a point inside a clusterer. The continuous engine uses a 32-bit
/// sequence number that wraps (compare with modular arithmetic); the batch
/// clusterer uses the position in its input. Spatial indexes store handles only.
using PointHandle = std::uint32_t;
inline constexpr PointHandle kNoPoint = std::numeric_limits<PointHandle>::max();

/// Linear index of a grid cell: row * cols + col.
using CellIndex = std::uint32_t;

/// Stable identifier of a connected component, unique over the lifetime of one
/// engine (never reused).
using ComponentId = std::uint64_t;
inline constexpr ComponentId kNoComponent = std::numeric_limits<ComponentId>::max();

/// Grid dimensions chosen by a Resolution policy.
struct GridSize {
  std::uint32_t rows = 0;  ///< vertical cells (elevation or height)
  std::uint32_t cols = 0;  ///< horizontal cells (azimuth)
  friend bool operator==(const GridSize& a, const GridSize& b) { return a.rows == b.rows && a.cols == b.cols; }
  friend bool operator!=(const GridSize& a, const GridSize& b) { return !(a == b); }
};

/// Grid geometry used by a spatial index: size plus whether columns wrap
/// around (a 360-degree horizontal field of view).
struct GridShape {
  std::uint32_t rows = 0;
  std::uint32_t cols = 0;
  bool wrap_columns = false;

  std::size_t cell_count() const { return std::size_t{rows} * cols; }

  /// Cell of normalised coordinates u (horizontal) and v (vertical), both in
  /// [0, 1]. Values at exactly 1 fall into the last cell. O(1).
  CellIndex cell_of(float u, float v) const {
    const auto col = clamp_index(u, cols);
    const auto row = clamp_index(v, rows);
    return row * cols + col;
  }
  std::uint32_t row_of(CellIndex c) const { return c / cols; }
  std::uint32_t col_of(CellIndex c) const { return c % cols; }

 private:
  static std::uint32_t clamp_index(float x, std::uint32_t n) {
    const float scaled = x * static_cast<float>(n);
    if (!(scaled > 0.0f)) return 0;  // also catches NaN
    const auto i = static_cast<std::uint32_t>(scaled);
    return i < n ? i : n - 1;
  }
};

/// Why a point was not inserted. `accepted` means it was.
enum class RejectReason : std::uint8_t {
  accepted = 0,
  non_finite,      ///< NaN or infinite coordinate or time
  too_close,       ///< range below the projection's minimum range (includes zero range)
  outside_fov,     ///< direction outside the projection's field of view
  time_backwards,  ///< timestamp earlier than the previous accepted point's
  no_pose,         ///< time outside the span of the sensor poses given (motion compensation)
  time_jump,       ///< timestamp too far ahead of the previous valid point's, or absurd (StreamTimeOrder)
};
inline constexpr std::size_t kRejectReasonCount = 7;

inline const char* to_string(RejectReason r) {
  switch (r) {
    case RejectReason::accepted: return "accepted";
    case RejectReason::non_finite: return "non_finite";
    case RejectReason::too_close: return "too_close";
    case RejectReason::outside_fov: return "outside_fov";
    case RejectReason::time_backwards: return "time_backwards";
    case RejectReason::no_pose: return "no_pose";
    case RejectReason::time_jump: return "time_jump";
  }
  return "unknown";
}

/// Counters of offered points by outcome. Index with a RejectReason.
struct RejectionCounts {
  std::array<std::uint64_t, kRejectReasonCount> by_reason{};

  std::uint64_t& operator[](RejectReason r) { return by_reason[static_cast<std::size_t>(r)]; }
  std::uint64_t operator[](RejectReason r) const { return by_reason[static_cast<std::size_t>(r)]; }
  /// Points offered but not inserted.
  std::uint64_t rejected() const {
    std::uint64_t n = 0;
    for (std::size_t i = 1; i < kRejectReasonCount; ++i) n += by_reason[i];
    return n;
  }
};

/// Result of projecting one position: normalised grid coordinates plus range.
struct Projected {
  float u = 0.0f;      ///< horizontal coordinate in [0, 1] (azimuth across the FOV)
  float v = 0.0f;      ///< vertical coordinate in [0, 1] (elevation or height across the FOV)
  float range = 0.0f;  ///< Euclidean distance to the sensor origin [m]
  RejectReason reason = RejectReason::accepted;

  bool accepted() const { return reason == RejectReason::accepted; }
};

/// What a clusterer stores per accepted point and what Linkage policies see.
/// 40 bytes. `direction` is the unit ray (position / range), precomputed so
/// angular criteria need no square roots or trigonometry per pair.
struct Sample {
  Eigen::Vector3f position = Eigen::Vector3f::Zero();   ///< world frame [m] (the sensor frame without a motion policy)
  Eigen::Vector3f direction = Eigen::Vector3f::Zero();  ///< unit ray from the sensor at capture time, world orientation
  float range = 0.0f;                                   ///< distance from the sensor at capture time [m] (|position| at rest)
  float intensity = 0.0f;                               ///< sensor units, 0 when absent
  double time = 0.0;                                    ///< stream time [s]
};

/// Build a Sample of a placed point: `position` in the world, `ray` the
/// vector from the sensor to it that passed projection with range `range`
/// (|ray|); direction = ray / range.
inline Sample make_sample(const Eigen::Vector3f& position, const Eigen::Vector3f& ray, float range, float intensity,
                          double time) {
  Sample s;
  s.position = position;
  s.range = range;
  s.direction = range > 0.0f ? Eigen::Vector3f(ray / range) : Eigen::Vector3f::Zero();
  s.intensity = intensity;
  s.time = time;
  return s;
}

/// Build a Sample from a position that has already passed projection.
inline Sample make_sample(const Eigen::Vector3f& position, float range, float intensity, double time) {
  Sample s;
  s.position = position;
  s.range = range;
  s.direction = range > 0.0f ? Eigen::Vector3f(position / range) : Eigen::Vector3f::Zero();
  s.intensity = intensity;
  s.time = time;
  return s;
}

}  // namespace streamclust
