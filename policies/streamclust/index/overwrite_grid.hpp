// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// OverwriteGrid: one handle per cell, the newest wins (a range image).

#include <streamclust/concepts/spatial_index.hpp>
#include <streamclust/detail/hints.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace streamclust {

/// Spatial index with exactly one slot per cell: a new point overwrites the
/// occupant, which `insert` returns (the displaced point stays in the window
/// with its edges). This is the range image of frame-based baselines
/// (depth_clustering keeps one range per pixel) and the cheapest index:
/// 4 bytes per cell, O(1) for every operation.
///
/// `remove(cell, h)` clears the cell only if `h` is its occupant; otherwise
/// (the point was overwritten earlier) it is a no-op.
///
/// Memory allocated by `reset` only. Thread safety: not thread-safe (one
/// writer, no concurrent readers).
///
/// Usage:
/// \code
///   streamclust::OverwriteGrid grid{{}};
///   grid.reset(streamclust::GridShape{64, 1024, true});
///   grid.insert(3, 10);             // kNoPoint
///   grid.insert(3, 11);             // returns 10
/// \endcode
class OverwriteGrid {
 public:
  struct Params {};

  explicit OverwriteGrid(const Params&) {}

  /// Allocate `shape.cell_count()` empty cells. O(cells).
  void reset(const GridShape& shape) {
    occupant_.assign(shape.cell_count(), kNoPoint);
    size_ = 0;
  }

  /// Empty every cell, keeping the allocation. O(cells).
  void clear() {
    std::fill(occupant_.begin(), occupant_.end(), kNoPoint);
    size_ = 0;
  }

  /// Make `h` the occupant; returns the previous occupant or kNoPoint. O(1).
  PointHandle insert(CellIndex cell, PointHandle h) {
    const PointHandle previous = occupant_[cell];
    occupant_[cell] = h;
    if (previous == kNoPoint) ++size_;
    return previous;
  }

  /// Clear the cell if `h` is its occupant. O(1).
  void remove(CellIndex cell, PointHandle h) {
    if (h == kNoPoint || occupant_[cell] != h) return;
    occupant_[cell] = kNoPoint;
    --size_;
  }

  /// Call `f(occupant)` if the cell is occupied. O(1).
  template <class F>
  void for_each(CellIndex cell, F&& f) const {
    const PointHandle h = occupant_[cell];
    if (h != kNoPoint) f(h);
  }

  /// Optional SpatialIndex capability: hint that `for_each(cell, ...)` follows
  /// soon (prefetches the cell). O(1).
  void prefetch(CellIndex cell) const { detail::prefetch(occupant_.data() + cell); }

  /// Occupied cells. O(1).
  std::size_t size() const { return size_; }

  /// Optional SpatialIndex capability: the most handles a cell holds, 1. O(1).
  std::size_t max_cell_size() const { return 1; }

  /// Heap bytes held [bytes]: 4 per cell after `reset`. O(1).
  std::size_t heap_bytes() const { return occupant_.capacity() * sizeof(PointHandle); }

 private:
  std::vector<PointHandle> occupant_;
  std::size_t size_ = 0;
};

}  // namespace streamclust

static_assert(streamclust::is_spatial_index_policy_v<streamclust::OverwriteGrid>,
              "STREAMCLUST_SPATIAL_INDEX_POLICY_INVALID: OverwriteGrid");
