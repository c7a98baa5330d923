// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Adjusted Rand index (Hubert & Arabie 1985) between the ground-truth
/// instances and the predicted clusters, computed from exact pair counts.

#include <streamclust/eval/contingency.hpp>
#include <streamclust/eval/options.hpp>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {
namespace eval {
namespace detail {

/// Unsigned 128-bit integer, just enough for exact ARI numerators:
/// products of two 64-bit pair counts and sums of two such products.
struct U128 {
  std::uint64_t hi = 0;
  std::uint64_t lo = 0;

  static U128 mul(std::uint64_t a, std::uint64_t b) {
    const std::uint64_t a_lo = a & 0xFFFFFFFFu, a_hi = a >> 32;
    const std::uint64_t b_lo = b & 0xFFFFFFFFu, b_hi = b >> 32;
    const std::uint64_t ll = a_lo * b_lo, lh = a_lo * b_hi, hl = a_hi * b_lo, hh = a_hi * b_hi;
    const std::uint64_t mid = (ll >> 32) + (lh & 0xFFFFFFFFu) + (hl & 0xFFFFFFFFu);
    U128 r;
    r.lo = (mid << 32) | (ll & 0xFFFFFFFFu);
    r.hi = hh + (lh >> 32) + (hl >> 32) + (mid >> 32);
    return r;
  }
  friend U128 operator+(U128 a, U128 b) {
    U128 r;
    r.lo = a.lo + b.lo;
    r.hi = a.hi + b.hi + (r.lo < a.lo ? 1u : 0u);
    return r;
  }
  /// a - b; requires a >= b.
  friend U128 operator-(U128 a, U128 b) {
    U128 r;
    r.lo = a.lo - b.lo;
    r.hi = a.hi - b.hi - (a.lo < b.lo ? 1u : 0u);
    return r;
  }
  friend bool operator<(U128 a, U128 b) { return a.hi != b.hi ? a.hi < b.hi : a.lo < b.lo; }
  long double to_long_double() const {
    return static_cast<long double>(hi) * 18446744073709551616.0L + static_cast<long double>(lo);
  }
};

/// k choose 2 without intermediate overflow for k < 2^32 (the caller checks).
inline std::uint64_t pairs_of(std::uint64_t k) { return (k % 2 == 0) ? (k / 2) * (k - 1) : k * ((k - 1) / 2); }

}  // namespace detail

/// Adjusted Rand index of the predicted clusters against the GT instances,
/// from a prebuilt table (see the vector overload for the definition).
inline double adjusted_rand_index(const ContingencyTable& table, const MetricOptions& options = {}) {
  options.validate();
  const auto& truth_sizes = table.truth_sizes();
  std::vector<std::uint64_t> column(table.predicted_labels().size(), 0);  // b_j over the rows used
  std::uint64_t n = 0;  // points used
  std::uint64_t sum_cells = 0;  // X = sum_ij C(n_ij, 2)
  std::uint64_t sum_rows = 0;   // A = sum_i C(a_i, 2)
  for (std::size_t i = 0; i < truth_sizes.size(); ++i) {
    if (!table.is_object(i) && !options.ari_include_structure) continue;
    n += truth_sizes[i];
    sum_rows += detail::pairs_of(truth_sizes[i]);
    for (std::size_t c = table.row_begin(i); c < table.row_end(i); ++c) {
      const auto& cell = table.cells()[c];
      if (table.is_unlabelled(cell.predicted_index)) continue;  // singletons: no pairs
      column[cell.predicted_index] += cell.count;
      sum_cells += detail::pairs_of(cell.count);
    }
  }
  if (n < 2) return 1.0;
  if (n >= (std::uint64_t{1} << 32)) {
    std::string msg = "adjusted_rand_index: ";
    msg.append(std::to_string(n)).append(" points exceed the exact pair-count range (< 2^32 points)");
    throw std::length_error(msg);
  }
  std::uint64_t sum_cols = 0;  // B = sum_j C(b_j, 2)
  for (const auto b : column) sum_cols += detail::pairs_of(b);
  const std::uint64_t total = detail::pairs_of(n);  // N = C(n, 2) < 2^63

  // ARI = (X - A B / N) / ((A + B) / 2 - A B / N)
  //     = 2 (N X - A B) / (N A + N B - 2 A B), all terms exact in 128 bits.
  using detail::U128;
  const U128 ab = U128::mul(sum_rows, sum_cols);
  const U128 nx = U128::mul(total, sum_cells);
  const U128 den = U128::mul(total, sum_rows) + U128::mul(total, sum_cols) - (ab + ab);  // >= 0 (AM-GM)
  if (den.hi == 0 && den.lo == 0) return 1.0;  // A = B = 0 or A = B = N: identical partitions
  const bool negative = nx < ab;
  const U128 num = negative ? ab - nx : nx - ab;
  const long double value = 2.0L * num.to_long_double() / den.to_long_double();
  return static_cast<double>(negative ? -value : value);
}

/// Adjusted Rand index (Hubert & Arabie 1985; equal to
/// sklearn.metrics.adjusted_rand_score) of `predicted` against `truth`:
///
///   ARI = (X - E) / ((A + B) / 2 - E),  E = A B / N,
///   X = sum_ij C(n_ij, 2), A = sum_i C(a_i, 2), B = sum_j C(b_j, 2), N = C(n, 2),
///
/// over the contingency table n_ij of the points used, with row sums a_i and
/// column sums b_j.
/// - Points used: OBJECT points only (truth > 0) by default, because one
///   ground or wall segment otherwise dominates the pair counts; with
///   `options.ari_include_structure`, every non-ignored point (truth >= 0).
///   Ignored points (truth < 0) are never used.
/// - Unlabelled points (predicted < 0) are each their own singleton cluster
///   (a lost point agrees with no other point), unlike the entropies, where
///   they form one "unlabelled" label.
/// - Degenerate cases: fewer than 2 points used -> 1.0; the denominator is 0
///   exactly when both partitions are all-singletons or both are one single
///   cluster (then they are identical) -> 1.0.
/// - Range [-1, 1]; 1 for identical partitions up to relabelling, about 0
///   for a random one. Exact: all pair counts are 64-bit integers and the
///   numerator and denominator are formed exactly in 128 bits before one
///   long-double division; throws std::length_error beyond 2^32 - 1 points.
///
/// Complexity O(n log n) (the table); thread safety: pure function.
/// Throws std::invalid_argument when the sizes differ or the options are invalid.
inline double adjusted_rand_index(const std::vector<std::int64_t>& truth, const std::vector<std::int64_t>& predicted,
                                  const MetricOptions& options = {}) {
  return adjusted_rand_index(ContingencyTable{truth, predicted}, options);
}

}  // namespace eval
}  // namespace streamclust
