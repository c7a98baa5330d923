// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Connectivity policy concept: how the engine keeps the connected
/// components of the window's point graph up to date as points leave.
///
/// | expression                   | type                   | meaning                                               | complexity |
/// |------------------------------|------------------------|-------------------------------------------------------|------------|
/// | `typename C::Params`         | aggregate              | parameters with defaults (may be empty)               |            |
/// | `C c{params}`                |                        | construct; throws std::invalid_argument if bad        |            |
/// | `C::strategy`                | `ConnectivityStrategy` | static constexpr: the algorithm the engine runs       | compile time |
///
/// Why a strategy selector and not callbacks: the algorithms work on the
/// engine's own ring buffers (points, back/forward edge lists, local
/// clusters); exposing those through a callback interface would put an
/// indirection on every edge of the hot path. The policy therefore names one
/// of the engine's strategies at compile time (`if constexpr`, no run-time
/// cost) and carries its parameters; a new strategy is added to the enum and
/// the engine. Every strategy gives exactly the batch partition
/// (tests/test_oracle.cpp).
///
/// | strategy             | insertion / eviction                               | retrieval                                     |
/// |----------------------|----------------------------------------------------|-----------------------------------------------|
/// | `lazy_bfs` (paper)   | local clusters, bridges with multiplicities; an eviction walks the point's forward edges and may mark its cluster pending | BFS over every pending cluster, splits; BFS over the component graph: O(pending points + edges + N) |
/// | `union_find_rebuild` | edges only: no cluster or bridge bookkeeping        | one union-find pass over the live edges in ring (FIFO) order: O(N + E), independent of what is pending |
/// | `spanning_forest`    | appends each new edge to a list (no edge ring, no per-point adjacency); eviction drops the point | folds the new edges into a maximum spanning forest (weight = older endpoint) by Kruskal: O(N + F + edges inserted since the last retrieval), F < N |
///
/// A `spanning_forest` policy also has `c.fold_threshold(points)` (std::size_t:
/// the new-edge count past which the engine folds without a retrieval, for a
/// window of `points` points) and may have `c.prune_witnesses()`
/// (std::uint32_t: witnesses per inserted point for dropping redundant new
/// edges, see SpanningForestConnectivity::Params; 0 when absent,
/// `connectivity_prune_witnesses(c)`).
///
/// Not thread-safe state is kept by the engine; a policy object is immutable.

#include <cstdint>
#include <type_traits>
#include <utility>

namespace streamclust {

/// The connectivity-maintenance algorithms the engine implements.
enum class ConnectivityStrategy : std::uint8_t {
  lazy_bfs,            ///< the paper's: local clusters + bridges, lazy BFS validation of pending clusters
  union_find_rebuild,  ///< edges only; components rebuilt by union-find over the live edges at each retrieval
  spanning_forest,     ///< new edges only; folded into a maximum spanning forest of the window at each retrieval
};

namespace detail {
/// Default of the optional `connectivity` slot: the paper's strategy (same
/// as `LazyBfsConnectivity` in <streamclust/connectivity/lazy_bfs.hpp>).
struct DefaultConnectivity {
  struct Params {};
  explicit DefaultConnectivity(const Params&) {}
  static constexpr ConnectivityStrategy strategy = ConnectivityStrategy::lazy_bfs;
};

template <class C, class = void>
struct is_connectivity_policy : std::false_type {};
template <class C>
struct is_connectivity_policy<C, std::void_t<typename C::Params, decltype(C{std::declval<const typename C::Params&>()}),
                                             decltype(C::strategy)>>
    : std::is_same<std::remove_cv_t<decltype(C::strategy)>, ConnectivityStrategy> {};

template <class C, class = void>
struct has_prune_witnesses : std::false_type {};
template <class C>
struct has_prune_witnesses<C, std::void_t<decltype(std::declval<const C&>().prune_witnesses())>> : std::true_type {};
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

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
template <class C>
concept ConnectivityPolicy = is_connectivity_policy_v<C>;
#endif

}  // namespace streamclust

#define STREAMCLUST_CHECK_CONNECTIVITY_POLICY(C)                                                             \
  static_assert(::streamclust::is_connectivity_policy_v<C>,                                                  \
                "STREAMCLUST_CONNECTIVITY_POLICY_INVALID: the connectivity slot needs a nested Params "       \
                "aggregate, a constructor from Params and `static constexpr ConnectivityStrategy strategy` " \
                "(see docs/policies.md)")
