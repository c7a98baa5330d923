// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// UnionFindRebuildConnectivity: components rebuilt from the stored edges at
/// each retrieval.

#include <streamclust/concepts/connectivity.hpp>

namespace streamclust {

/// Insertion only stores a point's edges (to the older neighbours that pass
/// the linkage); eviction only drops the point from the index. `retrieve()`
/// runs one union-find pass (union by index, path halving) over the live
/// edges, which the engine keeps in FIFO order in one ring, so the pass reads
/// memory sequentially: O(N + E) per retrieval whatever the share of the
/// window that changed, against the paper's O(pending points + their edges)
/// random-access BFS, which for a window dominated by one structure cluster
/// is the whole window at every retrieval.
///
/// Same partition as LazyBfsConnectivity and the batch clusterer (oracle
/// tests). What differs (documented in StreamClusterer):
///  - local clusters ARE the components of the last retrieval (no bridges;
///    `cluster_of` of a point inserted after it is kNoCluster);
///  - the visitor hooks are not called (there are no cluster events);
///  - stable ids: each point votes with weight 1 for the id its component had
///    at the previous retrieval (points inserted since do not vote); the rest
///    of the rule (heaviest claim wins, ties to the older id, fresh ids never
///    reused) is the paper strategy's.
///
/// Thread safety: immutable.
struct UnionFindRebuildConnectivity {
  struct Params {};
  explicit UnionFindRebuildConnectivity(const Params&) {}
  static constexpr ConnectivityStrategy strategy = ConnectivityStrategy::union_find_rebuild;
};

}  // namespace streamclust

static_assert(streamclust::is_connectivity_policy_v<streamclust::UnionFindRebuildConnectivity>,
              "STREAMCLUST_CONNECTIVITY_POLICY_INVALID: UnionFindRebuildConnectivity");
