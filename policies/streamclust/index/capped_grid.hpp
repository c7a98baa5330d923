// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// CappedGrid: at most K handles per cell in one contiguous array.

#include <streamclust/concepts/spatial_index.hpp>
#include <streamclust/detail/hints.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {

/// Spatial index keeping at most K = `Params::capacity` handles per cell, all
/// cells in ONE contiguous `std::vector<PointHandle>` of cells x K entries;
/// each cell holds its handles oldest first in its first `count` slots, with
/// an 8-bit count apart.
///
/// Displacement rule: inserting into a full cell makes the newest point replace
/// the OLDEST handle of that cell, and `insert` returns the displaced handle.
/// The displaced point stays in the window and keeps the edges it already
/// has; later points can no longer find it through this cell (the engine
/// handles this; see the SpatialIndex concept). This bounds the per-point
/// neighbour search to K x mask cells, whatever the scan pattern's revisits.
///
/// `insert` is O(1) into a cell with room and O(K) into a full one (the
/// others move up one slot); `remove` is O(K) (it finds the handle, usually
/// the first, and closes the gap); removing an absent (e.g. displaced)
/// handle is a no-op. `for_each` visits oldest first. With the default K = 4
/// a cell is 16 bytes: the moves stay inside one cache line.
///
/// Memory: cells x (4 K + 1) bytes, allocated by `reset` only; no allocation
/// afterwards. (A ring per cell with a head byte made every move O(1) for one
/// more byte per cell: 1.4 to 2.4 bytes per windowed point on the simulated
/// Livox streams; docs/design-decisions.md.) Thread safety: not
/// thread-safe (one writer, no concurrent readers).
///
/// Usage:
/// \code
///   streamclust::CappedGrid grid{{4}};
///   grid.reset(streamclust::GridShape{64, 1024, true});
///   for (streamclust::PointHandle h = 0; h < 5; ++h) grid.insert(0, h);  // the 5th returns 0
/// \endcode
class CappedGrid {
 public:
  struct Params {
    std::uint32_t capacity = 4;  ///< [handles per cell] K, in [1, 255]
  };

  /// Throws std::invalid_argument if capacity is outside [1, 255].
  explicit CappedGrid(const Params& params) : params_(params) {
    if (params.capacity < 1 || params.capacity > 255)
      throw std::invalid_argument("CappedGrid: parameter capacity = " + std::to_string(params.capacity) +
                                  " is invalid; allowed: [1, 255] handles per cell");
    k_ = static_cast<std::uint8_t>(params.capacity);
  }

  /// Allocate `shape.cell_count()` empty cells. O(cells x K).
  void reset(const GridShape& shape) {
    const std::size_t cells = shape.cell_count();
    slots_.assign(cells * k_, kNoPoint);
    counts_.assign(cells, 0);
    size_ = 0;
  }

  /// Empty every cell, keeping the allocation. O(cells).
  void clear() {
    std::fill(counts_.begin(), counts_.end(), std::uint8_t{0});
    size_ = 0;
  }

  /// Store `h`; if the cell is full, `h` replaces the oldest handle, which is
  /// returned; otherwise returns kNoPoint. O(1) with room, O(K) when full.
  PointHandle insert(CellIndex cell, PointHandle h) {
    PointHandle* const slots = slots_.data() + std::size_t{cell} * k_;
    std::uint8_t& count = counts_[cell];
    if (count < k_) {
      slots[count] = h;
      ++count;
      ++size_;
      return kNoPoint;
    }
    const PointHandle displaced = slots[0];
    std::copy(slots + 1, slots + k_, slots);  // the others move up: oldest first stays true
    slots[k_ - 1] = h;
    return displaced;
  }

  /// Forget `h` if stored in `cell`; no-op when absent. O(K).
  void remove(CellIndex cell, PointHandle h) {
    PointHandle* const slots = slots_.data() + std::size_t{cell} * k_;
    std::uint8_t& count = counts_[cell];
    for (unsigned i = 0; i < count; ++i) {
      if (slots[i] != h) continue;
      std::copy(slots + i + 1, slots + count, slots + i);
      --count;
      --size_;
      return;
    }
  }

  /// Call `f(PointHandle)` for each handle of the cell, oldest first. O(K).
  template <class F>
  void for_each(CellIndex cell, F&& f) const {
    const PointHandle* const slots = slots_.data() + std::size_t{cell} * k_;
    const unsigned count = counts_[cell];
    for (unsigned i = 0; i < count; ++i) f(slots[i]);
  }

  /// Optional SpatialIndex capability: the cell's handle count n and, when
  /// n <= room, its handles, oldest first, in out[0, n). With room >= K (as
  /// the engine gives) all K slots are copied whatever the count (those past
  /// n are stale), so gathering a mask takes no branch on the cells'
  /// occupancy, which varies from cell to cell and would mispredict. Writes
  /// nothing past out + room. O(K).
  std::size_t gather(CellIndex cell, PointHandle* out, std::size_t room) const {
    const PointHandle* const slots = slots_.data() + std::size_t{cell} * k_;
    const unsigned count = counts_[cell];
    if (room >= k_) {
      for (unsigned i = 0; i < k_; ++i) out[i] = slots[i];
    } else {
      std::copy_n(slots, std::min<std::size_t>(count, room), out);
    }
    return count;
  }

  /// Optional SpatialIndex capability: hint that `for_each(cell, ...)`,
  /// `insert` or `remove` on the cell follows soon (prefetches the cell's
  /// slots and its count). O(1).
  void prefetch(CellIndex cell) const {
    detail::prefetch(slots_.data() + std::size_t{cell} * k_);
    detail::prefetch(counts_.data() + cell);
  }

  /// Handles currently stored. O(1).
  std::size_t size() const { return size_; }

  /// Optional SpatialIndex capability: the most handles a cell holds, K. O(1).
  std::size_t max_cell_size() const { return k_; }

  /// Handles stored in one cell (<= capacity). O(1).
  std::size_t cell_size(CellIndex cell) const { return counts_[cell]; }

  const Params& params() const { return params_; }

  /// Heap bytes held [bytes]: cells x (4 K + 1) after `reset`. O(1).
  std::size_t heap_bytes() const { return slots_.capacity() * sizeof(PointHandle) + counts_.capacity(); }

 private:
  Params params_;
  std::uint8_t k_ = 1;
  std::vector<PointHandle> slots_;
  std::vector<std::uint8_t> counts_;  ///< handles stored per cell
  std::size_t size_ = 0;
};

}  // namespace streamclust

static_assert(streamclust::is_spatial_index_policy_v<streamclust::CappedGrid>,
              "STREAMCLUST_SPATIAL_INDEX_POLICY_INVALID: CappedGrid");
