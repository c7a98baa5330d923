// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Over- and under-segmentation entropy (OSE / USE) as defined by TRAVEL
/// (Oh et al., RA-L 2022) and used by continuous_clustering's KITTI evaluation.

#include <streamclust/eval/contingency.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {
namespace eval {

/// TRAVEL's segmentation entropies of one frame (natural log, nats).
struct SegmentationEntropy {
  double over = 0.0;         ///< OSE: sum over GT objects of their entropy over predicted labels
  double under = 0.0;        ///< USE: sum over counted predicted clusters of their entropy over GT labels
  double over_mean = 0.0;    ///< over / objects (0 when there is no object)
  double under_mean = 0.0;   ///< under / clusters (0 when no cluster is counted)
  std::size_t objects = 0;   ///< GT objects summed in `over`
  std::size_t clusters = 0;  ///< predicted clusters summed in `under`
};

/// OSE / USE from a prebuilt table (definition: see the vector overload).
inline SegmentationEntropy segmentation_entropy(const ContingencyTable& table) {
  SegmentationEntropy e;
  const auto& cells = table.cells();
  // OSE: rows of GT objects; the unlabelled label is one more predicted label.
  for (std::size_t i = 0; i < table.truth_labels().size(); ++i) {
    if (!table.is_object(i)) continue;
    const auto size = static_cast<double>(table.truth_sizes()[i]);
    double h = 0.0;
    for (std::size_t c = table.row_begin(i); c < table.row_end(i); ++c) {
      const double p = static_cast<double>(cells[c].count) / size;
      h -= p * std::log(p);
    }
    e.over += h;
    ++e.objects;
  }
  // USE: columns of labelled clusters holding at least one object point; GT
  // label 0 (structure) is one more GT label.
  const std::size_t k = table.predicted_labels().size();
  std::vector<double> h(k, 0.0);
  std::vector<char> has_object(k, 0);
  for (const auto& cell : cells) {
    const auto j = cell.predicted_index;
    const double p = static_cast<double>(cell.count) / static_cast<double>(table.predicted_sizes()[j]);
    h[j] -= p * std::log(p);
    if (table.is_object(cell.truth_index)) has_object[j] = 1;
  }
  for (std::size_t j = 0; j < k; ++j) {
    if (table.is_unlabelled(j) || !has_object[j]) continue;
    e.under += h[j];
    ++e.clusters;
  }
  e.over_mean = e.objects == 0 ? 0.0 : e.over / static_cast<double>(e.objects);
  e.under_mean = e.clusters == 0 ? 0.0 : e.under / static_cast<double>(e.clusters);
  return e;
}

/// TRAVEL's over- and under-segmentation entropies (field-notes 1.9), natural log:
///
///   OSE = sum_{GT object g}  [ -sum_{predicted label d} p ln p ],  p = |g ∩ d| / |g|,
///   USE = sum_{predicted cluster d} [ -sum_{GT label g} q ln q ],  q = |d ∩ g| / |d|,
///
/// - OSE runs over GT objects (truth > 0); d ranges over the predicted labels
///   INCLUDING the unlabelled label, which is ONE label (all points with
///   predicted < 0 together, TRAVEL's "0 = unclustered").
/// - USE runs over predicted clusters d >= 0 (never the unlabelled label)
///   that contain at least one object point (clusters of structure points
///   only are excluded); g ranges over GT labels INCLUDING structure (0), so a
///   cluster mixing an object with ground is penalised. |d| counts the
///   cluster's non-ignored points.
/// - Ignored points (truth < 0) are removed first.
/// - Both are sums (they grow with the number of objects/clusters in the
///   scene), so `over_mean` / `under_mean` divide by the number of terms.
///   Perfect clustering gives exactly 0; an object split in two equal halves
///   adds ln 2 to OSE; a cluster made of two equal objects adds ln 2 to USE.
///
/// Empty input: all zero. Complexity O(n log n) (the table); thread safety:
/// pure function. Throws std::invalid_argument when the sizes differ.
inline SegmentationEntropy segmentation_entropy(const std::vector<std::int64_t>& truth,
                                                const std::vector<std::int64_t>& predicted) {
  return segmentation_entropy(ContingencyTable{truth, predicted});
}

}  // namespace eval
}  // namespace streamclust
