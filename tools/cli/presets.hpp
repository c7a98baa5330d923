// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The presets of `streamclust cluster` (and of the Python module, which
/// parses its keywords with the same parser): each is a preset of the
/// library, its values read from the library's objects (CArcParams and
/// carc_*_params in presets.hpp, objects_params in objects_presets.hpp, the
/// sensors of sensors.hpp), never restated. A preset fills the options
/// before the other options override them; run_setup.hpp then places the
/// sensor (mount, poses, height) with the library's objects_params too.

#include "cli/options.hpp"

#include <streamclust/objects_presets.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/sensors.hpp>

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace streamclust::cli {

/// Every preset's name and a one-line summary, in the order the help lists
/// them. The first is the default.
inline std::vector<std::pair<std::string_view, std::string_view>> preset_catalogue() {
  return {
      {"carc", "the paper's C-ARC (CArcParams): angular linkage theta 10 deg, T_B 0.1 s, w 5, T_M 2, full sphere"},
      {"carc-mid360", "C-ARC for the Livox Mid-360 (carc_mid360_params): theta 30 deg, its field of view"},
      {"carc-avia", "C-ARC for the Livox Avia (carc_avia_params): theta 80 deg, its field of view"},
      {"baseline", "the frame-based range-image baseline (baseline_params): overwrite grid, frame mode, w 3"},
      {"objects", "objects of any sensor (objects_params, ObjectsConfig): --ground, range-adaptive linkage "
                  "max(0.4 m, 0.03 x range), capped grid, forest, T_B 0.5 s, full sphere"},
      {"objects-mid360", "objects with the Livox Mid-360 (objects_mid360_params): as objects, its field of view"},
      {"objects-avia", "objects with the Livox Avia (objects_avia_params): as objects, its field of view"},
  };
}

/// The --preset lines of the help: every preset of preset_catalogue() with
/// its summary.
inline std::string preset_help() {
  const auto catalogue = preset_catalogue();
  std::string names, lines;
  std::size_t width = 0;
  for (const auto& [name, summary] : catalogue) width = std::max(width, name.size());
  for (const auto& [name, summary] : catalogue) {
    names += (names.empty() ? "" : "|") + std::string(name);
    lines += "        " + std::string(name) + std::string(width + 2 - name.size(), ' ') + std::string(summary) + "\n";
  }
  return "  --preset " + names + "   (default " + std::string(catalogue.front().first) + ")\n" + lines;
}

namespace detail {

/// The options of the library's C-ARC parameters.
inline void apply_carc_params(const CArcParams& p, ClusterOptions& o) {
  AngularLinkage::Params& angular = o.params.get<AngularLinkage>();
  angular.theta_deg = p.theta_deg;
  angular.min_ray_angle_deg = p.min_ray_angle_deg;
  o.window_seconds = p.window_seconds;
  o.mask = p.mask_size;
  o.max_multiplicity = p.max_multiplicity;
  o.azimuth_min = p.field_of_view.azimuth_min_deg;
  o.azimuth_max = p.field_of_view.azimuth_max_deg;
  o.elevation_min = p.field_of_view.elevation_min_deg;
  o.elevation_max = p.field_of_view.elevation_max_deg;
  o.min_range = p.field_of_view.min_range;
}

/// The options of the library's objects parameters of a sensor whose rays
/// `sensor_fov` holds (sensor frame; the run setup turns it to world
/// orientation with the mount or poses, as objects_params does).
inline void apply_objects_params(const SphericalProjection::Params& sensor_fov, ClusterOptions& o) {
  using Objects = config_traits<ObjectsConfig>;
  static_assert(std::is_same_v<Objects::spatial_index, CappedGrid> &&
                    std::is_same_v<Objects::linkage, RangeAdaptiveLinkage> &&
                    std::is_same_v<Objects::window, TimeWindow> &&
                    std::is_same_v<Objects::resolution, AdaptiveResolution> &&
                    std::is_same_v<Objects::connectivity, SpanningForestConnectivity> &&
                    std::is_same_v<Objects::ground, HeightMapGround> && std::is_same_v<Objects::motion, PosedMotion>,
                "ObjectsConfig changed a slot: choose the tool's policies for it here");
  const ClustererParams<ObjectsConfig> p = objects_params(sensor_fov);
  o.index = "capped";
  o.params.get<CappedGrid>() = p.spatial_index;
  o.linkage = "range-adaptive";
  o.params.get<RangeAdaptiveLinkage>() = p.linkage;
  o.window_is_count = false;
  o.window_seconds = p.window.duration;
  o.max_multiplicity = p.resolution.max_multiplicity;
  o.mask = p.mask_size;
  o.connectivity = "forest";
  o.params.get<SpanningForestConnectivity>() = p.connectivity;
  o.max_time_jump = p.time_order.max_jump;
  o.azimuth_min = sensor_fov.azimuth_min_deg;
  o.azimuth_max = sensor_fov.azimuth_max_deg;
  o.elevation_min = sensor_fov.elevation_min_deg;
  o.elevation_max = sensor_fov.elevation_max_deg;
  o.min_range = sensor_fov.min_range;
  o.ground = true;
  o.ground_tolerance = p.ground.ground_tolerance;
  o.ground_cell = p.ground.cell_size;
  o.max_slope_deg = p.ground.max_slope_deg;
  o.ceiling = p.ground.detect_ceiling;
  o.walls = p.ground.detect_walls;
}

}  // namespace detail

/// Applies the preset `name` of preset_catalogue() to `o` (before the other
/// options override it). Throws UsageError naming the presets for any
/// other name.
inline void apply_preset(const std::string& name, ClusterOptions& o) {
  if (name == "carc") {
    detail::apply_carc_params(CArcParams{}, o);
  } else if (name == "carc-mid360") {
    detail::apply_carc_params(carc_mid360_params(), o);
  } else if (name == "carc-avia") {
    detail::apply_carc_params(carc_avia_params(), o);
  } else if (name == "baseline") {
    detail::apply_carc_params(baseline_params(), o);
    static_assert(std::is_same_v<config_traits<FrameBaselineConfig>::spatial_index, OverwriteGrid>,
                  "FrameBaselineConfig changed its index: choose the tool's index for it here");
    o.index = "overwrite";
    o.mode = Mode::frame;
  } else if (name == "objects") {
    detail::apply_objects_params(SphericalProjection::Params{}, o);
  } else if (name == "objects-mid360") {
    detail::apply_objects_params(field_of_view_of(livox_mid360), o);
  } else if (name == "objects-avia") {
    detail::apply_objects_params(field_of_view_of(livox_avia), o);
  } else {
    std::string names;
    const auto catalogue = preset_catalogue();
    for (std::size_t i = 0; i < catalogue.size(); ++i) {
      names += i == 0 ? "" : i + 1 == catalogue.size() ? " or " : ", ";
      names += catalogue[i].first;
    }
    throw UsageError("--preset: expected " + names + ", got '" + name + "'");
  }
}

}  // namespace streamclust::cli
