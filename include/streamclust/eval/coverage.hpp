// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Coverage: the fraction of points that received a cluster label (an
/// overwrite grid or an eviction loses points; this measures how many).

#include <streamclust/eval/contingency.hpp>
#include <streamclust/eval/options.hpp>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace streamclust {
namespace eval {

/// Which points the coverage is measured on.
enum class CoverageScope : std::uint8_t {
  all_points,  ///< every point, ignored truth included
  evaluated,   ///< points with truth >= 0 (ignored points removed)
  objects,     ///< object points only (truth > 0)
};

/// Fraction of points with predicted >= 0 (a label). Empty input -> 1.0
/// (nothing was lost). O(n); pure function.
inline double coverage(const std::vector<std::int64_t>& predicted) {
  std::size_t labelled = 0;
  for (const auto p : predicted) labelled += p >= 0 ? 1u : 0u;
  return detail::ratio_or(static_cast<double>(labelled), static_cast<double>(predicted.size()), 1.0);
}

/// Fraction of the points of `scope` with predicted >= 0; 1.0 when the scope
/// holds no point. O(n); pure function. Throws std::invalid_argument when the
/// sizes differ.
inline double coverage(const std::vector<std::int64_t>& truth, const std::vector<std::int64_t>& predicted,
                       CoverageScope scope = CoverageScope::evaluated) {
  detail::check_same_size(truth.size(), predicted.size());
  std::size_t in_scope = 0;
  std::size_t labelled = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const bool used = scope == CoverageScope::all_points || (scope == CoverageScope::evaluated && truth[i] >= 0) ||
                      (scope == CoverageScope::objects && truth[i] > 0);
    if (!used) continue;
    ++in_scope;
    labelled += predicted[i] >= 0 ? 1u : 0u;
  }
  return detail::ratio_or(static_cast<double>(labelled), static_cast<double>(in_scope), 1.0);
}

/// Coverage of the evaluated points (scope `evaluated`) or of the object
/// points (`objects`) from a prebuilt table; `all_points` is not available
/// from a table (it drops ignored points) and throws std::invalid_argument.
inline double coverage(const ContingencyTable& table, CoverageScope scope = CoverageScope::evaluated) {
  if (scope == CoverageScope::all_points) {
    throw std::invalid_argument("coverage(ContingencyTable, CoverageScope::all_points): the table holds no ignored points; "
                                "use coverage(predicted)");
  }
  std::uint64_t in_scope = 0;
  std::uint64_t labelled = 0;
  for (const auto& cell : table.cells()) {
    if (scope == CoverageScope::objects && !table.is_object(cell.truth_index)) continue;
    in_scope += cell.count;
    if (!table.is_unlabelled(cell.predicted_index)) labelled += cell.count;
  }
  return detail::ratio_or(static_cast<double>(labelled), static_cast<double>(in_scope), 1.0);
}

}  // namespace eval
}  // namespace streamclust
