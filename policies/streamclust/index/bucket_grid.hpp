// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// BucketGrid: unbounded per-cell buckets of point handles (C-ARC's range grid).

#include <streamclust/concepts/spatial_index.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {

/// Spatial index storing every handle of a cell (the bucket-based range grid
/// of C-ARC): nothing is ever displaced, so `insert` always returns kNoPoint.
///
/// Each cell is a `std::vector<PointHandle>` plus a head offset. Removing the
/// front handle (the common case: the engine removes points oldest first) just
/// advances the head, O(1); once the head passes half of the vector the live
/// tail is moved to the front (amortised O(1)). Removing any other handle
/// falls back to a linear search and erase, O(k); removing an absent handle is
/// a no-op. `for_each` visits a cell in insertion order.
///
/// Memory: one vector per cell (24 bytes + 4 for the head) plus 4 bytes per
/// stored handle. Vectors keep their capacity across `remove` and `clear`, so a
/// steady-state window allocates nothing; `Params::reserve_per_cell` pre-sizes
/// every bucket at `reset`.
///
/// Thread safety: not thread-safe (one writer, no concurrent readers).
///
/// Usage:
/// \code
///   streamclust::BucketGrid grid{{}};
///   grid.reset(streamclust::GridShape{64, 1024, true});
///   const auto cell = streamclust::GridShape{64, 1024, true}.cell_of(0.5f, 0.5f);
///   grid.insert(cell, 7);
///   grid.for_each(cell, [](streamclust::PointHandle h) { /* h == 7 */ });
///   grid.remove(cell, 7);
/// \endcode
class BucketGrid {
 public:
  struct Params {
    std::uint32_t reserve_per_cell = 0;  ///< [handles] capacity reserved in every cell at reset
  };

  explicit BucketGrid(const Params& params) : params_(params) {}

  /// Allocate `shape.cell_count()` empty cells (keeps existing bucket
  /// capacity where cells are reused). O(cells).
  void reset(const GridShape& shape) {
    cells_.resize(shape.cell_count());
    for (Cell& c : cells_) {
      c.items.clear();
      c.head = 0;
      if (params_.reserve_per_cell > 0) c.items.reserve(params_.reserve_per_cell);
    }
    size_ = 0;
  }

  /// Empty every cell, keeping the allocations. O(cells).
  void clear() {
    for (Cell& c : cells_) {
      c.items.clear();
      c.head = 0;
    }
    size_ = 0;
  }

  /// Append `h` to the cell; never displaces, returns kNoPoint. O(1) amortised.
  /// A full bucket with removed handles at its front is compacted instead of
  /// grown, so a bucket's capacity only grows past its largest live
  /// occupancy (steady state: no allocation).
  PointHandle insert(CellIndex cell, PointHandle h) {
    Cell& c = cells_[cell];
    if (c.head > 0 && c.items.size() == c.items.capacity()) {
      c.items.erase(c.items.begin(), c.items.begin() + c.head);
      c.head = 0;
    }
    c.items.push_back(h);
    ++size_;
    return kNoPoint;
  }

  /// Forget `h` if stored in `cell`. O(1) amortised for the oldest handle,
  /// O(k) otherwise; no-op when absent.
  void remove(CellIndex cell, PointHandle h) {
    Cell& c = cells_[cell];
    const std::size_t n = c.items.size();
    if (c.head >= n) return;
    if (c.items[c.head] == h) {
      ++c.head;
      --size_;
      if (c.head == n) {
        c.items.clear();
        c.head = 0;
      } else if (std::size_t{c.head} * 2 > n) {
        c.items.erase(c.items.begin(), c.items.begin() + c.head);
        c.head = 0;
      }
      return;
    }
    const auto first = c.items.begin() + c.head;
    const auto it = std::find(first + 1, c.items.end(), h);
    if (it == c.items.end()) return;
    c.items.erase(it);
    --size_;
  }

  /// Call `f(PointHandle)` for each handle of the cell, oldest first. O(k).
  template <class F>
  void for_each(CellIndex cell, F&& f) const {
    const Cell& c = cells_[cell];
    for (std::size_t i = c.head, n = c.items.size(); i < n; ++i) f(c.items[i]);
  }

  /// Handles currently stored. O(1).
  std::size_t size() const { return size_; }

  /// Handles stored in one cell. O(1).
  std::size_t cell_size(CellIndex cell) const { return cells_[cell].items.size() - cells_[cell].head; }

  const Params& params() const { return params_; }

  /// Heap bytes held [bytes]: the cell table plus every bucket's capacity
  /// (dead head slots and slack included). O(cells).
  std::size_t heap_bytes() const {
    std::size_t bytes = cells_.capacity() * sizeof(Cell);
    for (const Cell& c : cells_) bytes += c.items.capacity() * sizeof(PointHandle);
    return bytes;
  }

 private:
  struct Cell {
    std::vector<PointHandle> items;
    std::uint32_t head = 0;  ///< index of the oldest live handle in `items`
  };

  Params params_;
  std::vector<Cell> cells_;
  std::size_t size_ = 0;
};

}  // namespace streamclust

static_assert(streamclust::is_spatial_index_policy_v<streamclust::BucketGrid>,
              "STREAMCLUST_SPATIAL_INDEX_POLICY_INVALID: BucketGrid");
