// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Connectivity policy concept: how the engine keeps the connected
/// components of the window's point graph up to date as points arrive and
/// leave, and how it answers a retrieval.
///
/// A connectivity policy is a strategy with its own state and algorithm.
/// The engine finds each new point's older neighbours (the mask search) and
/// hands them over; the strategy stores what it needs, reacts to evictions
/// and, at a retrieval, numbers the window's components and has the engine's
/// one result writer (ComponentResult) write them. Everything is resolved at
/// compile time: no virtual call, no run-time dispatch on the hot path.
///
/// | expression                       | type / value           | meaning                                                  | complexity |
/// |----------------------------------|------------------------|----------------------------------------------------------|------------|
/// | `typename C::Params`             | aggregate              | parameters with defaults (may be empty)                  |            |
/// | `C c{params}`                    |                        | construct; throws std::invalid_argument if bad           |            |
/// | `typename C::PointState`         | trivially copyable     | the strategy's per-point bookkeeping, default-constructed when a point enters the window; the point ring keeps it beside each point (`ring.record(h).state`) | |
/// | `C::stores_point_edges`          | `static constexpr bool`| the point-level edges can be walked (`s.edges()`, a PointEdges): the engine's neighbour accessors and the Boost.Graph point view need it | compile time |
/// | `c.prune_witnesses()` (optional)| std::uint32_t          | witnesses of the neighbour search's redundant-edge filter (0 or absent: every edge is handed over; only for a strategy that needs the components alone); a member of that name with another signature (not const, not an integer) stops compilation (`STREAMCLUST_CONNECTIVITY_CAPABILITY_INVALID`) | O(1) |
/// | `typename C::template State<R>`  | class S                | the strategy's state for a point ring of type R          |            |
/// | `S s(c)`                         |                        | an empty window                                          | O(1)       |
/// | `s.on_link(ctx, h, nb, count)`   | void                   | point h was appended and its `count` older neighbours `nb` found (the engine inserts h into the index afterwards) | the strategy's |
/// | `s.on_evict(ctx, h)`             | void                   | h, the oldest point, leaves; the engine then drops it from the index and the ring | the strategy's |
/// | `s.retrieve(ctx)`                | `const Clustering&`    | the window's components, written through `ctx.result`    | the strategy's |
/// | `s.begin_replay(ctx)`, `s.end_replay(ctx)` | void         | the buffered first window is linked at once between them (calibration) | |
/// | `s.reserve(ring)`                | void                   | the ring was sized for the largest window expected        | O(window)  |
/// | `s.cluster_of(ring, h)`          | ClusterId              | h's local cluster, or kNoCluster                          | O(1)       |
/// | `s.cluster_slots()`, `s.cluster_alive(c)`, `s.cluster_count()`, `s.cluster_size(c)`, `s.cluster_pending(c)`, `s.bridges(c)` | | the local clusters and their bridges (`const std::vector<ClusterBridge>&`), as the engine shows them | |
/// | `s.add_memory(m)`                | void                   | adds the state's heap bytes to MemoryUsage `m`, by part    | O(clusters) |
///
/// `ctx` is a ConnectivityContext: the point ring, the visitor, the stats,
/// the result writer and the next fresh component id. Every strategy gives
/// exactly the batch partition (tests/test_oracle.cpp).
///
/// | strategy                        | insertion / eviction                               | retrieval                                     |
/// |---------------------------------|----------------------------------------------------|-----------------------------------------------|
/// | LazyBfsConnectivity (paper)     | local clusters, bridges with multiplicities; an eviction walks the point's forward edges and may mark its cluster pending | BFS over every pending cluster, splits; BFS over the component graph: O(pending points + edges + N) |
/// | UnionFindRebuildConnectivity    | edges only: no cluster or bridge bookkeeping        | one union-find pass over the live edges in ring (FIFO) order: O(N + E) |
/// | SpanningForestConnectivity      | appends each new edge to age bands (no edge ring, no per-point adjacency); eviction drops the point | folds the new edges into a maximum spanning forest (weight = older endpoint) by Kruskal: O(N + F + new edges), F < N |
///
/// A new strategy is one new file: a policy with the members above (see
/// union_find_rebuild.hpp, the shortest).
/// Thread safety: a policy object is immutable; a State belongs to one
/// engine, driven from one thread.

#include <streamclust/clustering.hpp>
#include <streamclust/concepts/visitor.hpp>
#include <streamclust/detail/member_named.hpp>
#include <streamclust/engine/component_result.hpp>
#include <streamclust/engine/retrieval_stats.hpp>
#include <streamclust/types.hpp>

#include <cstdint>
#include <type_traits>
#include <utility>

namespace streamclust {

/// A bridge of the component graph: another local cluster and the number of
/// live point-level edges between the two.
struct ClusterBridge {
  ClusterId other;
  std::uint32_t multiplicity;
};

/// What a connectivity strategy sees of the engine at each call: the window
/// (`points`, whose records hold the strategy's PointState), the visitor,
/// the counters, the result writer, the next fresh component id and the
/// stream time of the newest point [s]. `Clock` times the phases of a timed
/// configuration (free otherwise).
template <class Ring, class Visitor, bool Timed>
struct ConnectivityContext {
  using Clock = detail::PhaseClock<Timed>;
  Ring& points;
  Visitor& visitor;
  RetrievalStats& stats;
  ComponentResult& result;
  ComponentId& next_id;
  double time;
};

/// Base of a State whose strategy needs none of the optional hooks: no
/// work around the calibration replay, nothing to size up front.
struct ConnectivityStateDefaults {
  template <class Ctx>
  void begin_replay(Ctx&) {}
  template <class Ctx>
  void end_replay(Ctx&) {}
  template <class Ring>
  void reserve(const Ring&) {}
};

namespace detail {

template <class C, class = void>
struct is_connectivity_policy : std::false_type {};
template <class C>
struct is_connectivity_policy<C, std::void_t<typename C::Params, decltype(C{std::declval<const typename C::Params&>()}),
                                             typename C::PointState, decltype(C::stores_point_edges)>>
    : std::bool_constant<std::is_same_v<std::remove_cv_t<decltype(C::stores_point_edges)>, bool> &&
                         std::is_trivially_copyable_v<typename C::PointState> &&
                         std::is_default_constructible_v<typename C::PointState>> {};

template <class C, class = void>
struct has_prune_witnesses : std::false_type {};
template <class C>
struct has_prune_witnesses<C, std::void_t<decltype(std::declval<const C&>().prune_witnesses())>>
    : std::bool_constant<std::is_integral_v<decltype(std::declval<const C&>().prune_witnesses())> &&
                         !std::is_same_v<decltype(std::declval<const C&>().prune_witnesses()), bool>> {};

STREAMCLUST_DETAIL_MEMBER_NAME_TRAIT(prune_witnesses);

/// The members a strategy's State must have for a context type Ctx.
template <class S, class Ctx, class = void>
struct is_connectivity_state : std::false_type {};
template <class S, class Ctx>
struct is_connectivity_state<
    S, Ctx,
    std::void_t<decltype(std::declval<S&>().on_link(std::declval<Ctx&>(), PointHandle{},
                                                    std::declval<const PointHandle*>(), std::size_t{})),
                decltype(std::declval<S&>().on_evict(std::declval<Ctx&>(), PointHandle{})),
                decltype(std::declval<S&>().retrieve(std::declval<Ctx&>())),
                decltype(std::declval<S&>().begin_replay(std::declval<Ctx&>())),
                decltype(std::declval<S&>().end_replay(std::declval<Ctx&>())),
                decltype(std::declval<const S&>().cluster_slots()),
                decltype(std::declval<const S&>().cluster_count())>>
    : std::is_convertible<decltype(std::declval<S&>().retrieve(std::declval<Ctx&>())), const Clustering&> {};

}  // namespace detail

/// `c.prune_witnesses()` when the policy has it, else 0 (keep every edge).
template <class C>
std::uint32_t connectivity_prune_witnesses(const C& c) {
  if constexpr (detail::has_prune_witnesses<C>::value) {
    return static_cast<std::uint32_t>(c.prune_witnesses());
  } else {
    return 0;
  }
}

template <class C>
inline constexpr bool is_connectivity_policy_v = detail::is_connectivity_policy<C>::value;

/// True when State type S has the members the engine calls with context Ctx.
template <class S, class Ctx>
inline constexpr bool is_connectivity_state_v = detail::is_connectivity_state<S, Ctx>::value;

namespace detail {
/// A member of connectivity `C` named like its optional capability has its
/// signature (a near miss stops here). True, or a failed static_assert.
/// Used by STREAMCLUST_CHECK_CONNECTIVITY_POLICY.
template <class C>
constexpr bool check_connectivity_capabilities() {
  if constexpr (is_connectivity_policy_v<C>) {
    static_assert(!names_prune_witnesses<C> || has_prune_witnesses<C>::value,
                  "STREAMCLUST_CONNECTIVITY_CAPABILITY_INVALID: `prune_witnesses` is not the optional "
                  "redundant-edge filter: expected `std::uint32_t prune_witnesses() const` "
                  "(see docs/policies.md, Connectivity)");
  }
  return true;
}
}  // namespace detail

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
template <class C>
concept ConnectivityPolicy = is_connectivity_policy_v<C>;
#endif

}  // namespace streamclust

#define STREAMCLUST_CHECK_CONNECTIVITY_POLICY(C)                                                                \
  static_assert(::streamclust::is_connectivity_policy_v<C>,                                                     \
                "STREAMCLUST_CONNECTIVITY_POLICY_INVALID: the connectivity slot needs a nested Params "          \
                "aggregate, a constructor from Params, a trivially copyable `PointState`, `static constexpr " \
                "bool stores_point_edges` and a `State<Ring>` template (see concepts/connectivity.hpp)");         \
  static_assert(::streamclust::detail::check_connectivity_capabilities<C>(),                                   \
                "STREAMCLUST_CONNECTIVITY_CAPABILITY_INVALID")
