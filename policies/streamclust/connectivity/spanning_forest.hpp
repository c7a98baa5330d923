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
  };

  /// Throws std::invalid_argument if min_fold_edges is outside [1, 2^30] or
  /// fold_edges_per_point outside [1, 64].
  explicit SpanningForestConnectivity(const Params& params) : params_(params) {
    if (params.fold_edges_per_point < 1 || params.fold_edges_per_point > 64) {
      std::string message = "SpanningForestConnectivity: parameter fold_edges_per_point = ";
      message.append(std::to_string(params.fold_edges_per_point)).append(" is invalid; allowed: [1, 64] edges per point");
      throw std::invalid_argument(message);
    }
    if (params.min_fold_edges < 1 || params.min_fold_edges > kMaxFoldEdges) {
      std::string message = "SpanningForestConnectivity: parameter min_fold_edges = ";
      message.append(std::to_string(params.min_fold_edges))
          .append(" is invalid; allowed: [1, ")
          .append(std::to_string(kMaxFoldEdges))
          .append("] edges");
      throw std::invalid_argument(message);
    }
  }

  static constexpr ConnectivityStrategy strategy = ConnectivityStrategy::spanning_forest;
  static constexpr std::uint32_t kMaxFoldEdges = std::uint32_t{1} << 30;

  const Params& params() const { return params_; }
  /// The new-edge count past which the engine folds without a retrieval,
  /// for a window of `points` points [edges].
  std::size_t fold_threshold(std::size_t points) const {
    return std::max<std::size_t>(params_.fold_edges_per_point * points, params_.min_fold_edges);
  }

 private:
  Params params_;
};

}  // namespace streamclust

static_assert(streamclust::is_connectivity_policy_v<streamclust::SpanningForestConnectivity>,
              "STREAMCLUST_CONNECTIVITY_POLICY_INVALID: SpanningForestConnectivity");
