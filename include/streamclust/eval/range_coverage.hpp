// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// RangeCoverage: object-point coverage per range band from the sensor. A
/// structure stage that swallows far, sparse objects and keeps near ones
/// shows it here, where the frame's single coverage figure hides it.

#include <streamclust/eval/options.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {
namespace eval {

/// Object points and those kept as objects (not classed ground, ceiling or
/// wall: is_classed_structure()), per range band, summed over the frames
/// added. Bands: [0, 10) m, [10, 30) m, [30, inf) m from the sensor.
///
/// \code
///   streamclust::eval::RangeCoverage bands;
///   for (const auto& f : frames) bands.add(f.instance, f.predicted, f.range);
///   const double far = bands.coverage(2);  // object points beyond 30 m kept as objects
/// \endcode
///
/// add() is O(n) without allocation; the counts pool every frame (each
/// object point counts once). Not thread-safe (add mutates).
class RangeCoverage {
 public:
  static constexpr std::size_t kBands = 3;
  /// Lower edge of each band [m]; a band ends where the next begins.
  static constexpr std::array<double, kBands> kLowerEdges = {0.0, 10.0, 30.0};

  /// The band of a range [m]: 0, 1 or 2 (a negative or NaN range: band 0).
  static std::size_t band_of(double range) {
    std::size_t b = 0;
    while (b + 1 < kBands && range >= kLowerEdges[b + 1]) ++b;
    return b;
  }

  /// Adds one frame: per point its truth instance (> 0: an object point;
  /// others are not counted), its prediction and its range from the sensor
  /// [m]. Throws std::invalid_argument when the sizes differ.
  void add(const std::vector<std::int64_t>& truth_instance, const std::vector<std::int64_t>& predicted,
           const std::vector<float>& range) {
    detail::check_same_size(truth_instance.size(), predicted.size());
    detail::check_same_size(range.size(), predicted.size());
    for (std::size_t i = 0; i < predicted.size(); ++i) {
      if (truth_instance[i] <= 0) continue;
      const std::size_t b = band_of(static_cast<double>(range[i]));
      ++object_points_[b];
      kept_[b] += is_classed_structure(predicted[i]) ? 0u : 1u;
    }
  }

  /// Object points seen in band `b` over every frame.
  std::uint64_t object_points(std::size_t b) const { return object_points_[b]; }
  /// Of those, kept as objects.
  std::uint64_t kept(std::size_t b) const { return kept_[b]; }
  /// kept / object points of band `b`; 1 when the band held no object point.
  double coverage(std::size_t b) const {
    return detail::ratio_or(static_cast<double>(kept_[b]), static_cast<double>(object_points_[b]), 1.0);
  }

 private:
  std::array<std::uint64_t, kBands> object_points_{};
  std::array<std::uint64_t, kBands> kept_{};
};

}  // namespace eval
}  // namespace streamclust
