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
/// each cell is a ring of K slots with an 8-bit head and count.
///
/// Displacement rule: inserting into a full cell makes the newest point replace
/// the OLDEST handle of that cell, and `insert` returns the displaced handle.
/// The displaced point stays in the window and keeps the edges it already
/// has; later points can no longer find it through this cell (the engine
/// handles this; see the SpatialIndex concept). This bounds the per-point
/// neighbour search to K x mask cells, whatever the scan pattern's revisits.
///
/// `remove` pops the head in O(1) when the handle is the oldest (the engine's
/// insertion-order removal), otherwise searches the K slots and closes the gap
/// (O(K)); removing an absent (e.g. displaced) handle is a no-op. `for_each`
/// visits oldest first.
///
/// Memory: cells x (4 K + 2) bytes, allocated by `reset` only; no allocation
/// afterwards. Thread safety: not thread-safe (one writer, no concurrent readers).
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
    state_.assign(cells, CellState{});
    size_ = 0;
  }

  /// Empty every cell, keeping the allocation. O(cells).
  void clear() {
    std::fill(state_.begin(), state_.end(), CellState{});
    size_ = 0;
  }

  /// Store `h`; if the cell is full, `h` replaces the oldest handle, which is
  /// returned; otherwise returns kNoPoint. O(1).
  PointHandle insert(CellIndex cell, PointHandle h) {
    PointHandle* ring = slots_.data() + std::size_t{cell} * k_;
    std::uint8_t& head = state_[cell].head;
    std::uint8_t& count = state_[cell].count;
    if (count < k_) {
      ring[wrap(head + count)] = h;
      ++count;
      ++size_;
      return kNoPoint;
    }
    const PointHandle displaced = ring[head];
    ring[head] = h;  // the slot of the oldest becomes the newest
    head = static_cast<std::uint8_t>(wrap(head + 1u));
    return displaced;
  }

  /// Forget `h` if stored in `cell`: O(1) for the oldest handle, O(K)
  /// otherwise; no-op when absent.
  void remove(CellIndex cell, PointHandle h) {
    PointHandle* ring = slots_.data() + std::size_t{cell} * k_;
    std::uint8_t& head = state_[cell].head;
    std::uint8_t& count = state_[cell].count;
    if (count == 0) return;
    if (ring[head] == h) {
      head = static_cast<std::uint8_t>(wrap(head + 1u));
      --count;
      --size_;
      return;
    }
    for (unsigned i = 1; i < count; ++i) {
      if (ring[wrap(head + i)] != h) continue;
      for (unsigned j = i + 1; j < count; ++j) ring[wrap(head + j - 1)] = ring[wrap(head + j)];
      --count;
      --size_;
      return;
    }
  }

  /// Call `f(PointHandle)` for each handle of the cell, oldest first. O(K).
  template <class F>
  void for_each(CellIndex cell, F&& f) const {
    const PointHandle* ring = slots_.data() + std::size_t{cell} * k_;
    const unsigned head = state_[cell].head;
    const unsigned count = state_[cell].count;
    for (unsigned i = 0; i < count; ++i) f(ring[wrap(head + i)]);
  }

  /// Optional SpatialIndex capability: hint that `for_each(cell, ...)`,
  /// `insert` or `remove` on the cell follows soon (prefetches the cell's
  /// slots and its head/count pair). O(1).
  void prefetch(CellIndex cell) const {
    detail::prefetch(slots_.data() + std::size_t{cell} * k_);
    detail::prefetch(state_.data() + cell);
  }

  /// Handles currently stored. O(1).
  std::size_t size() const { return size_; }

  /// Optional SpatialIndex capability: the most handles a cell holds, K. O(1).
  std::size_t max_cell_size() const { return k_; }

  /// Handles stored in one cell (<= capacity). O(1).
  std::size_t cell_size(CellIndex cell) const { return state_[cell].count; }

  const Params& params() const { return params_; }

  /// Heap bytes held [bytes]: cells x (4 K + 2) after `reset`. O(1).
  std::size_t heap_bytes() const {
    return slots_.capacity() * sizeof(PointHandle) + state_.capacity() * sizeof(CellState);
  }

 private:
  unsigned wrap(unsigned i) const { return i < k_ ? i : i - k_; }

  Params params_;
  std::uint8_t k_ = 1;
  std::vector<PointHandle> slots_;
  /// A cell's ring state, head and count side by side: one cache line
  /// holds both (a lookup misses once, not twice).
  struct CellState {
    std::uint8_t head = 0;   ///< slot of the oldest handle
    std::uint8_t count = 0;  ///< handles stored
  };
  static_assert(sizeof(CellState) == 2, "CellState: two bytes per cell");
  std::vector<CellState> state_;
  std::size_t size_ = 0;
};

}  // namespace streamclust

static_assert(streamclust::is_spatial_index_policy_v<streamclust::CappedGrid>,
              "STREAMCLUST_SPATIAL_INDEX_POLICY_INVALID: CappedGrid");
