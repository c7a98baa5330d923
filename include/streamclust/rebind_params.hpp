// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// rebind_params: the parameters of one configuration carried over to a
/// configuration that swaps slots, so a preset serves a user's config.
///
/// \code
/// struct MyConfig : streamclust::ObjectsConfig {
///   using linkage = MyLinkage;
/// };
/// streamclust::ObjectsSetup setup;
/// setup.sensor_height = 1.2f;  // [m]
/// const auto params = streamclust::rebind_params<MyConfig>(streamclust::objects_mid360_params(setup),
///                                                           MyLinkage::Params{0.3f});
/// streamclust::StreamClusterer<MyConfig> engine(params);
/// \endcode
///
/// Every slot whose Params type is the same in both configurations keeps
/// the source's value; every engine parameter (mask_size,
/// crowded_cell_chains, time_order, first_stream_index) is kept. A Params
/// value passed after the source replaces the slot of the target whose
/// Params type it is (`MyLinkage::Params{}`: the new policy's defaults). A
/// slot whose Params type differs and that is given no value is a compile
/// error naming the slot; so is a value that is the Params of no slot, or of
/// two. A field added to ClustererParams breaks the build here until the
/// rebind carries it.

#include <streamclust/config.hpp>

#include <cstddef>
#include <type_traits>
#include <utility>

namespace streamclust {
namespace detail {

/// Converts to any type: counts an aggregate's fields in unevaluated
/// contexts (never defined, never called).
struct AnyField {
  template <class T>
  operator T() const;
};

template <class T, class... Fields>
constexpr auto brace_initializable(int) -> decltype(T{std::declval<Fields>()...}, true) {
  return true;
}
template <class T, class... Fields>
constexpr bool brace_initializable(...) {
  return false;
}

/// The number of fields of aggregate T whose fields are plain aggregates
/// (each AnyField converts to one field).
template <class T, class... Fields>
constexpr std::size_t aggregate_field_count() {
  if constexpr (brace_initializable<T, Fields..., AnyField>(0)) {
    return aggregate_field_count<T, Fields..., AnyField>();
  } else {
    return sizeof...(Fields);
  }
}

/// How many of `Types` are `T`.
template <class T, class... Types>
constexpr std::size_t count_type = (std::size_t{0} + ... + std::size_t{std::is_same_v<T, Types>});

template <class T, class First, class... Rest>
const T& first_of_type(const First& first, const Rest&... rest) {
  if constexpr (std::is_same_v<T, First>) {
    return first;
  } else {
    return first_of_type<T>(rest...);
  }
}

template <class T>
inline constexpr bool always_false = false;

/// rebind_<slot>: the target's Params of one slot, from the values given
/// (at most one of type To) or the source's (same type). The messages name
/// the slot.
#define STREAMCLUST_DETAIL_REBIND_SLOT(NAME)                                                              \
  template <class To, class From, class... Given>                                                         \
  To rebind_##NAME(const From& from, const Given&... given) {                                             \
    constexpr std::size_t given_count = count_type<To, Given...>;                                         \
    static_assert(given_count <= 1, "rebind_params: two Params values given for the " #NAME " slot");    \
    if constexpr (given_count == 1) {                                                                     \
      return first_of_type<To>(given...);                                                                 \
    } else if constexpr (std::is_same_v<To, From>) {                                                      \
      return from;                                                                                        \
    } else {                                                                                              \
      static_assert(always_false<To>, "rebind_params: the " #NAME                                         \
                    " slot's Params type differs between the configurations: pass the new " #NAME        \
                    " policy's Params (Policy::Params{} for its defaults)");                              \
      return To{};                                                                                        \
    }                                                                                                     \
  }
STREAMCLUST_DETAIL_REBIND_SLOT(projection)
STREAMCLUST_DETAIL_REBIND_SLOT(spatial_index)
STREAMCLUST_DETAIL_REBIND_SLOT(linkage)
STREAMCLUST_DETAIL_REBIND_SLOT(window)
STREAMCLUST_DETAIL_REBIND_SLOT(resolution)
STREAMCLUST_DETAIL_REBIND_SLOT(connectivity)
STREAMCLUST_DETAIL_REBIND_SLOT(motion)
STREAMCLUST_DETAIL_REBIND_SLOT(ground)
#undef STREAMCLUST_DETAIL_REBIND_SLOT

/// How many slots of ClustererParams `P` take Params of type `G`.
template <class P, class G>
constexpr std::size_t slots_taking =
    count_type<G, decltype(P::projection), decltype(P::spatial_index), decltype(P::linkage), decltype(P::window),
               decltype(P::resolution), decltype(P::connectivity), decltype(P::motion), decltype(P::ground)>;

/// A configuration without slots: its ClustererParams holds empty Params
/// for the required slots, which keeps the field count exact.
struct FieldCountProbe {};

/// rebind_params below carries 12 fields; a field added to (or removed from)
/// ClustererParams stops the build here until the rebind carries it.
static_assert(aggregate_field_count<ClustererParams<FieldCountProbe>>() == 12,
              "rebind_params: ClustererParams gained or lost a field: carry it in rebind_params "
              "(include/streamclust/rebind_params.hpp) and in its test");

}  // namespace detail

/// The parameters `from` of a `Source` configuration as those of `Target`:
/// every slot whose Params type is the same and every engine parameter
/// copied, the slots given in `given` (Params values, matched to the
/// target's slots by type) replaced. O(size of the Params); copies the
/// motion slot's trajectory pointer, not the trajectory.
template <class Target, class Source, class... Given>
ClustererParams<Target> rebind_params(const ClustererParams<Source>& from, const Given&... given) {
  using To = ClustererParams<Target>;
  static_assert(((detail::slots_taking<To, Given> == 1) && ...),
                "rebind_params: each value given must be the Params of exactly one slot of the target configuration");
  // Names every field: a field added to ClustererParams fails to compile here.
  const auto& [projection, spatial_index, linkage, window, resolution, mask_size, crowded_cell_chains, connectivity,
               motion, ground, time_order, first_stream_index] = from;
  return To{detail::rebind_projection<decltype(To::projection)>(projection, given...),
            detail::rebind_spatial_index<decltype(To::spatial_index)>(spatial_index, given...),
            detail::rebind_linkage<decltype(To::linkage)>(linkage, given...),
            detail::rebind_window<decltype(To::window)>(window, given...),
            detail::rebind_resolution<decltype(To::resolution)>(resolution, given...),
            mask_size,
            crowded_cell_chains,
            detail::rebind_connectivity<decltype(To::connectivity)>(connectivity, given...),
            detail::rebind_motion<decltype(To::motion)>(motion, given...),
            detail::rebind_ground<decltype(To::ground)>(ground, given...),
            time_order,
            first_stream_index};
}

}  // namespace streamclust
