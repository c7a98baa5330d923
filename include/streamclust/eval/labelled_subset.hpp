// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Scores restricted to the points a reference method labelled: a fair
/// comparison with a method that loses points (the overwrite frame baseline),
/// separating its information loss (the points it drops) from the quality of
/// what it keeps. Both methods are scored on the same subset of a window.

#include <streamclust/eval/options.hpp>
#include <streamclust/eval/report.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {
namespace eval {

/// The truth and predicted labels of the points kept by a restriction.
struct LabelledSubset {
  std::vector<std::int64_t> truth;
  std::vector<std::int64_t> predicted;
};

/// Keeps the points i where `reference[i] >= 0` (the reference method gave
/// them a label), in their order. `reference` may be `predicted` itself (a
/// method restricted to its own labelled points). Throws
/// std::invalid_argument unless the three vectors have the same length.
/// O(n); pure function.
inline LabelledSubset restrict_to_labelled(const std::vector<std::int64_t>& truth,
                                           const std::vector<std::int64_t>& predicted,
                                           const std::vector<std::int64_t>& reference) {
  detail::check_same_size(truth.size(), predicted.size());
  detail::check_same_size(truth.size(), reference.size());
  LabelledSubset s;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (reference[i] < 0) continue;
    s.truth.push_back(truth[i]);
    s.predicted.push_back(predicted[i]);
  }
  return s;
}

/// Every metric of `predicted` against `truth` on the points the reference
/// labelled (`reference[i] >= 0`): evaluate() on restrict_to_labelled().
/// Objects are what is left of them in the subset (an object the reference
/// lost entirely is not rated; `min_points` applies to the remaining points).
///
/// \code
///   // truth: two objects; the baseline dropped points 2 and 4, C-ARC kept all
///   std::vector<std::int64_t> truth{1, 1, 1, 2, 2}, baseline{4, 4, -1, 6, -1}, carc{7, 7, 8, 9, 9};
///   auto b = streamclust::eval::evaluate_on_labelled(truth, baseline, baseline);  // b.points == 3
///   auto c = streamclust::eval::evaluate_on_labelled(truth, carc, baseline);      // same 3 points, ARI 1
/// \endcode
///
/// O(n log n); pure function. Throws std::invalid_argument on differing
/// sizes or invalid options.
inline QualityReport evaluate_on_labelled(const std::vector<std::int64_t>& truth,
                                          const std::vector<std::int64_t>& predicted,
                                          const std::vector<std::int64_t>& reference, const MetricOptions& options = {}) {
  const LabelledSubset s = restrict_to_labelled(truth, predicted, reference);
  return evaluate(s.truth, s.predicted, options);
}

}  // namespace eval
}  // namespace streamclust
