// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// MeanObjectMetrics and ObjectMetricsAverage: the object metrics of many
/// frames, as per-frame means and as pooled counts.

#include <streamclust/eval/object_metrics.hpp>
#include <streamclust/eval/strict_object_rates.hpp>
#include <streamclust/eval/surface_scores.hpp>

#include <cstddef>
#include <cstdint>
#include <initializer_list>

namespace streamclust {
namespace eval {

/// Unweighted per-frame means of the scalar fields of ObjectMetrics
/// (ObjectMetricsAverage::mean()).
struct MeanObjectMetrics {
  std::size_t frames = 0;               ///< frames averaged
  std::size_t frames_with_objects = 0;  ///< frames that rated at least one object
  double objects = 0.0;                 ///< rated objects per frame (over all frames)
  double correct = 0.0;                 ///< objects.correct, over frames_with_objects
  double over_segmented = 0.0;          ///< objects.over_segmented, over frames_with_objects
  double under_segmented = 0.0;         ///< objects.under_segmented, over frames_with_objects
  double missed = 0.0;                  ///< objects.missed, over frames_with_objects
  double object_point_coverage = 0.0;   ///< over all frames
  double ground_precision = 0.0;        ///< over all frames (and so on below)
  double ground_recall = 0.0;
  double ground_f1 = 0.0;
  double ceiling_precision = 0.0;
  double ceiling_recall = 0.0;
  double ceiling_f1 = 0.0;
  double wall_precision = 0.0;
  double wall_recall = 0.0;
  double wall_f1 = 0.0;
  double ari = 0.0;  ///< adjusted_rand_index
};

/// Averages ObjectMetrics over frames in two ways:
/// - mean(): every frame counts once (as QualityAverage), except that the
///   object rates are averaged over the frames that rated an object (a frame
///   without objects has no rate; ObjectMetrics reports 0 there).
/// - pooled_*(): the counts of all frames summed, then the ratios taken once:
///   every object (point) counts once, and frames without ground do not pull
///   the ground scores towards their degenerate value 1.
///
/// \code
///   streamclust::eval::ObjectMetricsAverage average;
///   for (const auto& f : frames) average.add(streamclust::eval::object_metrics(f.instance, f.cls, f.predicted));
///   const auto m = average.mean();                   // m.correct, m.ground_f1, m.ari, ...
///   const double f1 = average.pooled_ground().f1;   // over every point of every frame
/// \endcode
///
/// O(1) per add, no allocation. Not thread-safe (add mutates).
class ObjectMetricsAverage {
 public:
  void add(const ObjectMetrics& m) {
    ++sum_.frames;
    sum_.objects += static_cast<double>(m.objects.objects);
    if (m.objects.objects > 0) {
      ++sum_.frames_with_objects;
      sum_.correct += m.objects.correct;
      sum_.over_segmented += m.objects.over_segmented;
      sum_.under_segmented += m.objects.under_segmented;
      sum_.missed += m.objects.missed;
    }
    sum_.object_point_coverage += m.object_point_coverage;
    sum_.ground_precision += m.ground.precision;
    sum_.ground_recall += m.ground.recall;
    sum_.ground_f1 += m.ground.f1;
    sum_.ceiling_precision += m.ceiling.precision;
    sum_.ceiling_recall += m.ceiling.recall;
    sum_.ceiling_f1 += m.ceiling.f1;
    sum_.wall_precision += m.wall.precision;
    sum_.wall_recall += m.wall.recall;
    sum_.wall_f1 += m.wall.f1;
    sum_.ari += m.adjusted_rand_index;

    objects_.objects += m.objects.objects;
    objects_.correct_objects += m.objects.correct_objects;
    objects_.over_segmented_objects += m.objects.over_segmented_objects;
    objects_.under_segmented_objects += m.objects.under_segmented_objects;
    objects_.missed_objects += m.objects.missed_objects;
    objects_.over_and_under_objects += m.objects.over_and_under_objects;
    object_points_ += m.object_points;
    classed_structure_ += m.object_points_classed_structure;
    add_counts(ground_, m.ground);
    add_counts(ceiling_, m.ceiling);
    add_counts(wall_, m.wall);
  }

  std::size_t frames() const { return sum_.frames; }

  /// Per-frame means (see the class comment); all zero when no frame was added.
  MeanObjectMetrics mean() const {
    MeanObjectMetrics m = sum_;
    if (m.frames == 0) return m;
    const auto frames = static_cast<double>(m.frames);
    const double with_objects = m.frames_with_objects > 0 ? static_cast<double>(m.frames_with_objects) : 1.0;
    m.objects /= frames;
    m.correct /= with_objects;
    m.over_segmented /= with_objects;
    m.under_segmented /= with_objects;
    m.missed /= with_objects;
    for (double* v : {&m.object_point_coverage, &m.ground_precision, &m.ground_recall, &m.ground_f1,
                      &m.ceiling_precision, &m.ceiling_recall, &m.ceiling_f1, &m.wall_precision, &m.wall_recall,
                      &m.wall_f1, &m.ari}) {
      *v /= frames;
    }
    return m;
  }

  /// Strict rates over every rated object of every frame (summed counts).
  StrictObjectRates pooled_objects() const {
    StrictObjectRates r = objects_;
    r.update_fractions();
    return r;
  }
  /// Ground scores from the summed TP / FP / FN of every frame.
  ClassScores pooled_ground() const { return class_scores(ground_[0], ground_[1], ground_[2]); }
  /// Ceiling scores from the summed TP / FP / FN of every frame.
  ClassScores pooled_ceiling() const { return class_scores(ceiling_[0], ceiling_[1], ceiling_[2]); }
  /// Wall scores from the summed TP / FP / FN of every frame.
  ClassScores pooled_wall() const { return class_scores(wall_[0], wall_[1], wall_[2]); }
  /// Object points of every frame not classed ground / ceiling / wall (fraction; 1 without object points).
  double pooled_object_point_coverage() const {
    return detail::ratio_or(static_cast<double>(object_points_ - classed_structure_),
                            static_cast<double>(object_points_), 1.0);
  }

 private:
  static void add_counts(std::uint64_t (&sum)[3], const ClassScores& s) {
    sum[0] += s.true_positives;
    sum[1] += s.false_positives;
    sum[2] += s.false_negatives;
  }

  MeanObjectMetrics sum_;
  StrictObjectRates objects_;
  std::uint64_t object_points_ = 0;
  std::uint64_t classed_structure_ = 0;
  std::uint64_t ground_[3] = {0, 0, 0};
  std::uint64_t ceiling_[3] = {0, 0, 0};
  std::uint64_t wall_[3] = {0, 0, 0};
};

}  // namespace eval
}  // namespace streamclust
