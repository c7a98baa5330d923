// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// How the library reads a user's point type. Algorithms call the free
/// functions `position(p)`, `stamp(p)` and `intensity(p)`, never the traits.
///
/// | expression                          | type            | meaning                          |
/// |-------------------------------------|-----------------|----------------------------------|
/// | `point_traits<P>::position(p)`      | Eigen::Vector3f | sensor-frame position [m]        |
/// | `point_traits<P>::stamp(p)`         | double          | stream time [s]                  |
/// | `point_traits<P>::intensity(p)`     | float           | optional; 0 when not provided    |
///
/// Any struct with arithmetic members `x`, `y`, `z` works out of the box; its
/// time is read from a member named `t`, `time` or `timestamp` (seconds), if
/// present. Anything else: specialise `point_traits` (see examples/03_own_point_type.cpp).

#include <streamclust/types.hpp>

#include <type_traits>
#include <utility>

namespace streamclust {

/// The default point: 32 bytes. Time is stream time in seconds as a double
/// (nanosecond resolution for more than 100 days of stream).
struct Point {
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;
  float intensity = 0.0f;
  double t = 0.0;  ///< stream time [s]
};

namespace detail {
template <class P, class = void>
struct has_xyz : std::false_type {};
template <class P>
struct has_xyz<P, std::void_t<decltype(std::declval<const P&>().x), decltype(std::declval<const P&>().y),
                              decltype(std::declval<const P&>().z)>>
    : std::bool_constant<std::is_arithmetic_v<std::decay_t<decltype(std::declval<const P&>().x)>>> {};

template <class P, class = void>
struct has_member_t : std::false_type {};
template <class P>
struct has_member_t<P, std::void_t<decltype(std::declval<const P&>().t)>> : std::true_type {};
template <class P, class = void>
struct has_member_time : std::false_type {};
template <class P>
struct has_member_time<P, std::void_t<decltype(std::declval<const P&>().time)>> : std::true_type {};
template <class P, class = void>
struct has_member_timestamp : std::false_type {};
template <class P>
struct has_member_timestamp<P, std::void_t<decltype(std::declval<const P&>().timestamp)>> : std::true_type {};
template <class P, class = void>
struct has_member_intensity : std::false_type {};
template <class P>
struct has_member_intensity<P, std::void_t<decltype(std::declval<const P&>().intensity)>> : std::true_type {};
}  // namespace detail

/// Primary template: enabled for structs with `x`, `y`, `z` members.
/// Specialise it for other types (a full specialisation wins over this one).
template <class P, class Enable = void>
struct point_traits;

template <class P>
struct point_traits<P, std::enable_if_t<detail::has_xyz<P>::value>> {
  static Eigen::Vector3f position(const P& p) {
    return {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
  }
  /// Time in seconds from `t`, `time` or `timestamp`; 0 when the type has none
  /// (pass the time explicitly to `insert(p, time)` then).
  static double stamp(const P& p) {
    if constexpr (detail::has_member_t<P>::value) {
      return static_cast<double>(p.t);
    } else if constexpr (detail::has_member_time<P>::value) {
      return static_cast<double>(p.time);
    } else if constexpr (detail::has_member_timestamp<P>::value) {
      return static_cast<double>(p.timestamp);
    } else {
      (void)p;
      return 0.0;
    }
  }
  static float intensity(const P& p) {
    if constexpr (detail::has_member_intensity<P>::value) {
      return static_cast<float>(p.intensity);
    } else {
      (void)p;
      return 0.0f;
    }
  }
};

/// A Sample is itself a point: lets a window be re-clustered from its samples.
template <>
struct point_traits<Sample> {
  static Eigen::Vector3f position(const Sample& s) { return s.position; }
  static double stamp(const Sample& s) { return s.time; }
  static float intensity(const Sample& s) { return s.intensity; }
};

namespace detail {
template <class P, class = void>
struct traits_have_intensity : std::false_type {};
template <class P>
struct traits_have_intensity<P, std::void_t<decltype(point_traits<P>::intensity(std::declval<const P&>()))>>
    : std::true_type {};
template <class P, class = void>
struct is_point : std::false_type {};
template <class P>
struct is_point<P, std::void_t<decltype(point_traits<P>::position(std::declval<const P&>())),
                               decltype(point_traits<P>::stamp(std::declval<const P&>()))>> : std::true_type {};
}  // namespace detail

/// True when P can be fed to a clusterer.
template <class P>
inline constexpr bool is_point_v = detail::is_point<P>::value;

/// Sensor-frame position of a point [m].
template <class P>
Eigen::Vector3f position(const P& p) {
  return point_traits<P>::position(p);
}
/// Stream time of a point [s].
template <class P>
double stamp(const P& p) {
  return static_cast<double>(point_traits<P>::stamp(p));
}
/// Intensity of a point, 0 when its traits provide none.
template <class P>
float intensity(const P& p) {
  if constexpr (detail::traits_have_intensity<P>::value) {
    return static_cast<float>(point_traits<P>::intensity(p));
  } else {
    (void)p;
    return 0.0f;
  }
}

}  // namespace streamclust
