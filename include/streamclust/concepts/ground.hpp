// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Ground policy concept: structure removal at insertion. Each accepted
/// point is classed, causally, from what the window held before it: an
/// object (clustered) or structure (ground, wall or ceiling: kept in the
/// window, never linked).
///
/// | expression                | type                     | meaning                                                        | complexity |
/// |---------------------------|--------------------------|----------------------------------------------------------------|------------|
/// | `typename G::Params`      | aggregate                | parameters with defaults                                       |            |
/// | `G g{params}`             |                          | construct; throws std::invalid_argument if bad                 |            |
/// | `G::enabled`              | `static constexpr bool`  | false: the engine skips the stage (NoGround)                   |            |
/// | `g.classify(world, ray)`  | `SurfaceClass`           | counts the point in the model, then classes it: `object`, `ground`, `wall` or `ceiling` | amortised O(1) |
/// | `g.forget(world, class)`  | void                     | uncounts a point `classify` counted and classed `class` (it left the window) | O(1) |
/// | `g.heap_bytes()`          | `std::size_t`            | heap held by the model [bytes]                                 | O(1)       |
///
/// Optional, for what reads the window after a retrieval (object boxes,
/// tracking: tracking/object_boxes.hpp); without the first a box stands on
/// its lowest point, without the second nothing is known of a ceiling:
///
/// | expression                          | type                   | meaning                                      |
/// |-------------------------------------|------------------------|----------------------------------------------|
/// | `g.ground_height_near(x, y, radius)` | `std::optional<float>` | the ground's height around (x, y) [m], nullopt when none is seen within `radius` [m] |
/// | `g.ceiling_height_near(x, y, radius)` | `std::optional<float>` | the ceiling's height over (x, y) [m], nullopt when none is seen within `radius` [m] |
///
/// `world` is the point in the world frame (+z up, against gravity) and
/// `ray` the vector from the sensor to it (PlacedPoint, concepts/motion.hpp);
/// the sensor is at `world - ray`. Every point `classify` counted is
/// forgotten exactly once, with the same `world` and the class it was given,
/// when it leaves the window (object and structure points alike). The decision for a point depends
/// only on the points counted before it and itself, so a replay of the same
/// accepted stream with the same evictions makes the same decisions.
/// Not thread-safe unless documented.

#include <streamclust/surface_class.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <type_traits>
#include <utility>

namespace streamclust {
namespace detail {
template <class G, class = void>
struct is_ground_policy : std::false_type {};
template <class G>
struct is_ground_policy<
    G, std::void_t<typename G::Params, decltype(G{std::declval<const typename G::Params&>()}), decltype(G::enabled),
                   decltype(std::declval<G&>().classify(std::declval<const Eigen::Vector3f&>(),
                                                        std::declval<const Eigen::Vector3f&>())),
                   decltype(std::declval<G&>().forget(std::declval<const Eigen::Vector3f&>(), SurfaceClass::object)),
                   decltype(std::declval<const G&>().heap_bytes())>>
    : std::bool_constant<std::is_same_v<decltype(std::declval<G&>().classify(std::declval<const Eigen::Vector3f&>(),
                                                                             std::declval<const Eigen::Vector3f&>())),
                                        SurfaceClass>> {};
}  // namespace detail

template <class G>
inline constexpr bool is_ground_policy_v = detail::is_ground_policy<G>::value;

namespace detail {
template <class G, class = void>
struct has_ground_height : std::false_type {};
template <class G>
struct has_ground_height<G, std::void_t<decltype(std::declval<const G&>().ground_height_near(0.0f, 0.0f, 0.0f))>>
    : std::true_type {};
}  // namespace detail

/// True when ground policy G tells the ground's height around a place
/// (`ground_height_near`, the optional row above).
template <class G>
inline constexpr bool has_ground_height_v = detail::has_ground_height<G>::value;

namespace detail {
template <class G, class = void>
struct has_ceiling_height : std::false_type {};
template <class G>
struct has_ceiling_height<G, std::void_t<decltype(std::declval<const G&>().ceiling_height_near(0.0f, 0.0f, 0.0f))>>
    : std::true_type {};
}  // namespace detail

/// True when ground policy G tells the ceiling's height over a place
/// (`ceiling_height_near`, the optional row above).
template <class G>
inline constexpr bool has_ceiling_height_v = detail::has_ceiling_height<G>::value;

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
template <class G>
concept GroundPolicy = is_ground_policy_v<G>;
#endif

}  // namespace streamclust

#define STREAMCLUST_CHECK_GROUND_POLICY(G)                                                                       \
  static_assert(::streamclust::is_ground_policy_v<G>,                                                            \
                "STREAMCLUST_GROUND_POLICY_INVALID: the ground slot needs a nested Params aggregate, a constructor " \
                "from Params, `static constexpr bool enabled`, `SurfaceClass classify(const Eigen::Vector3f& world, " \
                "const Eigen::Vector3f& ray)`, `void forget(const Eigen::Vector3f&, SurfaceClass)` and `std::size_t heap_bytes() " \
                "const` (see concepts/ground.hpp)")
