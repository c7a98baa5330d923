// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// MeanQuality and QualityAverage: the per-frame metrics of many frames
/// (e.g. every retrieval of a continuous run) averaged frame by frame.

#include <streamclust/eval/report.hpp>

#include <cstddef>

namespace streamclust {
namespace eval {

/// The scalar metrics of a QualityReport as doubles: one frame's values, or
/// (from QualityAverage::mean) their unweighted mean over frames. Field
/// meanings are those of QualityReport (docs/evaluation-metrics.md).
struct MeanQuality {
  std::size_t frames = 0;         ///< frames averaged (1 for a single frame)
  double points = 0.0;            ///< QualityReport::points
  double object_points = 0.0;     ///< QualityReport::object_points
  double objects = 0.0;           ///< objects rated (ObjectRates::objects)
  double ari = 0.0;               ///< adjusted_rand_index
  double ose = 0.0;               ///< entropy.over (sum over objects)
  double use = 0.0;               ///< entropy.under (sum over clusters)
  double ose_mean = 0.0;          ///< entropy.over_mean (per object)
  double use_mean = 0.0;          ///< entropy.under_mean (per cluster)
  double precision = 0.0;         ///< panoptic.precision
  double recall = 0.0;            ///< panoptic.recall
  double sq = 0.0;                ///< panoptic.sq
  double rq = 0.0;                ///< panoptic.rq
  double pq = 0.0;                ///< panoptic.pq
  double coverage = 0.0;          ///< labelled fraction of all points
  double object_coverage = 0.0;   ///< labelled fraction of the object points
  double correct = 0.0;           ///< objects.correct
  double over_segmented = 0.0;    ///< objects.over_segmented
  double under_segmented = 0.0;   ///< objects.under_segmented
  double missed = 0.0;            ///< objects.missed
};

/// The scalar metrics of one frame. O(1); pure function.
inline MeanQuality to_mean_quality(const QualityReport& r) {
  MeanQuality m;
  m.frames = 1;
  m.points = static_cast<double>(r.points);
  m.object_points = static_cast<double>(r.object_points);
  m.objects = static_cast<double>(r.objects.objects);
  m.ari = r.adjusted_rand_index;
  m.ose = r.entropy.over;
  m.use = r.entropy.under;
  m.ose_mean = r.entropy.over_mean;
  m.use_mean = r.entropy.under_mean;
  m.precision = r.panoptic.precision;
  m.recall = r.panoptic.recall;
  m.sq = r.panoptic.sq;
  m.rq = r.panoptic.rq;
  m.pq = r.panoptic.pq;
  m.coverage = r.coverage;
  m.object_coverage = r.object_coverage;
  m.correct = r.objects.correct;
  m.over_segmented = r.objects.over_segmented;
  m.under_segmented = r.objects.under_segmented;
  m.missed = r.objects.missed;
  return m;
}

/// Every averaged field of MeanQuality (all but `frames`), for generic code
/// (sums, output tables).
inline constexpr double MeanQuality::*kMeanQualityFields[] = {
    &MeanQuality::points,          &MeanQuality::object_points,  &MeanQuality::objects,   &MeanQuality::ari,
    &MeanQuality::ose,             &MeanQuality::use,            &MeanQuality::ose_mean,  &MeanQuality::use_mean,
    &MeanQuality::precision,       &MeanQuality::recall,         &MeanQuality::sq,        &MeanQuality::rq,
    &MeanQuality::pq,              &MeanQuality::coverage,       &MeanQuality::object_coverage,
    &MeanQuality::correct,         &MeanQuality::over_segmented, &MeanQuality::under_segmented,
    &MeanQuality::missed};

/// Unweighted mean of per-frame metrics: every frame counts once, whatever
/// its number of points (a sequence's score, as in TRAVEL's per-frame
/// averages).
///
/// \code
///   streamclust::eval::QualityAverage average;
///   for (const auto& frame : frames) average.add(streamclust::eval::evaluate(frame.truth, frame.predicted));
///   const auto m = average.mean();  // m.ari, m.pq, m.coverage, ... ; m.frames == frames.size()
/// \endcode
///
/// O(1) per add. Not thread-safe (add mutates).
class QualityAverage {
 public:
  void add(const QualityReport& r) { add(to_mean_quality(r)); }
  /// Adds one frame's values (`m.frames` is ignored: it counts as one frame).
  void add(const MeanQuality& m) {
    for (const auto field : kMeanQualityFields) sum_.*field += m.*field;
    ++sum_.frames;
  }
  std::size_t frames() const { return sum_.frames; }
  /// The mean of every field over the frames added; all zero when none was.
  MeanQuality mean() const {
    MeanQuality m = sum_;
    if (m.frames == 0) return m;
    for (const auto field : kMeanQualityFields) m.*field /= static_cast<double>(m.frames);
    return m;
  }

 private:
  MeanQuality sum_;
};

}  // namespace eval
}  // namespace streamclust
