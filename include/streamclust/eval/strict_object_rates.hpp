// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Strict object rates: is each ground-truth object one cluster of its own?
/// An object is correct when one cluster holds >= 80 % of it and >= 80 % of
/// that cluster is the object (both fractions configurable).

#include <streamclust/eval/contingency.hpp>
#include <streamclust/eval/options.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {
namespace eval {

/// Outcome of every rated GT object under the strict definition, as counts
/// and as fractions of `objects` (definitions: strict_object_rates()).
/// correct, missed and "over or under" partition the rated objects, so
/// correct + missed + over_segmented + under_segmented - over_and_under == 1
/// whenever objects > 0.
struct StrictObjectRates {
  std::size_t objects = 0;        ///< GT objects rated (truth > 0 and >= min_points points)
  double correct = 0.0;           ///< fraction correct
  double over_segmented = 0.0;    ///< fraction over-segmented (may also be under-segmented)
  double under_segmented = 0.0;   ///< fraction under-segmented (may also be over-segmented)
  double missed = 0.0;            ///< fraction missed (exclusive with every other outcome)
  double over_and_under = 0.0;    ///< fraction both over- and under-segmented
  std::size_t correct_objects = 0;
  std::size_t over_segmented_objects = 0;
  std::size_t under_segmented_objects = 0;
  std::size_t missed_objects = 0;
  std::size_t over_and_under_objects = 0;

  /// Sets the fractions from the counts (all 0 when objects == 0). O(1).
  void update_fractions() {
    const double n = objects > 0 ? static_cast<double>(objects) : 1.0;
    correct = static_cast<double>(correct_objects) / n;
    over_segmented = static_cast<double>(over_segmented_objects) / n;
    under_segmented = static_cast<double>(under_segmented_objects) / n;
    missed = static_cast<double>(missed_objects) / n;
    over_and_under = static_cast<double>(over_and_under_objects) / n;
  }
};

/// Strict object rates from a prebuilt table (definition: see the vector
/// overload). The table must be built from the same predicted labels (its
/// unlabelled column then holds every negative prediction: unlabelled,
/// classed ground, classed ceiling).
inline StrictObjectRates strict_object_rates(const ContingencyTable& table, const MetricOptions& options = {}) {
  options.validate();
  const auto& cells = table.cells();
  const auto& cluster_sizes = table.predicted_sizes();
  const std::uint64_t min_points = std::max<std::uint64_t>(options.min_points, 1);
  StrictObjectRates r;
  for (std::size_t i = 0; i < table.truth_labels().size(); ++i) {
    const std::uint64_t size = table.truth_sizes()[i];
    if (!table.is_object(i) || size < min_points) continue;
    ++r.objects;
    std::uint64_t outside = 0;  // points in no cluster (negative prediction)
    std::uint64_t best = 0;     // most points of the object in one cluster
    std::uint64_t best_cluster = 0;  // size of that cluster (ties: the smallest, i.e. the purest)
    for (std::size_t c = table.row_begin(i); c < table.row_end(i); ++c) {
      const auto& cell = cells[c];
      if (table.is_unlabelled(cell.predicted_index)) {
        outside += cell.count;
        continue;
      }
      const std::uint64_t cluster = cluster_sizes[cell.predicted_index];
      if (cell.count > best || (cell.count == best && cluster < best_cluster)) {
        best = cell.count;
        best_cluster = cluster;
      }
    }
    if (2 * outside > size) {
      ++r.missed_objects;
      continue;
    }
    // Not missed: at least half of the object is clustered, so best > 0.
    const bool over = !detail::at_least_fraction(best, options.strict_object_fraction, size);
    const bool under = !detail::at_least_fraction(best, options.strict_purity_fraction, best_cluster);
    if (over) ++r.over_segmented_objects;
    if (under) ++r.under_segmented_objects;
    if (over && under) ++r.over_and_under_objects;
    if (!over && !under) ++r.correct_objects;
  }
  r.update_fractions();
  return r;
}

/// Strict object rates. Ignored points (truth < 0) are removed first. Every
/// GT object g (truth > 0) with |g| >= min_points is rated. A point of g is
/// "outside" when its prediction is negative (unlabelled, classed ground,
/// classed ceiling): it is in no cluster. With n(g, d) the points of g in
/// cluster d >= 0, |d| all the non-ignored points of d (structure and other
/// objects included: they are foreign to g), m the cluster holding the most
/// of g (ties: the smallest |d|, i.e. the purest, so the result does not
/// depend on id values), a = strict_object_fraction and b =
/// strict_purity_fraction (defaults 0.8, 0.8), in this order:
/// 1. missed: strictly more than half of g is outside. Exclusive: a missed
///    object gets no other outcome.
/// 2. over-segmented: n(g, m) < a |g|: no cluster holds a share a of g
///    (split, or partly outside).
/// 3. under-segmented: n(g, m) < b |m|: the cluster holding the most of g
///    has more than a share 1 - b of foreign points (merged with another
///    object, a wall, the ground...). Both objects of a merge are flagged.
/// 4. correct: neither over nor under, i.e. n(g, m) >= a |g| and
///    n(g, m) >= b |m|: ONE cluster holds >= a of g and >= b of it is g.
/// Over and under may both hold (counted in over_and_under). Fractions
/// compare with a relative tolerance of 1e-12 (80 % of 100 is 80 points).
/// Rates are counts / objects; all 0 when objects == 0.
///
/// Complexity O(n log n) (the table) + O(cells); thread safety: pure function.
/// Throws std::invalid_argument when the sizes differ or the options are invalid.
inline StrictObjectRates strict_object_rates(const std::vector<std::int64_t>& truth,
                                             const std::vector<std::int64_t>& predicted,
                                             const MetricOptions& options = {}) {
  return strict_object_rates(ContingencyTable{truth, predicted}, options);
}

}  // namespace eval
}  // namespace streamclust
