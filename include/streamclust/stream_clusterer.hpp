// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// StreamClusterer: the continuous C-ARC engine (paper, section METHOD).

#include <streamclust/clustering.hpp>
#include <streamclust/config.hpp>
#include <streamclust/detail/age_bands.hpp>
#include <streamclust/detail/forest_merge.hpp>
#include <streamclust/detail/hints.hpp>
#include <streamclust/detail/mask.hpp>
#include <streamclust/detail/ring_queue.hpp>
#include <streamclust/memory_usage.hpp>
#include <streamclust/point_traits.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

/// The message of the point-level edge accessors under the spanning-forest
/// connectivity (a macro: static_assert needs a string literal).
#define STREAMCLUST_NO_POINT_EDGES_MESSAGE                                                                     \
  "STREAMCLUST_NO_POINT_EDGES: this engine's connectivity (SpanningForestConnectivity) stores no point-level " \
  "edges, only a spanning forest of the window; for_each_neighbor, the back/forward edge accessors and the "  \
  "Boost.Graph point view need LazyBfsConnectivity or UnionFindRebuildConnectivity"

namespace streamclust {

/// Handle of a point-graph edge (a 32-bit sequence number that wraps).
using EdgeHandle = std::uint32_t;
inline constexpr EdgeHandle kNoEdge = std::numeric_limits<EdgeHandle>::max();
inline constexpr ClusterId kNoCluster = std::numeric_limits<ClusterId>::max();

/// Wall time spent per phase [microseconds]; measured only for configs with
/// `static constexpr bool timed = true`, zero otherwise.
struct PhaseTimes {
  double insertion = 0.0;         ///< neighbour search, edges, isolation/expansion/bridging
  double eviction = 0.0;          ///< removing points that left the window
  double validation = 0.0;        ///< BFS over pending clusters, splits
  double component_update = 0.0;  ///< BFS over the component graph, stable ids
  double labelling = 0.0;         ///< labels and summaries of every window point
};

/// Counters of the work done since the previous retrieval.
struct RetrievalStats {
  std::uint64_t inserted = 0;           ///< points inserted into the graph
  std::uint64_t evicted = 0;            ///< points that left the window
  std::uint64_t clusters_validated = 0; ///< pending clusters checked by BFS
  std::uint64_t points_validated = 0;   ///< points of the clusters checked (validation work)
  std::uint64_t clusters_split = 0;     ///< new clusters created by splits
  std::uint64_t forest_folds = 0;       ///< spanning_forest: folds without labelling (new edges past the threshold)
  std::uint64_t edges_found = 0;        ///< spanning_forest: edges of the inserted points to older neighbours
  std::uint64_t edges_pruned = 0;       ///< spanning_forest: of those, dropped as redundant (prune_witnesses)
  std::uint64_t forest_displaced = 0;   ///< spanning_forest: kept forest edges a fold moved aside (detail::merge_forest)
  std::uint64_t edges_folded = 0;       ///< spanning_forest: new edges the folds read (those still live at their fold)
  std::uint64_t edges_accepted = 0;     ///< spanning_forest: of those, accepted into the forest (the rest closed cycles)
  std::uint64_t forest_edges = 0;       ///< spanning_forest: edges of the forest after this retrieval (window points - components)
  PhaseTimes phase_us{};                ///< timed configs only
};

/// The continuous clusterer: a sliding window over a point stream, a grid
/// index, a point graph of local clusters and a component graph of bridges.
///
/// Per accepted point (`insert`): points that left the window are evicted,
/// the point is projected to a grid cell, the w x w mask around it is
/// searched and every candidate passing the linkage becomes a neighbour.
/// No neighbour: a new local cluster (isolation). Neighbours in one cluster:
/// the point joins it (expansion). Neighbours in several: the point joins the
/// most recently created of them and each point-level edge to another
/// cluster adds one unit of multiplicity to the bridge between the two
/// clusters (bridging). Eviction removes the point from index and graph,
/// lowers the multiplicity of every bridge its edges carried (a bridge
/// disappears at zero) and marks its cluster pending when the point had two
/// or more edges inside its cluster (removing a vertex of degree <= 1 cannot
/// disconnect a graph). `retrieve()` validates pending clusters by BFS,
/// splitting disconnected ones, then labels the window by the connected
/// components of the component graph.
///
/// Stable ids: at each retrieval every component is matched to the ids its
/// clusters carried at the previous retrieval, weighted by their current
/// point counts. An old id goes to the component holding most of its points
/// (merge: the merged component keeps the id with the larger weight; split:
/// the largest part keeps the id); ties go to the older id. Components left
/// without an id get a fresh one; ids are never reused.
///
/// Connectivity (the optional `connectivity` slot): the above is the paper's
/// strategy (LazyBfsConnectivity, the default). With
/// UnionFindRebuildConnectivity insertion only stores edges, eviction only
/// drops the point, and `retrieve()` rebuilds the components by one
/// union-find pass over the live edges (O(N + E), whatever is pending).
/// Same partition; what differs: local clusters are the last retrieval's
/// components (no bridges; `cluster_of` is kNoCluster for points inserted
/// since), visitor hooks are not called, and in the stable-id rule each
/// point present at the previous retrieval votes with weight 1 (new points
/// do not vote) instead of clusters voting with their current size.
/// SpanningForestConnectivity behaves the same for users, but stores no
/// point-level edges: insertion appends the new edges to a list, and
/// `retrieve()` folds them into a maximum spanning forest of the window
/// (edge weight = older endpoint = expiry) by Kruskal, O(N + forest + new
/// edges) instead of O(N + E) (proof at `fold_forest`). Under it
/// `for_each_neighbor` and the back/forward edge accessors (hence the
/// Boost.Graph point view) do not compile (STREAMCLUST_NO_POINT_EDGES).
///
/// Input: `insert(p)` per point, or `insert_batch(packet)` per packet of
/// points (the same result; the points are projected and their mask cells
/// prefetched a few points ahead).
///
/// Time: monotone stream time in seconds. A point earlier than the previous
/// accepted one is rejected (`time_backwards`). Memory: 72 bytes per
/// windowed point (a 40-byte Sample and a 32-byte record, 12 bytes under
/// spanning_forest, in two rings with the same slots; 16 more in a third
/// ring when the linkage has a compact payload, and then only 24 bytes of
/// the Sample when the payload carries the ray, as the angular criterion's
/// does: 52 bytes for the C-ARC presets under spanning_forest; the rings
/// hold the peak window plus at most 1/8, not a power of two) plus
/// the index, plus the point graph: the paper's strategy and the rebuild keep
/// an edge ring of 12 bytes per edge, which holds an edge until its NEWER
/// endpoint leaves (about 14 live edges per point on a simulated Mid-360 at
/// w = 5, T_M = 2, and as many dead ones); the spanning forest keeps 8 bytes
/// per forest edge (< 1 per point) and per edge inserted since the last
/// fold (binned by the age of their older endpoint, so the fold needs no
/// sort buffer; see detail::AgeBands).
/// `memory_usage()` reports the parts. The point rings grow to the needed
/// size + 1/8, the edge ring by doubling, the scratch and result vectors
/// geometrically; none shrinks. Steady-state heap allocations: none with the capped grid
/// and a rebuilding strategy; a bucket-grid cell allocates when it first
/// exceeds its previous peak occupancy; the paper's strategy allocates bridge
/// lists.
///
/// Resolution: a policy that needs calibration (adaptive) makes the engine
/// buffer the first window unclustered. When a point arrives that completes
/// the window (time window: it is T_B or more after the first buffered
/// point; count window: it is the capacity-th), the grid is chosen from the
/// buffered points, they are inserted in their original order (no point is
/// lost; the paper clears them instead), and the new point follows.
/// Retrievals before that return an empty result and leave the calibration
/// running, so a client may retrieve at 20 Hz from the start without the
/// grid being chosen on 50 ms of data; `complete_calibration()` ends it
/// early on what is buffered (a stream shorter than one window).
///
/// Thread safety: none; drive one engine from one thread.
///
/// \code
/// #include <streamclust/streamclust.hpp>
/// streamclust::CArcParams params;          // C-ARC defaults from the paper
/// params.theta_deg = 30.0f;                // Livox Mid-360
/// auto engine = streamclust::make_carc(params);
/// for (const streamclust::Point& p : stream) {
///   engine.insert(p);                      // 200 kHz
///   if (publication_due()) {               // 10-20 Hz
///     const auto& result = engine.retrieve();
///     for (const auto& c : result.components_with_at_least(20)) use(c.id, c.centroid);
///   }
/// }
/// \endcode
template <class Config>
class StreamClusterer {
 public:
  using traits = config_traits<Config>;
  STREAMCLUST_CHECK_CONFIG(Config);

  using projection_type = typename traits::projection;
  using spatial_index_type = typename traits::spatial_index;
  using linkage_type = typename traits::linkage;
  using window_type = typename traits::window;
  using resolution_type = typename traits::resolution;
  using visitor_type = typename traits::visitor;
  using connectivity_type = typename traits::connectivity;
  using Params = ClustererParams<Config>;
  /// True for the strategies without local-cluster bookkeeping
  /// (union_find_rebuild, spanning_forest): the components are recomputed at
  /// each retrieval and become the local clusters.
  static constexpr bool rebuilds_components = connectivity_type::strategy != ConnectivityStrategy::lazy_bfs;
  /// True for ConnectivityStrategy::spanning_forest: a spanning forest of the
  /// window instead of stored point-level edges.
  static constexpr bool keeps_forest = connectivity_type::strategy == ConnectivityStrategy::spanning_forest;
  /// False under spanning_forest: the point-level edge accessors then do not compile.
  static constexpr bool stores_point_edges = !keeps_forest;
  /// True when the linkage has the compact payload (concepts/linkage.hpp):
  /// the engine then keeps a ring of payloads and the neighbour search reads
  /// it instead of the Samples.
  static constexpr bool uses_payload = has_linkage_payload_v<linkage_type>;
  /// The linkage's payload (`detail::NoPayload` without the capability).
  using payload_type = linkage_payload_t<linkage_type>;
  /// True when the payload carries the ray (`has_linkage_ray_payload_v`):
  /// the sample ring then keeps only position, intensity and time (24
  /// bytes), and `sample(h)` rebuilds the rest from the payload.
  static constexpr bool compact_samples = has_linkage_ray_payload_v<linkage_type>;
  /// True when the linkage tests one payload against many (`link_many`,
  /// concepts/linkage.hpp): the neighbour search then makes one call per
  /// point with all its candidates.
  static constexpr bool tests_many = has_linkage_link_many_v<linkage_type>;

  /// Throws std::invalid_argument when a parameter is out of range.
  explicit StreamClusterer(const Params& params = Params{}, visitor_type visitor = visitor_type{})
      : params_(params),
        projection_(params.projection),
        index_(params.spatial_index),
        linkage_(params.linkage),
        window_(params.window),
        resolution_(params.resolution),
        visitor_(std::move(visitor)),
        connectivity_(params.connectivity),
        half_(detail::checked_mask_half_width(params.mask_size)) {
    if (!resolution_.needs_calibration()) set_grid(resolution_.grid());
  }

  // ---------------------------------------------------------------- input

  /// Offers one point, its time read with `stamp(p)`. Returns why it was not
  /// inserted, or `accepted`. Every call advances the stream index.
  /// Amortised O(w^2 k + e) with k points per cell and e neighbours.
  template <class P>
  RejectReason insert(const P& p) {
    return insert(p, stamp(p));
  }

  /// Offers one point with an explicit stream time [s].
  template <class P>
  RejectReason insert(const P& p, double time) {
    static_assert(is_point_v<P>, "STREAMCLUST_POINT_TYPE_INVALID: specialise streamclust::point_traits for this type");
    return insert_position(position(p), intensity(p), time);
  }

  /// Offers the points of [first, last) in order: the same stream indexes,
  /// rejections and clusters as `insert(p)` on each, but faster on a batch
  /// such as a sensor packet (a Livox packet holds 96 points). Each point is
  /// projected, and its mask's index cells prefetched, kInsertLookahead
  /// points before it is linked, so those cache misses overlap the linking
  /// of the points before it. Returns the points accepted. Amortised as
  /// `insert` per point; no allocation of its own.
  template <class It>
  std::size_t insert_batch(It first, It last) {
    std::size_t accepted = 0;
    insert_each(first, last, [&accepted](RejectReason r) { accepted += r == RejectReason::accepted; });
    return accepted;
  }

  /// `insert_batch(first, last)` that also writes what `insert` would have
  /// returned for each point, in order, to `reasons` (an output iterator of
  /// RejectReason, e.g. a std::back_inserter, or a pointer to room for
  /// last - first values): for a driver that reports rejected records by
  /// their index. Returns `reasons` past the last value written.
  template <class It, class ReasonOut>
  ReasonOut insert_batch(It first, It last, ReasonOut reasons) {
    insert_each(first, last, [&reasons](RejectReason r) { *reasons++ = r; });
    return reasons;
  }

  /// `insert_batch` over a range of points (a std::vector, a span, a view).
  template <class Range>
  std::size_t insert_batch(const Range& points) {
    using std::begin;
    using std::end;
    return insert_batch(begin(points), end(points));
  }

  /// Sizes the engine now for windows of up to `window_points` points, so
  /// that a window growing up to that size later allocates nothing for its
  /// points: the point rings, the per-point vectors of the retrieval (which
  /// follow the rings' capacity at the next retrieval: labels, union-find,
  /// forest) and the spanning forest's band table (for a window plus as
  /// many new points between two folds). Without it they grow with the
  /// window, by 1/8 past each new maximum, which a scene that opens up can
  /// reach long after start-up. For a real-time loop that must not allocate
  /// once running: reserve the most points the window can hold, e.g. the
  /// sensor's point rate x T_B plus a margin. What grows with the edges and
  /// the components (edge storage, summaries, votes) still grows at its
  /// first peaks, as without it. Never shrinks. O(window_points + size());
  /// memory as `memory_usage()`'s point ring, result and scratch per point.
  void reserve(std::size_t window_points) {
    if (window_points > ring_capacity_) grow_rings(std::max<std::size_t>(window_points, kMinRingCapacity));
    if constexpr (keeps_forest) fresh_.reserve_span(2 * std::size_t{ring_capacity_});
  }

  /// Evicts the points that have left the window at stream time `time` [s]
  /// without inserting anything (a quiet sensor). A time earlier than the
  /// newest point's is ignored; later points earlier than `time` are then
  /// rejected as `time_backwards`. A time that completes the first window
  /// ends a running calibration.
  void advance_to(double time) {
    if (!std::isfinite(time) || (has_time_ && time < last_time_)) return;
    has_time_ = true;
    last_time_ = time;
    if (calibrating_) {
      if (size() > 0 && window_.complete(stored_time(oldest_), time, size())) finish_calibration();
      if (calibrating_) return;  // the first window is still filling: nothing expires
    }
    const auto t0 = clock_now();
    evict_expired(time, size());
    add_elapsed(stats_.phase_us.eviction, t0);
  }

  // ------------------------------------------------------------ retrieval

  /// Validates pending clusters, updates the component graph and labels every
  /// point in the window. May be called at any moment; while the first window
  /// is still buffered for calibration the result is empty (no labels yet,
  /// see `calibrating()`). O(N) for N points in the window plus the BFS over
  /// pending clusters. The reference stays valid until the next call.
  const Clustering& retrieve() {
    if (calibrating_) return empty_retrieval();
    const auto t0 = clock_now();
    if constexpr (rebuilds_components) {
      rebuild_components();
      add_elapsed(stats_.phase_us.component_update, t0);
    } else {
      validate_pending();
      add_elapsed(stats_.phase_us.validation, t0);
      label_components();
    }
    last_stats_ = stats_;
    stats_ = RetrievalStats{};
    return result_;
  }

  /// Ends the calibration now on the buffered points (e.g. at the end of a
  /// stream shorter than one window): the grid is chosen and the points are
  /// clustered. No-op when not calibrating or when nothing is buffered.
  void complete_calibration() {
    if (calibrating_ && size() > 0) finish_calibration();
  }

  /// The last retrieval's result.
  const Clustering& last_result() const { return result_; }
  /// Work done between the previous two retrievals.
  const RetrievalStats& last_stats() const { return last_stats_; }

  // ----------------------------------------------------------- inspection

  /// Points in the window.
  std::size_t size() const { return static_cast<std::uint32_t>(next_ - oldest_); }
  bool empty() const { return size() == 0; }
  /// Points offered so far; the next point's stream index is
  /// `params().first_stream_index + offered()`.
  std::uint64_t offered() const { return offered_; }
  const RejectionCounts& rejections() const { return rejections_; }
  /// True while the first window is buffered for the resolution policy.
  bool calibrating() const { return calibrating_; }
  /// The grid in use (zero-sized while calibrating).
  const GridShape& grid() const { return grid_; }
  const Params& params() const { return params_; }
  const projection_type& projection() const { return projection_; }
  const spatial_index_type& spatial_index() const { return index_; }
  const linkage_type& linkage() const { return linkage_; }
  const resolution_type& resolution() const { return resolution_; }
  visitor_type& visitor() { return visitor_; }
  const visitor_type& visitor() const { return visitor_; }
  const connectivity_type& connectivity() const { return connectivity_; }

  /// Heap footprint by part [bytes], as capacities (see MemoryUsage): what
  /// the engine holds, not what its window uses. The spatial index is
  /// counted when it has `heap_bytes()` (the standard grids do), otherwise
  /// reported unknown. O(clusters) plus the index's cost (O(cells) for the
  /// BucketGrid); allocates nothing.
  MemoryUsage memory_usage() const {
    MemoryUsage m;
    m.point_ring = capacity_bytes(samples_) + capacity_bytes(points_) + capacity_bytes(payloads_);
    m.edge_storage = capacity_bytes(edges_) + capacity_bytes(edge_older_) + capacity_bytes(forest_) +
                     fresh_.heap_bytes() + displaced_.heap_bytes();
    if constexpr (is_spatial_index_heap_reporting_v<spatial_index_type>) {
      m.spatial_index = static_cast<std::size_t>(index_.heap_bytes());
    } else {
      m.spatial_index_known = false;
    }
    m.clusters = capacity_bytes(clusters_) + capacity_bytes(free_clusters_) + capacity_bytes(pending_) +
                 capacity_bytes(cluster_size_);
    for (const Cluster& c : clusters_) m.clusters += capacity_bytes(c.bridges);
    m.scratch = capacity_bytes(neighbours_) + capacity_bytes(candidates_) + capacity_bytes(mask_cells_) +
                capacity_bytes(candidate_slots_) + capacity_bytes(link_flags_) + capacity_bytes(mask_at_) +
                capacity_bytes(candidate_cells_) +
                capacity_bytes(touched_) +
                capacity_bytes(order_) + capacity_bytes(fragment_begin_) + capacity_bytes(component_of_) +
                capacity_bytes(queue_) + capacity_bytes(component_ids_) + capacity_bytes(claims_) +
                capacity_bytes(parent_) + capacity_bytes(claim_head_) + capacity_bytes(votes_) +
                capacity_bytes(sums_) + capacity_bytes(won_weight_) + capacity_bytes(won_slot_) +
                capacity_bytes(by_slot_) + capacity_bytes(slot_of_);
    m.result = capacity_bytes(result_.points) + capacity_bytes(result_.components);
    return m;
  }

  /// Calls `f(const Sample&, std::uint64_t stream_index)` for every point in
  /// the window, oldest first. O(N).
  template <class F>
  void for_each_point(F&& f) const {
    for (PointHandle h = oldest_; h != next_; ++h) f(sample(h), stream_index(h));
  }

  // ------------------------------------------- low-level graph access
  // Used by the Boost.Graph adaptors in <streamclust/graph/...>; stable API.

  /// Handle of the point at window position `pos` (0 = oldest).
  PointHandle handle_at(std::size_t pos) const { return oldest_ + static_cast<PointHandle>(pos); }
  /// Window position of a live point.
  std::size_t position_of(PointHandle h) const { return static_cast<PointHandle>(h - oldest_); }
  /// True when `h` is in the window.
  bool is_live(PointHandle h) const { return static_cast<PointHandle>(h - oldest_) < size(); }
  /// The Sample of a live point, by value (40 bytes): with `compact_samples`
  /// it is rebuilt from the stored position, intensity and time and the
  /// payload's ray, equal bit for bit to the Sample inserted. O(1).
  Sample sample(PointHandle h) const {
    const std::uint32_t slot = ring_slot(h);
    if constexpr (compact_samples) {
      const StoredSample& stored = samples_[slot];
      Sample s;
      s.position = stored.position;
      s.intensity = stored.intensity;
      s.time = stored.time;
      linkage_type::restore_ray(payloads_[slot], s);
      return s;
    } else {
      return samples_[slot];
    }
  }
  /// The linkage payload of a live point (only with a payload linkage,
  /// `uses_payload`): `linkage_type::make_payload(sample(h))`.
  /// (A template so that explicit instantiations of the engine skip it.)
  template <bool Enabled = uses_payload>
  const payload_type& payload(PointHandle h) const {
    static_assert(Enabled, "StreamClusterer::payload: the linkage has no compact payload");
    return payloads_[ring_slot(h)];
  }
  /// Stream index of a live point (rejected points counted). O(1) (O(e)
  /// with e the 2^32-offer epochs the window spans, 1 unless it spans more
  /// than 4,294,967,296 offered points).
  std::uint64_t stream_index(PointHandle h) const {
    return (std::uint64_t{stream_epoch_high(h)} << 32) | point(h).stream_index_low;
  }
  /// Distinct high 32-bit words among the stream indexes of the window
  /// (plus the last one seen when the window is empty): 1 unless the window
  /// straddles a multiple of 2^32 offered points. O(1).
  std::size_t stream_epochs() const { return stream_epochs_.size(); }
  /// Local cluster of a live point (kNoCluster while calibrating; with
  /// union_find_rebuild or spanning_forest, also for a point inserted after
  /// the last retrieval).
  ClusterId cluster_of(PointHandle h) const {
    const ClusterId c = point(h).cluster;
    return c == kUnlabelled ? kNoCluster : c;
  }
  /// Calls `f(PointHandle)` for every live neighbour of live point `h`.
  /// O(degree). Not available under spanning_forest (no point-level edges).
  template <class F>
  void for_each_neighbor(PointHandle h, F&& f) const {
    static_assert(stores_point_edges, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    if constexpr (stores_point_edges) {  // only the assertion's error otherwise
      const PointRecord& r = point(h);
      for (std::uint32_t i = 0; i < r.back_count; ++i) {
        const PointHandle older = edge_older_at(r.back_begin + i);
        if (is_live(older)) f(older);
      }
      for (EdgeHandle e = r.fwd_head; e != kNoEdge; e = edge(e).next_fwd) f(edge(e).newer);
    }
  }
  /// Back edges of `h` (to older points, possibly dead) and the head of its
  /// forward list (to newer points, all live): the raw adjacency. Not
  /// available under spanning_forest.
  EdgeHandle back_edges_begin(PointHandle h) const {
    static_assert(stores_point_edges, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    if constexpr (stores_point_edges) {
      return point(h).back_begin;
    } else {
      return EdgeHandle{};
    }
  }
  std::uint32_t back_edges_count(PointHandle h) const {
    static_assert(stores_point_edges, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    if constexpr (stores_point_edges) {
      return point(h).back_count;
    } else {
      return std::uint32_t{};
    }
  }
  EdgeHandle forward_edges_head(PointHandle h) const {
    static_assert(stores_point_edges, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    if constexpr (stores_point_edges) {
      return point(h).fwd_head;
    } else {
      return EdgeHandle{};
    }
  }
  PointHandle edge_older(EdgeHandle e) const {
    static_assert(stores_point_edges, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    return edge_older_at(e);
  }
  PointHandle edge_newer(EdgeHandle e) const {
    static_assert(stores_point_edges, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    return edge(e).newer;
  }
  EdgeHandle edge_next_forward(EdgeHandle e) const {
    static_assert(stores_point_edges, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    return edge(e).next_fwd;
  }

  /// Size of the cluster table (live and recycled slots; rebuilding
  /// strategies: the last retrieval's components).
  std::size_t cluster_slots() const {
    if constexpr (rebuilds_components) {
      return cluster_size_.size();
    } else {
      return clusters_.size();
    }
  }
  bool cluster_alive(ClusterId c) const {
    if constexpr (rebuilds_components) {
      return c < cluster_size_.size() && cluster_size_[c] > 0;
    } else {
      return c < clusters_.size() && clusters_[c].alive;
    }
  }
  /// Live clusters. O(1); O(clusters) for the rebuilding strategies.
  std::size_t cluster_count() const {
    if constexpr (rebuilds_components) {
      return static_cast<std::size_t>(
          std::count_if(cluster_size_.begin(), cluster_size_.end(), [](std::uint32_t n) { return n > 0; }));
    } else {
      return clusters_.size() - free_clusters_.size();
    }
  }
  /// Points of a live cluster.
  std::size_t cluster_size(ClusterId c) const {
    if constexpr (rebuilds_components) {
      return cluster_size_[c];
    } else {
      return clusters_[c].size;
    }
  }
  /// Always false for the rebuilding strategies (nothing is validated lazily).
  bool cluster_pending(ClusterId c) const {
    if constexpr (rebuilds_components) {
      (void)c;
      return false;
    } else {
      return clusters_[c].pending;
    }
  }
  /// Bridge edges of cluster `c`: (other cluster, multiplicity = live
  /// point-level edges between the two). Valid until the next mutation.
  /// Always empty for the rebuilding strategies (no bridges).
  struct Bridge {
    ClusterId other;
    std::uint32_t multiplicity;
  };
  const std::vector<Bridge>& bridges(ClusterId c) const {
    if constexpr (rebuilds_components) {
      (void)c;
      return no_bridges_;
    } else {
      return clusters_[c].bridges;
    }
  }

 private:
  /// What the sample ring keeps of a Sample when the payload carries the
  /// ray (`compact_samples`). 24 bytes.
  struct SampleRest {
    Eigen::Vector3f position;  ///< sensor frame [m]
    float intensity;
    double time;  ///< [s]
  };
  static_assert(sizeof(SampleRest) == 24, "the compact sample is meant to stay 24 bytes");
  using StoredSample = std::conditional_t<compact_samples, SampleRest, Sample>;
  /// Position and time of a live point, read from the sample ring.
  const Eigen::Vector3f& stored_position(PointHandle h) const { return samples_[ring_slot(h)].position; }
  double stored_time(PointHandle h) const { return samples_[ring_slot(h)].time; }

  /// Per-point bookkeeping of the strategies that store point edges; the
  /// point's Sample is apart, in `samples_` (same slot), so the neighbour
  /// search reads a dense 40-byte-stride ring. 32 bytes.
  struct LinkedPointRecord {
    std::uint32_t stream_index_low = 0;  ///< low 32 bits of the stream index (see stream_epochs_)
    CellIndex cell = 0;
    ClusterId cluster = kNoCluster;
    PointHandle next_member = kNoPoint;  ///< next point of the same cluster, insertion order
    EdgeHandle back_begin = 0;           ///< first edge to an older neighbour
    std::uint32_t back_count = 0;
    EdgeHandle fwd_head = kNoEdge;  ///< newest edge from a newer neighbour
    std::uint32_t mark = 0;         ///< BFS epoch
  };
  static_assert(sizeof(LinkedPointRecord) == 32, "the linked point record is meant to stay 32 bytes");
  /// spanning_forest: no point edges, no member lists, no BFS. 12 bytes.
  struct ForestPointRecord {
    std::uint32_t stream_index_low = 0;  ///< low 32 bits of the stream index (see stream_epochs_)
    CellIndex cell = 0;
    ClusterId cluster = kNoCluster;
  };
  static_assert(sizeof(ForestPointRecord) == 12, "the forest's point record is meant to stay 12 bytes");
  /// The high 32 bits of the stream indexes from handle `first` on: the
  /// records keep the low 32 bits only (4 bytes per point instead of 8).
  struct StreamEpoch {
    PointHandle first;
    std::uint32_t high;
  };
  /// High 32 bits of live point `h`'s stream index: the newest epoch that
  /// starts at or before `h`. O(1) with one epoch (the window spans fewer
  /// than 2^32 offers at an epoch change: always, but for 4 billion rejected
  /// points in a row), O(epochs) otherwise. Invariant (kept by
  /// note_stream_epoch and evict_oldest): every epoch but the first starts
  /// at a live handle, so the modular distances below never alias (a
  /// rejection-free stream starts each epoch at the same handle value
  /// modulo 2^32).
  std::uint32_t stream_epoch_high(PointHandle h) const {
    std::size_t i = stream_epochs_.size() - 1;
    const auto back = static_cast<std::uint32_t>(next_ - h);  // handles appended since h, >= 1
    while (i > 0 && static_cast<std::uint32_t>(next_ - stream_epochs_[i].first) < back) --i;
    return stream_epochs_[i].high;
  }
  /// Records the epoch of point `h` (just appended: next_ == h + 1) when its
  /// high word differs from the last one, and forgets the epochs no live
  /// point needs (evict_oldest forgets them as the window moves on).
  /// Allocates only when the window spans a new maximum of epochs.
  void note_stream_epoch(PointHandle h, std::uint64_t stream_index) {
    const auto high = static_cast<std::uint32_t>(stream_index >> 32);
    if (!stream_epochs_.empty() && stream_epochs_.back().high == high) return;
    stream_epochs_.push_back(StreamEpoch{h, high});
    // epoch 1 starting at or before the oldest point: epoch 0 covers no live point
    const auto live = static_cast<std::uint32_t>(next_ - oldest_);
    while (stream_epochs_.size() >= 2 && static_cast<std::uint32_t>(next_ - stream_epochs_[1].first) >= live)
      stream_epochs_.erase(stream_epochs_.begin());
  }
  using PointRecord = std::conditional_t<stores_point_edges, LinkedPointRecord, ForestPointRecord>;
  struct EdgeRecord {  // the older endpoint is in edge_older_
    PointHandle newer = kNoPoint;
    EdgeHandle next_fwd = kNoEdge;  ///< next edge in `older`'s forward list
  };
  /// A local cluster of the paper's strategy (lazy_bfs). The rebuilding
  /// strategies keep none: their local clusters are the last retrieval's
  /// components: their sizes in `cluster_size_`, their places in the last
  /// result (which holds their ids) in `slot_of_`.
  struct Cluster {
    std::uint32_t size = 0;
    PointHandle head = kNoPoint;  ///< oldest member
    PointHandle tail = kNoPoint;  ///< newest member
    std::uint32_t result_slot = 0;  ///< place of its stable id's component in the last result (valid with stable_id)
    std::uint64_t created = 0;    ///< creation order, for the bridging rule
    ComponentId stable_id = kNoComponent;  ///< id of its component at the last retrieval
    bool alive = false;
    bool pending = false;
    std::vector<Bridge> bridges;
  };

  /// Cluster of a point linked since the last retrieval (union_find_rebuild
  /// and spanning_forest only).
  static constexpr ClusterId kUnlabelled = kNoCluster - 1;

  /// spanning_forest: an edge (older, newer) of the forest or of the new
  /// edges; the older endpoint is its expiry.
  using ForestEdge = detail::HandleEdge;
  /// Points ahead whose per-component records the retrieval's passes
  /// prefetch (rebuilding strategies) [points].
  static constexpr std::uint32_t kResultPrefetchDistance = 16;
  /// Components from which those passes prefetch: 4096 summaries are 288 KB.
  static constexpr std::uint32_t kResultPrefetchMinComponents = 4096;
  /// Points that `insert_batch` projects and prefetches ahead of the one it
  /// links [points].
  static constexpr std::size_t kInsertLookahead = 4;
  /// Gather room per mask cell for an index with unbounded cells [handles]
  /// (grown when a crowded mask needs more).
  static constexpr std::size_t kGatherCellRoom = 8;
  /// No cell found (yet).
  static constexpr CellIndex kNoCell = std::numeric_limits<CellIndex>::max();
  /// Evictions ahead whose index cell `evict_oldest` prefetches [points].
  static constexpr PointHandle kEvictPrefetchDistance = 8;
  /// Smallest point ring [slots].
  static constexpr std::size_t kMinRingCapacity = 1024;
  /// Points inserted between two folds at most, so that edge ages (newest
  /// handle - older endpoint) never wrap around 2^32.
  static constexpr PointHandle kMaxFoldSpan = PointHandle{1} << 30;

  PointRecord& point(PointHandle h) { return points_[ring_slot(h)]; }
  const PointRecord& point(PointHandle h) const { return points_[ring_slot(h)]; }
  /// Slot of a live handle (or of `next_`) in the point rings: h - origin,
  /// wrapped once. oldest_ - ring_origin_ < ring_capacity_ and the window
  /// holds at most ring_capacity_ points, so h - origin < 2 x capacity; all
  /// handle arithmetic is modulo 2^32. O(1), no division.
  static std::uint32_t ring_slot(PointHandle h, PointHandle origin, std::uint32_t capacity) {
    const std::uint32_t d = static_cast<std::uint32_t>(h - origin);
    return d >= capacity ? d - capacity : d;
  }
  std::uint32_t ring_slot(PointHandle h) const { return ring_slot(h, ring_origin_, ring_capacity_); }
  EdgeRecord& edge(EdgeHandle e) { return edges_[e & edge_mask_]; }
  const EdgeRecord& edge(EdgeHandle e) const { return edges_[e & edge_mask_]; }
  PointHandle& edge_older_at(EdgeHandle e) { return edge_older_[e & edge_mask_]; }
  PointHandle edge_older_at(EdgeHandle e) const { return edge_older_[e & edge_mask_]; }
  /// Records edge `e` from freshly linked point `h` to older neighbour `n`
  /// and threads it into `n`'s forward list.
  void store_edge(EdgeHandle e, PointHandle n, PointHandle h) {
    PointRecord& nr = point(n);
    edge_older_at(e) = n;
    edge(e) = EdgeRecord{h, nr.fwd_head};
    nr.fwd_head = e;
  }

  void set_grid(GridSize size) {
    if (size.rows == 0 || size.cols == 0) size = GridSize{1, 1};
    grid_ = GridShape{size.rows, size.cols, projection_.wraps_horizontally()};
    index_.reset(grid_);
    calibrating_ = false;
    if constexpr (has_spatial_index_cell_bound_v<spatial_index_type>) {
      // Bounded cells: the neighbour search's scratch gets its final size
      // now, so no later (denser) mask makes it grow in steady state.
      const auto width = static_cast<std::size_t>(2 * half_ + 1);
      const std::size_t most_candidates = width * width * index_.max_cell_size();
      candidates_.reserve(most_candidates);
      neighbours_.reserve(most_candidates);
      candidate_slots_.reserve(most_candidates);
      link_flags_.reserve(most_candidates);
      if constexpr (keeps_forest) candidate_cells_.reserve(most_candidates);
    }
  }

  RejectReason reject(RejectReason r) {
    ++rejections_[r];
    return r;
  }

  RejectReason insert_position(const Eigen::Vector3f& pos, float point_intensity, double time) {
    return insert_projected(pos, point_intensity, time, projection_.project(pos), kNoCell);
  }

  /// A point of `insert_batch` taken ahead of its turn: read, projected and,
  /// once the grid is known, its cell found and its mask prefetched.
  struct AheadPoint {
    Eigen::Vector3f position = Eigen::Vector3f::Zero();
    float intensity = 0.0f;
    double time = 0.0;
    Projected projected;
    CellIndex cell = kNoCell;  ///< kNoCell: not found yet (calibrating, or rejected)
  };

  template <class P>
  AheadPoint look_ahead(const P& p) {
    AheadPoint a;
    a.position = position(p);
    a.intensity = intensity(p);
    a.time = stamp(p);
    a.projected = projection_.project(a.position);
    if (a.projected.accepted() && !calibrating_) {
      a.cell = grid_.cell_of(a.projected.u, a.projected.v);
      if constexpr (has_spatial_index_prefetch_v<spatial_index_type>) {
        detail::for_each_mask_cell(grid_, a.cell, half_, [&](CellIndex c) { index_.prefetch(c); });
      }
    }
    return a;
  }

  /// The loop of `insert_batch`: inserts [first, last) with kInsertLookahead
  /// points projected and prefetched ahead, calling `on_reason(reason)` for
  /// each point in order.
  template <class It, class OnReason>
  void insert_each(It first, It last, OnReason&& on_reason) {
    static_assert(is_point_v<typename std::iterator_traits<It>::value_type>,
                  "STREAMCLUST_POINT_TYPE_INVALID: specialise streamclust::point_traits for this type");
    std::array<AheadPoint, kInsertLookahead> ahead;
    std::size_t queued = 0;
    It lead = first;
    for (; queued < kInsertLookahead && lead != last; ++queued, ++lead) ahead[queued] = look_ahead(*lead);
    for (std::size_t i = 0; first != last; ++first, ++i) {
      const std::size_t at = i % kInsertLookahead;
      const AheadPoint p = ahead[at];
      if (lead != last) {
        ahead[at] = look_ahead(*lead);
        ++lead;
      }
      on_reason(insert_projected(p.position, p.intensity, p.time, p.projected, p.cell));
    }
  }

  /// `insert` after the projection `pr` of `pos`; `known_cell` is pos's grid
  /// cell when found already, else kNoCell (the grid is fixed once chosen,
  /// so a cell found ahead stays valid).
  RejectReason insert_projected(const Eigen::Vector3f& pos, float point_intensity, double time, const Projected& pr,
                                CellIndex known_cell) {
    const std::uint64_t stream_index = params_.first_stream_index + offered_++;
    if (!std::isfinite(time)) return reject(RejectReason::non_finite);
    if (!pr.accepted()) return reject(pr.reason);
    if (has_time_ && time < last_time_) return reject(RejectReason::time_backwards);
    has_time_ = true;
    last_time_ = time;
    ++rejections_[RejectReason::accepted];

    if (calibrating_) {
      // Buffering the first window: nothing expires before it is complete
      // (expiry implies completeness), so no eviction here.
      if (size() > 0 && window_.complete(stored_time(oldest_), time, size() + 1)) {
        finish_calibration();  // on the complete first window; the new point is inserted below
      } else {
        append_point(pos, pr.range, point_intensity, time, stream_index);
        return RejectReason::accepted;
      }
    }
    // The mask is listed (and its index cells prefetched) before the
    // eviction, so those cache misses overlap the eviction's work.
    const CellIndex cell = known_cell != kNoCell ? known_cell : grid_.cell_of(pr.u, pr.v);
    list_mask_cells(cell);
    const auto t0 = clock_now();
    evict_expired(time, size() + 1);
    add_elapsed(stats_.phase_us.eviction, t0);
    const PointHandle h = append_point(pos, pr.range, point_intensity, time, stream_index);
    point(h).cell = cell;
    const auto t1 = clock_now();
    link(h);
    add_elapsed(stats_.phase_us.insertion, t1);
    return RejectReason::accepted;
  }

  /// Appends a point record (no index, no edges yet) to the ring.
  PointHandle append_point(const Eigen::Vector3f& pos, float range, float point_intensity, double time,
                           std::uint64_t stream_index) {
    reserve_points(size() + 1);
    const PointHandle h = next_++;
    PointRecord& r = point(h);
    const std::uint32_t slot = ring_slot(h);
    const Sample s = make_sample(pos, range, point_intensity, time);
    if constexpr (compact_samples) {
      samples_[slot] = SampleRest{s.position, s.intensity, s.time};
    } else {
      samples_[slot] = s;
    }
    if constexpr (uses_payload) payloads_[slot] = linkage_type::make_payload(s);
    r.stream_index_low = static_cast<std::uint32_t>(stream_index);
    note_stream_epoch(h, stream_index);
    r.cluster = kNoCluster;
    if constexpr (stores_point_edges) {
      r.next_member = kNoPoint;
      r.back_begin = next_edge_;
      r.back_count = 0;
      r.fwd_head = kNoEdge;
      r.mark = 0;
    }
    return h;
  }

  /// A retrieval while the first window is still buffered: no labels yet.
  const Clustering& empty_retrieval() {
    result_.time = last_time_;
    ++result_.cycle;
    result_.points.clear();
    result_.components.clear();
    last_stats_ = stats_;
    stats_ = RetrievalStats{};
    return result_;
  }

  /// Chooses the grid from the buffered first window, then inserts the
  /// buffered points into index and graph in their original order.
  void finish_calibration() {
    std::vector<Projected> coords;
    coords.reserve(size());
    for (PointHandle h = oldest_; h != next_; ++h) coords.push_back(projection_.project(stored_position(h)));
    set_grid(resolution_.calibrate(coords, projection_.fov_aspect()));
    std::size_t i = 0;
    replaying_ = true;
    if constexpr (keeps_forest) fresh_.reset(oldest_);  // no edge yet: the bands count from the window's start
    for (PointHandle h = oldest_; h != next_; ++h, ++i) {
      point(h).cell = grid_.cell_of(coords[i].u, coords[i].v);
      list_mask_cells(point(h).cell);
      link(h);
    }
    replaying_ = false;
    if constexpr (keeps_forest) {
      // And leaves no replayed edge to the next retrieval's fold, which
      // would otherwise carry them on top of the cycle's own.
      if (!fresh_.empty()) {
        fold_forest();
        ++stats_.forest_folds;
      }
    }
  }

  /// Lists the mask cells around `cell` into `mask_cells_` for the next
  /// `link` and, when the index offers it, prefetches them. O(w^2).
  void list_mask_cells(CellIndex cell) {
    const auto width = static_cast<std::size_t>(2 * half_ + 1);
    if (mask_cells_.size() < width * width) mask_cells_.resize(width * width);  // once: at most w^2 cells
    if constexpr (keeps_forest) {
      if (mask_at_.size() < width * width) mask_at_.resize(width * width);
    }
    CellIndex* const out = mask_cells_.data();
    MaskCellAt* const at = mask_at_.data();
    const bool with_at = keeps_forest && connectivity_prune_witnesses(connectivity_) != 0;  // only the filter reads them
    std::size_t n = 0;
    detail::for_each_mask_cell_at(grid_, cell, half_, [&](CellIndex c, std::int64_t row, std::int64_t col) {
      if (with_at) at[n] = MaskCellAt{static_cast<std::int32_t>(row), static_cast<std::int32_t>(col)};
      out[n++] = c;
      if constexpr (has_spatial_index_prefetch_v<spatial_index_type>) index_.prefetch(c);
    });
    mask_count_ = n;
  }

  /// Pass (2) of `link`: the handles of the listed mask cells into
  /// `candidates_[0, count)`, with their ring slots (`with_slots`) and mask
  /// cells (`pruning`), each candidate's payload or sample prefetched.
  /// Returns count. An index with `gather` is read cell by cell without a
  /// branch on the occupancy: the buffers stay sized to a room (w^2 K for
  /// bounded cells, at least w^2 kGatherCellRoom otherwise, grown when a
  /// crowded cell does not fit) and the stale handles past each cell's count
  /// are overwritten by the next cell's. O(w^2 k).
  std::size_t gather_candidates(bool pruning, bool with_slots) {
    const auto prefetch_candidate = [&](std::uint32_t slot) {
      if constexpr (uses_payload) {
        detail::prefetch(&payloads_[slot]);
      } else {
        detail::prefetch(&samples_[slot]);
      }
    };
    if constexpr (has_spatial_index_gather_v<spatial_index_type>) {
      constexpr bool bounded = has_spatial_index_cell_bound_v<spatial_index_type>;
      std::size_t per_cell = kGatherCellRoom;
      if constexpr (bounded) per_cell = index_.max_cell_size();
      const bool with_cells = keeps_forest && pruning;
      const auto grow = [&](std::size_t room) {  // O(room); once per grid, or when a crowded cell needs more
        candidates_.resize(room);
        if (with_slots) candidate_slots_.resize(room);
        if (with_cells) candidate_cells_.resize(room);
      };
      if (candidates_.size() < mask_count_ * per_cell) grow(mask_count_ * per_cell);  // reserved in set_grid when bounded
      if (with_slots && candidate_slots_.size() < candidates_.size()) candidate_slots_.resize(candidates_.size());
      if (with_cells && candidate_cells_.size() < candidates_.size()) candidate_cells_.resize(candidates_.size());
      std::size_t count = 0;
      for (std::size_t i = 0; i < mask_count_; ++i) {
        std::size_t n = 0;
        if constexpr (bounded) {  // n <= K, and K of room are left: count <= i K
          n = index_.gather(mask_cells_[i], candidates_.data() + count, per_cell);
        } else {
          const std::size_t room = candidates_.size() - count;
          n = index_.gather(mask_cells_[i], candidates_.data() + count, room);
          if (n > room) {  // a crowded cell: grow and gather it again
            grow(std::max(2 * candidates_.size(), count + n + mask_count_ * per_cell));
            n = index_.gather(mask_cells_[i], candidates_.data() + count, candidates_.size() - count);
          }
        }
        if constexpr (keeps_forest) {
          if (with_cells) std::fill_n(candidate_cells_.data() + count, n, static_cast<std::uint16_t>(i));
        }
        count += n;
      }
      const PointHandle* const cand = candidates_.data();
      std::uint32_t* const slots = candidate_slots_.data();
      const PointHandle origin = ring_origin_;
      const std::uint32_t ring_capacity = ring_capacity_;
      for (std::size_t k = 0; k < count; ++k) {
        const std::uint32_t slot = ring_slot(cand[k], origin, ring_capacity);
        if (with_slots) slots[k] = slot;
        prefetch_candidate(slot);
      }
      return count;
    } else {
      candidates_.clear();
      candidate_slots_.clear();
      if constexpr (keeps_forest) candidate_cells_.clear();
      for (std::size_t i = 0; i < mask_count_; ++i) {
        index_.for_each(mask_cells_[i], [&](PointHandle n) {
          const std::uint32_t slot = ring_slot(n);
          candidates_.push_back(n);
          if (with_slots) candidate_slots_.push_back(slot);
          if constexpr (keeps_forest) {
            if (pruning) candidate_cells_.push_back(static_cast<std::uint16_t>(i));
          }
          prefetch_candidate(slot);
        });
      }
      return candidates_.size();
    }
  }

  /// Finds the neighbours of freshly appended point `h`, records its edges
  /// and applies isolation, expansion or bridging. Requires
  /// `list_mask_cells(point(h).cell)` since the last link.
  void link(PointHandle h) {
    ++stats_.inserted;
    neighbours_.clear();
    {
      // Three passes, so that the cache misses overlap instead of stalling
      // one by one: (1) the caller listed the mask's cells and prefetched
      // them (list_mask_cells); (2) gather their handles, prefetching each
      // candidate's payload, or sample without one (scattered in the ring:
      // each is a likely miss); (3) test the linkage. A payload linkage reads
      // the dense 16-byte payload ring, the others the 40-byte Samples.
      // Ring slots are gathered for one test of many (link_many) and for the
      // redundant-edge filter (spanning_forest with prune_witnesses > 0),
      // mask cells for the filter only; else the test reads the slot itself.
      const bool pruning = connectivity_prune_witnesses(connectivity_) != 0;
      const bool with_slots = tests_many || pruning;
      const std::size_t count = gather_candidates(pruning, with_slots);
      // The linkage decisions with a branch-free compaction (whether a
      // candidate links is close to a coin flip: a branch on it would
      // mispredict often); with the filter, slots and mask cells are
      // compacted in place beside the neighbours.
      // Same capacity as candidates_: they grow only when they do.
      if (neighbours_.capacity() < candidates_.capacity()) neighbours_.reserve(candidates_.capacity());
      neighbours_.resize(count);
      PointHandle* const out = neighbours_.data();
      const PointHandle* const cand = candidates_.data();
      std::size_t found = 0;
      if (with_slots) {
        if (link_flags_.capacity() < candidates_.capacity()) link_flags_.reserve(candidates_.capacity());
        link_flags_.resize(count);
        test_links(ring_slot(h), candidate_slots_.data(), count, link_flags_.data());
        const std::uint8_t* const flags = link_flags_.data();
        if (keeps_forest && pruning) {
          std::uint32_t* const slots = candidate_slots_.data();
          std::uint16_t* const cells = candidate_cells_.data();
          for (std::size_t k = 0; k < count; ++k) {
            out[found] = cand[k];
            slots[found] = slots[k];
            cells[found] = cells[k];
            found += flags[k];
          }
          stats_.edges_found += found;
          found = prune_redundant_edges(h, found);
        } else {
          for (std::size_t k = 0; k < count; ++k) {
            out[found] = cand[k];
            found += flags[k];
          }
          stats_.edges_found += keeps_forest ? found : 0;
        }
      } else if constexpr (uses_payload) {
        const PointHandle origin = ring_origin_;
        const std::uint32_t ring_capacity = ring_capacity_;
        const payload_type s = payloads_[ring_slot(h, origin, ring_capacity)];  // a copy: the stores below cannot alias it
        const payload_type* const ring = payloads_.data();
        for (std::size_t k = 0; k < count; ++k) {
          out[found] = cand[k];
          found += linkage_(s, ring[ring_slot(cand[k], origin, ring_capacity)]) ? 1u : 0u;
        }
        stats_.edges_found += keeps_forest ? found : 0;
      } else {
        const PointHandle origin = ring_origin_;
        const std::uint32_t ring_capacity = ring_capacity_;
        const Sample& s = samples_[ring_slot(h, origin, ring_capacity)];
        const Sample* const ring = samples_.data();  // hoisted: the stores below cannot alias them
        for (std::size_t k = 0; k < count; ++k) {
          out[found] = cand[k];
          found += linkage_(s, ring[ring_slot(cand[k], origin, ring_capacity)]) ? 1u : 0u;
        }
        stats_.edges_found += keeps_forest ? found : 0;
      }
      neighbours_.resize(found);
      if constexpr (stores_point_edges) {
        for (const PointHandle n : neighbours_) detail::prefetch(&point(n));  // written when the edge is stored
      }
    }
    if constexpr (keeps_forest) {
      // Edges go to the bands of new edges, folded at the next retrieval.
      fresh_.append(neighbours_.data(), neighbours_.size(), h);
      PointRecord& r = point(h);
      r.cluster = kUnlabelled;  // labelled by the next retrieval
      index_.insert(r.cell, h);
      // Bound the new edges (memory) and the handle span since the last fold
      // (so that edge ages never wrap): fold without labelling.
      // The calibration replay links a whole window at once: it folds at the
      // threshold of a quarter window, so that it does not set the capacity
      // of fresh_ and forest_ (which never shrink) above what a cycle needs.
      const std::size_t threshold = connectivity_.fold_threshold(replaying_ ? size() / 4 : size());
      if (fresh_.size() > threshold || static_cast<PointHandle>(next_ - fold_mark_) >= kMaxFoldSpan) {
        fold_forest();
        ++stats_.forest_folds;
      }
    } else {
      link_stored_edges(h);
    }
  }

  /// flags[k] = whether the point in ring slot `subject` links to the one in
  /// ring slot `slots[k]`, for k < count: one `link_many` call when the
  /// linkage has it (vectorised), else the pairwise operator on payloads or
  /// Samples. O(count).
  void test_links(std::uint32_t subject, const std::uint32_t* slots, std::size_t count, std::uint8_t* flags) const {
    if constexpr (tests_many) {
      linkage_.link_many(payloads_[subject], payloads_.data(), slots, count, flags);
    } else if constexpr (uses_payload) {
      const payload_type s = payloads_[subject];  // a copy: the stores below cannot alias it
      const payload_type* const ring = payloads_.data();
      for (std::size_t k = 0; k < count; ++k) flags[k] = linkage_(s, ring[slots[k]]) ? 1u : 0u;
    } else {
      const Sample& s = samples_[subject];
      const Sample* const ring = samples_.data();
      for (std::size_t k = 0; k < count; ++k) flags[k] = linkage_(s, ring[slots[k]]) ? 1u : 0u;
    }
  }

  /// spanning_forest: drops from the first `found` entries of `neighbours_`
  /// (the neighbours of `h`, just found; their ring slots and mask cells in
  /// `candidate_slots_` and `candidate_cells_`) the edges the window's
  /// components can do without, for as long as they live; returns how many
  /// are kept (compacted to the front). O(found x witnesses).
  ///
  /// An edge (h, n), n older than h, lives until n leaves. If a neighbour y
  /// of h younger than n also has an edge (y, n), then while (h, n) lives so
  /// do (y, n) (same expiry, n) and h - y (expiry y, later): h and n stay
  /// connected through points no older than n at every moment. By induction
  /// on insertion that holds when (y, n) or (h, y) were dropped themselves
  /// (a dropped edge's endpoints are always joined by kept edges between
  /// points no older than its expiry), so the window's components, at every
  /// moment, and the folds (fold_forest's proof holds for any edge set with
  /// those components) do not change. The edge (y, n) exists iff n's cell
  /// was in y's mask (detail::MaskMembership), n was in the index when y was linked
  /// (an index holds a point from its insertion until it is removed for
  /// good, and n is in it now, after y's insertion) and the linkage accepts
  /// them. The witnesses y are the youngest neighbours, youngest first, up
  /// to SpanningForestConnectivity::Params::prune_witnesses; each is tested
  /// against the kept neighbours older than itself in one `test_links` call.
  std::size_t prune_redundant_edges(PointHandle h, std::size_t found) {
    const std::uint32_t witnesses = connectivity_prune_witnesses(connectivity_);
    PointHandle* const nb = neighbours_.data();
    std::uint32_t* const slots = candidate_slots_.data();
    std::uint16_t* const cells = candidate_cells_.data();
    std::uint8_t* const linked = link_flags_.data();  // free again: reused for the witness's decisions
    const MaskCellAt* const at = mask_at_.data();
    const detail::MaskMembership in_mask(grid_, half_);
    std::uint32_t witness_age = 0;  // the previous witness's age: the next one is older
    for (std::uint32_t w = 0; w < witnesses && found >= 2; ++w) {
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
      const MaskCellAt wy = at[cells[y]];
      test_links(slots[y], slots, found, linked);
      std::size_t kept = 0;
      for (std::size_t k = 0; k < found; ++k) {
        const MaskCellAt c = at[cells[k]];
        const bool older = static_cast<std::uint32_t>(h - nb[k]) > age;
        const bool redundant = older & in_mask(wy.row, wy.col, c.row, c.col) & (linked[k] != 0);
        nb[kept] = nb[k];
        slots[kept] = slots[k];
        cells[kept] = cells[k];
        kept += redundant ? 0u : 1u;
      }
      stats_.edges_pruned += found - kept;
      found = kept;
      witness_age = age;
    }
    return found;
  }

  /// link()'s second half for the strategies that store point edges: the
  /// edges go to the edge ring, then (lazy_bfs) isolation, expansion or
  /// bridging.
  void link_stored_edges(PointHandle h) {
    reserve_edges(neighbours_.size());
    PointRecord& r = point(h);
    r.back_begin = next_edge_;
    r.back_count = static_cast<std::uint32_t>(neighbours_.size());
    if constexpr (rebuilds_components) {
      for (const PointHandle n : neighbours_) {
        store_edge(next_edge_++, n, h);
      }
      r.cluster = kUnlabelled;  // labelled by the next retrieval
      index_.insert(r.cell, h);
      return;
    }
    touched_.clear();
    for (const PointHandle n : neighbours_) {
      store_edge(next_edge_++, n, h);
      const PointRecord& nr = point(n);
      auto it = std::find_if(touched_.begin(), touched_.end(),
                             [&](const Bridge& b) { return b.other == nr.cluster; });
      if (it == touched_.end()) {
        touched_.push_back(Bridge{nr.cluster, 1});
      } else {
        ++it->multiplicity;
      }
    }
    ClusterId target;
    if (touched_.empty()) {
      target = create_cluster();  // isolation
    } else {
      target = touched_.front().other;  // expansion, or bridging into the newest cluster
      for (const Bridge& t : touched_) {
        if (clusters_[t.other].created > clusters_[target].created) target = t.other;
      }
      for (const Bridge& t : touched_) {
        if (t.other != target) add_bridge(target, t.other, t.multiplicity, true);
      }
    }
    append_member(target, h);
    index_.insert(point(h).cell, h);  // a displaced point keeps its edges
  }

  ClusterId create_cluster() {
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
    visitor_.cluster_created(id);
    return id;
  }

  void append_member(ClusterId c, PointHandle h) {
    Cluster& cl = clusters_[c];
    PointRecord& r = point(h);
    r.cluster = c;
    r.next_member = kNoPoint;
    if (cl.tail == kNoPoint) {
      cl.head = h;
    } else {
      point(cl.tail).next_member = h;
    }
    cl.tail = h;
    ++cl.size;
  }

  void add_bridge(ClusterId a, ClusterId b, std::uint32_t multiplicity, bool notify) {
    auto& la = clusters_[a].bridges;
    auto it = std::find_if(la.begin(), la.end(), [&](const Bridge& x) { return x.other == b; });
    if (it != la.end()) {
      it->multiplicity += multiplicity;
      auto& lb = clusters_[b].bridges;
      std::find_if(lb.begin(), lb.end(), [&](const Bridge& x) { return x.other == a; })->multiplicity += multiplicity;
      return;
    }
    la.push_back(Bridge{b, multiplicity});
    clusters_[b].bridges.push_back(Bridge{a, multiplicity});
    if (notify) visitor_.clusters_merged(a, b);
  }

  static void lower_bridge_entry(std::vector<Bridge>& list, ClusterId other, std::uint32_t by) {
    auto it = std::find_if(list.begin(), list.end(), [&](const Bridge& x) { return x.other == other; });
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

  void evict_expired(double newest_time, std::size_t count) {
    while (size() > 0 && window_.expired(stored_time(oldest_), newest_time, count)) {
      evict_oldest();
      --count;
    }
  }

  void evict_oldest() {
    const PointHandle h = oldest_;
    PointRecord& r = point(h);
    if constexpr (has_spatial_index_prefetch_v<spatial_index_type>) {
      // The index cell of a later eviction: its line has long left L1/L2 (it
      // was last touched when that point was linked, a window ago).
      const PointHandle ahead = h + kEvictPrefetchDistance;
      if (static_cast<PointHandle>(ahead - oldest_) < size()) index_.prefetch(point(ahead).cell);
    }
    if constexpr (rebuilds_components) {
      if (r.cluster != kNoCluster) {
        ++stats_.evicted;
        index_.remove(r.cell, h);
        if (r.cluster < cluster_size_.size()) --cluster_size_[r.cluster];
      }
    } else if (r.cluster != kNoCluster) {
      ++stats_.evicted;
      index_.remove(r.cell, h);
      const ClusterId c = r.cluster;
      std::uint32_t intra_degree = 0;
      for (EdgeHandle e = r.fwd_head; e != kNoEdge; e = edge(e).next_fwd) {
        const ClusterId other = point(edge(e).newer).cluster;
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
        visitor_.cluster_evicted(c);
      } else if (intra_degree >= 2 && !cl.pending) {
        cl.pending = true;
        pending_.push_back(c);
      }
    }
    ++oldest_;
    // The next epoch starts at the new oldest point: the first covers no
    // live point. Dropping it now keeps every epoch but the first starting
    // at a live handle, which stream_epoch_high compares modulo 2^32.
    if (stream_epochs_.size() >= 2 && stream_epochs_[1].first == oldest_) stream_epochs_.erase(stream_epochs_.begin());
    if (static_cast<std::uint32_t>(oldest_ - ring_origin_) == ring_capacity_) ring_origin_ += ring_capacity_;
    if constexpr (stores_point_edges) oldest_edge_ = size() > 0 ? point(oldest_).back_begin : next_edge_;
  }

  void validate_pending() {
    for (std::size_t i = 0; i < pending_.size(); ++i) {
      const ClusterId c = pending_[i];
      if (!clusters_[c].alive || !clusters_[c].pending) continue;
      clusters_[c].pending = false;
      ++stats_.clusters_validated;
      stats_.points_validated += clusters_[c].size;
      validate(c);
    }
    pending_.clear();
  }

  std::uint32_t next_epoch() {
    if (++epoch_ == 0) {  // wrapped: clear all marks once every 2^32 BFS runs
      for (PointHandle h = oldest_; h != next_; ++h) point(h).mark = 0;
      epoch_ = 1;
    }
    return epoch_;
  }

  /// BFS over the intra-cluster edges of cluster `c`; splits it into its
  /// connected fragments. The largest fragment keeps the id. O(points + edges
  /// of c), plus bridge re-attribution for the new fragments.
  void validate(ClusterId c) {
    const std::uint32_t epoch = next_epoch();
    order_.clear();
    fragment_begin_.clear();
    for (PointHandle m = clusters_[c].head; m != kNoPoint; m = point(m).next_member) {
      if (point(m).mark == epoch) continue;
      fragment_begin_.push_back(order_.size());
      point(m).mark = epoch;
      order_.push_back(m);
      for (std::size_t q = fragment_begin_.back(); q < order_.size(); ++q) {
        for_each_neighbor(order_[q], [&](PointHandle n) {
          PointRecord& nr = point(n);
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
      if (fragment_begin_[f + 1] - fragment_begin_[f] > fragment_begin_[keeper + 1] - fragment_begin_[keeper]) keeper = f;
    }
    // Relabel the other fragments with new clusters.
    const ComponentId inherited = clusters_[c].stable_id;
    for (std::size_t f = 0; f < fragments; ++f) {
      if (f == keeper) continue;
      const ClusterId piece = create_cluster();
      clusters_[piece].stable_id = inherited;
      clusters_[piece].result_slot = clusters_[c].result_slot;
      for (std::size_t q = fragment_begin_[f]; q < fragment_begin_[f + 1]; ++q) point(order_[q]).cluster = piece;
      ++stats_.clusters_split;
    }
    // Rebuild the member lists in insertion order.
    PointHandle m = clusters_[c].head;
    clusters_[c].head = clusters_[c].tail = kNoPoint;
    clusters_[c].size = 0;
    while (m != kNoPoint) {
      const PointHandle next = point(m).next_member;
      append_member(point(m).cluster, m);
      m = next;
    }
    // Move the bridges carried by the new fragments' edges.
    for (std::size_t f = 0; f < fragments; ++f) {
      if (f == keeper) continue;
      const ClusterId piece = point(order_[fragment_begin_[f]]).cluster;
      for (std::size_t q = fragment_begin_[f]; q < fragment_begin_[f + 1]; ++q) {
        for_each_neighbor(order_[q], [&](PointHandle n) {
          const ClusterId other = point(n).cluster;
          if (other != piece) {
            lower_bridge(c, other, 1);
            add_bridge(piece, other, 1, false);
          }
        });
      }
      visitor_.cluster_split(c, piece);
    }
  }

  /// BFS over the component graph, stable-id assignment, then one pass over
  /// the window for labels and summaries. O(N + clusters + bridges) plus
  /// the claims' sort.
  void label_components() {
    const auto t0 = clock_now();
    const std::size_t slots = clusters_.size();
    reserve_geometric(component_of_, slots);
    component_of_.assign(slots, kNoCluster);
    std::uint32_t components = 0;
    for (ClusterId c = 0; c < slots; ++c) {
      if (!clusters_[c].alive || component_of_[c] != kNoCluster) continue;
      queue_.clear();
      queue_.push_back(c);
      component_of_[c] = components;
      for (std::size_t q = 0; q < queue_.size(); ++q) {
        for (const Bridge& b : clusters_[queue_[q]].bridges) {
          if (component_of_[b.other] == kNoCluster) {
            component_of_[b.other] = components;
            queue_.push_back(b.other);
          }
        }
      }
      ++components;
    }
    assign_stable_ids(components);
    add_elapsed(stats_.phase_us.component_update, t0);
    write_result(components);
    // The clusters carry their component's id and place to the next retrieval.
    for (ClusterId c = 0; c < slots; ++c) {
      Cluster& cl = clusters_[c];
      if (!cl.alive) continue;
      const std::uint32_t r = slot_of_[component_of_[c]];
      cl.stable_id = result_.components[r].id;
      cl.result_slot = r;
    }
  }

  /// Labels and summaries of every window point from `component_of_` and
  /// `won_slot_` (lazy_bfs). O(N + components).
  void write_result(std::uint32_t components) {
    const auto t1 = clock_now();
    const auto previous = static_cast<std::uint32_t>(result_.components.size());
    begin_result(components, previous);
    order_components(components, previous);
    std::size_t labelled = 0;
    for (PointHandle h = oldest_; h != next_; ++h) {
      const PointRecord& r = point(h);
      if (r.cluster == kNoCluster) continue;  // only while calibrating
      add_to_result(labelled++, slot_of_[component_of_[r.cluster]], h, stream_index(h));
    }
    result_.points.resize(labelled);
    finish_summaries(components);
    add_elapsed(stats_.phase_us.labelling, t1);
  }

  /// Room for every window point's label and `components` summaries; the
  /// previous result's summaries stay (order_components reads their ids and
  /// then clears them). O(1) amortised: the vectors only grow, and no
  /// element is filled here.
  void begin_result(std::uint32_t components, std::uint32_t previous) {
    result_.time = last_time_;
    ++result_.cycle;
    reserve_window(result_.points, size());
    result_.points.resize(size());
    reserve_geometric(result_.components, std::max(components, previous));
    result_.components.resize(std::max(components, previous));
    reserve_geometric(sums_, components);
    sums_.resize(components);
  }

  /// The result order, without a comparison sort, and empty summaries
  /// carrying the ids. Requires `begin_result` and per component `k` the
  /// place in the previous result (`previous` components, still in
  /// `result_.components`) of the old id it kept in `won_slot_[k]`
  /// (kNoSlot: none). The kept ids come first, in their previous order (the
  /// previous result was sorted by id), then the fresh ids, handed out here
  /// in component order: they exceed every id handed out before. Leaves
  /// `slot_of_[k]` = the place of component `k`. O(components + previous).
  void order_components(std::uint32_t components, std::uint32_t previous) {
    index_kept_places(components, previous);
    ComponentSummary* const summaries = result_.components.data();
    const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
    std::uint32_t placed = 0;
    // Compaction in place: place `placed` <= s, whose old id was read already.
    for (std::uint32_t s = 0; s < previous; ++s) {
      const std::uint32_t k = by_slot_[s];
      if (k == kNoSlot) continue;
      const ComponentId id = summaries[s].id;
      slot_of_[k] = placed;
      summaries[placed] = ComponentSummary{};
      summaries[placed].id = id;
      sums_[placed++] = zero;
    }
    for (std::uint32_t k = 0; k < components; ++k) {
      if (won_slot_[k] != kNoSlot) continue;
      slot_of_[k] = placed;
      summaries[placed] = ComponentSummary{};
      summaries[placed].id = next_component_id_++;
      sums_[placed++] = zero;
    }
    result_.components.resize(components);
  }

  /// `by_slot_[s]` = the component that kept the id at place `s` of the
  /// previous result (kNoSlot: none), from `won_slot_`; `slot_of_` sized
  /// for `components`. O(components + previous).
  void index_kept_places(std::uint32_t components, std::uint32_t previous) {
    reserve_geometric(by_slot_, previous);
    by_slot_.assign(previous, kNoSlot);
    for (std::uint32_t k = 0; k < components; ++k) {
      if (won_slot_[k] != kNoSlot) by_slot_[won_slot_[k]] = k;
    }
    reserve_geometric(slot_of_, components);
    slot_of_.resize(components);
  }

  /// Writes the label of point `h` (window order `i`) and adds it to the
  /// summary at place `slot`. O(1).
  void add_to_result(std::size_t i, std::uint32_t slot, PointHandle h, std::uint64_t stream_index) {
    ComponentSummary& s = result_.components[slot];
    result_.points[i] = PointLabel{stream_index, s.id};
    const StoredSample& sa = samples_[ring_slot(h)];  // position and time only
    const Eigen::Vector3f& p = sa.position;
    if (s.size == 0) {
      s.min = s.max = p;
      s.time_begin = sa.time;
    } else {
      s.min = s.min.cwiseMin(p);
      s.max = s.max.cwiseMax(p);
    }
    s.time_end = sa.time;
    sums_[slot] += p.template cast<double>();
    ++s.size;
  }

  /// The centroids, from the sums. O(components).
  void finish_summaries(std::uint32_t components) {
    for (std::uint32_t r = 0; r < components; ++r) {
      ComponentSummary& s = result_.components[r];
      if (s.size > 0) s.centroid = (sums_[r] / static_cast<double>(s.size)).template cast<float>();
    }
  }

  // Phase timing, compiled away unless the config is `timed`.
  struct NoClock {};
  static auto clock_now() {
    if constexpr (traits::timed) {
      return std::chrono::steady_clock::now();
    } else {
      return NoClock{};
    }
  }
  template <class T>
  static void add_elapsed(double& microseconds, const T& since) {
    if constexpr (traits::timed) {
      microseconds += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - since).count();
    } else {
      (void)microseconds;
      (void)since;
    }
  }

  struct Claim {
    std::uint32_t component;
    ComponentId id;
    std::uint64_t weight;
  };
  /// One (new component, old cluster) pair of the rebuilding strategies'
  /// per-point votes; the old cluster is the list it is chained in. The
  /// weight counts points, at most the window size (< 2^32).
  struct Vote {
    std::uint32_t component;
    std::uint32_t weight;
    std::uint32_t next;  ///< next vote of the same old cluster
  };
  /// No place in the last result / no vote.
  static constexpr std::uint32_t kNoSlot = std::numeric_limits<std::uint32_t>::max();
  /// claim_head_ of an old cluster with one point left, before it voted.
  static constexpr std::uint32_t kSoleMark = kNoSlot - 1;
  /// claim_head_ = kSoleVote + k: that one point voted for component k
  /// (components and votes stay below 2^31: fewer than 2^31 window points).
  static constexpr std::uint32_t kSoleVote = std::uint32_t{1} << 31;

  /// lazy_bfs: the old ids claimed by the clusters, weighted by their
  /// current size, resolved by `resolve_claims`; fills `component_ids_`
  /// (kNoComponent: fresh, handed out by `order_components`) and `won_slot_`.
  void assign_stable_ids(std::uint32_t components) {
    claims_.clear();
    for (ClusterId c = 0; c < clusters_.size(); ++c) {
      const Cluster& cl = clusters_[c];
      if (cl.alive && cl.stable_id != kNoComponent) claims_.push_back(Claim{component_of_[c], cl.stable_id, cl.size});
    }
    resolve_claims(components);
    // A kept id's place in the previous result: the clusters that carry it
    // (the pieces of one old component share it) all know it.
    reserve_geometric(won_slot_, components);
    won_slot_.assign(components, kNoSlot);
    for (ClusterId c = 0; c < clusters_.size(); ++c) {
      const Cluster& cl = clusters_[c];
      if (!cl.alive || cl.stable_id == kNoComponent) continue;
      const std::uint32_t k = component_of_[c];
      if (component_ids_[k] == cl.stable_id) won_slot_[k] = cl.result_slot;
    }
  }

  /// From `claims_` (component, old id, weight), possibly with repeated
  /// pairs: each old id goes to its heaviest claimant, each component keeps
  /// its heaviest old id; fills `component_ids_` (kNoComponent for the
  /// others). O(claims log claims).
  void resolve_claims(std::uint32_t components) {
    // Sum the weight of each (component, old id) pair.
    std::sort(claims_.begin(), claims_.end(), [](const Claim& a, const Claim& b) {
      return a.id != b.id ? a.id < b.id : a.component < b.component;
    });
    std::size_t merged = 0;
    for (std::size_t i = 0; i < claims_.size(); ++i) {
      if (merged > 0 && claims_[merged - 1].id == claims_[i].id && claims_[merged - 1].component == claims_[i].component) {
        claims_[merged - 1].weight += claims_[i].weight;
      } else {
        claims_[merged++] = claims_[i];
      }
    }
    claims_.resize(merged);
    // Each old id goes to its heaviest claimant (ties: lower component).
    std::sort(claims_.begin(), claims_.end(), [](const Claim& a, const Claim& b) {
      if (a.id != b.id) return a.id < b.id;
      return a.weight != b.weight ? a.weight > b.weight : a.component < b.component;
    });
    merged = 0;
    for (std::size_t i = 0; i < claims_.size(); ++i) {
      if (i == 0 || claims_[i].id != claims_[i - 1].id) claims_[merged++] = claims_[i];
    }
    claims_.resize(merged);
    // Each component keeps its heaviest old id (ties: the older id).
    std::sort(claims_.begin(), claims_.end(), [](const Claim& a, const Claim& b) {
      if (a.component != b.component) return a.component < b.component;
      return a.weight != b.weight ? a.weight > b.weight : a.id < b.id;
    });
    reserve_geometric(component_ids_, components);
    component_ids_.assign(components, kNoComponent);
    for (const Claim& cl : claims_) {
      if (component_ids_[cl.component] == kNoComponent) component_ids_[cl.component] = cl.id;
    }
  }

  // ------------------------------------ union_find_rebuild, spanning_forest

  /// Grows `v`'s capacity by at least half when it cannot hold `n` elements.
  /// The scratch and result vectors are assign()ed or resize()d to the
  /// window or component count; exact growth would reallocate at every new
  /// maximum (a trickle of allocations per cycle), this a few times in all.
  /// O(1) when `n` fits, else O(size).
  template <class T, class A>
  static void reserve_geometric(std::vector<T, A>& v, std::size_t n) {
    if (n > v.capacity()) v.reserve(std::max(n, v.capacity() + v.capacity() / 2));
  }

  /// Room in a per-window-point vector (labels, union-find) for `n` <=
  /// size() points: when it cannot hold them, the point rings' capacity.
  /// The window cannot outgrow the rings without them growing first, so
  /// these vectors allocate only after the rings did, never on a window
  /// that merely reaches a new maximum within them (geometric growth from
  /// an exact first size did, once in a few hundred cycles on the Livox
  /// streams), and hold at most the rings' 1/8 of slack.
  template <class T, class A>
  void reserve_window(std::vector<T, A>& v, std::size_t n) const {
    if (n > v.capacity()) v.reserve(std::max<std::size_t>(n, ring_capacity_));
  }

  /// union_find_rebuild: root of `x` (every parent older than its child),
  /// halving the path.
  std::uint32_t find_root(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }

  // spanning_forest: a union-find by rank with path halving over window
  // positions. parent_[x] < kRankedRoot: x's parent; >= kRankedRoot: x is a
  // root, the low bits its rank (< 32). Needs fewer than 2^31 window points
  // (a 2^31-point window would take more than 100 GiB).
  static constexpr std::uint32_t kRankedRoot = std::uint32_t{1} << 31;
  static constexpr std::uint32_t kMaxRank = 32;

  /// All `n` window positions as singletons of rank 0. O(n).
  void reset_ranked(std::uint32_t n) {
    reserve_window(parent_, n);
    parent_.assign(n, kRankedRoot);
  }

  /// Root of `x` in the ranked union-find, halving the path. Amortised
  /// near O(1): by rank, trees are at most log2(n) deep.
  std::uint32_t find_ranked(std::uint32_t x) {
    for (;;) {
      const std::uint32_t p = parent_[x];
      if (p >= kRankedRoot) return x;
      const std::uint32_t g = parent_[p];
      if (g >= kRankedRoot) return p;
      parent_[x] = g;
      x = g;
    }
  }

  /// Unites the sets of window positions `a` and `b` by rank. False when
  /// they were already one set. Amortised near O(1).
  bool unite_ranked(std::uint32_t a, std::uint32_t b) {
    std::uint32_t ra = find_ranked(a);
    std::uint32_t rb = find_ranked(b);
    if (ra == rb) return false;
    if (parent_[ra] < parent_[rb]) std::swap(ra, rb);  // ra: the higher rank
    if (parent_[ra] == parent_[rb]) ++parent_[ra];
    parent_[rb] = ra;
    return true;
  }

  /// Turns the ranked union-find into dense component numbers in order of
  /// each component's oldest point, as `number_components` does for the
  /// age-ordered one: afterwards parent_[i] is the component of window
  /// position i. Returns the number of components. O(n): one pass of finds
  /// (short after Kruskal's halving) that points every position at its
  /// root, then one pass in window order in which a root, until numbered,
  /// keeps the root flag and holds kMaxRank + its number once numbered.
  std::uint32_t number_ranked_components(std::uint32_t n) {
    for (std::uint32_t i = 0; i < n; ++i) {
      if (parent_[i] < kRankedRoot) parent_[i] = find_ranked(i);
    }
    constexpr std::uint32_t kNumbered = kRankedRoot + kMaxRank;
    std::uint32_t components = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t v = parent_[i];
      if (v >= kRankedRoot) {  // a root: numbered already by an older member, or the component's oldest point
        parent_[i] = v >= kNumbered ? v - kNumbered : components++;
      } else if (v < i) {  // the root was older: it holds its number now
        parent_[i] = parent_[v];
      } else {  // the root is younger: number it at its oldest point, i
        std::uint32_t& root = parent_[v];
        if (root < kNumbered) root = kNumbered + components++;
        parent_[i] = root - kNumbered;
      }
    }
    return components;
  }

  /// The union-find over window positions as `n` singletons. O(n).
  void reset_parents(std::uint32_t n) {
    reserve_window(parent_, n);
    parent_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) parent_[i] = i;
  }

  /// The retrieval of the strategies without local-cluster bookkeeping: the
  /// union-find of the window (ring pass or forest fold), dense component
  /// numbers, stable ids by per-point votes, then the local clusters become
  /// the components and the result is written. O(N + edges read) plus the claims.
  void rebuild_components() {
    const auto n = static_cast<std::uint32_t>(size());
    stats_.points_validated += n;
    if constexpr (keeps_forest) {
      fold_forest();
      adopt_components(n, number_ranked_components(n));
    } else {
      unite_ring_edges(n);
      adopt_components(n, number_components(n));
    }
  }

  /// union_find_rebuild: one union-find pass over the live edges (window
  /// order, so the edge ring is read sequentially; the root of a set is its
  /// oldest point). O(N + E).
  void unite_ring_edges(std::uint32_t n) {
    reset_parents(n);
    // The window's edges are [oldest_edge_, next_edge_), grouped by newer
    // endpoint in insertion order: stream them. When the newer endpoint
    // changes it is still a singleton (no earlier edge touches it).
    std::uint32_t current = n;
    std::uint32_t root = n;
    for (EdgeHandle e = oldest_edge_; e != next_edge_; ++e) {
      const auto j = static_cast<std::uint32_t>(edge_older_at(e) - oldest_);
      if (j >= n) continue;  // the older endpoint has left the window
      const auto i = static_cast<std::uint32_t>(edge(e).newer - oldest_);
      if (i != current) current = root = i;
      const std::uint32_t rj = find_root(j);
      if (rj == root) continue;
      if (rj < root) {
        parent_[root] = rj;
        root = rj;
      } else {
        parent_[rj] = root;
      }
    }
  }

  /// Turns the union-find in `parent_` (every parent older than its child)
  /// into dense component numbers in order of each component's oldest
  /// point: afterwards parent_[i] is the component of window position i.
  /// Returns the number of components. O(N), no find: in increasing order a
  /// non-root's parent already holds its component number.
  std::uint32_t number_components(std::uint32_t n) {
    std::uint32_t components = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t p = parent_[i];
      parent_[i] = p == i ? components++ : parent_[p];
    }
    return components;
  }

  /// From the component of every window position (`parent_`): the stable
  /// ids by per-point votes, the components as the new local clusters, the
  /// result. Two passes over the window: the votes (and the new local
  /// clusters), then the labels and summaries straight to their place in id
  /// order; between them, per component (the ids and their order, no sort)
  /// and per vote. O(N + components + votes).
  void adopt_components(std::uint32_t n, std::uint32_t components) {
    const auto t1 = clock_now();
    // The old clusters are the previous retrieval's components, at places
    // slot_of_[c] in the previous result, which holds their ids.
    const auto old_clusters = static_cast<std::uint32_t>(cluster_size_.size());
    // claim_head_[c]: kNoSlot while no point of old cluster c voted (none
    // is left: evicted entirely), else the head of c's list of votes. An old
    // cluster with one point left (most of them in a fragmented window: the
    // Avia office's single points) keeps no list: kSoleMark, then
    // kSoleVote + k once its point voted for component k, the whole claim.
    // (cluster_size_ counts the points still in the window: evict_oldest
    // decrements it.)
    reserve_geometric(claim_head_, old_clusters);
    claim_head_.resize(old_clusters);
    for (ClusterId c = 0; c < old_clusters; ++c) claim_head_[c] = cluster_size_[c] == 1 ? kSoleMark : kNoSlot;
    votes_.clear();
    if (votes_.capacity() == 0) reserve_first_votes(old_clusters);
    reserve_geometric(cluster_size_, components);
    cluster_size_.assign(components, 0);
    std::uint32_t multiple = 0;  // components of two or more points
    // Prefetch only when the per-cluster records outgrow the L1/L2 caches
    // (a fragmented window); otherwise it only costs instructions.
    const bool scattered_old = old_clusters >= kResultPrefetchMinComponents;
    for (std::uint32_t i = 0; i < n; ++i) {
      if (scattered_old && i + kResultPrefetchDistance < n) {
        const ClusterId ahead = point(oldest_ + i + kResultPrefetchDistance).cluster;
        if (ahead < old_clusters) detail::prefetch(&claim_head_[ahead]);
      }
      PointRecord& r = point(oldest_ + i);
      const ClusterId old = r.cluster;
      const std::uint32_t k = parent_[i];
      r.cluster = k;
      multiple += ++cluster_size_[k] == 2 ? 1u : 0u;
      if (old < old_clusters) {  // else inserted since the last retrieval
        std::uint32_t& head = claim_head_[old];
        if (head == kSoleMark) {
          head = kSoleVote + k;
        } else {
          vote(old, k);
        }
      }
    }
    // Stable ids: resolve_claims' rule in linear time. Each (component, old
    // cluster) pair is one vote and the old clusters carry distinct ids, so:
    // each old id goes to its heaviest vote (ties: the lower component), and
    // each component keeps the heaviest id it won (ties: the older id, that
    // is the lower place in the previous result, which is sorted by id); the
    // others get fresh ids (order_components). O(votes + components).
    reserve_geometric(won_weight_, components);
    won_weight_.resize(components);  // read only where an id was won
    reserve_geometric(won_slot_, components);
    won_slot_.assign(components, kNoSlot);
    for (ClusterId c = 0; c < old_clusters; ++c) {
      std::uint32_t best = claim_head_[c];
      if (best >= kSoleMark) continue;  // evicted entirely (kSoleMark cannot remain: its point voted)
      std::uint32_t k = 0;
      std::uint32_t w = 1;
      if (best >= kSoleVote) {
        k = best - kSoleVote;
      } else {
        for (std::uint32_t v = votes_[best].next; v != kNoSlot; v = votes_[v].next) {
          if (votes_[v].weight > votes_[best].weight ||
              (votes_[v].weight == votes_[best].weight && votes_[v].component < votes_[best].component)) {
            best = v;
          }
        }
        k = votes_[best].component;
        w = votes_[best].weight;
      }
      const std::uint32_t slot = slot_of_[c];
      if (won_slot_[k] == kNoSlot || w > won_weight_[k] || (w == won_weight_[k] && slot < won_slot_[k])) {
        won_weight_[k] = w;
        won_slot_[k] = slot;
      }
    }
    order_ids(components, old_clusters);
    result_.time = last_time_;
    ++result_.cycle;
    reserve_window(result_.points, n);
    result_.points.resize(n);
    reserve_geometric(result_.components, components);
    result_.components.resize(components);
    // A sum per component of two or more points only (few of them in a
    // fragmented window), numbered as the labels pass opens them: sum s of
    // component k is won_weight_[k], and its place in the result is
    // won_slot_[s] (both free once the ids are resolved).
    reserve_geometric(sums_, multiple);
    sums_.resize(multiple);
    std::uint32_t summed = 0;
    // Labels and summaries in window order. The components are numbered by
    // their oldest point (number_components, number_ranked_components), so a
    // point opens its component's summary exactly when its number is the
    // next one not seen yet: the first point writes the whole summary (no
    // zeroing pass before, no read of a stale one), the others update it. A
    // single point (most components of a fragmented window) is its own
    // centroid and needs no sum.
    ComponentSummary* const summaries = result_.components.data();
    PointLabel* const labels = result_.points.data();
    const ComponentId* const ids = component_ids_.data();
    const bool scattered = components >= kResultPrefetchMinComponents;
    std::uint32_t unseen = 0;  // the next component number to open
    for (std::uint32_t i = 0; i < n; ++i) {
      if (scattered && i + kResultPrefetchDistance < n) {
        // The summary's lines (72 bytes may straddle two) and sum: scattered
        // over the components, likely misses.
        const std::uint32_t ahead = slot_of_[parent_[i + kResultPrefetchDistance]];
        detail::prefetch(&summaries[ahead]);
        detail::prefetch(&summaries[ahead].time_end);
      }
      const PointHandle h = oldest_ + i;
      const std::uint32_t k = parent_[i];
      const std::uint32_t slot = slot_of_[k];
      const ComponentId id = ids[slot];
      labels[i] = PointLabel{stream_index(h), id};
      const StoredSample& sa = samples_[ring_slot(h)];  // position and time only
      const Eigen::Vector3f& p = sa.position;
      ComponentSummary& sm = summaries[slot];
      if (k == unseen) {
        ++unseen;
        sm.id = id;
        sm.size = 1;
        sm.min = p;
        sm.max = p;
        sm.centroid = p;  // (double(p) / 1) as float is p: final for a single point
        sm.time_begin = sa.time;
        sm.time_end = sa.time;
        if (cluster_size_[k] > 1) {
          won_weight_[k] = summed;
          won_slot_[summed] = slot;
          sums_[summed++] = p.template cast<double>();
        }
      } else {
        sm.min = sm.min.cwiseMin(p);
        sm.max = sm.max.cwiseMax(p);
        sm.time_end = sa.time;
        sums_[won_weight_[k]] += p.template cast<double>();
        ++sm.size;
      }
    }
    // The centroids of the components of two or more points.
    for (std::uint32_t sum = 0; sum < summed; ++sum) {
      ComponentSummary& sm = summaries[won_slot_[sum]];
      sm.centroid = (sums_[sum] / static_cast<double>(sm.size)).template cast<float>();
    }
    add_elapsed(stats_.phase_us.labelling, t1);
  }

  /// The first room for votes (adopt_components): one vote per (listed old
  /// cluster, component) pair met, a listed cluster being one of two or
  /// more points left; 1.05-1.75 per such cluster on the simulated Livox
  /// streams (the most where they are few: the Mid-360 office's 19 at T_B =
  /// 0.1 s), never more than their points. Room for two each, once;
  /// afterwards the votes grow only when they outgrow it (a reservation
  /// that followed the listed clusters grew with them: on the Avia office,
  /// 6,000 to 9,300 over 1,000 cycles while the votes stayed below 9,900).
  /// O(old clusters).
  void reserve_first_votes(std::uint32_t old_clusters) {
    std::size_t listed = 0;
    std::size_t listed_points = 0;
    for (ClusterId c = 0; c < old_clusters; ++c) {
      const std::uint32_t left = cluster_size_[c];
      listed += left > 1 ? 1u : 0u;
      listed_points += left > 1 ? left : 0u;
    }
    votes_.reserve(std::min(listed_points, 2 * listed + 64));
  }

  /// The rebuilding strategies' `order_components` on the ids alone: the
  /// last result's ids by place are in `component_ids_` (written here at the
  /// previous retrieval), so the 72-byte summaries are neither read nor
  /// zeroed. Requires `won_slot_`; leaves `slot_of_[k]` = the place of
  /// component `k` and `component_ids_[r]` = the id at place `r` (kept ids
  /// in their previous order, then fresh ones in component order, as
  /// `order_components`). O(components + previous), 12 bytes per component.
  void order_ids(std::uint32_t components, std::uint32_t previous) {
    index_kept_places(components, previous);
    reserve_geometric(component_ids_, std::max(components, previous));
    component_ids_.resize(std::max(components, previous));
    ComponentId* const ids = component_ids_.data();
    std::uint32_t placed = 0;
    // Compaction in place: place `placed` <= s, whose old id was read already.
    for (std::uint32_t s = 0; s < previous; ++s) {
      const std::uint32_t k = by_slot_[s];
      if (k == kNoSlot) continue;
      slot_of_[k] = placed;
      ids[placed++] = ids[s];
    }
    for (std::uint32_t k = 0; k < components; ++k) {
      if (won_slot_[k] != kNoSlot) continue;
      slot_of_[k] = placed;
      ids[placed++] = next_component_id_++;
    }
    component_ids_.resize(components);
  }

  /// One point of old cluster `old` votes for component `k`. O(votes of
  /// `old`), in practice O(1): the list is kept most recent first.
  void vote(ClusterId old, std::uint32_t k) {
    std::uint32_t before = kNoSlot;
    std::uint32_t v = claim_head_[old];
    while (v != kNoSlot && votes_[v].component != k) {
      before = v;
      v = votes_[v].next;
    }
    if (v == kNoSlot) {
      votes_.push_back(Vote{k, 1, claim_head_[old]});
      claim_head_[old] = static_cast<std::uint32_t>(votes_.size() - 1);
      return;
    }
    ++votes_[v].weight;
    if (before != kNoSlot) {
      // Move to front: the next points of `old` most likely vote the same
      // way. Without it, an old component that shed many small pieces made
      // each of its points walk past all their votes (O(N x pieces), 7 ms
      // per retrieval on the Mid-360 office).
      votes_[before].next = votes_[v].next;
      votes_[v].next = claim_head_[old];
      claim_head_[old] = v;
    }
  }

  /// spanning_forest: folds the edges inserted since the last fold
  /// (`fresh_`) into the forest (`forest_`) and leaves in `parent_` a
  /// ranked union-find over the window positions whose sets are the
  /// window's connected components (`number_ranked_components` numbers them).
  /// O(N + forest + new edges): the new edges sorted band by band (their
  /// age bands, detail::AgeBands), one merge, Kruskal with union by rank and
  /// path halving. (Hanging the younger root under the older, as the
  /// rebuild does, built long chains here: Kruskal takes the newest edges
  /// first, and the finds were 40 % of the fold.)
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
  /// their age bands (detail::AgeBands), which hand them back sorted one
  /// band at a time; the expired suffix of the forest is cut off, and
  /// detail::merge_forest runs Kruskal in place in `forest_`, whose capacity
  /// (at least the window) exceeds any forest of the window.
  void fold_forest() {
    const auto n = static_cast<std::uint32_t>(size());
    const PointHandle newest = next_ - 1;
    const auto age = [newest](const ForestEdge& e) { return static_cast<std::uint32_t>(newest - e.older); };
    reset_ranked(n);
    // The expired edges are a suffix (increasing age; ages do not wrap, see kMaxFoldSpan).
    forest_.erase(std::partition_point(forest_.begin(), forest_.end(), [&](const ForestEdge& e) { return age(e) < n; }),
                  forest_.end());
    reserve_window(forest_, n);  // room for any forest of the window: merge_forest's gap
    const PointHandle base = oldest_;
    const detail::MergeCounts counts =
        detail::merge_forest(forest_, fresh_, displaced_, oldest_, n, age, [&](const ForestEdge& e) {
          return unite_ranked(static_cast<std::uint32_t>(e.older - base), static_cast<std::uint32_t>(e.newer - base));
        });
    stats_.forest_displaced += counts.displaced;
    stats_.edges_folded += counts.new_read;
    stats_.edges_accepted += counts.new_accepted;
    stats_.forest_edges = forest_.size();
    fresh_.reset(oldest_);
    fold_mark_ = next_;
  }

  /// Grows the point rings so they can hold `needed` points: to needed +
  /// needed / 8 slots (at least kMinRingCapacity), not to a power of two, so
  /// a steady window of N points holds at most 1.125 N slots (a power of two
  /// held up to 2 N). The live points move to slots [0, size) and the origin
  /// to the oldest point. O(1) when `needed` fits, else O(size); a window
  /// growing from empty reallocates O(log N) times (factor 1.125).
  void reserve_points(std::size_t needed) {
    if (needed <= ring_capacity_) return;
    grow_rings(std::max<std::size_t>(needed + needed / 8, kMinRingCapacity));
  }

  /// Reallocates the point rings to `capacity` (> ring_capacity_) slots;
  /// the live points move to slots [0, size) and the origin to the oldest
  /// point. O(capacity).
  void grow_rings(std::size_t capacity) {
    std::vector<PointRecord> grown(capacity);
    std::vector<StoredSample> grown_samples(capacity);
    std::vector<payload_type> grown_payloads(uses_payload ? capacity : 0);  // no ring without a payload
    std::uint32_t slot = 0;
    for (PointHandle h = oldest_; h != next_; ++h, ++slot) {
      const std::uint32_t from = ring_slot(h);
      grown[slot] = points_[from];
      grown_samples[slot] = samples_[from];
      if constexpr (uses_payload) grown_payloads[slot] = payloads_[from];
    }
    points_.swap(grown);
    samples_.swap(grown_samples);
    payloads_.swap(grown_payloads);
    ring_capacity_ = static_cast<std::uint32_t>(capacity);
    ring_origin_ = oldest_;
  }

  /// Grows the edge ring so `extra` more edges fit.
  void reserve_edges(std::size_t extra) {
    const std::size_t needed = static_cast<std::uint32_t>(next_edge_ - oldest_edge_) + extra;
    if (needed <= edges_.size()) return;
    std::size_t capacity = std::max<std::size_t>(edges_.size() * 2, 4096);
    while (capacity < needed) capacity *= 2;
    std::vector<EdgeRecord> grown(capacity);
    std::vector<PointHandle> grown_older(capacity);
    const auto new_mask = static_cast<std::uint32_t>(capacity - 1);
    for (EdgeHandle e = oldest_edge_; e != next_edge_; ++e) {
      grown[e & new_mask] = edge(e);
      grown_older[e & new_mask] = edge_older_at(e);
    }
    edges_.swap(grown);
    edge_older_.swap(grown_older);
    edge_mask_ = new_mask;
  }

  Params params_;
  projection_type projection_;
  spatial_index_type index_;
  linkage_type linkage_;
  window_type window_;
  resolution_type resolution_;
  visitor_type visitor_;
  connectivity_type connectivity_;
  int half_;
  GridShape grid_{};
  bool calibrating_ = true;
  bool replaying_ = false;  // finish_calibration is linking the buffered window

  // Ring buffers of the window (same slots): live handles are [oldest_, next_).
  std::vector<StoredSample> samples_;  // Samples (what a payload-less linkage reads), or their rest (compact_samples)
  std::vector<PointRecord> points_;  // the bookkeeping
  std::vector<payload_type> payloads_;  // with a payload linkage: what it reads (16 bytes); else empty
  std::uint32_t ring_capacity_ = 0;  // slots of each point ring
  PointHandle ring_origin_ = 0;      // the handle in slot 0: oldest_ - ring_origin_ < ring_capacity_ (mod 2^32)
  PointHandle oldest_ = 0;
  PointHandle next_ = 0;
  // Ring buffer of edges, freed in the same FIFO order: live handles are [oldest_edge_, next_edge_).
  std::vector<EdgeRecord> edges_;        // newer endpoint and forward-list link
  std::vector<PointHandle> edge_older_;  // older endpoint, apart: the rebuild streams it alone
  std::uint32_t edge_mask_ = 0;
  EdgeHandle oldest_edge_ = 0;
  EdgeHandle next_edge_ = 0;

  std::vector<Cluster> clusters_;
  std::vector<ClusterId> free_clusters_;
  std::vector<ClusterId> pending_;
  std::uint64_t clusters_created_ = 0;
  ComponentId next_component_id_ = 0;

  std::uint64_t offered_ = 0;
  /// Epochs of the stream indexes of the live points, oldest first; never
  /// empty once a point was appended (see StreamEpoch).
  std::vector<StreamEpoch> stream_epochs_;
  bool has_time_ = false;
  double last_time_ = 0.0;
  RejectionCounts rejections_{};
  RetrievalStats stats_{};
  RetrievalStats last_stats_{};
  std::uint32_t epoch_ = 0;

  // Scratch buffers, reused so the steady state does not allocate.
  std::vector<PointHandle> neighbours_;
  std::vector<PointHandle> candidates_;
  std::vector<CellIndex> mask_cells_;  // the mask of the point being linked: [0, mask_count_)
  std::vector<std::uint32_t> candidate_slots_;  // the ring slot of each candidate
  std::vector<std::uint8_t> link_flags_;        // whether each candidate links (then: to the witness)
  struct MaskCellAt {
    std::int32_t row;
    std::int32_t col;
  };
  std::vector<MaskCellAt> mask_at_;             // spanning_forest: grid row and column of each mask cell
  std::vector<std::uint16_t> candidate_cells_;  // spanning_forest: the mask cell (place in mask_cells_) of each candidate
  std::size_t mask_count_ = 0;
  std::vector<Bridge> touched_;
  std::vector<PointHandle> order_;
  std::vector<std::size_t> fragment_begin_;
  std::vector<std::uint32_t> component_of_;
  std::vector<ClusterId> queue_;
  std::vector<ComponentId> component_ids_;  // lazy_bfs, per component: the old id it keeps, or kNoComponent; rebuilding: the last result's id per place
  std::vector<Claim> claims_;
  std::vector<std::uint32_t> parent_;       // rebuilding strategies: union-find, then component per point
  std::vector<std::uint32_t> claim_head_;   // rebuilding strategies: most recent vote per old cluster
  std::vector<Vote> votes_;
  std::vector<std::uint32_t> won_weight_;   // rebuilding strategies, per component: weight of the id it won, then the index of its sum
  std::vector<std::uint32_t> won_slot_;     // per component: the last result's place of the id it kept, or kNoSlot; then (rebuilding) per sum: its component's place
  std::vector<std::uint32_t> by_slot_;      // order_components: place in the previous result -> component
  std::vector<std::uint32_t> slot_of_;      // component -> place in the result (rebuilding: kept, per local cluster)
  std::vector<std::uint32_t> cluster_size_; // rebuilding strategies: points of each local cluster still in the window
  std::vector<Bridge> no_bridges_;          // rebuilding strategies: what bridges() returns (always empty)
  std::vector<Eigen::Vector3d> sums_;       // per component (rebuilding: per component of 2+ points): sum of the positions, for the centroid
  // spanning_forest: the maximum spanning forest of the window in Kruskal's
  // order (non-increasing older endpoint; expired edges form a suffix; during
  // a fold also the new forest, see fold_forest), the edges inserted since
  // the last fold by age band, and the fold's queue of displaced kept edges.
  std::vector<ForestEdge> forest_;
  detail::AgeBands fresh_;
  detail::RingQueue<ForestEdge> displaced_;
  PointHandle fold_mark_ = 0;  // next_ at the last fold
  Clustering result_;
};

}  // namespace streamclust
