// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// UnionFindRebuildConnectivity: components rebuilt from the stored edges at
/// each retrieval.

#include <streamclust/concepts/connectivity.hpp>
#include <streamclust/detail/union_find.hpp>
#include <streamclust/engine/point_edges.hpp>
#include <streamclust/engine/rebuilt_components.hpp>
#include <streamclust/memory_usage.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {

/// Insertion only stores a point's edges (to the older neighbours that pass
/// the linkage); eviction only drops the point. `retrieve()` runs one
/// union-find pass over the live edges, which PointEdges keeps in FIFO order
/// in one ring, so the pass reads memory sequentially: O(N + E) per
/// retrieval whatever the share of the window that changed, against the
/// paper's O(pending points + their edges) random-access BFS, which for a
/// window dominated by one structure cluster is the whole window at every
/// retrieval.
///
/// Same partition as LazyBfsConnectivity and the batch clusterer (oracle
/// tests). What differs (RebuiltComponents):
///  - local clusters ARE the components of the last retrieval (no bridges;
///    `cluster_of` of a point inserted after it is kNoCluster);
///  - the visitor hooks are not called (there are no cluster events);
///  - stable ids: each point votes with weight 1 for the id its component had
///    at the previous retrieval (points inserted since do not vote).
/// Memory: 16 bytes of state per point, 12 per edge.
///
/// Thread safety: the policy is immutable; a State belongs to one engine.
struct UnionFindRebuildConnectivity {
  struct Params {};
  explicit UnionFindRebuildConnectivity(const Params&) {}

  static constexpr bool stores_point_edges = true;

  /// Per point: its component at the last retrieval, its edges. 16 bytes.
  struct PointState {
    ClusterId cluster = kNoCluster;
    EdgeLinks links;
  };

  template <class Ring>
  class State : public ConnectivityStateDefaults, public RebuiltComponents {
   public:
    explicit State(const UnionFindRebuildConnectivity&) {}

    template <class Ctx>
    void on_link(Ctx& ctx, PointHandle h, const PointHandle* nb, std::size_t count) {
      edges_.store(ctx.points, h, nb, count);
      mark_linked(ctx.points.record(h).state.cluster);
    }
    template <class Ctx>
    void on_evict(Ctx& ctx, PointHandle h) {
      forget(ctx.points.record(h).state.cluster);
      edges_.release(ctx.points, h);
    }

    /// One union-find pass over the live edges, then RebuiltComponents.
    /// O(N + E) plus the votes.
    template <class Ctx>
    const Clustering& retrieve(Ctx& ctx) {
      const auto t0 = Ctx::Clock::now();
      unite_edges(ctx.points, static_cast<std::uint32_t>(ctx.points.size()));
      const Clustering& out = adopt_sets(ctx, sets_);
      Ctx::Clock::add_since(ctx.stats.phase_us.component_update, t0);
      return out;
    }

    const PointEdges& edges() const { return edges_; }

    void add_memory(MemoryUsage& m) const {
      m.edge_storage += edges_.heap_bytes();
      m.clusters += cluster_bytes();
      m.scratch += sets_.heap_bytes() + scratch_bytes();
    }

   private:
    /// The window's edges are [oldest, next) of the edge ring, grouped by
    /// newer endpoint in insertion order: stream them. When the newer
    /// endpoint changes it is still a singleton (no earlier edge touches it),
    /// and every root is its set's oldest point. O(N + E).
    void unite_edges(const Ring& ring, std::uint32_t n) {
      sets_.reset(n, ring.capacity());
      const PointHandle oldest = ring.oldest();
      std::uint32_t current = n;
      std::uint32_t root = n;
      edges_.ring().for_each([&](PointHandle older, PointHandle newer) {
        const auto j = static_cast<std::uint32_t>(older - oldest);
        if (j >= n) return;  // the older endpoint has left the window
        const auto i = static_cast<std::uint32_t>(newer - oldest);
        if (i != current) current = root = i;
        const std::uint32_t rj = sets_.find(j);
        if (rj == root) return;
        if (rj < root) {
          sets_.attach(root, rj);
          root = rj;
        } else {
          sets_.attach(rj, root);
        }
      });
    }

    PointEdges edges_;
    detail::OldestRootUnionFind sets_;
  };
};

}  // namespace streamclust

static_assert(streamclust::is_connectivity_policy_v<streamclust::UnionFindRebuildConnectivity>,
              "STREAMCLUST_CONNECTIVITY_POLICY_INVALID: UnionFindRebuildConnectivity");
