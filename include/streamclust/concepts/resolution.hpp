// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Resolution policy concept: chooses the grid size, either fixed or from
/// the first window's projected coordinates (calibration).
///
/// | expression                          | type      | meaning                                                      | complexity   |
/// |-------------------------------------|-----------|--------------------------------------------------------------|--------------|
/// | `typename R::Params`                | aggregate | parameters with defaults                                     |              |
/// | `R r{params}`                       |           | construct; throws std::invalid_argument if bad               |              |
/// | `r.needs_calibration()`             | bool      | true: the engine buffers a first window and calls calibrate  | O(1)         |
/// | `r.grid()`                          | GridSize  | the current grid (valid when no calibration is pending)      | O(1)         |
/// | `r.calibrate(coords, fov_aspect)`   | GridSize  | choose the grid from `coords` (const std::vector<Projected>&, | policy's own |
/// |                                     |           | accepted points only); afterwards needs_calibration() is false |            |
///
/// `grid()` never returns a zero dimension. Not thread-safe (calibrate mutates).

#include <streamclust/types.hpp>

#include <type_traits>
#include <utility>
#include <vector>

namespace streamclust {
namespace detail {
template <class R, class = void>
struct is_resolution_policy : std::false_type {};
template <class R>
struct is_resolution_policy<
    R, std::void_t<typename R::Params, decltype(R{std::declval<const typename R::Params&>()}),
                   decltype(std::declval<const R&>().needs_calibration()), decltype(std::declval<const R&>().grid()),
                   decltype(std::declval<R&>().calibrate(std::declval<const std::vector<Projected>&>(), float{}))>>
    : std::bool_constant<
          std::is_convertible_v<decltype(std::declval<const R&>().needs_calibration()), bool> &&
          std::is_convertible_v<decltype(std::declval<const R&>().grid()), GridSize> &&
          std::is_convertible_v<decltype(std::declval<R&>().calibrate(std::declval<const std::vector<Projected>&>(),
                                                                      float{})),
                                GridSize>> {};
}  // namespace detail

template <class R>
inline constexpr bool is_resolution_policy_v = detail::is_resolution_policy<R>::value;

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
template <class R>
concept ResolutionPolicy = is_resolution_policy_v<R>;
#endif

}  // namespace streamclust

#define STREAMCLUST_CHECK_RESOLUTION_POLICY(R)                                                              \
  static_assert(::streamclust::is_resolution_policy_v<R>,                                                   \
                "STREAMCLUST_RESOLUTION_POLICY_INVALID: the resolution slot needs a nested Params aggregate, " \
                "a constructor from Params, `bool needs_calibration() const`, `GridSize grid() const` and "   \
                "`GridSize calibrate(const std::vector<Projected>&, float fov_aspect)` (see docs/policies.md)")
