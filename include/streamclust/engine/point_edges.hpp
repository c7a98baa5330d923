// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// PointEdges: the window's point-level adjacency (every edge found, until
/// its newer endpoint leaves), for the connectivity strategies that keep it.

#include <streamclust/detail/hints.hpp>
#include <streamclust/engine/edge_ring.hpp>
#include <streamclust/types.hpp>

#include <cstddef>
#include <cstdint>

namespace streamclust {

/// Where a point's edges are: its back edges (to older neighbours, possibly
/// evicted already) are the run [back_begin, back_begin + back_count) of the
/// edge ring; its forward edges (from newer neighbours, all live) a list
/// from fwd_head. 12 bytes, part of a strategy's PointState as `links`.
struct EdgeLinks {
  EdgeHandle back_begin = 0;
  std::uint32_t back_count = 0;
  EdgeHandle fwd_head = kNoEdge;
};

/// The adjacency of the window's points over an EdgeRing. The strategy's
/// PointState must have an `EdgeLinks links` member. Storing a point's edges
/// is O(its edges) (one sequential append, one write into each neighbour's
/// record); an eviction releases the point's back edges in O(1).
/// Thread safety: none (one engine, one thread).
class PointEdges {
 public:
  /// Records the edges of just-appended point `h` to its `count` older
  /// neighbours `nb`, threading each into the neighbour's forward list.
  /// O(count).
  template <class Ring>
  void store(Ring& ring, PointHandle h, const PointHandle* nb, std::size_t count) {
    for (std::size_t k = 0; k < count; ++k) detail::prefetch(&ring.record(nb[k]));  // written just below
    ring_.reserve(count);
    EdgeLinks& links = ring.record(h).state.links;
    links.back_begin = ring_.next();
    links.back_count = static_cast<std::uint32_t>(count);
    for (std::size_t k = 0; k < count; ++k) {
      EdgeLinks& older = ring.record(nb[k]).state.links;
      older.fwd_head = ring_.push(nb[k], h, older.fwd_head);
    }
  }

  /// Point `h`, the oldest, is leaving: its back edges go (their older
  /// endpoints left before it). Call before the ring drops it. O(1).
  template <class Ring>
  void release(const Ring& ring, PointHandle h) {
    ring_.release_before(ring.size() > 1 ? ring.record(h + 1).state.links.back_begin : ring_.next());
  }

  /// Calls `f(PointHandle)` for every live neighbour of live point `h`. O(degree).
  template <class Ring, class F>
  void for_each_neighbor(const Ring& ring, PointHandle h, F&& f) const {
    const EdgeLinks& links = ring.record(h).state.links;
    for (std::uint32_t i = 0; i < links.back_count; ++i) {
      const PointHandle older = ring_.older(links.back_begin + i);
      if (ring.is_live(older)) f(older);
    }
    for (EdgeHandle e = links.fwd_head; e != kNoEdge; e = ring_.next_forward(e)) f(ring_.newer(e));
  }

  const EdgeRing& ring() const { return ring_; }
  std::size_t heap_bytes() const { return ring_.heap_bytes(); }

 private:
  EdgeRing ring_;
};

}  // namespace streamclust
