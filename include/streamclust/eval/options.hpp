// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// MetricOptions: the knobs of the clustering-quality metrics, and the input
/// conventions shared by every metric of streamclust::eval.
///
/// Input conventions (every function of streamclust::eval):
/// - `truth[i]`: ground-truth instance id of point i. 0 = structure / stuff
///   (ground, walls, vegetation...), > 0 = object instance, < 0 = ignore (the
///   point is removed before any metric is computed, except coverage over all
///   points).
/// - `predicted[i]`: predicted cluster id of point i; any negative value
///   (conventionally -1, `kUnlabelled`) means the point received no label
///   (dropped, lost by an overwrite grid, evicted...). All negative values are
///   the same "unlabelled" label, except in object_metrics(), which tells
///   `kClassedGround` (-2), `kClassedCeiling` (-3) and `kClassedWall` (-4)
///   apart from the rest.
/// - Both vectors have the same length, else std::invalid_argument naming both
///   sizes. Label values are arbitrary (not dense): every metric is invariant
///   to a relabelling of either side (see the tie rule of ObjectRates).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {
namespace eval {

/// Predicted id of a point that received no cluster label. Any negative
/// predicted id is treated the same way.
inline constexpr std::int64_t kUnlabelled = -1;

/// Predicted id of a point a ground-removal stage classed as ground and took
/// out of clustering. object_metrics() scores it as a ground prediction;
/// every other metric treats it as unlabelled.
inline constexpr std::int64_t kClassedGround = -2;

/// Predicted id of a point classed as ceiling (taken out of clustering); as
/// kClassedGround, for the ceiling.
inline constexpr std::int64_t kClassedCeiling = -3;

/// Predicted id of a point classed as wall (vertical structure taken out of
/// clustering); as kClassedGround, for walls.
inline constexpr std::int64_t kClassedWall = -4;

/// True for the predicted ids of points a structure stage took out of
/// clustering: kClassedGround, kClassedCeiling or kClassedWall.
inline constexpr bool is_classed_structure(std::int64_t predicted) {
  return predicted == kClassedGround || predicted == kClassedCeiling || predicted == kClassedWall;
}

/// Options of the metrics; a plain aggregate, construct with braces:
/// `MetricOptions o; o.min_points = 30;`. Checked by `validate()` (called by
/// every metric that reads it).
struct MetricOptions {
  /// Adjusted Rand index over object points only (truth > 0, default), or,
  /// when true, over every non-ignored point (truth >= 0, structure included:
  /// then one big ground/wall segment dominates the pair counts).
  bool ari_include_structure = false;

  /// Panoptic scores and object rates: GT instances with fewer points are not
  /// counted as false negatives / not rated; predicted segments with fewer
  /// points are not counted as false positives. Default 1 (count everything);
  /// SemanticKITTI's PanopticEval uses 30. 0 behaves like 1.
  std::size_t min_points = 1;

  /// Object rates: a predicted cluster is a "piece" of a GT object when it
  /// holds at least this fraction of the object's points; an object with
  /// >= 2 pieces is over-segmented. In (0, 1]; default 0.1.
  double over_segmentation_fraction = 0.1;

  /// Object rates: an object is under-segmented when the points of its
  /// majority cluster that are NOT from this object (other objects and
  /// structure) make up at least this fraction of that cluster. In (0, 1];
  /// default 0.1.
  double under_segmentation_fraction = 0.1;

  /// Strict object rates: an object is correct only when one cluster holds at
  /// least this fraction of the object's points (completeness). In (0.5, 1],
  /// so that at most one cluster can qualify; default 0.8.
  double strict_object_fraction = 0.8;

  /// Strict object rates: ... and at least this fraction of that cluster's
  /// points are the object's (purity; structure and other objects are
  /// foreign). In (0.5, 1], so that a cluster can be correct for at most one
  /// object; default 0.8.
  double strict_purity_fraction = 0.8;

  /// Throws std::invalid_argument naming the field, its value and the range.
  void validate() const {
    check_fraction("over_segmentation_fraction", over_segmentation_fraction, false);
    check_fraction("under_segmentation_fraction", under_segmentation_fraction, false);
    check_fraction("strict_object_fraction", strict_object_fraction, true);
    check_fraction("strict_purity_fraction", strict_purity_fraction, true);
  }

 private:
  /// value in (0, 1], or in (0.5, 1] when `above_half`.
  static void check_fraction(const char* name, double value, bool above_half) {
    const double lower = above_half ? 0.5 : 0.0;
    if (!(value > lower && value <= 1.0)) {  // also rejects NaN
      std::string msg = "MetricOptions::";
      msg.append(name).append(" = ").append(std::to_string(value)).append(" is invalid: expected a value in ");
      msg.append(above_half ? "(0.5, 1]" : "(0, 1]");
      throw std::invalid_argument(msg);
    }
  }
};

namespace detail {

/// Throws std::invalid_argument unless both label vectors have one entry per point.
inline void check_same_size(std::size_t truth_size, std::size_t predicted_size) {
  if (truth_size != predicted_size) {
    std::string msg = "streamclust::eval: truth has ";
    msg.append(std::to_string(truth_size))
        .append(" labels but predicted has ")
        .append(std::to_string(predicted_size))
        .append(": expected one label per point on both sides");
    throw std::invalid_argument(msg);
  }
}

/// a / b, or `if_empty` when b == 0.
inline double ratio_or(double a, double b, double if_empty) { return b == 0.0 ? if_empty : a / b; }

/// count >= fraction * total with a relative tolerance of 1e-12, so that 7 %
/// of 100 points is 7 points (0.07 * 100 is 7.000000000000001 in double).
inline bool at_least_fraction(std::uint64_t count, double fraction, std::uint64_t total) {
  return static_cast<double>(count) >= fraction * static_cast<double>(total) * (1.0 - 1e-12);
}

}  // namespace detail
}  // namespace eval
}  // namespace streamclust
