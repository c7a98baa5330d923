// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The compiled configurations the tool runs: one StreamClusterer (or
/// FrameClusterer) configuration per combination of options it offers, so
/// that every run gets its policies' fast paths (the linkage's payloads and
/// link_many, the window's inlined test). `with_engine_config` maps the
/// options to that configuration once, at start-up, through the tool's
/// registry (cli/tool_policies.hpp): every registered index and
/// connectivity, the time and count windows.

#include "cli/options.hpp"
#include "cli/run_setup.hpp"

#include <streamclust/config.hpp>
#include <streamclust/connectivity/lazy_bfs.hpp>
#include <streamclust/connectivity/spanning_forest.hpp>
#include <streamclust/ground/runtime_ground.hpp>
#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/index/overwrite_grid.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/motion/runtime_motion.hpp>
#include <streamclust/linkage/range_adaptive.hpp>
#include <streamclust/projection/cylindrical.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/resolution/runtime_resolution.hpp>
#include <streamclust/window/count_window.hpp>
#include <streamclust/window/time_window.hpp>

#include <stdexcept>
#include <type_traits>

namespace streamclust::cli {

/// A configuration of the tool. Every slot is compiled in except the
/// resolution, which only runs once (the calibration of the first window)
/// and so costs nothing per point as a run-time choice, and the motion and
/// ground stages, run-time forwarders (a predictable branch per point; the
/// object partition is what the compiled policies give). Not `timed`: the
/// engine's phase timers read the clock a few times per point (about 15 %
/// of a Mid-360 cycle); the report times insertion and retrieval from
/// outside instead, and bench_latency's timed pass gives the full split.
template <class Projection, class Index, class Linkage, class Window, class Connectivity = SpanningForestConnectivity>
struct CliConfig {
  using projection = Projection;
  using spatial_index = Index;
  using linkage = Linkage;
  using window = Window;
  using resolution = RuntimeResolution;
  using connectivity = Connectivity;
  using motion = RuntimeMotion;
  using ground = RuntimeGround;
  static constexpr bool timed = false;
};

/// The time order's parameters of the options (the clusterer's and the
/// driver's copy are the same).
inline StreamTimeOrder::Params engine_time_order_params(const ClusterOptions& o) {
  StreamTimeOrder::Params p;
  p.max_jump = o.max_time_jump;
  return p;
}

/// The parameters of `Config` from the options. Throws UsageError for a
/// value a policy rejects.
template <class Config>
ClustererParams<Config> make_params(const ClusterOptions& o) {
  ClustererParams<Config> p;
  p.projection.azimuth_min_deg = o.azimuth_min;
  p.projection.azimuth_max_deg = o.azimuth_max;
  p.projection.min_range = o.min_range;
  if constexpr (std::is_same_v<typename Config::projection, SphericalProjection>) {
    p.projection.elevation_min_deg = o.elevation_min;
    p.projection.elevation_max_deg = o.elevation_max;
  } else {
    p.projection.z_min = o.z_min;
    p.projection.z_max = o.z_max;
  }
  p.spatial_index = o.params.template get<typename Config::spatial_index>();
  p.linkage = o.params.template get<typename Config::linkage>();
  p.connectivity = o.params.template get<typename Config::connectivity>();
  if constexpr (std::is_same_v<typename Config::window, TimeWindow>) {
    p.window.duration = o.window_seconds;
  } else {
    p.window.capacity = o.window_count;
  }
  p.resolution.adaptive = !o.grid.has_value();
  if (o.grid) p.resolution.fixed = {o.grid->first, o.grid->second};
  p.resolution.adaptive_loop.max_multiplicity = o.max_multiplicity;
  p.mask_size = o.mask;
  p.time_order = engine_time_order_params(o);
  if constexpr (has_sensor_fit_v<typename Config::linkage>) {
    if (o.setup && o.setup->sensor_fit) {
      try {
        p.linkage = Config::linkage::fit_to_sensor(p.linkage, *o.setup->sensor_fit);
      } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--linkage ") + o.linkage + ": fitting it to the first window: " + e.what());
      }
    }
  }
  if (o.setup) {
    p.motion = o.setup->motion;
    p.ground = o.setup->ground;
    if constexpr (std::is_same_v<typename Config::projection, SphericalProjection>) {
      if (o.setup->world_fov) {
        p.projection.azimuth_min_deg = o.setup->world_fov->azimuth_min_deg;
        p.projection.azimuth_max_deg = o.setup->world_fov->azimuth_max_deg;
        p.projection.elevation_min_deg = o.setup->world_fov->elevation_min_deg;
        p.projection.elevation_max_deg = o.setup->world_fov->elevation_max_deg;
      }
    }
  }
  return p;
}

using registry::TypeTag;

namespace detail {

/// `Frame`: frame mode, which has no connectivity strategy (one
/// configuration per index and window, the connectivity slot left at its
/// default).
template <bool Frame, class Projection, class Linkage, class Window, class F>
decltype(auto) with_index_and_connectivity(const ClusterOptions& o, F&& f) {
  return ToolRegistry::with_policy<Slot::spatial_index>(o.index, [&](auto index) -> decltype(auto) {
    using I = typename decltype(index)::type;
    if constexpr (Frame) {
      return f(TypeTag<CliConfig<Projection, I, Linkage, Window>>{});
    } else {
      return ToolRegistry::with_policy<Slot::connectivity>(o.connectivity, [&](auto connectivity) -> decltype(auto) {
        return f(TypeTag<CliConfig<Projection, I, Linkage, Window, typename decltype(connectivity)::type>>{});
      });
    }
  });
}

}  // namespace detail

/// Calls `f(TypeTag<Config>{})` with the compiled configuration of the
/// options (projection `Projection` and linkage `Linkage` as chosen by the
/// caller; index, window and, unless `Frame`, connectivity from `o`) and
/// returns its result.
template <bool Frame, class Projection, class Linkage, class F>
decltype(auto) with_engine_config(const ClusterOptions& o, F&& f) {
  if (o.window_is_count) return detail::with_index_and_connectivity<Frame, Projection, Linkage, CountWindow>(o, f);
  return detail::with_index_and_connectivity<Frame, Projection, Linkage, TimeWindow>(o, f);
}

/// Calls `f(TypeTag<Projection>{}, TypeTag<Linkage>{})` with the projection and
/// the linkage the options name.
template <class F>
decltype(auto) with_projection_and_linkage(const ClusterOptions& o, F&& f) {
  return ToolRegistry::with_policy<Slot::projection>(o.projection, [&](auto projection) -> decltype(auto) {
    return ToolRegistry::with_policy<Slot::linkage>(o.linkage,
                                                   [&](auto linkage) -> decltype(auto) { return f(projection, linkage); });
  });
}

}  // namespace streamclust::cli
