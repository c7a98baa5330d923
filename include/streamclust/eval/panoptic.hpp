// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Class-agnostic panoptic-style matching of predicted segments to GT objects
/// at IoU > 0.5: precision, recall, SQ, RQ, PQ (Kirillov et al. 2019, as in
/// SemanticKITTI's PanopticEval, on "things" only).

#include <streamclust/eval/contingency.hpp>
#include <streamclust/eval/options.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {
namespace eval {

/// Result of the panoptic matching of one frame.
struct PanopticScores {
  std::size_t true_positives = 0;   ///< matched (GT object, predicted segment) pairs
  std::size_t false_positives = 0;  ///< counted predicted segments without a match
  std::size_t false_negatives = 0;  ///< counted GT objects without a match
  double precision = 1.0;           ///< TP / (TP + FP); 1 when TP + FP = 0
  double recall = 1.0;              ///< TP / (TP + FN); 1 when TP + FN = 0
  double sq = 1.0;                  ///< mean IoU over TP; 0 when TP = 0 unless nothing is counted (then 1)
  double rq = 1.0;                  ///< TP / (TP + FP/2 + FN/2); 1 when the denominator is 0
  double pq = 1.0;                  ///< sq * rq
};

/// Panoptic scores from a prebuilt table (definition: see the vector overload).
inline PanopticScores panoptic_scores(const ContingencyTable& table, const MetricOptions& options = {}) {
  options.validate();
  const auto& truth_sizes = table.truth_sizes();
  const auto& pred_sizes = table.predicted_sizes();
  std::vector<char> gt_matched(truth_sizes.size(), 0);
  std::vector<char> pred_matched(pred_sizes.size(), 0);
  std::vector<std::uint64_t> structure(pred_sizes.size(), 0);
  PanopticScores s;
  double iou_sum = 0.0;
  for (const auto& cell : table.cells()) {
    const auto i = cell.truth_index;
    const auto j = cell.predicted_index;
    if (table.is_unlabelled(j)) continue;
    if (table.is_structure(i)) {
      structure[j] += cell.count;
      continue;
    }
    // IoU = |g ∩ d| / (|g| + |d| - |g ∩ d|) > 0.5  <=>  2 |g ∩ d| > |g ∪ d|, tested in integers.
    const std::uint64_t uni = truth_sizes[i] + pred_sizes[j] - cell.count;
    if (2 * cell.count > uni) {
      ++s.true_positives;
      iou_sum += static_cast<double>(cell.count) / static_cast<double>(uni);
      gt_matched[i] = 1;
      pred_matched[j] = 1;
    }
  }
  const std::uint64_t min_points = options.min_points;
  for (std::size_t i = 0; i < truth_sizes.size(); ++i) {
    if (table.is_object(i) && !gt_matched[i] && truth_sizes[i] >= min_points) ++s.false_negatives;
  }
  for (std::size_t j = 0; j < pred_sizes.size(); ++j) {
    if (table.is_unlabelled(j) || pred_matched[j] || pred_sizes[j] < min_points) continue;
    if (2 * structure[j] > pred_sizes[j]) continue;  // mostly structure: not an object hypothesis
    ++s.false_positives;
  }
  const auto tp = static_cast<double>(s.true_positives);
  const auto fp = static_cast<double>(s.false_positives);
  const auto fn = static_cast<double>(s.false_negatives);
  s.precision = detail::ratio_or(tp, tp + fp, 1.0);
  s.recall = detail::ratio_or(tp, tp + fn, 1.0);
  s.rq = detail::ratio_or(tp, tp + 0.5 * fp + 0.5 * fn, 1.0);
  s.sq = s.true_positives > 0 ? iou_sum / tp : (s.false_positives + s.false_negatives == 0 ? 1.0 : 0.0);
  s.pq = s.sq * s.rq;
  return s;
}

/// Class-agnostic panoptic matching on objects (PanopticEval of
/// SemanticKITTI applied to one "thing" class):
/// - Segments: GT objects g (truth > 0) and predicted segments d (predicted
///   >= 0; unlabelled points form no segment). Ignored points (truth < 0)
///   are removed first. |d| counts ALL the non-ignored points of d,
///   structure included, so a cluster that swallowed ground loses IoU.
/// - Match: IoU(g, d) = |g ∩ d| / |g ∪ d| > 0.5, strictly (exactly 0.5 is
///   no match); tested exactly in integers as 2 |g ∩ d| > |g ∪ d|. Such a
///   match is unique by construction (each side overlaps at most one other
///   segment by more than half), so no assignment is needed.
/// - TP = matched pairs (any size). FN = unmatched GT objects with
///   |g| >= min_points. FP = unmatched predicted segments with
///   |d| >= min_points, EXCEPT segments made mostly of structure: when
///   strictly more than half of d's points are structure (truth 0), d is a
///   ground/wall segment and is ignored (exactly half still counts). Such a
///   segment can never be a TP either (its IoU with any object is < 0.5).
///   min_points defaults to 1 here; SemanticKITTI uses 30.
/// - precision = TP / (TP + FP), recall = TP / (TP + FN),
///   SQ = sum_TP IoU / TP, RQ = TP / (TP + FP/2 + FN/2), PQ = SQ * RQ.
/// - 0/0 cases: precision (recall) is 1 when nothing was predicted (nothing
///   is to be found): no counted segment can be wrong (missed). SQ is 0 when
///   TP = 0 but something is counted (so PQ = 0, as PanopticEval). When TP =
///   FP = FN = 0 (empty frame), every score is 1.
///
/// Complexity O(n log n) (the table) + O(cells); thread safety: pure function.
/// Throws std::invalid_argument when the sizes differ or the options are invalid.
inline PanopticScores panoptic_scores(const std::vector<std::int64_t>& truth, const std::vector<std::int64_t>& predicted,
                                      const MetricOptions& options = {}) {
  return panoptic_scores(ContingencyTable{truth, predicted}, options);
}

}  // namespace eval
}  // namespace streamclust
