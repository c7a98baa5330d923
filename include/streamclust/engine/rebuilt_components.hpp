// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// RebuiltComponents: the local clusters of the strategies that recompute
/// the window's components at each retrieval (union-find rebuild, spanning
/// forest): the last retrieval's components, their stable ids by per-point
/// votes, and the result.

#include <streamclust/clustering.hpp>
#include <streamclust/concepts/connectivity.hpp>
#include <streamclust/concepts/visitor.hpp>
#include <streamclust/detail/growth.hpp>
#include <streamclust/detail/hints.hpp>
#include <streamclust/engine/component_result.hpp>
#include <streamclust/engine/retrieval_stats.hpp>
#include <streamclust/engine/stable_ids.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace streamclust {

/// Local clusters that ARE the last retrieval's components: each point's
/// PointState holds `ClusterId cluster` (its component at the last
/// retrieval, kUnlabelled when linked since), and the sizes count the
/// points still in the window. `adopt` turns a fresh component numbering
/// into the new local clusters, resolves the stable ids (each point present
/// at the previous retrieval votes with weight 1 for its old component) and
/// writes the result, in one pass over the window plus the writer's. The
/// rebuilding strategies' States derive from it: its public members are
/// their inspection members.
/// Thread safety: none (one engine, one thread).
class RebuiltComponents {
 public:
  /// Cluster of a point linked since the last retrieval.
  static constexpr ClusterId kUnlabelled = kNoCluster - 1;

  /// A point was linked: it has no component yet.
  static void mark_linked(ClusterId& cluster) { cluster = kUnlabelled; }
  /// A point is leaving the window. O(1).
  void forget(ClusterId cluster) {
    if (cluster < sizes_.size()) --sizes_[cluster];
  }

  // The local clusters as the engine shows them (a strategy's inspection
  // members, inherited).
  /// The local cluster of a point (kNoCluster for a point not labelled by a
  /// retrieval yet). O(1).
  template <class Ring>
  ClusterId cluster_of(const Ring& ring, PointHandle h) const {
    const ClusterId stored = ring.record(h).state.cluster;
    return stored == kUnlabelled ? kNoCluster : stored;
  }
  std::size_t cluster_slots() const { return sizes_.size(); }
  bool cluster_alive(ClusterId c) const { return c < sizes_.size() && sizes_[c] > 0; }
  std::size_t cluster_count() const {
    return static_cast<std::size_t>(std::count_if(sizes_.begin(), sizes_.end(), [](std::uint32_t n) { return n > 0; }));
  }
  std::size_t cluster_size(ClusterId c) const { return sizes_[c]; }
  /// Never: nothing is validated lazily.
  bool cluster_pending(ClusterId) const { return false; }
  /// Always empty: no bridges.
  const std::vector<ClusterBridge>& bridges(ClusterId) const { return no_bridges_; }

  /// The retrieval's second half: `sets` (a window union-find of
  /// detail/union_find.hpp, its sets the window's components) numbered, then
  /// `adopt`ed. Counts the window as validated. O(N + components + votes).
  template <class Ctx, class Sets>
  const Clustering& adopt_sets(Ctx& ctx, Sets& sets) {
    const auto n = static_cast<std::uint32_t>(ctx.points.size());
    ctx.stats.points_validated += n;
    const std::uint32_t components = sets.number_components(n);
    return adopt(ctx.points, n, components, [&](std::uint32_t i) { return sets.component(i); }, ctx.result,
                 ctx.next_id, ctx.time, ctx.stats, typename Ctx::Clock{});
  }

  /// The window's `n` points (oldest first in `ring`) have component
  /// `component_at(i)` of `components`, numbered in order of each
  /// component's oldest point: they become the local clusters, vote for the
  /// stable ids and the result is written by `result`. O(n + components +
  /// votes).
  template <class Ring, class ComponentAt, bool Timed>
  const Clustering& adopt(Ring& ring, std::uint32_t n, std::uint32_t components, ComponentAt&& component_at,
                          ComponentResult& result, ComponentId& next_id, double time, RetrievalStats& stats,
                          detail::PhaseClock<Timed>) {
    using Clock = detail::PhaseClock<Timed>;
    // The old clusters are the previous retrieval's components, at
    // result.place_of(c) in the previous result. One with a single point
    // left (most of them in a fragmented window) keeps no vote list.
    const auto old_clusters = static_cast<std::uint32_t>(sizes_.size());
    votes_.begin(old_clusters, [&](std::uint32_t c) { return sizes_[c] == 1; });
    if (!votes_.reserved()) reserve_first_votes(old_clusters);
    detail::reserve_geometric(sizes_, components);
    sizes_.assign(components, 0);
    std::uint32_t multiple = 0;  // components of two or more points
    // Prefetch only when the per-cluster records outgrow the L1/L2 caches.
    const bool scattered_old = old_clusters >= kPrefetchMinClusters;
    const PointHandle oldest = ring.oldest();
    const PointHandle origin = ring.origin();  // hoisted: the stores below could alias the ring's members
    const std::uint32_t capacity = ring.capacity();
    auto* const records = ring.records();
    for (std::uint32_t i = 0; i < n; ++i) {
      if (scattered_old && i + kPrefetchDistance < n) {
        const ClusterId ahead = records[Ring::slot(oldest + i + kPrefetchDistance, origin, capacity)].state.cluster;
        if (ahead < old_clusters) votes_.prefetch(ahead);
      }
      ClusterId& cluster = records[Ring::slot(oldest + i, origin, capacity)].state.cluster;
      const ClusterId old = cluster;
      const std::uint32_t k = component_at(i);
      cluster = k;
      multiple += ++sizes_[k] == 2 ? 1u : 0u;
      if (old < old_clusters) votes_.vote_one(old, k);  // else linked since the last retrieval
    }
    const std::vector<std::uint32_t>& kept =
        votes_.resolve(components, [&](std::uint32_t c) { return result.place_of(c); });
    const auto t1 = Clock::now();
    const Clustering& out = result.write(
        ring, n, components, multiple, kept, component_at, [&](std::uint32_t k) { return sizes_[k]; }, time, next_id,
        ring.capacity());
    Clock::add_since(stats.phase_us.labelling, t1);
    return out;
  }

  std::size_t cluster_bytes() const { return sizes_.capacity() * sizeof(std::uint32_t); }
  std::size_t scratch_bytes() const { return votes_.heap_bytes(); }

 private:
  /// Points ahead whose vote lists the adoption pass prefetches [points].
  static constexpr std::uint32_t kPrefetchDistance = 16;
  /// Old clusters from which it prefetches: 4096 vote heads are 16 KB.
  static constexpr std::uint32_t kPrefetchMinClusters = 4096;


  /// The first room for votes: one per (listed old cluster, component) pair
  /// met, a listed cluster being one of two or more points left; 1.05-1.75
  /// per such cluster on the simulated Livox streams, never more than their
  /// points. Room for two each, once; afterwards the votes grow only past
  /// their peak (a reservation that followed the listed clusters grew with
  /// them). O(old clusters).
  void reserve_first_votes(std::uint32_t old_clusters) {
    std::size_t listed = 0;
    std::size_t listed_points = 0;
    for (ClusterId c = 0; c < old_clusters; ++c) {
      const std::uint32_t left = sizes_[c];
      listed += left > 1 ? 1u : 0u;
      listed_points += left > 1 ? left : 0u;
    }
    votes_.reserve(std::min(listed_points, 2 * listed + 64));
  }

  std::vector<std::uint32_t> sizes_;  ///< points of each local cluster still in the window
  StableIdVotes votes_;
  std::vector<ClusterBridge> no_bridges_;  ///< what bridges() returns
};

}  // namespace streamclust
