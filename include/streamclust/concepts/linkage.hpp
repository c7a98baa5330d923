// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Linkage policy concept: the single-linkage predicate between two points
/// found in the same w x w mask.
///
/// | expression             | type      | meaning                                          | complexity |
/// |------------------------|-----------|--------------------------------------------------|------------|
/// | `typename L::Params`   | aggregate | parameters with defaults                         |            |
/// | `L l{params}`          |           | construct; throws std::invalid_argument if bad   |            |
/// | `l(a, b)`              | bool      | a and b (const Sample&) are linked               | O(1)       |
///
/// Must be symmetric (`l(a, b) == l(b, a)`), deterministic, const and
/// thread-safe. It sees position, unit direction, range, intensity and time.

#include <streamclust/types.hpp>

#include <type_traits>
#include <utility>

namespace streamclust {
namespace detail {
template <class L, class = void>
struct is_linkage_policy : std::false_type {};
template <class L>
struct is_linkage_policy<
    L, std::void_t<typename L::Params, decltype(L{std::declval<const typename L::Params&>()}),
                   decltype(std::declval<const L&>()(std::declval<const Sample&>(), std::declval<const Sample&>()))>>
    : std::is_convertible<decltype(std::declval<const L&>()(std::declval<const Sample&>(),
                                                              std::declval<const Sample&>())),
                          bool> {};
}  // namespace detail

template <class L>
inline constexpr bool is_linkage_policy_v = detail::is_linkage_policy<L>::value;

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
template <class L>
concept LinkagePolicy = is_linkage_policy_v<L>;
#endif

}  // namespace streamclust

#define STREAMCLUST_CHECK_LINKAGE_POLICY(L)                                                                  \
  static_assert(::streamclust::is_linkage_policy_v<L>,                                                       \
                "STREAMCLUST_LINKAGE_POLICY_INVALID: the linkage slot needs a nested Params aggregate, a "     \
                "constructor from Params and `bool operator()(const Sample&, const Sample&) const` "           \
                "(see docs/policies.md)")
