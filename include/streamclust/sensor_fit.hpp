// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// SensorFit: what a policy can be fitted to before an engine starts (the
/// sensor's first window and how it is carried), and the optional policy
/// capability `fit_to_sensor` that the tools call.
///
/// | expression                      | type             | meaning                                            | complexity |
/// |---------------------------------|------------------|----------------------------------------------------|------------|
/// | `P::fit_to_sensor(params, fit)` | `P::Params`      | static: `params` completed from `fit` (e.g. a table built from the first window) | the policy's |
///
/// `has_sensor_fit_v<P>` detects it. The fitted Params are then fixed: an
/// engine and its batch oracle built from them decide alike. The
/// `streamclust` tool fits the linkage it runs (`cluster`, `evaluate
/// --objects`) from the input's first window and the run's mount and poses.

#include <streamclust/motion/pose.hpp>
#include <streamclust/motion/trajectory.hpp>

#include <Eigen/Core>

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace streamclust {

/// The sensor a policy is fitted to.
struct SensorFit {
  /// [m] the first window T_B of points in the SENSOR frame (as the sensor
  /// measured them, before any placement), in firing order.
  std::vector<Eigen::Vector3f> first_window;
  Pose mount;                                        ///< vehicle (or world) from sensor; identity: level
  std::shared_ptr<const PoseTrajectory> trajectory;  ///< world from vehicle over time; null: at rest
};

namespace detail {
template <class P, class = void>
struct has_sensor_fit : std::false_type {};
template <class P>
struct has_sensor_fit<P, std::void_t<decltype(P::fit_to_sensor(std::declval<const typename P::Params&>(),
                                                                std::declval<const SensorFit&>()))>>
    : std::is_same<decltype(P::fit_to_sensor(std::declval<const typename P::Params&>(),
                                             std::declval<const SensorFit&>())),
                   typename P::Params> {};
}  // namespace detail

/// True when policy `P` has `static Params fit_to_sensor(const Params&, const SensorFit&)`.
template <class P>
inline constexpr bool has_sensor_fit_v = detail::has_sensor_fit<P>::value;

}  // namespace streamclust
