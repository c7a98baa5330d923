// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Projection policy concept: maps a sensor-frame position to normalised
/// grid coordinates, or rejects it with a reason.
///
/// | expression                     | type                  | meaning                                              | complexity |
/// |--------------------------------|-----------------------|------------------------------------------------------|------------|
/// | `typename P::Params`           | aggregate             | parameters with defaults, brace-constructible         |            |
/// | `P p{params}`                  |                       | construct; throws std::invalid_argument on bad params |            |
/// | `p.project(position)`          | Projected             | u, v in [0, 1], range [m], reason (accepted or not)   | O(1)       |
/// | `p.wraps_horizontally()`       | bool                  | u = 0 and u = 1 are neighbours (360-degree FOV)       | O(1)       |
/// | `p.fov_aspect()`               | float                 | horizontal / vertical FOV extent (for resolution)     | O(1)       |
///
/// `position` is an `Eigen::Vector3f`. `project` must be deterministic, must
/// reject NaN/inf coordinates (`non_finite`), ranges below its minimum
/// (`too_close`) and directions outside its FOV (`outside_fov`), and must be
/// const and thread-safe.

#include <streamclust/types.hpp>

#include <type_traits>
#include <utility>

namespace streamclust {
namespace detail {
template <class P, class = void>
struct is_projection_policy : std::false_type {};
template <class P>
struct is_projection_policy<
    P, std::void_t<typename P::Params, decltype(P{std::declval<const typename P::Params&>()}),
                   decltype(std::declval<const P&>().project(std::declval<const Eigen::Vector3f&>())),
                   decltype(std::declval<const P&>().wraps_horizontally()),
                   decltype(std::declval<const P&>().fov_aspect())>>
    : std::bool_constant<
          std::is_same_v<decltype(std::declval<const P&>().project(std::declval<const Eigen::Vector3f&>())),
                         Projected> &&
          std::is_convertible_v<decltype(std::declval<const P&>().wraps_horizontally()), bool> &&
          std::is_convertible_v<decltype(std::declval<const P&>().fov_aspect()), float>> {};
}  // namespace detail

template <class P>
inline constexpr bool is_projection_policy_v = detail::is_projection_policy<P>::value;

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
template <class P>
concept ProjectionPolicy = is_projection_policy_v<P>;
#endif

}  // namespace streamclust

#define STREAMCLUST_CHECK_PROJECTION_POLICY(P)                                                               \
  static_assert(::streamclust::is_projection_policy_v<P>,                                                    \
                "STREAMCLUST_PROJECTION_POLICY_INVALID: the projection slot needs a nested Params aggregate, " \
                "a constructor from Params, `Projected project(const Eigen::Vector3f&) const`, "               \
                "`bool wraps_horizontally() const` and `float fov_aspect() const` (see docs/policies.md)")
