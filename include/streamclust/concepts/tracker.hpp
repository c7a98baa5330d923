// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Tracker policy concept: objects followed over retrievals. A tracker
/// reads each retrieval's observed objects (tracking/object_boxes.hpp) and
/// keeps tracks with ids of their own; it changes no partition.
///
/// | expression                    | type                              | meaning                                                | complexity |
/// |-------------------------------|-----------------------------------|--------------------------------------------------------|------------|
/// | `typename T::Params`          | aggregate                         | parameters with defaults                               |            |
/// | `T t{params}`                 |                                   | construct; throws std::invalid_argument if bad         |            |
/// | `T::enabled`                  | `static constexpr bool`           | false: nothing is tracked (NullTracker), no box is fitted |         |
/// | `t.update(objects, time)`     | `const std::vector<tracking::Track>&` | the tracks after the retrieval at `time` [s] whose objects (`const std::vector<tracking::ObjectObservation>&`) are given; valid until the next call | the tracker's |
/// | `t.tracks()`                  | `const std::vector<tracking::Track>&` | the last update's tracks                           | O(1)       |
///
/// Times increase from call to call (a smaller time throws
/// std::invalid_argument). Not thread-safe unless documented.

#include <streamclust/tracking/object_boxes.hpp>
#include <streamclust/tracking/track.hpp>

#include <type_traits>
#include <utility>
#include <vector>

namespace streamclust {
namespace detail {
template <class T, class = void>
struct is_tracker_policy : std::false_type {};
template <class T>
struct is_tracker_policy<
    T, std::void_t<typename T::Params, decltype(T{std::declval<const typename T::Params&>()}), decltype(T::enabled),
                   decltype(std::declval<T&>().update(
                       std::declval<const std::vector<tracking::ObjectObservation>&>(), 0.0)),
                   decltype(std::declval<const T&>().tracks())>>
    : std::bool_constant<
          std::is_same_v<decltype(std::declval<T&>().update(
                             std::declval<const std::vector<tracking::ObjectObservation>&>(), 0.0)),
                         const std::vector<tracking::Track>&> &&
          std::is_same_v<decltype(std::declval<const T&>().tracks()), const std::vector<tracking::Track>&>> {};
}  // namespace detail

template <class T>
inline constexpr bool is_tracker_policy_v = detail::is_tracker_policy<T>::value;

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
template <class T>
concept TrackerPolicy = is_tracker_policy_v<T>;
#endif

}  // namespace streamclust
