// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// SpanningForestConnectivity: the window's components kept as a maximum
/// spanning forest whose edge weight is the edge's expiry.

#include <streamclust/concepts/connectivity.hpp>
#include <streamclust/detail/age_bands.hpp>
#include <streamclust/detail/forest_merge.hpp>
#include <streamclust/detail/growth.hpp>
#include <streamclust/detail/ring_queue.hpp>
#include <streamclust/detail/union_find.hpp>
#include <streamclust/engine/rebuilt_components.hpp>
#include <streamclust/memory_usage.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {

/// Points leave the window in insertion order, so an edge dies exactly when
/// its older endpoint leaves: its older endpoint is its expiry. The strategy
/// keeps a maximum spanning forest F of the window's point graph for that
/// weight (at most N - 1 edges), plus the edges inserted since the last fold
/// in age bands (detail::AgeBands). Insertion appends the new point's edges
/// to their bands (no edge ring, no per-point adjacency, no write into the
/// older endpoint's record); eviction only drops the point. `retrieve()`
/// folds: the expired suffix of F is cut, the bands hand the new edges back
/// in increasing age, and Kruskal merges them with F in place
/// (detail::merge_forest) with a ranked union-find over window positions,
/// whose sets are then the window's components. O(N + F + new edges) per
/// retrieval instead of the rebuild's O(N + E), and 8 bytes per forest or
/// new edge instead of 12 per live edge. The proof is at `State::fold`.
///
/// When the client rarely retrieves, the new edges are folded into F without
/// labelling once they outnumber max(`fold_edges_per_point` x window points,
/// `min_fold_edges`), which bounds the edges held at (1 + r) x 8 bytes per
/// point for r = fold_edges_per_point. The default r = 2 keeps a 20 Hz
/// client on a Mid-360 (T_B = 0.5 s: about 1.4 new edges per window point
/// per cycle) at one fold per retrieval; r = 1 folds mid-cycle as well,
/// which cost as much as the forest saved (docs/design-decisions.md).
///
/// Same partition as the other strategies (oracle tests); what a user sees
/// is UnionFindRebuildConnectivity's (RebuiltComponents): local clusters are
/// the last retrieval's components (no bridges; `cluster_of` of a point
/// inserted since is kNoCluster), visitor hooks are not called, each point
/// present at the previous retrieval votes with weight 1 for its stable id.
/// In addition there are no point-level edges to inspect: the engine's
/// `for_each_neighbor`, back/forward edge accessors and the Boost.Graph
/// point view (<streamclust/graph/point_graph.hpp>) do not compile with it
/// (STREAMCLUST_NO_POINT_EDGES).
///
/// Thread safety: the policy is immutable; a State belongs to one engine.
struct SpanningForestConnectivity {
  struct Params {
    /// Lower bound of the fold threshold [edges]: the edges inserted since
    /// the last fold are folded without a retrieval once they outnumber
    /// max(fold_edges_per_point x points in the window, min_fold_edges).
    /// Allowed: [1, 2^30].
    std::uint32_t min_fold_edges = 65536;
    /// Fold threshold per window point [edges per point]. Allowed: [1, 64].
    std::uint32_t fold_edges_per_point = 2;
    /// Witnesses per inserted point for dropping redundant new edges
    /// (0 = keep every edge). A new point's edge to neighbour n is dropped
    /// when a younger neighbour y (a witness: the youngest neighbours,
    /// youngest first) has an edge to n itself: the path through y keeps
    /// what the edge connects for as long as the edge would live (proof at
    /// NeighbourSearch). Same partition, fewer
    /// edges to store, sort and merge; each witness costs one linkage test
    /// per neighbour (vectorised with `link_many`). Off by default: on the
    /// Mid-360 office stream (T_B 0.5 s) one witness keeps 50 % of the new
    /// edges and cuts memory from 122.8 to 117.3 bytes per window point, but
    /// adds about 0.6 ms to a 8.4 ms cycle (the tests cost more than the
    /// shorter fold saves; docs/design-decisions.md). Allowed: [0, 8].
    std::uint32_t prune_witnesses = 0;
  };

  /// Throws std::invalid_argument if min_fold_edges is outside [1, 2^30],
  /// fold_edges_per_point outside [1, 64] or prune_witnesses above 8.
  explicit SpanningForestConnectivity(const Params& params) : params_(params) {
    check_range("fold_edges_per_point", params.fold_edges_per_point, 1, 64, "edges per point");
    check_range("prune_witnesses", params.prune_witnesses, 0, kMaxPruneWitnesses, "witnesses per point");
    check_range("min_fold_edges", params.min_fold_edges, 1, kMaxFoldEdges, "edges");
  }

  static constexpr bool stores_point_edges = false;
  /// Per point: its component at the last retrieval. 4 bytes.
  struct PointState {
    ClusterId cluster = kNoCluster;
  };
  static constexpr std::uint32_t kMaxFoldEdges = std::uint32_t{1} << 30;
  static constexpr std::uint32_t kMaxPruneWitnesses = 8;

  const Params& params() const { return params_; }
  /// Witnesses per inserted point for the redundant-edge filter (Params).
  std::uint32_t prune_witnesses() const { return params_.prune_witnesses; }
  /// The new-edge count past which the engine folds without a retrieval,
  /// for a window of `points` points [edges].
  std::size_t fold_threshold(std::size_t points) const { return fold_threshold(params_, points); }
  static std::size_t fold_threshold(const Params& params, std::size_t points) {
    return std::max<std::size_t>(params.fold_edges_per_point * points, params.min_fold_edges);
  }

  template <class Ring>
  class State : public RebuiltComponents {
   public:
    explicit State(const SpanningForestConnectivity& policy) : params_(policy.params()) {}

    /// The new edges go to their age bands, folded at the next retrieval;
    /// a fold without labelling bounds them (memory) and the handle span
    /// since the last fold (so that edge ages never wrap). O(count).
    template <class Ctx>
    void on_link(Ctx& ctx, PointHandle h, const PointHandle* nb, std::size_t count) {
      Ring& ring = ctx.points;
      fresh_.append(nb, count, h);
      mark_linked(ring.record(h).state.cluster);
      // The calibration replay links a whole window at once: it folds at a
      // quarter window, so that it does not set the capacity of the bands and
      // the forest (which never shrink) above what a cycle needs.
      const std::size_t threshold = fold_threshold(params_, replaying_ ? ring.size() / 4 : ring.size());
      if (fresh_.size() > threshold || static_cast<PointHandle>(ring.next() - fold_mark_) >= kMaxFoldSpan) {
        fold(ring, ctx.stats);
        ++ctx.stats.forest_folds;
      }
    }
    template <class Ctx>
    void on_evict(Ctx& ctx, PointHandle h) {
      forget(ctx.points.record(h).state.cluster);
    }
    template <class Ctx>
    void begin_replay(Ctx& ctx) {
      replaying_ = true;
      fresh_.reset(ctx.points.oldest());  // no edge yet: the bands count from the window's start
    }
    /// And leaves no replayed edge to the next retrieval's fold, which would
    /// otherwise carry them on top of the cycle's own.
    template <class Ctx>
    void end_replay(Ctx& ctx) {
      replaying_ = false;
      if (!fresh_.empty()) {
        fold(ctx.points, ctx.stats);
        ++ctx.stats.forest_folds;
      }
    }
    /// The band table for a window of the ring's capacity plus as many new
    /// points between two folds.
    void reserve(const Ring& ring) { fresh_.reserve_span(2 * std::size_t{ring.capacity()}); }

    /// Folds, then RebuiltComponents. O(N + F + new edges) plus the votes.
    template <class Ctx>
    const Clustering& retrieve(Ctx& ctx) {
      const auto t0 = Ctx::Clock::now();
      fold(ctx.points, ctx.stats);
      const Clustering& out = adopt_sets(ctx, sets_);
      Ctx::Clock::add_since(ctx.stats.phase_us.component_update, t0);
      return out;
    }

    void add_memory(MemoryUsage& m) const {
      m.edge_storage += capacity_bytes(forest_) + fresh_.heap_bytes() + displaced_.heap_bytes();
      m.clusters += cluster_bytes();
      m.scratch += sets_.heap_bytes() + scratch_bytes();
    }

   private:
    using Edge = detail::HandleEdge;
    /// Points inserted between two folds at most, so that edge ages (newest
    /// handle - older endpoint) never wrap around 2^32.
    static constexpr PointHandle kMaxFoldSpan = PointHandle{1} << 30;

    /// Folds the edges inserted since the last fold into the forest and
    /// leaves in `sets_` a ranked union-find over the window positions whose
    /// sets are the window's connected components. O(N + forest + new
    /// edges): the new edges sorted band by band, one merge, Kruskal with
    /// union by rank and path halving. (Hanging the younger root under the
    /// older, as the rebuild does, built long chains here: Kruskal takes the
    /// newest edges first.)
    ///
    /// Why it is exact. Give every edge (a, b), a older than b, the weight a:
    /// FIFO eviction kills the edge exactly when a leaves, so a is its expiry
    /// (compared as ages newest - a, which survive the 32-bit handle wrap).
    /// (1) Threshold property. Let F be the forest Kruskal builds from a graph
    ///     G taking the edges by non-increasing weight, ties in any order. For
    ///     every t, {e in G : w(e) >= t} and {e in F : w(e) >= t} have the
    ///     same components: the edges of weight >= t are a prefix of Kruskal's
    ///     order; once it is processed, the union-find's sets are the
    ///     components of that prefix, and the edges accepted so far are
    ///     exactly F's edges of weight >= t, whose components are those sets.
    /// (2) Eviction. The live graph is {e in G : w(e) >= oldest}, a threshold
    ///     (the newer endpoint of a live edge is live; an evicted point has no
    ///     live edge left). By (1) its components are those of
    ///     F_live = {e in F : w(e) >= oldest}, and F_live has the threshold
    ///     property for it (t >= oldest: nothing changed; t < oldest: both
    ///     sides are their own t = oldest case).
    /// (3) Folding. Let N be the live edges inserted since F was built; the
    ///     live graph is G_live + N. Kruskal over H = F_live + N gives F' with
    ///     comp(F'_{>=t}) = comp(H_{>=t}) for every t, by (1). And
    ///     comp(H_{>=t}) = comp((G_live + N)_{>=t}): H is a subgraph; an edge
    ///     e = (u, v) of G_live outside F with w(e) >= t has u and v connected
    ///     in F_{>=w(e)} (threshold property of F at w(e)), by edges of weight
    ///     >= w(e) >= oldest, so live, in F_live, and >= t (the cycle property).
    /// So F' has the threshold property for the live graph; by induction from
    /// the empty forest it holds after every fold, and the union-find at the
    /// end of a fold holds the window's components. F is kept in Kruskal's
    /// order (non-increasing weight = increasing age): its expired edges are
    /// a suffix and the new edges are merged into it, not re-sorted with it.
    ///
    /// Memory: no second forest and no sort buffer. The new edges wait in
    /// their age bands, which hand them back sorted one band at a time; the
    /// expired suffix of the forest is cut off, and detail::merge_forest runs
    /// Kruskal in place in `forest_`, whose capacity (at least the window)
    /// exceeds any forest of the window.
    void fold(const Ring& ring, RetrievalStats& stats) {
      const auto n = static_cast<std::uint32_t>(ring.size());
      const PointHandle newest = ring.next() - 1;
      const auto age = [newest](const Edge& e) { return static_cast<std::uint32_t>(newest - e.older); };
      sets_.reset(n, ring.capacity());
      // The expired edges are a suffix (increasing age; ages do not wrap, see kMaxFoldSpan).
      forest_.erase(std::partition_point(forest_.begin(), forest_.end(), [&](const Edge& e) { return age(e) < n; }),
                    forest_.end());
      detail::reserve_window(forest_, n, ring.capacity());  // room for any forest of the window: merge_forest's gap
      const PointHandle base = ring.oldest();
      const detail::MergeCounts counts =
          detail::merge_forest(forest_, fresh_, displaced_, base, n, age, [&](const Edge& e) {
            return sets_.unite(static_cast<std::uint32_t>(e.older - base), static_cast<std::uint32_t>(e.newer - base));
          });
      stats.forest_displaced += counts.displaced;
      stats.edges_folded += counts.new_read;
      stats.edges_accepted += counts.new_accepted;
      stats.forest_edges = forest_.size();
      fresh_.reset(base);
      fold_mark_ = ring.next();
    }

    Params params_;
    /// The maximum spanning forest of the window in Kruskal's order
    /// (non-increasing older endpoint; expired edges form a suffix).
    std::vector<Edge> forest_;
    detail::AgeBands fresh_;                 ///< the edges inserted since the last fold
    detail::RingQueue<Edge> displaced_;      ///< the fold's queue of displaced kept edges
    PointHandle fold_mark_ = 0;              ///< the ring's next() at the last fold
    bool replaying_ = false;                 ///< the calibration replay is linking the first window
    detail::RankedUnionFind sets_;
  };

 private:
  /// Throws std::invalid_argument naming the parameter, its value and the
  /// allowed range unless lo <= value <= hi.
  static void check_range(const char* name, std::uint32_t value, std::uint32_t lo, std::uint32_t hi,
                          const char* unit) {
    if (value >= lo && value <= hi) return;
    std::string message = "SpanningForestConnectivity: parameter ";
    message.append(name)
        .append(" = ")
        .append(std::to_string(value))
        .append(" is invalid; allowed: [")
        .append(std::to_string(lo))
        .append(", ")
        .append(std::to_string(hi))
        .append("] ")
        .append(unit);
    throw std::invalid_argument(message);
  }

  Params params_;
};

}  // namespace streamclust

static_assert(streamclust::is_connectivity_policy_v<streamclust::SpanningForestConnectivity>,
              "STREAMCLUST_CONNECTIVITY_POLICY_INVALID: SpanningForestConnectivity");
