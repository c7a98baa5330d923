// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Object-level segmentation outcome rates: correct, over-segmented,
/// under-segmented, missed (majority matching in the style of Douillard et
/// al. 2011).

#include <streamclust/eval/contingency.hpp>
#include <streamclust/eval/options.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {
namespace eval {

/// Outcome of every rated GT object, as counts and as fractions of `objects`.
struct ObjectRates {
  std::size_t objects = 0;  ///< GT objects rated (truth > 0 and >= min_points points)
  double correct = 0.0;          ///< fraction correct
  double over_segmented = 0.0;   ///< fraction over-segmented (may also be under-segmented)
  double under_segmented = 0.0;  ///< fraction under-segmented (may also be over-segmented)
  double missed = 0.0;           ///< fraction missed (exclusive with every other outcome)
  double other = 0.0;            ///< fraction in none of the four outcomes
  std::size_t correct_objects = 0;
  std::size_t over_segmented_objects = 0;
  std::size_t under_segmented_objects = 0;
  std::size_t missed_objects = 0;
  std::size_t other_objects = 0;
};

/// Object rates from a prebuilt table (definition: see the vector overload).
inline ObjectRates object_rates(const ContingencyTable& table, const MetricOptions& options = {}) {
  options.validate();
  const auto& cells = table.cells();
  const auto& pred_sizes = table.predicted_sizes();
  ObjectRates r;
  for (std::size_t i = 0; i < table.truth_labels().size(); ++i) {
    const std::uint64_t size = table.truth_sizes()[i];
    if (!table.is_object(i) || size < options.min_points || size == 0) continue;
    ++r.objects;
    std::uint64_t unlabelled = 0;
    std::size_t pieces = 0;
    std::size_t major = 0;  // cell index of the majority cluster
    std::uint64_t major_count = 0;
    for (std::size_t c = table.row_begin(i); c < table.row_end(i); ++c) {
      if (table.is_unlabelled(cells[c].predicted_index)) {
        unlabelled += cells[c].count;
        continue;
      }
      // Cells are sorted by predicted label: ">" keeps the smallest label on ties.
      if (cells[c].count > major_count) {
        major_count = cells[c].count;
        major = c;
      }
      if (detail::at_least_fraction(cells[c].count, options.over_segmentation_fraction, size)) ++pieces;
    }
    if (2 * unlabelled > size) {
      ++r.missed_objects;
      continue;
    }
    // Not missed, so at least half of the object is labelled and major is set.
    const std::uint64_t cluster_size = pred_sizes[cells[major].predicted_index];
    const bool over = pieces >= 2;
    const bool under =
        detail::at_least_fraction(cluster_size - major_count, options.under_segmentation_fraction, cluster_size);
    if (over) ++r.over_segmented_objects;
    if (under) ++r.under_segmented_objects;
    if (!over && !under) {
      if (2 * major_count >= size) {
        ++r.correct_objects;
      } else {
        ++r.other_objects;
      }
    }
  }
  if (r.objects > 0) {
    const auto n = static_cast<double>(r.objects);
    r.correct = static_cast<double>(r.correct_objects) / n;
    r.over_segmented = static_cast<double>(r.over_segmented_objects) / n;
    r.under_segmented = static_cast<double>(r.under_segmented_objects) / n;
    r.missed = static_cast<double>(r.missed_objects) / n;
    r.other = static_cast<double>(r.other_objects) / n;
  }
  return r;
}

/// Object-level outcome rates. Every GT object g (truth > 0) with
/// |g| >= min_points is rated; ignored points (truth < 0) are removed first.
/// With u = unlabelled points of g, n(g, d) its points in cluster d >= 0,
/// and m = the majority cluster argmax_d n(g, d) (ties: the smallest
/// predicted id), in this order:
/// 1. missed: 2 u > |g| (strictly more than half of g received no label).
///    Exclusive: a missed object gets no other outcome.
/// 2. over-segmented: at least 2 clusters d >= 0 each hold
///    n(g, d) >= over_segmentation_fraction * |g| (default 10 %; unlabelled
///    points are never a piece).
/// 3. under-segmented: the points of m that are not from g (other objects
///    and structure) are >= under_segmentation_fraction * |m| (default 10 %),
///    i.e. g's majority cluster is merged with something else. When two
///    objects are merged, both are flagged (each sees the other as foreign).
///    Over and under may both hold: their rates need not sum with the others to 1.
/// 4. correct: neither over nor under, and n(g, m) >= |g| / 2.
/// 5. other: none of the above (a labelled object whose majority cluster holds
///    < 50 % of it, the rest being unlabelled or crumbs below the piece fraction).
/// Fractions compare with a relative tolerance of 1e-12 (7 % of 100 points
/// is 7 points, although 0.07 * 100 is 7.000000000000001 in double).
/// Rates are counts / objects; all 0 when objects == 0.
///
/// Complexity O(n log n) (the table) + O(cells); thread safety: pure function.
/// Throws std::invalid_argument when the sizes differ or the options are invalid.
inline ObjectRates object_rates(const std::vector<std::int64_t>& truth, const std::vector<std::int64_t>& predicted,
                                const MetricOptions& options = {}) {
  return object_rates(ContingencyTable{truth, predicted}, options);
}

}  // namespace eval
}  // namespace streamclust
