// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Iteration over the w x w neighbourhood mask of a grid cell, shared by the
/// continuous engine and the batch clusterer so both see the same cells.

#include <streamclust/detail/hints.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cstdint>

namespace streamclust::detail {

/// Calls `f(CellIndex, row, col)` once for every distinct cell within `half`
/// rows and columns of `center` (the centre included), in row-major order
/// from the top-left corner; `row` and `col` are the cell's grid coordinates
/// (std::int64_t, wrapped into [0, cols)). Rows are clamped at the grid
/// border; columns wrap around when `grid.wrap_columns`, and a mask wider
/// than the grid visits each column once. O(w^2).
template <class F>
void for_each_mask_cell_at(const GridShape& grid, CellIndex center, int half, F&& f) {
  const auto row = static_cast<std::int64_t>(grid.row_of(center));
  const auto col = static_cast<std::int64_t>(grid.col_of(center));
  const auto rows = static_cast<std::int64_t>(grid.rows);
  const auto cols = static_cast<std::int64_t>(grid.cols);
  const std::int64_t r0 = std::max<std::int64_t>(0, row - half);
  const std::int64_t r1 = std::min<std::int64_t>(rows - 1, row + half);
  std::int64_t c0 = col - half;
  std::int64_t c1 = col + half;
  if (grid.wrap_columns) {
    if (c1 - c0 + 1 >= cols) {  // the mask covers the whole ring: each column once
      c0 = 0;
      c1 = cols - 1;
    }
  } else {
    c0 = std::max<std::int64_t>(0, c0);
    c1 = std::min<std::int64_t>(cols - 1, c1);
  }
  // The first column wrapped once (c0 >= -half > -cols when the mask is
  // narrower than the ring, else 0); then one compare per cell, no division.
  const std::int64_t first = c0 < 0 ? c0 + cols : c0;
  const std::int64_t width = c1 - c0 + 1;
  for (std::int64_t r = r0; r <= r1; ++r) {
    const std::int64_t row_start = r * cols;
    std::int64_t wrapped = first;
    for (std::int64_t k = 0; k < width; ++k) {
      f(static_cast<CellIndex>(row_start + wrapped), r, wrapped);
      if (++wrapped == cols) wrapped = 0;
    }
  }
}

/// Calls `f(CellIndex)` once for every cell of `for_each_mask_cell_at`, in
/// the same order. O(w^2).
template <class F>
void for_each_mask_cell(const GridShape& grid, CellIndex center, int half, F&& f) {
  for_each_mask_cell_at(grid, center, half, [&](CellIndex c, std::int64_t, std::int64_t) { f(c); });
}

/// Mask membership: `(*this)(row_a, col_a, row_b, col_b)` is true when the
/// cell at (row_b, col_b) is in the mask of the cell at (row_a, col_a), i.e.
/// `for_each_mask_cell_at` around a visits b (rows clamped, columns wrapped
/// when the grid wraps). Holds the grid's width, wrap flag and the mask's
/// half width by value, so a hot loop can keep them in registers. O(1),
/// branch-free.
class MaskMembership {
 public:
  MaskMembership(const GridShape& grid, int half)
      : cols_(static_cast<std::int32_t>(grid.cols)), half_(half), wrap_(grid.wrap_columns) {}

  bool operator()(std::int32_t row_a, std::int32_t col_a, std::int32_t row_b, std::int32_t col_b) const {
    const std::int32_t dr = row_a > row_b ? row_a - row_b : row_b - row_a;
    const std::int32_t dc = col_a > col_b ? col_a - col_b : col_b - col_a;
    const std::int32_t around = cols_ - dc;  // the distance the other way round a wrapping grid
    const std::int32_t dist = wrap_ && around < dc ? around : dc;
    return (dr <= half_) & (dist <= half_);
  }

 private:
  std::int32_t cols_;
  std::int32_t half_;
  bool wrap_;
};

}  // namespace streamclust::detail
