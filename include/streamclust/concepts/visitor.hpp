// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Visitor policy concept: observers of local-cluster events. Derive from
/// NullVisitor and hide the members you need; the rest stay no-ops and the
/// compiler removes the calls, so an unused visitor costs nothing.
///
/// | expression                         | meaning                                                             |
/// |------------------------------------|---------------------------------------------------------------------|
/// | `v.cluster_created(c)`             | isolation created local cluster c (uint32_t id)                     |
/// | `v.clusters_merged(a, b)`          | a bridge edge now joins clusters a and b (their components merge)   |
/// | `v.cluster_split(parent, piece)`   | validation found `piece` disconnected from `parent`; new cluster id |
/// | `v.cluster_evicted(c)`             | the last point of cluster c left the window; the id may be reused   |
///
/// Called from the thread that drives the engine.

#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>

namespace streamclust {

/// Local cluster id inside one engine (recycled after `cluster_evicted`).
using ClusterId = std::uint32_t;
/// No local cluster (e.g. a point buffered for calibration).
inline constexpr ClusterId kNoCluster = std::numeric_limits<ClusterId>::max();

/// Observer with no-op hooks: the default visitor.
struct NullVisitor {
  void cluster_created(ClusterId) {}
  void clusters_merged(ClusterId, ClusterId) {}
  void cluster_split(ClusterId, ClusterId) {}
  void cluster_evicted(ClusterId) {}
};

namespace detail {
template <class V, class = void>
struct is_visitor_policy : std::false_type {};
template <class V>
struct is_visitor_policy<V, std::void_t<decltype(std::declval<V&>().cluster_created(ClusterId{})),
                                        decltype(std::declval<V&>().clusters_merged(ClusterId{}, ClusterId{})),
                                        decltype(std::declval<V&>().cluster_split(ClusterId{}, ClusterId{})),
                                        decltype(std::declval<V&>().cluster_evicted(ClusterId{}))>>
    : std::true_type {};
}  // namespace detail

template <class V>
inline constexpr bool is_visitor_policy_v = detail::is_visitor_policy<V>::value;

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
template <class V>
concept VisitorPolicy = is_visitor_policy_v<V>;
#endif

}  // namespace streamclust

#define STREAMCLUST_CHECK_VISITOR_POLICY(V)                                                                 \
  static_assert(::streamclust::is_visitor_policy_v<V>,                                                      \
                "STREAMCLUST_VISITOR_POLICY_INVALID: the visitor slot needs cluster_created(ClusterId), "     \
                "clusters_merged(ClusterId, ClusterId), cluster_split(ClusterId, ClusterId) and "             \
                "cluster_evicted(ClusterId); derive from streamclust::NullVisitor (see docs/policies.md)")
