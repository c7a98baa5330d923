// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Scores of a structure stage (ground, wall and ceiling removal):
/// precision, recall and F1 of the points classed ground (wall, ceiling)
/// against the truth class, and the fraction of object points it left to
/// clustering.

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

/// What a structure stage did to one frame (surface_scores()).
struct SurfaceScores {
  std::size_t object_points = 0;                    ///< non-ignored points with truth instance > 0
  std::size_t object_points_classed_structure = 0;  ///< of those, predicted kClassedGround, kClassedCeiling or kClassedWall
  double object_point_coverage = 1.0;               ///< 1 - classed_structure / object_points; 1 when no object point
  ClassScores ground;                               ///< kClassedGround against SurfaceClass::ground
  ClassScores ceiling;                              ///< kClassedCeiling against SurfaceClass::ceiling
  ClassScores wall;                                 ///< kClassedWall against SurfaceClass::wall
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
///   > 0) NOT predicted kClassedGround (-2), kClassedCeiling (-3) or
///   kClassedWall (-4): what the structure stage left to clustering
///   (unlabelled, -1, still counts as left). 1 when there is no object point.
/// - ground: TP = predicted -2 and truth class ground, FP = predicted -2 and
///   another class, FN = truth class ground and predicted anything but -2
///   (a cluster, unlabelled, -3 or -4). ceiling: the same with -3 and the
///   class ceiling; wall: with -4 and the class wall. Each class is its own:
///   a wall point classed ground is a ground false positive (and a wall
///   false negative), a ground point classed wall a ground false negative
///   (and a wall false positive). Precision is 1 when nothing is predicted as
///   the class (no classed point can be wrong), recall is 1 when no point has
///   the class (nothing to find), F1 = 2 TP / (2 TP + FP + FN), 1 when both
///   are empty. So a frame without ground scores 1 / 1 / 1 when no point is
///   classed ground, and precision 0, recall 1, F1 0 when some are.
/// - Other negative predictions (-1, -5, ...) are unlabelled: no class.
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
  // TP, FP, FN of each structure class, indexed by SurfaceClass.
  std::uint64_t counts[kSurfaceClassCount][3] = {};
  SurfaceScores s;
  for (std::size_t i = 0; i < predicted.size(); ++i) {
    const std::int64_t instance = truth_instance[i];
    const SurfaceClass c = truth_class[i];
    detail::check_surface_point(i, instance, c);
    if (instance < 0) continue;
    const std::int64_t p = predicted[i];
    const bool classed = is_classed_structure(p);
    if (instance > 0) {
      ++s.object_points;
      if (classed) ++s.object_points_classed_structure;
    }
    const int truth = static_cast<int>(c);
    const int called = p == kClassedGround    ? static_cast<int>(SurfaceClass::ground)
                       : p == kClassedCeiling ? static_cast<int>(SurfaceClass::ceiling)
                       : p == kClassedWall    ? static_cast<int>(SurfaceClass::wall)
                                              : static_cast<int>(SurfaceClass::object);
    if (called != static_cast<int>(SurfaceClass::object)) ++counts[called][called == truth ? 0 : 1];
    if (truth != static_cast<int>(SurfaceClass::object) && called != truth) ++counts[truth][2];
  }
  s.object_point_coverage =
      detail::ratio_or(static_cast<double>(s.object_points - s.object_points_classed_structure),
                       static_cast<double>(s.object_points), 1.0);
  const auto scores_of = [&counts](SurfaceClass k) {
    const std::uint64_t* n = counts[static_cast<int>(k)];
    return class_scores(n[0], n[1], n[2]);
  };
  s.ground = scores_of(SurfaceClass::ground);
  s.ceiling = scores_of(SurfaceClass::ceiling);
  s.wall = scores_of(SurfaceClass::wall);
  return s;
}

}  // namespace eval
}  // namespace streamclust
