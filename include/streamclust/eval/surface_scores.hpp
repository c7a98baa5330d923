// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Scores of a ground / ceiling removal stage: precision, recall and F1 of
/// the points classed ground (ceiling) against the truth class, and the
/// fraction of object points it left to clustering.

#include <streamclust/eval/options.hpp>
#include <streamclust/surface_class.hpp>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {
namespace eval {

/// Precision, recall and F1 of one binary classification (points predicted
/// as a class against points of that class), with their counts.
struct ClassScores {
  std::uint64_t true_positives = 0;   ///< predicted the class and of the class
  std::uint64_t false_positives = 0;  ///< predicted the class, of another class
  std::uint64_t false_negatives = 0;  ///< of the class, predicted otherwise
  double precision = 1.0;             ///< TP / (TP + FP); 1 when nothing is predicted as the class
  double recall = 1.0;                ///< TP / (TP + FN); 1 when no point is of the class
  double f1 = 1.0;                    ///< 2 TP / (2 TP + FP + FN); 1 when both are empty
};

/// The scores of the counts (definitions and degenerate cases: the field
/// comments of ClassScores). F1 is the harmonic mean of precision and recall
/// whenever that is defined, and 0 when TP = 0 but FP + FN > 0. O(1).
inline ClassScores class_scores(std::uint64_t true_positives, std::uint64_t false_positives,
                                std::uint64_t false_negatives) {
  ClassScores s;
  s.true_positives = true_positives;
  s.false_positives = false_positives;
  s.false_negatives = false_negatives;
  const auto tp = static_cast<double>(true_positives);
  const auto fp = static_cast<double>(false_positives);
  const auto fn = static_cast<double>(false_negatives);
  s.precision = detail::ratio_or(tp, tp + fp, 1.0);
  s.recall = detail::ratio_or(tp, tp + fn, 1.0);
  s.f1 = detail::ratio_or(2.0 * tp, 2.0 * tp + fp + fn, 1.0);
  return s;
}

/// What a ground / ceiling removal stage did to one frame (surface_scores()).
struct SurfaceScores {
  std::size_t object_points = 0;                    ///< non-ignored points with truth instance > 0
  std::size_t object_points_classed_structure = 0;  ///< of those, predicted kClassedGround or kClassedCeiling
  double object_point_coverage = 1.0;               ///< 1 - classed_structure / object_points; 1 when no object point
  ClassScores ground;                               ///< kClassedGround against SurfaceClass::ground
  ClassScores ceiling;                              ///< kClassedCeiling against SurfaceClass::ceiling
};

namespace detail {

/// Throws std::invalid_argument unless `c` is a SurfaceClass enumerator and an
/// object instance (> 0) has the class object.
inline void check_surface_point(std::size_t i, std::int64_t instance, SurfaceClass c) {
  const auto value = static_cast<unsigned>(c);
  if (value >= static_cast<unsigned>(kSurfaceClassCount)) {
    std::string msg = "streamclust::eval: point ";
    msg.append(std::to_string(i))
        .append(" has truth class ")
        .append(std::to_string(value))
        .append(": expected 0 (object), 1 (ground), 2 (wall) or 3 (ceiling)");
    throw std::invalid_argument(msg);
  }
  if (instance > 0 && c != SurfaceClass::object) {
    std::string msg = "streamclust::eval: point ";
    msg.append(std::to_string(i))
        .append(" has truth instance ")
        .append(std::to_string(instance))
        .append(" but truth class ")
        .append(to_string(c))
        .append(": an object instance (> 0) must have the class object");
    throw std::invalid_argument(msg);
  }
}

}  // namespace detail

/// Scores of the structure classification of one frame. Ignored points
/// (truth_instance < 0) are removed first.
/// - object_point_coverage: the fraction of object points (truth_instance
///   > 0) NOT predicted kClassedGround (-2) or kClassedCeiling (-3): what the
///   removal stage left to clustering (unlabelled, -1, still counts as left).
///   1 when there is no object point.
/// - ground: TP = predicted -2 and truth class ground, FP = predicted -2 and
///   another class, FN = truth class ground and predicted anything but -2
///   (a cluster, unlabelled, or -3). ceiling: the same with -3 and the class
///   ceiling. Precision is 1 when nothing is predicted as the class (no
///   classed point can be wrong), recall is 1 when no point has the class
///   (nothing to find), F1 = 2 TP / (2 TP + FP + FN), 1 when both are empty.
///   So a frame without ground scores 1 / 1 / 1 when no point is classed
///   ground, and precision 0, recall 1, F1 0 when some are.
/// - Other negative predictions (-1, -4, ...) are unlabelled: neither ground
///   nor ceiling.
///
/// Throws std::invalid_argument when the sizes differ, a class is not a
/// SurfaceClass enumerator, or a point with truth_instance > 0 has a class
/// other than object (instance 0 with the class object, such as vegetation
/// kept as stuff, is allowed). Complexity O(n), no allocation; thread
/// safety: pure function.
inline SurfaceScores surface_scores(const std::vector<std::int64_t>& truth_instance,
                                    const std::vector<SurfaceClass>& truth_class,
                                    const std::vector<std::int64_t>& predicted) {
  detail::check_same_size(truth_instance.size(), predicted.size());
  detail::check_same_size(truth_class.size(), predicted.size());
  std::uint64_t ground[3] = {0, 0, 0};   // TP, FP, FN
  std::uint64_t ceiling[3] = {0, 0, 0};  // TP, FP, FN
  SurfaceScores s;
  for (std::size_t i = 0; i < predicted.size(); ++i) {
    const std::int64_t instance = truth_instance[i];
    const SurfaceClass c = truth_class[i];
    detail::check_surface_point(i, instance, c);
    if (instance < 0) continue;
    const std::int64_t p = predicted[i];
    const bool classed_ground = p == kClassedGround;
    const bool classed_ceiling = p == kClassedCeiling;
    if (instance > 0) {
      ++s.object_points;
      if (classed_ground || classed_ceiling) ++s.object_points_classed_structure;
    }
    const bool is_ground = c == SurfaceClass::ground;
    const bool is_ceiling = c == SurfaceClass::ceiling;
    ground[0] += (classed_ground && is_ground) ? 1u : 0u;
    ground[1] += (classed_ground && !is_ground) ? 1u : 0u;
    ground[2] += (!classed_ground && is_ground) ? 1u : 0u;
    ceiling[0] += (classed_ceiling && is_ceiling) ? 1u : 0u;
    ceiling[1] += (classed_ceiling && !is_ceiling) ? 1u : 0u;
    ceiling[2] += (!classed_ceiling && is_ceiling) ? 1u : 0u;
  }
  s.object_point_coverage =
      detail::ratio_or(static_cast<double>(s.object_points - s.object_points_classed_structure),
                       static_cast<double>(s.object_points), 1.0);
  s.ground = class_scores(ground[0], ground[1], ground[2]);
  s.ceiling = class_scores(ceiling[0], ceiling[1], ceiling[2]);
  return s;
}

}  // namespace eval
}  // namespace streamclust
