// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// StreamClusterer: the continuous C-ARC engine (paper, section METHOD,
/// Algorithm 1), assembled from its parts.

#include <streamclust/acceptance.hpp>
#include <streamclust/clustering.hpp>
#include <streamclust/config.hpp>
#include <streamclust/engine/component_result.hpp>
#include <streamclust/engine/edge_ring.hpp>
#include <streamclust/engine/neighbour_search.hpp>
#include <streamclust/engine/point_ring.hpp>
#include <streamclust/engine/retrieval_stats.hpp>
#include <streamclust/engine/structure_ring.hpp>
#include <streamclust/grid_choice.hpp>
#include <streamclust/memory_usage.hpp>
#include <streamclust/point_traits.hpp>
#include <streamclust/types.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

/// The message of the point-level edge accessors under a connectivity
/// strategy without point edges (a macro: static_assert needs a literal).
#define STREAMCLUST_NO_POINT_EDGES_MESSAGE                                                                       \
  "STREAMCLUST_NO_POINT_EDGES: this engine's connectivity (e.g. SpanningForestConnectivity) stores no "        \
  "point-level edges; for_each_neighbor, the back/forward edge accessors and the Boost.Graph point view need " \
  "a strategy with stores_point_edges (LazyBfsConnectivity or UnionFindRebuildConnectivity)"

namespace streamclust {

/// The continuous clusterer: a sliding window over a point stream, a grid
/// index and a connectivity strategy that keeps the window's components.
///
/// Per accepted point (`insert`, Algorithm 1): the point is judged
/// (acceptance.hpp), points that left the window are evicted, the point is
/// projected to a grid cell, the w x w mask around it is searched and every
/// candidate passing the linkage becomes a neighbour (NeighbourSearch; a
/// crowded cell is read by its chain of linked points, CellChains); the
/// neighbours go to the connectivity strategy, then the point to the index.
/// `retrieve()` asks the strategy for the components, which it writes
/// through the one result writer (ComponentResult) with stable ids
/// (StableIdVotes): an old id goes to the component holding most of it
/// (merge: the larger part's id; split: the largest part keeps it); ties go
/// to the older id; new components get fresh ids, never reused.
///
/// Connectivity (the optional `connectivity` slot, concepts/connectivity.hpp):
/// LazyBfsConnectivity (the paper's, the default), UnionFindRebuildConnectivity
/// or SpanningForestConnectivity (the fastest): the same partition; they
/// differ in cost, in what the local clusters are and in whether point-level
/// edges can be walked (see each policy).
///
/// Input: `insert(p)` per point, or `insert_batch(packet)` per packet (the
/// same result; each point is projected and its mask cells prefetched a few
/// points ahead). Time: monotone stream time in seconds; a point earlier
/// than the previous accepted one is rejected (`time_backwards`).
///
/// Motion (the optional `motion` slot, concepts/motion.hpp): before
/// anything else a point is placed in the world at its capture time
/// (PosedMotion: sensor poses or a fixed mount); the linkage, the ground
/// model and the summaries see the world position, the projection sees the
/// ray from the sensor in world orientation (docs/design-decisions.md).
/// NoMotion (the default) leaves points in the sensor frame at no cost.
///
/// Structure (the optional `ground` slot, concepts/ground.hpp): each
/// accepted point is classed at insertion, from the window before it, as an
/// object point (clustered as above) or structure (ground, wall or ceiling: kept
/// in the window, in the result's `structure`, never linked). Points leave
/// the ground model with the window. The decisions are causal, so the
/// batch oracle replays them: it clusters the window's object points.
/// NoGround (the default) skips the stage.
///
/// Memory (`memory_usage()` by part): the point ring (PointRing: 40 bytes of
/// Sample, or 24 with a payload carrying the ray, sizeof(Payload) (16; 32
/// for a combinator's composed payload) with a payload linkage, 8 + the
/// strategy's PointState per point; the peak window
/// plus 1/8), the index, the strategy's edges (12 bytes per stored edge, or
/// 8 per forest and new edge for the spanning forest), the crowded-cell
/// chain starts (4 bytes per grid cell, with a bucket grid: CellChains),
/// scratch and result vectors that grow geometrically; none shrinks. `reserve(n)` sizes the
/// per-point parts up front.
///
/// Resolution: a policy that needs calibration (adaptive) makes the engine
/// buffer the first window unclustered. When a point arrives that completes
/// it (`window.complete(first, t, buffered + 1)`), the grid is chosen from
/// the buffered points (choose_grid), they are linked in their original
/// order (no point is lost; the paper clears them instead), and the new
/// point follows. Retrievals before that return an empty result;
/// `complete_calibration()` ends it early on what is buffered.
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
  using motion_type = typename traits::motion;
  using ground_type = typename traits::ground;
  /// True when the ground policy takes structure out of clustering.
  static constexpr bool removes_structure = ground_type::enabled;
  using Params = ClustererParams<Config>;
  /// The window's points, with the strategy's per-point state.
  using ring_type = PointRing<linkage_type, typename connectivity_type::PointState>;
  /// False when the strategy keeps no point-level edges: the edge accessors
  /// then do not compile.
  static constexpr bool stores_point_edges = connectivity_type::stores_point_edges;
  static constexpr bool uses_payload = ring_type::uses_payload;
  using payload_type = typename ring_type::payload_type;
  static constexpr bool compact_samples = ring_type::compact_samples;
  static constexpr bool tests_many = has_linkage_link_many_v<linkage_type>;
  using Bridge = ClusterBridge;

 private:
  using state_type = typename connectivity_type::template State<ring_type>;
  using Context = ConnectivityContext<ring_type, visitor_type, traits::timed>;
  using Clock = detail::PhaseClock<traits::timed>;
  static_assert(is_connectivity_state_v<state_type, Context>,
                "STREAMCLUST_CONNECTIVITY_POLICY_INVALID: the connectivity's State lacks a member the engine calls "
                "(see the table in concepts/connectivity.hpp)");

 public:
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
        motion_(params.motion),
        ground_(params.ground),
        search_(detail::checked_mask_half_width(params.mask_size), connectivity_prune_witnesses(connectivity_),
                params.crowded_cell_chains),
        state_(connectivity_),
        time_order_(params.time_order) {
    if (!resolution_.needs_calibration()) set_grid(choose_grid(resolution_, projection_, {}));
  }

  // ---------------------------------------------------------------- input

  /// Offers one point, its time read with `stamp(p)`. Returns why it was not
  /// inserted, or `accepted`. Every call advances the stream index.
  /// Amortised O(w^2 k + e) with k points per cell and e neighbours; a
  /// crowded cell whose chain the point links counts only its points older
  /// than the chain start, and its youngest (CellChains).
  template <class P>
  RejectReason insert(const P& p) {
    return insert(p, stamp(p));
  }

  /// Offers one point with an explicit stream time [s].
  template <class P>
  RejectReason insert(const P& p, double time) {
    static_assert(is_point_v<P>, "STREAMCLUST_POINT_TYPE_INVALID: specialise streamclust::point_traits for this type");
    return insert_prepared(prepare(position(p), intensity(p), time));
  }

  /// Offers the points of [first, last) in order: the same stream indexes,
  /// rejections and clusters as `insert(p)` on each, but faster on a packet
  /// (a Livox packet holds 96 points): each point is projected, and its
  /// mask's index cells prefetched, kInsertLookahead points before it is
  /// linked. Returns the points accepted. No allocation of its own.
  template <class It>
  std::size_t insert_batch(It first, It last) {
    std::size_t accepted = 0;
    insert_each(first, last, [&accepted](RejectReason r) { accepted += r == RejectReason::accepted; });
    return accepted;
  }

  /// `insert_batch(first, last)` that also writes what `insert` would have
  /// returned for each point, in order, to output iterator `reasons`.
  /// Returns `reasons` past the last value written.
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

  /// Sizes the engine now for windows of up to `window_points` points, so a
  /// window growing up to that size later allocates nothing for its points
  /// (the point ring, the per-point vectors of the retrieval, which follow
  /// the ring's capacity at the next retrieval, and the strategy's per-point
  /// tables). For a real-time loop: reserve the sensor's point rate x T_B
  /// plus a margin. What grows with the edges and the components still grows
  /// at its first peaks. Never shrinks. O(window_points + size()).
  void reserve(std::size_t window_points) {
    ring_.reserve(window_points);
    state_.reserve(ring_);
  }

  /// Evicts the points that have left the window at stream time `time` [s]
  /// without inserting anything (a quiet sensor). A time earlier than the
  /// newest point's is ignored; a time that completes the first window ends
  /// a running calibration.
  void advance_to(double time) {
    if (!time_order_.may_advance_to(time)) return;
    time_order_.advance(time);
    if constexpr (removes_structure) evict_structure(time);
    if (calibrating_) {
      if (size() > 0 && window_.complete(ring_.time(ring_.oldest()), time, size())) finish_calibration();
      if (calibrating_) return;  // the first window is still filling: nothing expires
    }
    const auto t0 = Clock::now();
    evict_expired(time, size());
    Clock::add_since(stats_.phase_us.eviction, t0);
  }

  // ------------------------------------------------------------ retrieval

  /// The components of the window: a label for every point and a summary
  /// per component. While the first window is buffered for calibration the
  /// result is empty (see `calibrating()`). O(N) plus the strategy's work.
  /// The reference stays valid until the next call.
  const Clustering& retrieve() {
    if (calibrating_) {
      result_.write_empty(time_order_.last());
    } else {
      Context ctx = context();
      state_.retrieve(ctx);
    }
    if constexpr (removes_structure) structure_.write(result_.structure());
    last_stats_ = stats_;
    stats_ = RetrievalStats{};
    return result_.result();
  }

  /// Ends the calibration now on the buffered points (e.g. at the end of a
  /// stream shorter than one window). No-op when not calibrating or when
  /// nothing is buffered.
  void complete_calibration() {
    if (calibrating_ && size() > 0) finish_calibration();
  }

  /// The last retrieval's result.
  const Clustering& last_result() const { return result_.result(); }
  /// Work done between the previous two retrievals.
  const RetrievalStats& last_stats() const { return last_stats_; }

  // ----------------------------------------------------------- inspection

  /// Points in the window.
  std::size_t size() const { return ring_.size(); }
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
  const motion_type& motion() const { return motion_; }
  const ground_type& ground() const { return ground_; }
  /// Structure points (ground, wall, ceiling) in the window.
  std::size_t structure_size() const { return structure_.size(); }

  /// Heap footprint by part [bytes], as capacities (MemoryUsage). The index
  /// is counted when it has `heap_bytes()`. Allocates nothing.
  MemoryUsage memory_usage() const {
    MemoryUsage m;
    m.point_ring = ring_.heap_bytes();
    if constexpr (is_spatial_index_heap_reporting_v<spatial_index_type>) {
      m.spatial_index = static_cast<std::size_t>(index_.heap_bytes());
    } else {
      m.spatial_index_known = false;
    }
    m.scratch = search_.heap_bytes() + result_.scratch_bytes();
    m.result = result_.heap_bytes();
    m.structure = ground_.heap_bytes() + structure_.heap_bytes();
    state_.add_memory(m);
    return m;
  }

  /// Calls `f(const Sample&, std::uint64_t stream_index)` for every object
  /// point in the window, oldest first. O(N).
  template <class F>
  void for_each_point(F&& f) const {
    for (PointHandle h = ring_.oldest(); h != ring_.next(); ++h) f(ring_.sample(h), ring_.stream_index(h));
  }

  /// Calls `f(const StructureEntry&)` for every structure point in the
  /// window, oldest first. O(structure points).
  template <class F>
  void for_each_structure_point(F&& f) const {
    structure_.for_each(f);
  }

  // ------------------------------------------- low-level graph access
  // Used by the Boost.Graph adaptors in <streamclust/graph/...>; stable API.

  /// Handle of the point at window position `pos` (0 = oldest).
  PointHandle handle_at(std::size_t pos) const { return ring_.oldest() + static_cast<PointHandle>(pos); }
  /// Window position of a live point.
  std::size_t position_of(PointHandle h) const { return static_cast<PointHandle>(h - ring_.oldest()); }
  bool is_live(PointHandle h) const { return ring_.is_live(h); }
  /// The Sample of a live point, by value, equal bit for bit to the one inserted. O(1).
  Sample sample(PointHandle h) const { return ring_.sample(h); }
  /// The linkage payload of a live point (only with a payload linkage).
  template <bool Enabled = uses_payload>
  const payload_type& payload(PointHandle h) const {
    static_assert(Enabled, "StreamClusterer::payload: the linkage has no compact payload");
    return ring_.payload(h);
  }
  /// Stream index of a live point (rejected points counted). O(1).
  std::uint64_t stream_index(PointHandle h) const { return ring_.stream_index(h); }
  /// Distinct high 32-bit words among the window's stream indexes. O(1).
  std::size_t stream_epochs() const { return ring_.stream_epochs(); }
  /// Local cluster of a live point (kNoCluster while calibrating; with a
  /// rebuilding strategy, also for a point inserted after the last retrieval).
  ClusterId cluster_of(PointHandle h) const { return state_.cluster_of(ring_, h); }

  /// Calls `f(PointHandle)` for every live neighbour of live point `h`.
  /// O(degree). Needs a strategy with point edges.
  template <class F>
  void for_each_neighbor(PointHandle h, F&& f) const {
    static_assert(stores_point_edges, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    if constexpr (stores_point_edges) state_.edges().for_each_neighbor(ring_, h, f);
  }
  /// The raw adjacency: back edges of `h` (to older points, possibly dead)
  /// and the head of its forward list (to newer points, all live).
  template <bool Enabled = stores_point_edges>
  EdgeHandle back_edges_begin(PointHandle h) const {
    static_assert(Enabled, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    return ring_.record(h).state.links.back_begin;
  }
  template <bool Enabled = stores_point_edges>
  std::uint32_t back_edges_count(PointHandle h) const {
    static_assert(Enabled, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    return ring_.record(h).state.links.back_count;
  }
  template <bool Enabled = stores_point_edges>
  EdgeHandle forward_edges_head(PointHandle h) const {
    static_assert(Enabled, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    return ring_.record(h).state.links.fwd_head;
  }
  template <bool Enabled = stores_point_edges>
  PointHandle edge_older(EdgeHandle e) const {
    static_assert(Enabled, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    return state_.edges().ring().older(e);
  }
  template <bool Enabled = stores_point_edges>
  PointHandle edge_newer(EdgeHandle e) const {
    static_assert(Enabled, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    return state_.edges().ring().newer(e);
  }
  template <bool Enabled = stores_point_edges>
  EdgeHandle edge_next_forward(EdgeHandle e) const {
    static_assert(Enabled, STREAMCLUST_NO_POINT_EDGES_MESSAGE);
    return state_.edges().ring().next_forward(e);
  }

  /// The local clusters, as the strategy keeps them (rebuilding strategies:
  /// the last retrieval's components, never pending, without bridges).
  std::size_t cluster_slots() const { return state_.cluster_slots(); }
  bool cluster_alive(ClusterId c) const { return state_.cluster_alive(c); }
  std::size_t cluster_count() const { return state_.cluster_count(); }
  std::size_t cluster_size(ClusterId c) const { return state_.cluster_size(c); }
  bool cluster_pending(ClusterId c) const { return state_.cluster_pending(c); }
  /// Bridges of cluster `c`: (other cluster, multiplicity = live point-level
  /// edges between the two). Valid until the next mutation.
  const std::vector<Bridge>& bridges(ClusterId c) const { return state_.bridges(c); }

 private:
  /// No cell found (yet).
  static constexpr CellIndex kNoCell = std::numeric_limits<CellIndex>::max();
  /// Points that `insert_batch` projects and prefetches ahead of the one it
  /// links [points].
  static constexpr std::size_t kInsertLookahead = 4;
  /// Evictions ahead whose index cell `evict_oldest` prefetches [points].
  static constexpr PointHandle kEvictPrefetchDistance = 8;

  Context context() { return Context{ring_, visitor_, stats_, result_, next_component_id_, time_order_.last()}; }

  void set_grid(const GridShape& grid) {
    grid_ = grid;
    index_.reset(grid_);
    search_.set_grid(grid_, index_);
    calibrating_ = false;
  }

  /// A point placed and projected, ahead of its turn or not: its world
  /// position, the ray the projection saw, the projection and, once the grid
  /// is known and the point accepted, its cell (else kNoCell).
  struct Prepared {
    Eigen::Vector3f world = Eigen::Vector3f::Zero();
    Eigen::Vector3f ray = Eigen::Vector3f::Zero();
    float intensity = 0.0f;
    double time = 0.0;
    Projected projected;
    CellIndex cell = kNoCell;
  };

  /// Places the point (motion policy) and projects its ray. O(1) amortised.
  Prepared prepare(const Eigen::Vector3f& pos, float point_intensity, double time) {
    Prepared a;
    a.intensity = point_intensity;
    a.time = time;
    if constexpr (motion_type::identity) {
      a.world = pos;
      a.ray = pos;
      a.projected = projection_.project(pos);
    } else {
      const auto t0 = Clock::now();
      PlacedPoint placed;
      const RejectReason placement =
          std::isfinite(time) ? motion_.place(pos, time, placed) : RejectReason::non_finite;
      if (placement == RejectReason::accepted) {
        a.world = placed.world;
        a.ray = placed.ray;
        a.projected = projection_.project(placed.ray);
      } else {
        a.world = pos;
        a.ray = pos;
        a.projected.reason = placement;
      }
      Clock::add_since(stats_.phase_us.placement, t0);
    }
    return a;
  }

  /// Algorithm 1 for one prepared point; `a.cell` is its grid cell when
  /// found ahead (the grid is fixed once chosen), else kNoCell.
  RejectReason insert_prepared(const Prepared& a) {
    const std::uint64_t stream_index = params_.first_stream_index + offered_++;
    const double time = a.time;
    const Projected& pr = a.projected;
    const RejectReason verdict = time_order_.admit(pr, time);
    ++rejections_[verdict];
    if (verdict != RejectReason::accepted) return verdict;
    if constexpr (removes_structure) {
      if (classify_structure(a, stream_index)) return RejectReason::accepted;
    }
    const Sample sample = motion_type::identity ? make_sample(a.world, pr.range, a.intensity, time)
                                                : make_sample(a.world, a.ray, pr.range, a.intensity, time);
    if (calibrating_) {
      // Buffering the first window: nothing expires before it is complete.
      if (size() == 0 || !window_.complete(ring_.time(ring_.oldest()), time, size() + 1)) {
        ring_.append(sample, stream_index, linkage_);
        calibration_coords_.push_back(pr);
        return RejectReason::accepted;
      }
      finish_calibration();  // on the complete first window; the new point follows
    }
    // The mask is listed (and its index cells prefetched) before the
    // eviction, so those cache misses overlap the eviction's work.
    const CellIndex cell = a.cell != kNoCell ? a.cell : grid_.cell_of(pr.u, pr.v);
    search_.list_mask(index_, cell);
    const auto t0 = Clock::now();
    evict_expired(time, size() + 1);
    Clock::add_since(stats_.phase_us.eviction, t0);
    const PointHandle h = ring_.append(sample, stream_index, linkage_);
    ring_.record(h).cell = cell;
    const auto t1 = Clock::now();
    link(h);
    Clock::add_since(stats_.phase_us.insertion, t1);
    return RejectReason::accepted;
  }

  /// The mask search for appended point `h` (its mask listed), the
  /// neighbours to the strategy, the point to the index.
  void link(PointHandle h) {
    ++stats_.inserted;
    const std::size_t found = search_.find(ring_, index_, linkage_, h, stats_);
    Context ctx = context();
    state_.on_link(ctx, h, search_.neighbours(), found);
    index_.insert(ring_.record(h).cell, h);
  }

  /// The ground policy's decision for accepted point `a`: true when it is
  /// structure (then kept in the structure ring). The model first drops the
  /// points that left the window at `a.time` (object points counted without
  /// `a`: a count window evicts for `a` only once it is an object point).
  bool classify_structure(const Prepared& a, std::uint64_t stream_index) {
    const auto t0 = Clock::now();
    evict_structure(a.time);
    if (!calibrating_) evict_expired(a.time, size());
    const SurfaceClass surface = ground_.classify(a.world, a.ray);
    Clock::add_since(stats_.phase_us.ground, t0);
    if (surface == SurfaceClass::object) return false;
    structure_.push(StructureEntry{stream_index, a.time, a.world, surface});
    ++(surface == SurfaceClass::ceiling ? stats_.ceiling : surface == SurfaceClass::wall ? stats_.wall : stats_.ground);
    return true;
  }

  /// Evicts the structure points that have left the window at `newest_time`
  /// (the window rule on the structure ring's own times and count).
  void evict_structure(double newest_time) {
    while (!structure_.empty() && window_.expired(structure_.oldest().time, newest_time, structure_.size())) {
      ground_.forget(structure_.oldest().world, structure_.oldest().surface);
      structure_.pop();
      ++stats_.evicted;
    }
  }

  /// Evicts the points that have left a window whose newest point is at
  /// `newest_time` and which holds `count` points.
  void evict_expired(double newest_time, std::size_t count) {
    while (size() > 0 && window_.expired(ring_.time(ring_.oldest()), newest_time, count)) {
      evict_oldest();
      --count;
    }
  }

  void evict_oldest() {
    const PointHandle h = ring_.oldest();
    if constexpr (has_spatial_index_prefetch_v<spatial_index_type>) {
      // The index cell of a later eviction: its line has long left L1/L2.
      const PointHandle ahead = h + kEvictPrefetchDistance;
      if (static_cast<PointHandle>(ahead - h) < size()) index_.prefetch(ring_.record(ahead).cell);
    }
    ++stats_.evicted;
    index_.remove(ring_.record(h).cell, h);
    Context ctx = context();
    state_.on_evict(ctx, h);
    if constexpr (removes_structure) ground_.forget(ring_.position(h), SurfaceClass::object);
    ring_.pop_oldest();
  }

  /// Chooses the grid from the buffered first window, then links the
  /// buffered points in their original order.
  void finish_calibration() {
    std::vector<Projected> coords;
    coords.swap(calibration_coords_);  // released after the replay: needed once
    set_grid(choose_grid(resolution_, projection_, coords));
    Context ctx = context();
    state_.begin_replay(ctx);
    std::size_t i = 0;
    for (PointHandle h = ring_.oldest(); h != ring_.next(); ++h, ++i) {
      ring_.record(h).cell = grid_.cell_of(coords[i].u, coords[i].v);
      search_.list_mask(index_, ring_.record(h).cell);
      link(h);
    }
    state_.end_replay(ctx);
  }

  /// A point of `insert_batch` taken ahead of its turn: read, placed,
  /// projected and, once the grid is known, its cell found and its mask
  /// prefetched.
  template <class P>
  Prepared look_ahead(const P& p) {
    Prepared a = prepare(position(p), intensity(p), stamp(p));
    if (a.projected.accepted() && !calibrating_) {
      a.cell = grid_.cell_of(a.projected.u, a.projected.v);
      search_.prefetch_mask(index_, a.cell);
    }
    return a;
  }

  /// The loop of `insert_batch`: kInsertLookahead points projected and
  /// prefetched ahead, `on_reason(reason)` for each point in order.
  template <class It, class OnReason>
  void insert_each(It first, It last, OnReason&& on_reason) {
    static_assert(is_point_v<typename std::iterator_traits<It>::value_type>,
                  "STREAMCLUST_POINT_TYPE_INVALID: specialise streamclust::point_traits for this type");
    std::array<Prepared, kInsertLookahead> ahead;
    std::size_t queued = 0;
    It lead = first;
    for (; queued < kInsertLookahead && lead != last; ++queued, ++lead) ahead[queued] = look_ahead(*lead);
    for (std::size_t i = 0; first != last; ++first, ++i) {
      const std::size_t at = i % kInsertLookahead;
      const Prepared p = ahead[at];
      if (lead != last) {
        ahead[at] = look_ahead(*lead);
        ++lead;
      }
      on_reason(insert_prepared(p));
    }
  }

  Params params_;
  projection_type projection_;
  spatial_index_type index_;
  linkage_type linkage_;
  window_type window_;
  resolution_type resolution_;
  visitor_type visitor_;
  connectivity_type connectivity_;
  motion_type motion_;
  ground_type ground_;
  GridShape grid_{};
  bool calibrating_ = true;
  ring_type ring_;                                                    ///< the window
  NeighbourSearch<spatial_index_type, linkage_type, ring_type> search_;  ///< mask search and its scratch
  state_type state_;                                                  ///< the connectivity strategy
  ComponentResult result_;                                            ///< the one result writer
  StructureRing structure_;                                           ///< the window's structure points
  std::vector<Projected> calibration_coords_;                         ///< projections of the buffered first window
  ComponentId next_component_id_ = 0;
  std::uint64_t offered_ = 0;
  StreamTimeOrder time_order_;
  RejectionCounts rejections_{};
  RetrievalStats stats_{};
  RetrievalStats last_stats_{};
};

}  // namespace streamclust
