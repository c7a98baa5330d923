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

/// Calls `f(CellIndex)` once for every distinct cell within `half` rows and
/// columns of `center` (the centre included). Rows are clamped at the grid
/// border; columns wrap around when `grid.wrap_columns`, and a mask wider
/// than the grid visits each column once. O(w^2).
template <class F>
void for_each_mask_cell(const GridShape& grid, CellIndex center, int half, F&& f) {
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
  // The first column wrapped once; then one compare per cell, no division.
  const std::int64_t first = ((c0 % cols) + cols) % cols;
  const std::int64_t width = c1 - c0 + 1;
  for (std::int64_t r = r0; r <= r1; ++r) {
    const std::int64_t row_start = r * cols;
    std::int64_t wrapped = first;
    for (std::int64_t k = 0; k < width; ++k) {
      f(static_cast<CellIndex>(row_start + wrapped));
      if (++wrapped == cols) wrapped = 0;
    }
  }
}

}  // namespace streamclust::detail
