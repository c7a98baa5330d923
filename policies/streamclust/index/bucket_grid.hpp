// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// BucketGrid: unbounded per-cell buckets of point handles (C-ARC's range grid).

#include <streamclust/concepts/spatial_index.hpp>
#include <streamclust/detail/hints.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {

/// Spatial index storing every handle of a cell (the bucket-based range grid
/// of C-ARC): nothing is ever displaced, so `insert` always returns kNoPoint.
///
/// Layout (chosen for the engine's neighbour search, docs/design-decisions.md):
/// every cell is one 32-byte, 32-byte-aligned record in ONE row-major array,
/// holding up to `kInlineCapacity` = 6 handles inline, oldest first. A cell
/// holding more keeps its 6 oldest handles inline and the newer ones in a
/// spill bucket (a `std::vector` plus a head offset) taken from a
/// recycled pool. With the C-ARC grid (about 2 points per occupied cell) the
/// search of a cell is ONE cache line, and the cells of a mask row are
/// contiguous; only crowded cells (the Avia rosette's centre) pay a second
/// indirection.
///
/// Removing the oldest handle (the engine removes points oldest first) shifts
/// at most 5 inline handles and, for a spilled cell, moves the spill's oldest
/// handle inline (the spill advances its head; once the head passes half of
/// the spill the live part is moved to the front: amortised O(1)). Removing
/// any other handle searches the cell, O(k); removing an absent handle is a
/// no-op. `for_each` visits a cell in insertion order.
///
/// Memory: 32 bytes per cell, plus per spill bucket in use or pooled
/// 32 bytes and 4 bytes per handle of capacity (at least
/// `kMinSpillCapacity`: a bucket is born with room for a cell of 16 handles,
/// so the few mildly crowded cells of an ordinary scan never grow one; a
/// bucket grown from empty would allocate at 1, 2, 4 and 8 spilled handles,
/// whenever a cell of the window reached a new peak). Spill buckets keep their
/// capacity when released (`remove`, `clear`, `reset`), a full spill
/// with removed handles at its front is compacted instead of grown, and a
/// cell that spills takes the pooled bucket of the largest capacity (the
/// pool is a max-heap by capacity), and a full bucket trades places with a
/// larger pooled one before it grows, so a bucket grows only when no pooled
/// bucket is larger: the pool's capacity rises to the peak of the window's
/// crowded cells and then the window allocates nothing. Heap blocks: `cells_`, `spills_` (each with its
/// `items` vector), `free_spills_`.
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
  /// Handles a cell holds without a spill bucket.
  static constexpr std::uint32_t kInlineCapacity = 6;
  /// [handles] capacity a new spill bucket reserves: with the inline
  /// handles, a cell of 16 (where the engine's crowded-cell chains start).
  static constexpr std::uint32_t kMinSpillCapacity = 10;

  struct Params {
    /// [handles] expected handles of a crowded cell: a spill bucket reserves
    /// room for `reserve_per_cell - kInlineCapacity` handles, and at least
    /// `kMinSpillCapacity`, when it is first created.
    std::uint32_t reserve_per_cell = 0;
  };

  explicit BucketGrid(const Params& params) : params_(params) {}

  /// Allocate `shape.cell_count()` empty cells; spill buckets return to the
  /// pool with their capacity. O(cells + spill buckets).
  void reset(const GridShape& shape) {
    cells_.assign(shape.cell_count(), Cell{});
    release_all_spills();
    size_ = 0;
  }

  /// Empty every cell, keeping the allocations. O(cells + spill buckets).
  void clear() {
    std::fill(cells_.begin(), cells_.end(), Cell{});
    release_all_spills();
    size_ = 0;
  }

  /// Append `h` to the cell; never displaces, returns kNoPoint. O(1)
  /// amortised (a spill bucket may grow).
  PointHandle insert(CellIndex cell, PointHandle h) {
    Cell& c = cells_[cell];
    ++size_;
    if (c.count < kInlineCapacity) {  // then the cell has no spill (invariant)
      c.items[c.count++] = h;
      return kNoPoint;
    }
    if (c.spill == kNoSpill) c.spill = acquire_spill();
    if (spills_[c.spill].items.size() == spills_[c.spill].items.capacity()) make_room(c);
    spills_[c.spill].items.push_back(h);
    return kNoPoint;
  }

  /// Forget `h` if stored in `cell`. O(1) amortised for the oldest handle,
  /// O(k) otherwise; no-op when absent.
  void remove(CellIndex cell, PointHandle h) {
    Cell& c = cells_[cell];
    for (std::uint32_t i = 0; i < c.count; ++i) {
      if (c.items[i] != h) continue;
      for (std::uint32_t j = i + 1; j < c.count; ++j) c.items[j - 1] = c.items[j];
      --c.count;
      --size_;
      if (c.spill != kNoSpill) {  // keep the invariant: the oldest spilled handle moves inline
        Spill& s = spills_[c.spill];
        c.items[c.count++] = s.items[s.head];
        pop_front(c, s);
      }
      return;
    }
    if (c.spill == kNoSpill) return;
    Spill& s = spills_[c.spill];
    if (s.items[s.head] == h) {
      --size_;
      pop_front(c, s);
      return;
    }
    const auto first = s.items.begin() + static_cast<std::ptrdiff_t>(s.head);
    const auto it = std::find(first + 1, s.items.end(), h);
    if (it == s.items.end()) return;
    s.items.erase(it);  // never empties the spill: its head stays
    --size_;
  }

  /// Call `f(PointHandle)` for each handle of the cell, oldest first. O(k).
  template <class F>
  void for_each(CellIndex cell, F&& f) const {
    const Cell& c = cells_[cell];
    for (std::uint32_t i = 0; i < c.count; ++i) f(c.items[i]);
    if (c.spill == kNoSpill) return;
    const Spill& s = spills_[c.spill];
    for (std::size_t i = s.head, n = s.items.size(); i < n; ++i) f(s.items[i]);
  }

  /// Optional SpatialIndex capability: the cell's handle count n and, when
  /// n <= room, its handles, oldest first, in out[0, n). With room >= 6 the
  /// six inline slots are copied whatever the count (one 24-byte move; those
  /// past n are stale), so gathering a mask takes no branch on the cells'
  /// occupancy; a spilled cell's bucket follows. Writes nothing past
  /// out + room. O(k).
  std::size_t gather(CellIndex cell, PointHandle* out, std::size_t room) const {
    const Cell& c = cells_[cell];
    if (room >= kInlineCapacity) {
      for (std::uint32_t i = 0; i < kInlineCapacity; ++i) out[i] = c.items[i];
    } else {
      std::copy_n(c.items, std::min<std::size_t>(c.count, room), out);
    }
    if (c.spill == kNoSpill) return c.count;
    const Spill& s = spills_[c.spill];
    const auto first = s.items.begin() + static_cast<std::ptrdiff_t>(s.head);
    const std::size_t n = c.count + static_cast<std::size_t>(s.items.end() - first);
    if (n <= room) std::copy(first, s.items.end(), out + c.count);
    return n;
  }

  /// Optional SpatialIndex capability: the handle stored last in `cell`
  /// (not empty). O(1).
  PointHandle youngest(CellIndex cell) const {
    const Cell& c = cells_[cell];
    if (c.spill == kNoSpill) return c.items[c.count - 1];
    return spills_[c.spill].items.back();
  }

  /// Optional SpatialIndex capability: the count n of the cell's handles
  /// stored before handle `bound` (`std::int32_t(h - bound) < 0`) and, as far
  /// as `room` allows, those handles, oldest first, in out[0, min(n, room)).
  /// The cell is oldest first, so they are its prefix. O(n + 1).
  std::size_t gather_older(CellIndex cell, PointHandle bound, PointHandle* out, std::size_t room) const {
    const auto older = [bound](PointHandle h) { return static_cast<std::int32_t>(h - bound) < 0; };
    const Cell& c = cells_[cell];
    std::size_t n = 0;
    for (std::uint32_t i = 0; i < c.count && older(c.items[i]); ++i, ++n) {
      if (n < room) out[n] = c.items[i];
    }
    if (n < c.count || c.spill == kNoSpill) return n;
    const Spill& s = spills_[c.spill];
    for (std::size_t i = s.head, end = s.items.size(); i < end && older(s.items[i]); ++i, ++n) {
      if (n < room) out[n] = s.items[i];
    }
    return n;
  }

  /// Optional SpatialIndex capability: hint that `for_each(cell, ...)` follows
  /// soon (prefetches the cell's record; no effect on the contents). O(1).
  void prefetch(CellIndex cell) const { detail::prefetch(cells_.data() + cell); }

  /// Handles currently stored. O(1).
  std::size_t size() const { return size_; }

  /// Handles stored in one cell. O(1).
  std::size_t cell_size(CellIndex cell) const {
    const Cell& c = cells_[cell];
    if (c.spill == kNoSpill) return c.count;
    const Spill& s = spills_[c.spill];
    return c.count + (s.items.size() - s.head);
  }

  /// Spill buckets in use (cells holding more than kInlineCapacity handles). O(1).
  std::size_t spilled_cells() const { return spills_.size() - free_spills_.size(); }

  const Params& params() const { return params_; }

  /// Heap bytes held [bytes]: the cell table, the spill pool and every spill
  /// bucket's capacity (dead head slots and slack included). O(spill buckets).
  std::size_t heap_bytes() const {
    std::size_t bytes = cells_.capacity() * sizeof(Cell) + spills_.capacity() * sizeof(Spill) +
                        free_spills_.capacity() * sizeof(std::uint32_t);
    for (const Spill& s : spills_) bytes += s.items.capacity() * sizeof(PointHandle);
    return bytes;
  }

 private:
  static constexpr std::uint32_t kNoSpill = 0xFFFFFFFFu;

  /// One cache-line half: count, the oldest handles, the spill bucket.
  /// Invariant: `spill != kNoSpill` implies `count == kInlineCapacity`.
  struct alignas(32) Cell {
    std::uint32_t count = 0;
    PointHandle items[kInlineCapacity] = {};
    std::uint32_t spill = kNoSpill;
  };
  static_assert(sizeof(Cell) == 32, "BucketGrid::Cell must stay 32 bytes");

  struct Spill {
    std::vector<PointHandle> items;
    std::uint32_t head = 0;  ///< index of the oldest live handle in `items`
  };

  /// Max-heap order of the pool: by capacity.
  bool smaller_spill(std::uint32_t a, std::uint32_t b) const {
    return spills_[a].items.capacity() < spills_[b].items.capacity();
  }

  /// A pooled spill bucket, the largest, or a new one. O(log pooled) or
  /// O(1) amortised.
  STREAMCLUST_NOINLINE std::uint32_t acquire_spill() {
    const auto smaller = [this](std::uint32_t a, std::uint32_t b) { return smaller_spill(a, b); };
    if (!free_spills_.empty()) {
      std::pop_heap(free_spills_.begin(), free_spills_.end(), smaller);
      const std::uint32_t s = free_spills_.back();
      free_spills_.pop_back();
      return s;
    }
    spills_.emplace_back();
    // The pool never holds more than every bucket: sized with them, so a
    // release never allocates.
    if (free_spills_.capacity() < spills_.capacity()) free_spills_.reserve(spills_.capacity());
    const std::uint32_t wanted = params_.reserve_per_cell > kInlineCapacity ? params_.reserve_per_cell - kInlineCapacity : 0;
    spills_.back().items.reserve(std::max(wanted, kMinSpillCapacity));
    return static_cast<std::uint32_t>(spills_.size() - 1);
  }

  /// Room for one more handle in `c`'s full spill bucket, without an
  /// allocation where one can be avoided: compact the removed front, or
  /// move the handles into the largest pooled bucket when it is larger
  /// (the full one goes to the pool); only else does the bucket grow.
  /// O(k + log pooled).
  STREAMCLUST_NOINLINE void make_room(Cell& c) {
    Spill& s = spills_[c.spill];
    if (s.head > 0) {  // compact the removed front instead of growing
      s.items.erase(s.items.begin(), s.items.begin() + s.head);
      s.head = 0;
      return;
    }
    if (free_spills_.empty() || spills_[free_spills_.front()].items.capacity() <= s.items.size()) return;
    const std::uint32_t full = c.spill;
    c.spill = acquire_spill();  // the largest pooled bucket (the heap's front)
    Spill& larger = spills_[c.spill];
    larger.items.assign(spills_[full].items.begin(), spills_[full].items.end());
    larger.head = 0;
    release_spill(full);
  }

  /// Empties spill bucket `spill` and returns it to the pool. O(log pooled).
  STREAMCLUST_NOINLINE void release_spill(std::uint32_t spill) {
    spills_[spill].items.clear();
    spills_[spill].head = 0;
    free_spills_.push_back(spill);  // never allocates: reserved with spills_
    std::push_heap(free_spills_.begin(), free_spills_.end(),
                   [this](std::uint32_t a, std::uint32_t b) { return smaller_spill(a, b); });
  }

  /// Drops the spill's oldest handle; releases the spill when it empties.
  void pop_front(Cell& c, Spill& s) {
    ++s.head;
    const std::size_t n = s.items.size();
    if (s.head == n) {
      release_spill(c.spill);
      c.spill = kNoSpill;
    } else if (std::size_t{s.head} * 2 > n) {
      s.items.erase(s.items.begin(), s.items.begin() + static_cast<std::ptrdiff_t>(s.head));
      s.head = 0;
    }
  }

  void release_all_spills() {
    free_spills_.clear();
    for (std::size_t i = spills_.size(); i-- > 0;) {
      spills_[i].items.clear();
      spills_[i].head = 0;
      free_spills_.push_back(static_cast<std::uint32_t>(i));
    }
    std::make_heap(free_spills_.begin(), free_spills_.end(),
                   [this](std::uint32_t a, std::uint32_t b) { return smaller_spill(a, b); });
  }

  Params params_;
  std::vector<Cell> cells_;
  std::vector<Spill> spills_;
  std::vector<std::uint32_t> free_spills_;
  std::size_t size_ = 0;
};

}  // namespace streamclust

static_assert(streamclust::is_spatial_index_policy_v<streamclust::BucketGrid>,
              "STREAMCLUST_SPATIAL_INDEX_POLICY_INVALID: BucketGrid");
