// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// QualityReport and evaluate(): every clustering-quality metric of one
/// frame from one contingency table.

#include <streamclust/eval/contingency.hpp>
#include <streamclust/eval/coverage.hpp>
#include <streamclust/eval/object_rates.hpp>
#include <streamclust/eval/options.hpp>
#include <streamclust/eval/panoptic.hpp>
#include <streamclust/eval/rand_index.hpp>
#include <streamclust/eval/segmentation_entropy.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {
namespace eval {

/// All metrics of one frame. Each field is defined by the function of the
/// same name; see docs/evaluation-metrics.md.
struct QualityReport {
  std::size_t points = 0;            ///< input length
  std::size_t evaluated_points = 0;  ///< points with truth >= 0
  std::size_t object_points = 0;     ///< points with truth > 0
  double adjusted_rand_index = 1.0;  ///< adjusted_rand_index(), objects only unless options say otherwise
  SegmentationEntropy entropy;       ///< TRAVEL's OSE / USE
  PanopticScores panoptic;           ///< IoU > 0.5 matching on objects
  double coverage = 1.0;             ///< labelled fraction of all points
  double evaluated_coverage = 1.0;   ///< labelled fraction of the points with truth >= 0
  double object_coverage = 1.0;      ///< labelled fraction of the object points
  ObjectRates objects;               ///< correct / over / under / missed rates
};

/// Computes every metric of `predicted` against `truth` (conventions in
/// options.hpp), building the contingency table once.
///
/// \code
///   std::vector<std::int64_t> truth{0, 0, 1, 1, 1, 2, 2};
///   std::vector<std::int64_t> pred{-1, -1, 4, 4, 4, 9, 9};
///   auto r = streamclust::eval::evaluate(truth, pred);
///   // r.adjusted_rand_index == 1, r.entropy.over == 0, r.panoptic.pq == 1
/// \endcode
///
/// Complexity O(n log n); thread safety: pure function. Throws
/// std::invalid_argument when the sizes differ or the options are invalid.
inline QualityReport evaluate(const std::vector<std::int64_t>& truth, const std::vector<std::int64_t>& predicted,
                              const MetricOptions& options = {}) {
  options.validate();
  const ContingencyTable table{truth, predicted};
  QualityReport r;
  r.points = table.input_points();
  r.evaluated_points = table.evaluated_points();
  for (std::size_t i = 0; i < table.truth_labels().size(); ++i) {
    if (table.is_object(i)) r.object_points += table.truth_sizes()[i];
  }
  r.adjusted_rand_index = adjusted_rand_index(table, options);
  r.entropy = segmentation_entropy(table);
  r.panoptic = panoptic_scores(table, options);
  r.coverage = coverage(predicted);
  r.evaluated_coverage = coverage(table, CoverageScope::evaluated);
  r.object_coverage = coverage(table, CoverageScope::objects);
  r.objects = object_rates(table, options);
  return r;
}

}  // namespace eval
}  // namespace streamclust
