// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// NeighbourSearch: the older neighbours of a new point, from the w x w mask
/// of grid cells around it and the linkage predicate (paper, Algorithm 1,
/// the mask search), with an optional filter of redundant edges.

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/concepts/spatial_index.hpp>
#include <streamclust/detail/hints.hpp>
#include <streamclust/detail/mask.hpp>
#include <streamclust/engine/cell_chains.hpp>
#include <streamclust/engine/retrieval_stats.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace streamclust {

/// Finds the neighbours of a new point among the points an index holds in
/// the mask around its cell, in three passes so that cache misses overlap
/// instead of stalling one by one: (1) `list_mask` lists the mask's cells and
/// prefetches them (called early, before the eviction, by the engine);
/// (2) `find` gathers their handles, prefetching each candidate's payload
/// (or Sample without one: scattered in the ring, each a likely miss);
/// (3) it tests the linkage with a branch-free compaction (whether a
/// candidate links is close to a coin flip). A payload linkage reads the
/// dense payload ring, the others the Samples; a linkage with `link_many`
/// gets one call per point with all its candidates.
///
/// The redundant-edge filter (`witnesses` > 0, for a connectivity strategy
/// that only needs the window's components): an edge (h, n), n older than
/// h, is dropped when a younger neighbour y of h (a witness: the youngest
/// neighbours, youngest first) has an edge (y, n) itself. While (h, n)
/// lives so do (y, n) (same expiry, n) and (h, y) (expiry y, later): h and
/// n stay connected through points no older than n at every moment. By
/// induction that holds when (y, n) or (h, y) were dropped themselves (a
/// dropped edge's endpoints are always joined by kept edges between points
/// no older than its expiry), so the window's components never change. The
/// edge (y, n) exists iff n's cell was in y's mask (detail::MaskMembership),
/// n was in the index when y was linked (an index holds a point from its
/// insertion until it is removed for good, and n is in it now) and the
/// linkage accepts them. Each witness costs one linkage test per kept
/// neighbour older than itself (one `link_many` call).
///
/// Crowded cells (`chains` on, an index with unbounded cells, `gather` and
/// the chain capability, e.g. BucketGrid): in a cell holding
/// CellChains::kCrowdedCell points or more, the new point first tests the
/// cell's youngest point; when they link, only the youngest and the points
/// older than the cell's chain start are candidates (engine/cell_chains.hpp
/// says why the rest add nothing to the components). The point-level graph
/// then holds the window's connectivity, not every linked pair.
///
/// Cost: O(w^2 + candidates) per point, plus O(found x witnesses). The
/// scratch buffers keep their size: sized once per grid for an index with
/// bounded cells (w^2 x max_cell_size()), else grown when a crowded mask
/// needs more; no allocation in steady state.
/// Thread safety: none (one engine, one thread).
template <class Index, class Linkage, class Ring>
class NeighbourSearch {
 public:
  static constexpr bool uses_payload = Ring::uses_payload;
  static constexpr bool tests_many = has_linkage_link_many_v<Linkage>;
  using payload_type = typename Ring::payload_type;
  /// True when the index lets crowded cells be read by their chains.
  static constexpr bool can_chain = has_spatial_index_chain_v<Index> && has_spatial_index_gather_v<Index> &&
                                    !has_spatial_index_cell_bound_v<Index>;

  /// `half`: the mask's half width [cells]; `witnesses`: the filter's
  /// witnesses per point (0: keep every edge); `chains`: read crowded cells
  /// by their chains (when the index can).
  NeighbourSearch(int half, std::uint32_t witnesses, bool chains = true)
      : half_(half), witnesses_(witnesses), chains_on_(can_chain && chains) {}

  /// The grid is chosen: for an index with bounded cells the scratch gets its
  /// final size now, so no denser mask later makes it grow in steady state.
  void set_grid(const GridShape& grid, const Index& index) {
    grid_ = grid;
    if (chains_on_) chains_.reset(grid.cell_count());
    if constexpr (has_spatial_index_cell_bound_v<Index>) {
      const auto width = static_cast<std::size_t>(2 * half_ + 1);
      const std::size_t most = width * width * index.max_cell_size();
      candidates_.reserve(most);
      neighbours_.reserve(most);
      slots_.reserve(most);
      flags_.reserve(most);
      if (witnesses_ != 0) cells_.reserve(most);
    }
  }

  /// Prefetches the index cells of the mask around `cell` (a point taken
  /// ahead of its turn). O(w^2).
  void prefetch_mask(const Index& index, CellIndex cell) const {
    if constexpr (has_spatial_index_prefetch_v<Index>) {
      detail::for_each_mask_cell(grid_, cell, half_, [&](CellIndex c) { index.prefetch(c); });
    } else {
      (void)index;
      (void)cell;
    }
  }

  /// Pass (1): lists the mask cells around `cell` for the next `find` and,
  /// when the index offers it, prefetches them. O(w^2).
  void list_mask(const Index& index, CellIndex cell) {
    const auto width = static_cast<std::size_t>(2 * half_ + 1);
    if (mask_cells_.size() < width * width) mask_cells_.resize(width * width);  // once: at most w^2 cells
    const bool with_at = witnesses_ != 0;  // only the filter reads the cells' rows and columns
    if (with_at && mask_at_.size() < width * width) mask_at_.resize(width * width);
    CellIndex* const out = mask_cells_.data();
    CellAt* const at = mask_at_.data();
    std::size_t n = 0;
    detail::for_each_mask_cell_at(grid_, cell, half_, [&](CellIndex c, std::int64_t row, std::int64_t col) {
      if (with_at) at[n] = CellAt{static_cast<std::int32_t>(row), static_cast<std::int32_t>(col)};
      out[n++] = c;
      if constexpr (has_spatial_index_prefetch_v<Index>) index.prefetch(c);
    });
    mask_count_ = n;
    own_cell_ = cell;
  }

  /// Passes (2) and (3): the neighbours of point `h` (in `ring`, not in the
  /// index yet) among the listed mask's points, after the filter when it is
  /// on; `neighbours()[0, count)`. Counts `stats.edges_found` (before the
  /// filter) and `stats.edges_pruned`. O(candidates + found x witnesses).
  std::size_t find(const Ring& ring, const Index& index, const Linkage& linkage, PointHandle h,
                   RetrievalStats& stats) {
    const bool pruning = witnesses_ != 0;
    const bool with_slots = tests_many || pruning;
    const std::size_t count = gather(ring, index, linkage, h, pruning, with_slots, stats);
    // Same capacity as candidates_: they grow only when it does.
    if (neighbours_.capacity() < candidates_.capacity()) neighbours_.reserve(candidates_.capacity());
    neighbours_.resize(count);
    PointHandle* const out = neighbours_.data();
    const PointHandle* const cand = candidates_.data();
    std::size_t found = 0;
    if (with_slots) {
      if (flags_.capacity() < candidates_.capacity()) flags_.reserve(candidates_.capacity());
      flags_.resize(count);
      test_links(ring, linkage, ring.slot(h), slots_.data(), count, flags_.data());
      const std::uint8_t* const flags = flags_.data();
      if (pruning) {
        std::uint32_t* const slots = slots_.data();
        std::uint16_t* const cells = cells_.data();
        for (std::size_t k = 0; k < count; ++k) {
          out[found] = cand[k];
          slots[found] = slots[k];
          cells[found] = cells[k];
          found += flags[k];
        }
        stats.edges_found += found;
        found = prune(ring, linkage, h, found, stats);
      } else {
        for (std::size_t k = 0; k < count; ++k) {
          out[found] = cand[k];
          found += flags[k];
        }
        stats.edges_found += found;
      }
    } else {
      const PointHandle origin = ring.origin();
      const std::uint32_t capacity = ring.capacity();
      if constexpr (uses_payload) {
        const payload_type s = ring.payloads()[Ring::slot(h, origin, capacity)];  // a copy: the stores below cannot alias it
        const payload_type* const payloads = ring.payloads();
        for (std::size_t k = 0; k < count; ++k) {
          out[found] = cand[k];
          found += linkage(s, payloads[Ring::slot(cand[k], origin, capacity)]) ? 1u : 0u;
        }
      } else {
        const Sample& s = ring.samples()[Ring::slot(h, origin, capacity)];
        const Sample* const samples = ring.samples();  // hoisted: the stores below cannot alias them
        for (std::size_t k = 0; k < count; ++k) {
          out[found] = cand[k];
          found += linkage(s, samples[Ring::slot(cand[k], origin, capacity)]) ? 1u : 0u;
        }
      }
      stats.edges_found += found;
    }
    neighbours_.resize(found);
    return found;
  }

  /// The neighbours of the last `find`, in mask order.
  const PointHandle* neighbours() const { return neighbours_.data(); }

  std::size_t heap_bytes() const {
    return mask_cells_.capacity() * sizeof(CellIndex) + mask_at_.capacity() * sizeof(CellAt) +
           (candidates_.capacity() + neighbours_.capacity()) * sizeof(PointHandle) +
           slots_.capacity() * sizeof(std::uint32_t) + flags_.capacity() + cells_.capacity() * sizeof(std::uint16_t) +
           chains_.heap_bytes();
  }

 private:
  /// Grid row and column of a mask cell (the filter's membership test).
  struct CellAt {
    std::int32_t row;
    std::int32_t col;
  };
  /// Gather room per mask cell for an index with unbounded cells [handles]
  /// (grown when a crowded mask needs more).
  static constexpr std::size_t kGatherCellRoom = 8;

  /// flags[k] = whether the point in ring slot `subject` links to the one in
  /// slot `slots[k]`, k < count: one `link_many` call when the linkage has
  /// it (vectorised), else the pairwise operator. O(count).
  static void test_links(const Ring& ring, const Linkage& linkage, std::uint32_t subject, const std::uint32_t* slots,
                         std::size_t count, std::uint8_t* flags) {
    if constexpr (tests_many) {
      linkage.link_many(ring.payloads()[subject], ring.payloads(), slots, count, flags);
    } else if constexpr (uses_payload) {
      const payload_type s = ring.payloads()[subject];  // a copy: the stores below cannot alias it
      const payload_type* const payloads = ring.payloads();
      for (std::size_t k = 0; k < count; ++k) flags[k] = linkage(s, payloads[slots[k]]) ? 1u : 0u;
    } else {
      const Sample& s = ring.samples()[subject];
      const Sample* const samples = ring.samples();
      for (std::size_t k = 0; k < count; ++k) flags[k] = linkage(s, samples[slots[k]]) ? 1u : 0u;
    }
  }

  /// Pass (2): the handles of the listed mask cells into candidates_[0,
  /// count), with their ring slots (`with_slots`) and mask cells (`pruning`),
  /// each candidate's payload or sample prefetched. Returns count. An index
  /// with `gather` is read cell by cell without a branch on the occupancy:
  /// the buffers stay sized to a room (w^2 K for bounded cells, at least
  /// w^2 kGatherCellRoom otherwise, grown when a crowded cell does not fit)
  /// and the stale handles past each cell's count are overwritten by the
  /// next cell's. With chains, a cell is read with room for fewer than
  /// kCrowdedCell handles first; a crowded one goes to `gather_crowded`.
  /// O(w^2 k), O(w^2 kCrowdedCell) where every crowded cell's chain is linked.
  std::size_t gather(const Ring& ring, const Index& index, const Linkage& linkage, PointHandle h, bool pruning,
                     bool with_slots, RetrievalStats& stats) {
    const auto prefetch_candidate = [&](std::uint32_t slot) {
      if constexpr (uses_payload) {
        detail::prefetch(&ring.payloads()[slot]);
      } else {
        detail::prefetch(&ring.samples()[slot]);
      }
    };
    if constexpr (has_spatial_index_gather_v<Index>) {
      constexpr bool bounded = has_spatial_index_cell_bound_v<Index>;
      std::size_t per_cell = kGatherCellRoom;
      if constexpr (bounded) per_cell = index.max_cell_size();
      const auto grow = [&](std::size_t room) {  // once per grid, or when a crowded cell needs more
        candidates_.resize(room);
        if (with_slots) slots_.resize(room);
        if (pruning) cells_.resize(room);
      };
      if (candidates_.size() < mask_count_ * per_cell) grow(mask_count_ * per_cell);  // reserved in set_grid when bounded
      if (with_slots && slots_.size() < candidates_.size()) slots_.resize(candidates_.size());
      if (pruning && cells_.size() < candidates_.size()) cells_.resize(candidates_.size());
      std::size_t count = 0;
      bool keep_own_chain = false;  // the new point extends its own cell's chain
      // With chains a cell is read with room for fewer than kCrowdedCell
      // handles: a crowded cell's are never copied whole.
      const std::size_t room_cap = chains_on_ ? CellChains::kCrowdedCell - 1 : candidates_.max_size();
      for (std::size_t i = 0; i < mask_count_; ++i) {
        std::size_t n = 0;
        if constexpr (bounded) {  // n <= K, and K of room are left: count <= i K
          n = index.gather(mask_cells_[i], candidates_.data() + count, per_cell);
        } else {
          const std::size_t room = candidates_.size() - count;
          const std::size_t read_room = std::min(room, room_cap);
          n = index.gather(mask_cells_[i], candidates_.data() + count, read_room);
          if (n > read_room) {  // rare: a crowded cell, or the room ran out
            bool crowded = false;
            if constexpr (can_chain) {
              crowded = chains_on_ && n >= CellChains::kCrowdedCell;
              if (crowded) n = gather_crowded(ring, index, linkage, h, mask_cells_[i], count, n, grow, keep_own_chain, stats);
            }
            if (!crowded) {  // grow and gather it again
              if (n > room) grow(std::max(2 * candidates_.size(), count + n + mask_count_ * per_cell));
              n = index.gather(mask_cells_[i], candidates_.data() + count, candidates_.size() - count);
            }
          }
        }
        if (pruning) std::fill_n(cells_.data() + count, n, static_cast<std::uint16_t>(i));
        count += n;
      }
      if (chains_on_ && !keep_own_chain) chains_.restart(own_cell_, h);
      const PointHandle* const cand = candidates_.data();
      std::uint32_t* const slots = slots_.data();
      const PointHandle origin = ring.origin();
      const std::uint32_t capacity = ring.capacity();
      for (std::size_t k = 0; k < count; ++k) {
        const std::uint32_t slot = Ring::slot(cand[k], origin, capacity);
        if (with_slots) slots[k] = slot;
        prefetch_candidate(slot);
      }
      return count;
    } else {
      candidates_.clear();
      slots_.clear();
      cells_.clear();
      for (std::size_t i = 0; i < mask_count_; ++i) {
        index.for_each(mask_cells_[i], [&](PointHandle n) {
          const std::uint32_t slot = ring.slot(n);
          candidates_.push_back(n);
          if (with_slots) slots_.push_back(slot);
          if (pruning) cells_.push_back(static_cast<std::uint16_t>(i));
          prefetch_candidate(slot);
        });
      }
      return candidates_.size();
    }
  }

  /// A crowded cell (`n` points, at candidates_[count...]): when `h` links the
  /// cell's youngest point, the youngest and the points older than the
  /// cell's chain start, else every point (`grow(room)` makes room). Keeps
  /// the chain of `h`'s own cell when they link (`keep_own_chain`). Returns
  /// the candidates written; counts the rest in `stats.candidates_skipped`.
  /// O(1 + points older than the chain start), O(n) when they do not link.
  template <class Grow>
  STREAMCLUST_NOINLINE std::size_t gather_crowded(const Ring& ring, const Index& index, const Linkage& linkage, PointHandle h,
                             CellIndex cell, std::size_t count, std::size_t n, const Grow& grow,
                             bool& keep_own_chain, RetrievalStats& stats) {
    const auto fit = [&](std::size_t wanted) {
      if (count + wanted > candidates_.size()) grow(std::max(2 * candidates_.size(), count + wanted + mask_count_));
    };
    const PointHandle youngest = index.youngest(cell);
    const std::uint32_t youngest_slot = ring.slot(youngest);
    std::uint8_t linked = 0;
    test_links(ring, linkage, ring.slot(h), &youngest_slot, 1, &linked);
    if (linked == 0) {  // the chain ends here: every point is a candidate
      fit(n);
      return index.gather(cell, candidates_.data() + count, candidates_.size() - count);
    }
    keep_own_chain = keep_own_chain || cell == own_cell_;
    const PointHandle start = chains_.start(cell, ring.oldest(), h);
    std::size_t older = index.gather_older(cell, start, candidates_.data() + count, candidates_.size() - count);
    if (count + older + 1 > candidates_.size()) {
      fit(older + 1);
      older = index.gather_older(cell, start, candidates_.data() + count, candidates_.size() - count);
    }
    candidates_[count + older] = youngest;
    stats.candidates_skipped += n - (older + 1);
    return older + 1;
  }

  /// The redundant-edge filter (see the class comment) over the first
  /// `found` neighbours of `h`, whose slots and mask cells are beside them;
  /// returns how many are kept (compacted to the front).
  /// O(found x witnesses).
  std::size_t prune(const Ring& ring, const Linkage& linkage, PointHandle h, std::size_t found,
                    RetrievalStats& stats) {
    PointHandle* const nb = neighbours_.data();
    std::uint32_t* const slots = slots_.data();
    std::uint16_t* const cells = cells_.data();
    std::uint8_t* const linked = flags_.data();  // free again: reused for the witness's decisions
    const CellAt* const at = mask_at_.data();
    const detail::MaskMembership in_mask(grid_, half_);
    std::uint32_t witness_age = 0;  // the previous witness's age: the next one is older
    for (std::uint32_t w = 0; w < witnesses_ && found >= 2; ++w) {
      // The youngest kept neighbour older than the previous witness.
      std::uint32_t age = std::numeric_limits<std::uint32_t>::max();
      std::size_t y = found;
      for (std::size_t k = 0; k < found; ++k) {
        const auto a = static_cast<std::uint32_t>(h - nb[k]);
        const bool better = a > witness_age && a < age;
        y = better ? k : y;
        age = better ? a : age;
      }
      if (y == found) break;
      const CellAt wy = at[cells[y]];
      test_links(ring, linkage, slots[y], slots, found, linked);
      std::size_t kept = 0;
      for (std::size_t k = 0; k < found; ++k) {
        const CellAt c = at[cells[k]];
        const bool older = static_cast<std::uint32_t>(h - nb[k]) > age;
        const bool redundant = older & in_mask(wy.row, wy.col, c.row, c.col) & (linked[k] != 0);
        nb[kept] = nb[k];
        slots[kept] = slots[k];
        cells[kept] = cells[k];
        kept += redundant ? 0u : 1u;
      }
      stats.edges_pruned += found - kept;
      found = kept;
      witness_age = age;
    }
    return found;
  }

  int half_;
  std::uint32_t witnesses_;
  bool chains_on_;
  GridShape grid_{};
  CellIndex own_cell_ = 0;                  ///< the cell of the point being linked (the mask's centre)
  CellChains chains_;                       ///< crowded cells: each cell's chain start
  std::vector<CellIndex> mask_cells_;       ///< the listed mask: [0, mask_count_)
  std::vector<CellAt> mask_at_;             ///< filter: row and column of each listed cell
  std::size_t mask_count_ = 0;
  std::vector<PointHandle> candidates_;
  std::vector<std::uint32_t> slots_;        ///< ring slot of each candidate (link_many, filter)
  std::vector<std::uint16_t> cells_;        ///< filter: place in the mask of each candidate's cell
  std::vector<std::uint8_t> flags_;         ///< whether each candidate links (then: to the witness)
  std::vector<PointHandle> neighbours_;
};

}  // namespace streamclust
