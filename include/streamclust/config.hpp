// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Reading a configuration struct: its named policy slots, the optional
/// visitor slot, the runtime parameter aggregate of a clusterer, and the
/// concept checks that open every clusterer.
///
/// A configuration is a struct of named slots:
/// \code
/// struct MyConfig {
///   using projection = SphericalProjection;
///   using spatial_index = BucketGrid;
///   using linkage = AngularLinkage;
///   using window = TimeWindow;
///   using resolution = FixedResolution;
///   using visitor = NullVisitor;  // optional
///   using connectivity = LazyBfsConnectivity;  // optional (the paper's, the default)
///   using motion = NoMotion;      // optional: sensor poses / mount (PosedMotion)
///   using ground = NoGround;      // optional: structure removal (HeightMapGround)
///   static constexpr bool timed = false;  // optional: measure phase latencies
/// };
/// \endcode
/// Presets are such structs; derive from one and override a slot.

#include <streamclust/acceptance.hpp>
#include <streamclust/concepts.hpp>
#include <streamclust/concepts/connectivity.hpp>
#include <streamclust/concepts/ground.hpp>
#include <streamclust/concepts/motion.hpp>
#include <streamclust/connectivity/lazy_bfs.hpp>
#include <streamclust/ground/no_ground.hpp>
#include <streamclust/motion/no_motion.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace streamclust {
namespace detail {

/// Stand-in for a missing slot: satisfies no concept, so the slot's static
/// assertion names what is missing instead of a wall of template errors.
struct MissingSlot {};

#define STREAMCLUST_DETAIL_SLOT(NAME)                                                  \
  template <class C, class = void>                                                     \
  struct slot_##NAME {                                                                 \
    using type = MissingSlot;                                                          \
  };                                                                                   \
  template <class C>                                                                   \
  struct slot_##NAME<C, std::void_t<typename C::NAME>> {                               \
    using type = typename C::NAME;                                                     \
  };
STREAMCLUST_DETAIL_SLOT(projection)
STREAMCLUST_DETAIL_SLOT(spatial_index)
STREAMCLUST_DETAIL_SLOT(linkage)
STREAMCLUST_DETAIL_SLOT(window)
STREAMCLUST_DETAIL_SLOT(resolution)
#undef STREAMCLUST_DETAIL_SLOT

/// Optional slots: the configuration's type, else the default.
#define STREAMCLUST_DETAIL_SLOT_OR(NAME, DEFAULT)                                      \
  template <class C, class = void>                                                     \
  struct slot_##NAME {                                                                 \
    using type = DEFAULT;                                                              \
  };                                                                                   \
  template <class C>                                                                   \
  struct slot_##NAME<C, std::void_t<typename C::NAME>> {                               \
    using type = typename C::NAME;                                                     \
  };
STREAMCLUST_DETAIL_SLOT_OR(visitor, NullVisitor)
STREAMCLUST_DETAIL_SLOT_OR(connectivity, LazyBfsConnectivity)
STREAMCLUST_DETAIL_SLOT_OR(motion, NoMotion)
STREAMCLUST_DETAIL_SLOT_OR(ground, NoGround)
#undef STREAMCLUST_DETAIL_SLOT_OR

template <class C, class = void>
struct config_timed : std::false_type {};
template <class C>
struct config_timed<C, std::void_t<decltype(C::timed)>> : std::bool_constant<C::timed> {};

/// Params of a policy, or an empty struct when the slot is invalid (the
/// static assertion reports the real problem).
template <class P, class = void>
struct params_of {
  struct type {};
};
template <class P>
struct params_of<P, std::void_t<typename P::Params>> {
  using type = typename P::Params;
};

}  // namespace detail

/// The policies of a configuration, with the visitor defaulted to NullVisitor.
template <class Config>
struct config_traits {
  using projection = typename detail::slot_projection<Config>::type;
  using spatial_index = typename detail::slot_spatial_index<Config>::type;
  using linkage = typename detail::slot_linkage<Config>::type;
  using window = typename detail::slot_window<Config>::type;
  using resolution = typename detail::slot_resolution<Config>::type;
  using visitor = typename detail::slot_visitor<Config>::type;
  /// Optional slot; absent => the paper's strategy (LazyBfsConnectivity).
  using connectivity = typename detail::slot_connectivity<Config>::type;
  /// Optional slot; absent => NoMotion (the world is the sensor frame).
  using motion = typename detail::slot_motion<Config>::type;
  /// Optional slot; absent => NoGround (every accepted point is clustered).
  using ground = typename detail::slot_ground<Config>::type;
  /// `static constexpr bool timed = true;` in a config makes the engine
  /// measure its phases (RetrievalStats::phase_us); off by default, free when off.
  static constexpr bool timed = detail::config_timed<Config>::value;
};

/// Runtime parameters of a clusterer built from `Config`: one Params per
/// policy plus the neighbourhood mask width. Brace-constructible:
/// `ClustererParams<CArcConfig> p; p.linkage.theta_deg = 30.0f;`.
template <class Config>
struct ClustererParams {
  typename detail::params_of<typename config_traits<Config>::projection>::type projection{};
  typename detail::params_of<typename config_traits<Config>::spatial_index>::type spatial_index{};
  typename detail::params_of<typename config_traits<Config>::linkage>::type linkage{};
  typename detail::params_of<typename config_traits<Config>::window>::type window{};
  typename detail::params_of<typename config_traits<Config>::resolution>::type resolution{};
  /// Width w of the w x w neighbourhood mask in cells; odd, 1 to 255.
  int mask_size = 5;
  /// StreamClusterer: read crowded cells by their chains of linked points
  /// (engine/cell_chains.hpp; an index with unbounded cells and the chain
  /// capability, e.g. BucketGrid): the same components, O(1) per point in a
  /// cell of duplicates. Off: every linked pair is an edge (a point graph of
  /// all linkage edges, O(k^2) in a crowded cell).
  bool crowded_cell_chains = true;
  typename detail::params_of<typename config_traits<Config>::connectivity>::type connectivity{};
  typename detail::params_of<typename config_traits<Config>::motion>::type motion{};
  typename detail::params_of<typename config_traits<Config>::ground>::type ground{};
  /// The time order's jump guard (acceptance.hpp; StreamClusterer and
  /// FrameClusterer).
  StreamTimeOrder::Params time_order{};
  /// Stream index of the first offered point (StreamClusterer and
  /// FrameClusterer; the batch clusterer numbers its input from 0): a
  /// clusterer that resumes a stream continues its numbering.
  std::uint64_t first_stream_index = 0;
};

namespace detail {
inline int checked_mask_half_width(int mask_size) {
  if (mask_size < 1 || mask_size > 255 || mask_size % 2 == 0) {
    throw std::invalid_argument("mask_size = " + std::to_string(mask_size) +
                                " is invalid: expected an odd number of cells in [1, 255]");
  }
  return mask_size / 2;
}
}  // namespace detail

}  // namespace streamclust

/// Checks every slot of a configuration; used at the top of each clusterer.
#define STREAMCLUST_CHECK_CONFIG(Config)                                                     \
  STREAMCLUST_CHECK_PROJECTION_POLICY(typename ::streamclust::config_traits<Config>::projection);       \
  STREAMCLUST_CHECK_SPATIAL_INDEX_POLICY(typename ::streamclust::config_traits<Config>::spatial_index); \
  STREAMCLUST_CHECK_LINKAGE_POLICY(typename ::streamclust::config_traits<Config>::linkage);             \
  STREAMCLUST_CHECK_WINDOW_POLICY(typename ::streamclust::config_traits<Config>::window);               \
  STREAMCLUST_CHECK_RESOLUTION_POLICY(typename ::streamclust::config_traits<Config>::resolution);       \
  STREAMCLUST_CHECK_VISITOR_POLICY(typename ::streamclust::config_traits<Config>::visitor);             \
  STREAMCLUST_CHECK_CONNECTIVITY_POLICY(typename ::streamclust::config_traits<Config>::connectivity);   \
  STREAMCLUST_CHECK_MOTION_POLICY(typename ::streamclust::config_traits<Config>::motion);               \
  STREAMCLUST_CHECK_GROUND_POLICY(typename ::streamclust::config_traits<Config>::ground)
