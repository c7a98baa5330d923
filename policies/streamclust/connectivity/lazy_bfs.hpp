// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// LazyBfsConnectivity: the paper's connectivity maintenance.

#include <streamclust/concepts/connectivity.hpp>

namespace streamclust {

/// C-ARC's strategy (paper, section METHOD): points join local clusters
/// (isolation, expansion, bridging); bridges between clusters carry the
/// number of point-level edges they stand for; evicting a point with two or
/// more intra-cluster edges marks its cluster pending, and `retrieve()`
/// validates pending clusters by BFS, splitting disconnected ones.
///
/// Cost: an eviction walks the point's forward edges (lowering bridges);
/// a retrieval costs the BFS over every pending cluster, which on scenes
/// with one huge structure cluster (floor, walls) is the whole window.
/// Visitor hooks (created, merged, split, evicted) and the component graph
/// of local clusters and bridges are meaningful at all times.
///
/// The default when a configuration has no `connectivity` slot.
/// Thread safety: immutable.
struct LazyBfsConnectivity {
  struct Params {};
  explicit LazyBfsConnectivity(const Params&) {}
  static constexpr ConnectivityStrategy strategy = ConnectivityStrategy::lazy_bfs;
};

}  // namespace streamclust

static_assert(streamclust::is_connectivity_policy_v<streamclust::LazyBfsConnectivity>,
              "STREAMCLUST_CONNECTIVITY_POLICY_INVALID: LazyBfsConnectivity");
