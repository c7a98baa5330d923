// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// min_cost_assignment(): the optimal one-to-one assignment of rows to
/// columns of a cost matrix (the Hungarian method with potentials and
/// shortest augmenting paths), pairs at or above a forbidden cost left
/// unassigned. For the tracking metrics' per-frame matching and IDF1.

#include <algorithm>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace streamclust {
namespace eval {

/// The assignment of rows to columns of a rows x cols cost matrix (row
/// major, `cost[r * cols + c]`) with the least total cost among the
/// assignments of the most pairs below `forbidden`; a pair costing
/// `forbidden` or more is never made. Returns the column of each row, -1
/// when unassigned. Costs must be finite and >= 0 (std::invalid_argument
/// otherwise). O(n^2 m) for n = min(rows, cols), m = max.
inline std::vector<long> min_cost_assignment(const std::vector<double>& cost, std::size_t rows, std::size_t cols,
                                             double forbidden) {
  if (cost.size() != rows * cols) throw std::invalid_argument("min_cost_assignment: cost is not rows x cols");
  for (const double c : cost) {
    if (!(c >= 0.0) || c == std::numeric_limits<double>::infinity()) {
      throw std::invalid_argument("min_cost_assignment: costs must be finite and >= 0");
    }
  }
  std::vector<long> row_to_col(rows, -1);
  if (rows == 0 || cols == 0) return row_to_col;
  // Rows are the smaller side; a forbidden pair costs `big`, more than any
  // set of allowed pairs, so the optimum makes as many allowed pairs as it can.
  const bool transposed = rows > cols;
  const std::size_t n = transposed ? cols : rows, m = transposed ? rows : cols;
  double allowed_total = 0.0;
  for (const double c : cost) allowed_total += c < forbidden ? c : 0.0;
  const double big = 2.0 * allowed_total + 1.0;
  const auto at = [&](std::size_t i, std::size_t j) {
    const double c = transposed ? cost[j * cols + i] : cost[i * cols + j];
    return c < forbidden ? c : big;
  };
  // Potentials u (rows, 1-based) and v (columns, 0 = the virtual start),
  // match[j] = the row on column j (0: none).
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0), reach(m + 1);
  std::vector<std::size_t> match(m + 1, 0), way(m + 1, 0);
  std::vector<char> used(m + 1);
  for (std::size_t i = 1; i <= n; ++i) {
    match[0] = i;
    std::size_t j0 = 0;
    std::fill(reach.begin(), reach.end(), kInf);
    std::fill(used.begin(), used.end(), 0);
    do {
      used[j0] = 1;
      const std::size_t i0 = match[j0];
      double delta = kInf;
      std::size_t j1 = 0;
      for (std::size_t j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double reduced = at(i0 - 1, j - 1) - u[i0] - v[j];
        if (reduced < reach[j]) {
          reach[j] = reduced;
          way[j] = j0;
        }
        if (reach[j] < delta) {
          delta = reach[j];
          j1 = j;
        }
      }
      for (std::size_t j = 0; j <= m; ++j) {
        if (used[j]) {
          u[match[j]] += delta;
          v[j] -= delta;
        } else {
          reach[j] -= delta;
        }
      }
      j0 = j1;
    } while (match[j0] != 0);
    do {  // flip the augmenting path
      const std::size_t j1 = way[j0];
      match[j0] = match[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  for (std::size_t j = 1; j <= m; ++j) {
    if (match[j] == 0) continue;
    const std::size_t i = match[j] - 1, c = j - 1;
    if (!(at(i, c) < big)) continue;  // a forbidden pair: left unassigned
    if (transposed) {
      row_to_col[c] = static_cast<long>(i);
    } else {
      row_to_col[i] = static_cast<long>(c);
    }
  }
  return row_to_col;
}

}  // namespace eval
}  // namespace streamclust
