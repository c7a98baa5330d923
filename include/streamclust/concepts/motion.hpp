// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Motion policy concept: where an offered point is in the world at its
/// capture time (motion compensation and the sensor's mount).
///
/// | expression                  | type                     | meaning                                                       | complexity |
/// |-----------------------------|--------------------------|---------------------------------------------------------------|------------|
/// | `typename M::Params`        | aggregate                | parameters with defaults                                      |            |
/// | `M m{params}`               |                          | construct; throws std::invalid_argument if bad                |            |
/// | `M::identity`               | `static constexpr bool`  | true: the world is the sensor frame (the engine skips the stage) |          |
/// | `m.place(p, t, placed)`     | `RejectReason`           | `accepted` and `placed` written, or `no_pose` (t outside the poses' span) | O(1) amortised for non-decreasing t |
///
/// `p` is the point in the sensor frame [m], `t` its capture time [s]
/// (finite; the engine rejects non-finite times before), `placed` a
/// PlacedPoint: `world`, the point in the world frame (+z up), which the
/// linkage, the ground model and the summaries see; and `ray`, the vector
/// from the sensor's position at time t to the point in world orientation,
/// which the projection sees. `world - ray` is the sensor's position at t.
/// Why the projection sees `ray` (see docs/design-decisions.md): a grid in
/// world orientation keeps a static point in its cell while the sensor turns
/// during the window; a grid around the sensor's position at capture time
/// keeps the projection's range and field of view meaningful.
///
/// `place` may keep a cursor (non-const). Not thread-safe unless documented.

#include <streamclust/types.hpp>

#include <Eigen/Core>

#include <type_traits>
#include <utility>

namespace streamclust {

/// A point placed in the world at its capture time.
struct PlacedPoint {
  Eigen::Vector3f world = Eigen::Vector3f::Zero();  ///< world frame [m]
  Eigen::Vector3f ray = Eigen::Vector3f::Zero();    ///< from the sensor at capture time, world orientation [m]
};

namespace detail {
template <class M, class = void>
struct is_motion_policy : std::false_type {};
template <class M>
struct is_motion_policy<M, std::void_t<typename M::Params, decltype(M{std::declval<const typename M::Params&>()}),
                                       decltype(M::identity),
                                       decltype(std::declval<M&>().place(std::declval<const Eigen::Vector3f&>(),
                                                                         double{}, std::declval<PlacedPoint&>()))>>
    : std::bool_constant<std::is_same_v<decltype(std::declval<M&>().place(std::declval<const Eigen::Vector3f&>(),
                                                                           double{}, std::declval<PlacedPoint&>())),
                                        RejectReason>> {};
}  // namespace detail

template <class M>
inline constexpr bool is_motion_policy_v = detail::is_motion_policy<M>::value;

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
template <class M>
concept MotionPolicy = is_motion_policy_v<M>;
#endif

}  // namespace streamclust

#define STREAMCLUST_CHECK_MOTION_POLICY(M)                                                                 \
  static_assert(::streamclust::is_motion_policy_v<M>,                                                      \
                "STREAMCLUST_MOTION_POLICY_INVALID: the motion slot needs a nested Params aggregate, a "     \
                "constructor from Params, `static constexpr bool identity` and `RejectReason "               \
                "place(const Eigen::Vector3f&, double, PlacedPoint&)` (see concepts/motion.hpp)")
