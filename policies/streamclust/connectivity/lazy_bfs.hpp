// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// LazyBfsConnectivity: the paper's connectivity maintenance (local
/// clusters, bridges, lazy deletion validated by BFS).

#include <streamclust/concepts/connectivity.hpp>
#include <streamclust/detail/growth.hpp>
#include <streamclust/engine/point_edges.hpp>
#include <streamclust/engine/stable_ids.hpp>
#include <streamclust/memory_usage.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {

/// C-ARC's strategy (paper, section METHOD). Each new point either starts a
/// local cluster (isolation: no neighbour), joins its neighbours' one
/// (expansion) or, with neighbours in several, joins the most recently
/// created of them, and each point-level edge to another cluster adds one
/// unit of multiplicity to the bridge between the two (bridging). Eviction
/// lowers the multiplicity of every bridge the point's edges carried (a
/// bridge disappears at zero) and marks its cluster pending when the point
/// had two or more edges inside it (removing a vertex of degree <= 1 cannot
/// disconnect a graph). `retrieve()` validates pending clusters by BFS,
/// splitting disconnected ones (the largest fragment keeps the cluster),
/// then labels the window by the components of the graph of clusters and
/// bridges.
///
/// Stable ids: every cluster votes, with its current size, for the id its
/// component had at the previous retrieval (StableIdVotes).
///
/// Cost: an eviction walks the point's forward edges; a retrieval costs the
/// BFS over every pending cluster, which on scenes with one huge structure
/// cluster (floor, walls) is the whole window. Memory: 24 bytes of state per
/// point and 12 per edge (PointEdges), plus the clusters and bridge lists.
/// Visitor hooks (created, merged, split, evicted) and the component graph
/// of local clusters and bridges are meaningful at all times.
///
/// The default when a configuration has no `connectivity` slot.
/// Thread safety: the policy is immutable; a State belongs to one engine.
struct LazyBfsConnectivity {
  struct Params {};
  explicit LazyBfsConnectivity(const Params&) {}

  static constexpr bool stores_point_edges = true;

  /// Per point: its cluster, the next member of it, a BFS mark, its edges.
  /// 24 bytes.
  struct PointState {
    ClusterId cluster = kNoCluster;
    PointHandle next_member = kNoPoint;  ///< next point of the same cluster, insertion order
    std::uint32_t mark = 0;              ///< BFS epoch
    EdgeLinks links;
  };

  template <class Ring>
  class State : public ConnectivityStateDefaults {
   public:
    explicit State(const LazyBfsConnectivity&) {}

    // ------------------------------------------------------------ changes
    template <class Ctx>
    void on_link(Ctx& ctx, PointHandle h, const PointHandle* nb, std::size_t count) {
      Ring& ring = ctx.points;
      edges_.store(ring, h, nb, count);
      touched_.clear();
      for (std::size_t k = 0; k < count; ++k) {
        const ClusterId other = ring.record(nb[k]).state.cluster;
        auto it = std::find_if(touched_.begin(), touched_.end(), [&](const ClusterBridge& b) { return b.other == other; });
        if (it == touched_.end()) {
          touched_.push_back(ClusterBridge{other, 1});
        } else {
          ++it->multiplicity;
        }
      }
      ClusterId target;
      if (touched_.empty()) {
        target = create_cluster(ctx);  // isolation
      } else {
        target = touched_.front().other;  // expansion, or bridging into the newest cluster
        for (const ClusterBridge& t : touched_) {
          if (clusters_[t.other].created > clusters_[target].created) target = t.other;
        }
        for (const ClusterBridge& t : touched_) {
          if (t.other != target) add_bridge(ctx, target, t.other, t.multiplicity, true);
        }
      }
      append_member(ring, target, h);
    }

    template <class Ctx>
    void on_evict(Ctx& ctx, PointHandle h) {
      Ring& ring = ctx.points;
      const PointState& r = ring.record(h).state;
      const ClusterId c = r.cluster;
      std::uint32_t intra_degree = 0;
      const EdgeRing& edges = edges_.ring();
      for (EdgeHandle e = r.links.fwd_head; e != kNoEdge; e = edges.next_forward(e)) {
        const ClusterId other = ring.record(edges.newer(e)).state.cluster;
        if (other == c) {
          ++intra_degree;
        } else {
          lower_bridge(c, other, 1);
        }
      }
      // Back edges point to older points, all evicted already (FIFO).
      Cluster& cl = clusters_[c];
      cl.head = r.next_member;  // the globally oldest point heads its cluster's list
      if (cl.head == kNoPoint) cl.tail = kNoPoint;
      --cl.size;
      if (cl.size == 0) {
        cl.alive = false;
        cl.pending = false;
        free_clusters_.push_back(c);
        ctx.visitor.cluster_evicted(c);
      } else if (intra_degree >= 2 && !cl.pending) {
        cl.pending = true;
        pending_.push_back(c);
      }
      edges_.release(ring, h);
    }

    // ---------------------------------------------------------- retrieval
    /// Validates the pending clusters, then labels the components of the
    /// cluster graph. O(pending points + their edges + N + clusters + bridges).
    template <class Ctx>
    const Clustering& retrieve(Ctx& ctx) {
      using Clock = typename Ctx::Clock;
      const auto t0 = Clock::now();
      validate_pending(ctx);
      Clock::add_since(ctx.stats.phase_us.validation, t0);
      const auto t1 = Clock::now();
      const std::uint32_t components = number_components();
      // Stable ids: each cluster votes for its old component's place with its size.
      votes_.begin(ctx.result.components(), [](std::uint32_t) { return false; });
      std::uint32_t multiple = 0;
      for (ClusterId c = 0; c < clusters_.size(); ++c) {
        const Cluster& cl = clusters_[c];
        if (cl.alive && cl.stable_id != kNoComponent) votes_.vote(cl.result_slot, component_of_[c], cl.size);
      }
      for (std::uint32_t k = 0; k < components; ++k) multiple += component_size_[k] > 1 ? 1u : 0u;
      const std::vector<std::uint32_t>& kept = votes_.resolve(components, [](std::uint32_t place) { return place; });
      Clock::add_since(ctx.stats.phase_us.component_update, t1);
      const auto t2 = Clock::now();
      Ring& ring = ctx.points;
      const PointHandle oldest = ring.oldest();
      const Clustering& out = ctx.result.write(
          ring, static_cast<std::uint32_t>(ring.size()), components, multiple, kept,
          [&](std::uint32_t i) { return component_of_[ring.record(oldest + i).state.cluster]; },
          [&](std::uint32_t k) { return component_size_[k]; }, ctx.time, ctx.next_id, ring.capacity());
      Clock::add_since(ctx.stats.phase_us.labelling, t2);
      // The clusters carry their component's id and place to the next retrieval.
      for (ClusterId c = 0; c < clusters_.size(); ++c) {
        Cluster& cl = clusters_[c];
        if (!cl.alive) continue;
        cl.result_slot = ctx.result.place_of(component_of_[c]);
        cl.stable_id = ctx.result.id_at(cl.result_slot);
      }
      return out;
    }

    // -------------------------------------------------------- inspection
    ClusterId cluster_of(const Ring& ring, PointHandle h) const { return ring.record(h).state.cluster; }
    std::size_t cluster_slots() const { return clusters_.size(); }
    bool cluster_alive(ClusterId c) const { return c < clusters_.size() && clusters_[c].alive; }
    std::size_t cluster_count() const { return clusters_.size() - free_clusters_.size(); }
    std::size_t cluster_size(ClusterId c) const { return clusters_[c].size; }
    bool cluster_pending(ClusterId c) const { return clusters_[c].pending; }
    const std::vector<ClusterBridge>& bridges(ClusterId c) const { return clusters_[c].bridges; }
    const PointEdges& edges() const { return edges_; }

    void add_memory(MemoryUsage& m) const {
      m.edge_storage += edges_.heap_bytes();
      m.clusters += capacity_bytes(clusters_) + capacity_bytes(free_clusters_) + capacity_bytes(pending_);
      for (const Cluster& c : clusters_) m.clusters += capacity_bytes(c.bridges);
      m.scratch += capacity_bytes(touched_) + capacity_bytes(order_) + capacity_bytes(fragment_begin_) +
                   capacity_bytes(component_of_) + capacity_bytes(component_size_) + capacity_bytes(queue_) +
                   votes_.heap_bytes();
    }

   private:
    struct Cluster {
      std::uint32_t size = 0;
      PointHandle head = kNoPoint;    ///< oldest member
      PointHandle tail = kNoPoint;    ///< newest member
      std::uint32_t result_slot = 0;  ///< place of its stable id's component in the last result (valid with stable_id)
      std::uint64_t created = 0;      ///< creation order, for the bridging rule
      ComponentId stable_id = kNoComponent;  ///< id of its component at the last retrieval
      bool alive = false;
      bool pending = false;
      std::vector<ClusterBridge> bridges;
    };

    template <class Ctx>
    ClusterId create_cluster(Ctx& ctx) {
      ClusterId id;
      if (!free_clusters_.empty()) {
        id = free_clusters_.back();
        free_clusters_.pop_back();
      } else {
        id = static_cast<ClusterId>(clusters_.size());
        clusters_.emplace_back();
      }
      Cluster& c = clusters_[id];
      c.size = 0;
      c.head = c.tail = kNoPoint;
      c.created = clusters_created_++;
      c.stable_id = kNoComponent;
      c.alive = true;
      c.pending = false;
      c.bridges.clear();
      ctx.visitor.cluster_created(id);
      return id;
    }

    void append_member(Ring& ring, ClusterId c, PointHandle h) {
      Cluster& cl = clusters_[c];
      PointState& r = ring.record(h).state;
      r.cluster = c;
      r.next_member = kNoPoint;
      if (cl.tail == kNoPoint) {
        cl.head = h;
      } else {
        ring.record(cl.tail).state.next_member = h;
      }
      cl.tail = h;
      ++cl.size;
    }

    template <class Ctx>
    void add_bridge(Ctx& ctx, ClusterId a, ClusterId b, std::uint32_t multiplicity, bool notify) {
      auto& la = clusters_[a].bridges;
      auto it = std::find_if(la.begin(), la.end(), [&](const ClusterBridge& x) { return x.other == b; });
      if (it != la.end()) {
        it->multiplicity += multiplicity;
        auto& lb = clusters_[b].bridges;
        std::find_if(lb.begin(), lb.end(), [&](const ClusterBridge& x) { return x.other == a; })->multiplicity +=
            multiplicity;
        return;
      }
      la.push_back(ClusterBridge{b, multiplicity});
      clusters_[b].bridges.push_back(ClusterBridge{a, multiplicity});
      if (notify) ctx.visitor.clusters_merged(a, b);
    }

    static void lower_bridge_entry(std::vector<ClusterBridge>& list, ClusterId other, std::uint32_t by) {
      auto it = std::find_if(list.begin(), list.end(), [&](const ClusterBridge& x) { return x.other == other; });
      it->multiplicity -= by;
      if (it->multiplicity == 0) {
        *it = list.back();
        list.pop_back();
      }
    }

    void lower_bridge(ClusterId a, ClusterId b, std::uint32_t by) {
      lower_bridge_entry(clusters_[a].bridges, b, by);
      lower_bridge_entry(clusters_[b].bridges, a, by);
    }

    template <class Ctx>
    void validate_pending(Ctx& ctx) {
      for (std::size_t i = 0; i < pending_.size(); ++i) {
        const ClusterId c = pending_[i];
        if (!clusters_[c].alive || !clusters_[c].pending) continue;
        clusters_[c].pending = false;
        ++ctx.stats.clusters_validated;
        ctx.stats.points_validated += clusters_[c].size;
        validate(ctx, c);
      }
      pending_.clear();
    }

    std::uint32_t next_epoch(Ring& ring) {
      if (++epoch_ == 0) {  // wrapped: clear all marks once every 2^32 BFS runs
        for (PointHandle h = ring.oldest(); h != ring.next(); ++h) ring.record(h).state.mark = 0;
        epoch_ = 1;
      }
      return epoch_;
    }

    /// BFS over the intra-cluster edges of cluster `c`; splits it into its
    /// connected fragments. The largest fragment keeps the id. O(points +
    /// edges of c), plus bridge re-attribution for the new fragments.
    template <class Ctx>
    void validate(Ctx& ctx, ClusterId c) {
      Ring& ring = ctx.points;
      const std::uint32_t epoch = next_epoch(ring);
      order_.clear();
      fragment_begin_.clear();
      for (PointHandle m = clusters_[c].head; m != kNoPoint; m = ring.record(m).state.next_member) {
        if (ring.record(m).state.mark == epoch) continue;
        fragment_begin_.push_back(order_.size());
        ring.record(m).state.mark = epoch;
        order_.push_back(m);
        for (std::size_t q = fragment_begin_.back(); q < order_.size(); ++q) {
          edges_.for_each_neighbor(ring, order_[q], [&](PointHandle n) {
            PointState& nr = ring.record(n).state;
            if (nr.cluster == c && nr.mark != epoch) {
              nr.mark = epoch;
              order_.push_back(n);
            }
          });
        }
        if (fragment_begin_.size() == 1 && order_.size() == clusters_[c].size) return;  // still connected
      }
      fragment_begin_.push_back(order_.size());
      const std::size_t fragments = fragment_begin_.size() - 1;
      std::size_t keeper = 0;
      for (std::size_t f = 1; f < fragments; ++f) {
        if (fragment_begin_[f + 1] - fragment_begin_[f] > fragment_begin_[keeper + 1] - fragment_begin_[keeper]) {
          keeper = f;
        }
      }
      // Relabel the other fragments with new clusters.
      const ComponentId inherited = clusters_[c].stable_id;
      for (std::size_t f = 0; f < fragments; ++f) {
        if (f == keeper) continue;
        const ClusterId piece = create_cluster(ctx);
        clusters_[piece].stable_id = inherited;
        clusters_[piece].result_slot = clusters_[c].result_slot;
        for (std::size_t q = fragment_begin_[f]; q < fragment_begin_[f + 1]; ++q) {
          ring.record(order_[q]).state.cluster = piece;
        }
        ++ctx.stats.clusters_split;
      }
      // Rebuild the member lists in insertion order.
      PointHandle m = clusters_[c].head;
      clusters_[c].head = clusters_[c].tail = kNoPoint;
      clusters_[c].size = 0;
      while (m != kNoPoint) {
        const PointHandle next = ring.record(m).state.next_member;
        append_member(ring, ring.record(m).state.cluster, m);
        m = next;
      }
      // Move the bridges carried by the new fragments' edges.
      for (std::size_t f = 0; f < fragments; ++f) {
        if (f == keeper) continue;
        const ClusterId piece = ring.record(order_[fragment_begin_[f]]).state.cluster;
        for (std::size_t q = fragment_begin_[f]; q < fragment_begin_[f + 1]; ++q) {
          edges_.for_each_neighbor(ring, order_[q], [&](PointHandle n) {
            const ClusterId other = ring.record(n).state.cluster;
            if (other != piece) {
              lower_bridge(c, other, 1);
              add_bridge(ctx, piece, other, 1, false);
            }
          });
        }
        ctx.visitor.cluster_split(c, piece);
      }
    }

    /// BFS over the component graph: `component_of_[cluster]` and the
    /// components' sizes [points]. Returns the component count.
    /// O(clusters + bridges).
    std::uint32_t number_components() {
      const std::size_t slots = clusters_.size();
      detail::reserve_geometric(component_of_, slots);
      component_of_.assign(slots, kNoCluster);
      component_size_.clear();
      std::uint32_t components = 0;
      for (ClusterId c = 0; c < slots; ++c) {
        if (!clusters_[c].alive || component_of_[c] != kNoCluster) continue;
        queue_.clear();
        queue_.push_back(c);
        component_of_[c] = components;
        std::uint32_t points = 0;
        for (std::size_t q = 0; q < queue_.size(); ++q) {
          points += clusters_[queue_[q]].size;
          for (const ClusterBridge& b : clusters_[queue_[q]].bridges) {
            if (component_of_[b.other] == kNoCluster) {
              component_of_[b.other] = components;
              queue_.push_back(b.other);
            }
          }
        }
        component_size_.push_back(points);
        ++components;
      }
      return components;
    }


    PointEdges edges_;
    std::vector<Cluster> clusters_;
    std::vector<ClusterId> free_clusters_;
    std::vector<ClusterId> pending_;
    std::uint64_t clusters_created_ = 0;
    std::uint32_t epoch_ = 0;
    std::vector<ClusterBridge> touched_;
    std::vector<PointHandle> order_;
    std::vector<std::size_t> fragment_begin_;
    std::vector<std::uint32_t> component_of_;    ///< per cluster slot
    std::vector<std::uint32_t> component_size_;  ///< per component [points]
    std::vector<ClusterId> queue_;
    StableIdVotes votes_;
  };
};

}  // namespace streamclust

static_assert(streamclust::is_connectivity_policy_v<streamclust::LazyBfsConnectivity>,
              "STREAMCLUST_CONNECTIVITY_POLICY_INVALID: LazyBfsConnectivity");
static_assert(sizeof(streamclust::LazyBfsConnectivity::PointState) == 24,
              "the paper strategy's point state is meant to stay 24 bytes");
