// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Window policy concept: which points form the sliding window.
///
/// | expression                              | type      | meaning                                                        | complexity |
/// |-----------------------------------------|-----------|----------------------------------------------------------------|------------|
/// | `typename W::Params`                    | aggregate | parameters with defaults                                       |            |
/// | `W w{params}`                           |           | construct; throws std::invalid_argument if bad                 |            |
/// | `w.expired(oldest, newest, size)`       | bool      | the oldest point must leave (times in s, size in points)       | O(1)       |
/// | `w.complete(oldest, newest, size)`      | bool      | the window has reached its nominal extent (ends calibration)   | O(1)       |
///
/// The engine evicts the oldest point while `expired` holds, with `newest` the
/// time of the point about to be inserted (or the time passed to
/// `advance_to`) and `size` the count including it. Points leave in insertion
/// order. Must be const and thread-safe.

#include <cstddef>
#include <type_traits>
#include <utility>

namespace streamclust {
namespace detail {
template <class W, class = void>
struct is_window_policy : std::false_type {};
template <class W>
struct is_window_policy<
    W, std::void_t<typename W::Params, decltype(W{std::declval<const typename W::Params&>()}),
                   decltype(std::declval<const W&>().expired(double{}, double{}, std::size_t{})),
                   decltype(std::declval<const W&>().complete(double{}, double{}, std::size_t{}))>>
    : std::bool_constant<
          std::is_convertible_v<decltype(std::declval<const W&>().expired(double{}, double{}, std::size_t{})),
                                bool> &&
          std::is_convertible_v<decltype(std::declval<const W&>().complete(double{}, double{}, std::size_t{})),
                                bool>> {};
}  // namespace detail

template <class W>
inline constexpr bool is_window_policy_v = detail::is_window_policy<W>::value;

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
template <class W>
concept WindowPolicy = is_window_policy_v<W>;
#endif

}  // namespace streamclust

#define STREAMCLUST_CHECK_WINDOW_POLICY(W)                                                                  \
  static_assert(::streamclust::is_window_policy_v<W>,                                                       \
                "STREAMCLUST_WINDOW_POLICY_INVALID: the window slot needs a nested Params aggregate, a "      \
                "constructor from Params, `bool expired(double oldest, double newest, std::size_t size) "     \
                "const` and `bool complete(double, double, std::size_t) const` (see docs/policies.md)")
