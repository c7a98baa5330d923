// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// SpanningForestConnectivity: the window's components kept as a maximum
/// spanning forest whose edge weight is the edge's expiry.

#include <streamclust/concepts/connectivity.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace streamclust {

/// Points leave the window in insertion order, so an edge dies exactly when
/// its older endpoint leaves: its older endpoint is its expiry. The engine
/// keeps a maximum spanning forest F of the window's point graph for that
/// weight (at most N - 1 edges), plus the list of edges inserted since the
/// last fold. Insertion appends the new point's edges to that list (a
/// sequential write: no edge ring, no per-point adjacency, no write into the
/// older endpoint's record); eviction only drops the point from the index.
/// `retrieve()` sorts the new edges by expiry (radix sort), merges them with
/// the live part of F (a prefix: F is kept newest-expiry first) and runs
/// Kruskal with a union-find over window positions; the accepted edges are
/// the new F and the union-find gives the components.
/// O(N + F + new edges) per retrieval instead of the rebuild's O(N + E), and
/// 8 bytes per forest or new edge instead of 12 per live edge. The proof is
/// at `StreamClusterer::fold_forest`.
///
/// When the client rarely retrieves, the new edges are folded into F without
/// labelling once they outnumber max(`fold_edges_per_point` x window points,
/// `min_fold_edges`), which bounds the edges held at (1 + r) x 8 bytes per
/// point for r = fold_edges_per_point (plus the radix sort's second buffer,
/// kept in the forest's spare tail: the merge is in place). The default
/// r = 2 keeps a 20 Hz client on a Mid-360
/// (T_B = 0.5 s: about 1.4 new edges per window point per cycle) at one fold
/// per retrieval; r = 1 folds mid-cycle as well, which cost as much as the
/// forest saved (docs/optimization-log.md, section 7).
///
/// Same partition as the other strategies (oracle tests); what a user sees
/// is UnionFindRebuildConnectivity's: local clusters are the last
/// retrieval's components (no bridges; `cluster_of` of a point inserted
/// since is kNoCluster), visitor hooks are not called, each point present at
/// the previous retrieval votes with weight 1 for its stable id. In
/// addition there are no point-level edges to inspect: the engine's
/// `for_each_neighbor`, back/forward edge accessors and the Boost.Graph
/// point view (<streamclust/graph/point_graph.hpp>) do not compile with it
/// (STREAMCLUST_NO_POINT_EDGES).
///
/// Thread safety: immutable.
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
    /// `StreamClusterer::prune_redundant_edges`). Same partition, fewer
    /// edges to store, sort and merge; each witness costs one linkage test
    /// per neighbour (vectorised with `link_many`). Off by default: on the
    /// Mid-360 office stream (T_B 0.5 s) one witness keeps 50 % of the new
    /// edges and cuts memory from 122.8 to 117.3 bytes per window point, but
    /// adds about 0.6 ms to a 8.4 ms cycle (the tests cost more than the
    /// shorter fold saves; optimization log, sections 17 and 19 G). Allowed: [0, 8].
    std::uint32_t prune_witnesses = 0;
  };

  /// Throws std::invalid_argument if min_fold_edges is outside [1, 2^30],
  /// fold_edges_per_point outside [1, 64] or prune_witnesses above 8.
  explicit SpanningForestConnectivity(const Params& params) : params_(params) {
    check_range("fold_edges_per_point", params.fold_edges_per_point, 1, 64, "edges per point");
    check_range("prune_witnesses", params.prune_witnesses, 0, kMaxPruneWitnesses, "witnesses per point");
    check_range("min_fold_edges", params.min_fold_edges, 1, kMaxFoldEdges, "edges");
  }

  static constexpr ConnectivityStrategy strategy = ConnectivityStrategy::spanning_forest;
  static constexpr std::uint32_t kMaxFoldEdges = std::uint32_t{1} << 30;
  static constexpr std::uint32_t kMaxPruneWitnesses = 8;

  const Params& params() const { return params_; }
  /// Witnesses per inserted point for the redundant-edge filter (Params).
  std::uint32_t prune_witnesses() const { return params_.prune_witnesses; }
  /// The new-edge count past which the engine folds without a retrieval,
  /// for a window of `points` points [edges].
  std::size_t fold_threshold(std::size_t points) const {
    return std::max<std::size_t>(params_.fold_edges_per_point * points, params_.min_fold_edges);
  }

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
