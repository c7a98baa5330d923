// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Ready-made configurations and the plain helper API for users who never
/// touch templates. A preset is a struct of policy slots: derive from one and
/// override a slot to make your own.
///
/// | preset                | projection | index     | linkage  | window | resolution | connectivity        |
/// |-----------------------|------------|-----------|----------|--------|------------|---------------------|
/// | CArcConfig            | spherical  | bucket    | angular  | time   | adaptive   | lazy BFS (paper)    |
/// | CArcFixedConfig       | spherical  | bucket    | angular  | time   | fixed      | lazy BFS (paper)    |
/// | CArcCappedConfig      | spherical  | capped    | angular  | time   | adaptive   | lazy BFS (paper)    |
/// | FrameBaselineConfig   | spherical  | overwrite | angular  | time   | adaptive   | lazy BFS (paper)    |
/// | EuclideanConfig       | spherical  | bucket    | euclidean| time   | adaptive   | lazy BFS (paper)    |
/// | CArcFastConfig        | spherical  | bucket    | angular  | time   | adaptive   | spanning forest     |
/// | CArcCappedFastConfig  | spherical  | capped    | angular  | time   | adaptive   | spanning forest     |
/// | CArcRebuildConfig     | spherical  | bucket    | angular  | time   | adaptive   | union-find rebuild  |
/// | CArcCappedRebuildConfig | spherical | capped   | angular  | time   | adaptive   | union-find rebuild  |
///
/// Which to pick: all give exactly the same partition for the same index
/// (the batch oracle). CArcConfig is the paper's algorithm, with visitor
/// hooks and a component graph of local clusters and bridges at all times.
/// CArcFastConfig is the one to deploy when only the labels/components of
/// each retrieval matter: its cost per retrieval does not depend on how much
/// of the window is pending, and is O(N + edges inserted since the previous
/// retrieval) (docs/design-decisions.md). The rebuild
/// presets are the previous fast presets (O(N + E) per retrieval), kept for
/// comparison and for the point-level edge accessors, which the spanning
/// forest does not store. The capped variants bound the work per point on
/// scan patterns that revisit cells (Avia).

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/concepts/visitor.hpp>
#include <streamclust/connectivity/lazy_bfs.hpp>
#include <streamclust/connectivity/spanning_forest.hpp>
#include <streamclust/connectivity/union_find_rebuild.hpp>
#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/index/overwrite_grid.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/resolution/adaptive.hpp>
#include <streamclust/resolution/fixed.hpp>
#include <streamclust/sensors.hpp>
#include <streamclust/stream_clusterer.hpp>
#include <streamclust/window/time_window.hpp>

#include <type_traits>

namespace streamclust {

/// C-ARC as in the paper: spherical projection, bucket grid, angular
/// (Bogoslavskyi) linkage, time window, adaptive resolution.
struct CArcConfig {
  using projection = SphericalProjection;
  using spatial_index = BucketGrid;
  using linkage = AngularLinkage;
  using window = TimeWindow;
  using resolution = AdaptiveResolution;
  using visitor = NullVisitor;
  using connectivity = LazyBfsConnectivity;
};

/// C-ARC with a grid given by the user (no calibration window).
struct CArcFixedConfig : CArcConfig {
  using resolution = FixedResolution;
};

/// C-ARC with at most K points per cell (bounded insertion cost).
struct CArcCappedConfig : CArcConfig {
  using spatial_index = CappedGrid;
};

/// The frame-based baseline's range image: one point per cell, newest wins.
/// Use with BatchClusterer in BatchMode::range_image for the classic method.
struct FrameBaselineConfig : CArcConfig {
  using spatial_index = OverwriteGrid;
};

/// C-ARC's engine with plain Euclidean single linkage.
struct EuclideanConfig : CArcConfig {
  using linkage = EuclideanLinkage;
};

/// C-ARC's policies with a spanning forest of the window folded at each
/// retrieval instead of the paper's lazy BFS: same partition, cost per
/// retrieval O(N + edges inserted since the previous one) whatever is
/// pending, no stored point-level edges; no visitor events, no bridges (see
/// SpanningForestConnectivity).
struct CArcFastConfig : CArcConfig {
  using connectivity = SpanningForestConnectivity;
};

/// CArcFastConfig with at most K points per cell.
struct CArcCappedFastConfig : CArcFastConfig {
  using spatial_index = CappedGrid;
};

/// C-ARC's policies with the union-find rebuild at each retrieval: same
/// partition, cost per retrieval O(N + E) whatever is pending, the point
/// graph's edges stored (see UnionFindRebuildConnectivity). CArcFastConfig
/// before the spanning forest.
struct CArcRebuildConfig : CArcConfig {
  using connectivity = UnionFindRebuildConnectivity;
};

/// CArcRebuildConfig with at most K points per cell.
struct CArcCappedRebuildConfig : CArcRebuildConfig {
  using spatial_index = CappedGrid;
};

using CArcClusterer = StreamClusterer<CArcConfig>;

/// The C-ARC parameters in one flat aggregate. Defaults are the paper's
/// (w = 5, T_M = 2, T_G = 0.1, T_D = 0.9, lambda_G = lambda_D = 0.2) and
/// Bogoslavskyi's theta = 10 degrees; the paper tunes theta per sensor
/// (see carc_mid360_params and carc_avia_params).
struct CArcParams {
  float theta_deg = 10.0f;           ///< angular linkage threshold [deg], (0, 90)
  float min_ray_angle_deg = 0.2f;    ///< floor on the ray angle alpha [deg] (near-coincident Livox rays); 0 = off
  double window_seconds = 0.1;       ///< sliding window T_B [s]
  int mask_size = 5;                 ///< w of the w x w mask, odd
  float max_multiplicity = 2.0f;     ///< T_M: mean points per occupied cell at calibration
  float target_gap = 0.1f;           ///< T_G
  float target_density = 0.9f;       ///< T_D
  float gain_gap = 0.2f;             ///< lambda_G
  float gain_density = 0.2f;         ///< lambda_D
  SphericalProjection::Params field_of_view{};  ///< FOV bounds and minimum range
};

/// The projection bounds of a sensor of the table in sensors.hpp: its field
/// of view widened by kFieldOfViewMarginDeg on each side, minimum range
/// SphericalProjection's default.
inline SphericalProjection::Params field_of_view_of(const SensorFacts& sensor) {
  SphericalProjection::Params fov;
  fov.azimuth_min_deg = sensor.projection_azimuth_min_deg();
  fov.azimuth_max_deg = sensor.projection_azimuth_max_deg();
  fov.elevation_min_deg = sensor.projection_elevation_min_deg();
  fov.elevation_max_deg = sensor.projection_elevation_max_deg();
  return fov;
}

/// The rays' field of view of a sensor whose projection bounds are
/// `projection_fov` (the inverse of field_of_view_of): each bound narrowed by
/// kFieldOfViewMarginDeg, except a full azimuth circle and an elevation
/// bound within the margin of a pole, which stay. For the Mid-360's bounds,
/// elevation -7 to 52 degrees, the spec sheet's lowest ray.
inline SphericalProjection::Params ray_field_of_view(const SphericalProjection::Params& projection_fov) {
  constexpr auto margin = static_cast<float>(kFieldOfViewMarginDeg);
  SphericalProjection::Params rays = projection_fov;
  if (projection_fov.azimuth_max_deg - projection_fov.azimuth_min_deg < 360.0f - 2.0f * margin) {
    rays.azimuth_min_deg += margin;
    rays.azimuth_max_deg -= margin;
  }
  if (projection_fov.elevation_min_deg > -90.0f + margin) rays.elevation_min_deg += margin;
  if (projection_fov.elevation_max_deg < 90.0f - margin) rays.elevation_max_deg -= margin;
  return rays;
}

/// The Livox Mid-360 (livox_mid360: 360 x 59 degrees, elevation -7 to 52;
/// projection -7.5 to 52.5), theta = 30 degrees as in the paper.
inline CArcParams carc_mid360_params() {
  CArcParams p;
  p.theta_deg = 30.0f;
  p.field_of_view = field_of_view_of(livox_mid360);
  return p;
}

/// The Livox Avia (livox_avia: 70.4 x 77.2 degrees; projection 71.4 x 78.2),
/// theta = 80 degrees as in the paper.
inline CArcParams carc_avia_params() {
  CArcParams p;
  p.theta_deg = 80.0f;
  p.field_of_view = field_of_view_of(livox_avia);
  return p;
}

/// The frame-based baseline of the paper's comparison (Bogoslavskyi and
/// Stachniss's range image): FrameBaselineConfig in a FrameClusterer (or
/// BatchClusterer in BatchMode::range_image) with C-ARC's parameters and a
/// 3 x 3 mask (w = 3, as the paper compares both).
inline CArcParams baseline_params() {
  CArcParams p;
  p.mask_size = 3;
  return p;
}

/// Template-level parameters of any config whose slots match C-ARC's
/// (spherical projection, time window); theta and the ray-angle floor are
/// copied when the linkage slot is AngularLinkage (other linkages keep their
/// default Params), the calibration targets when the resolution slot is
/// AdaptiveResolution.
template <class Config = CArcConfig>
ClustererParams<Config> to_clusterer_params(const CArcParams& p) {
  ClustererParams<Config> out;
  out.projection = p.field_of_view;
  if constexpr (std::is_same_v<typename config_traits<Config>::linkage, AngularLinkage>) {
    out.linkage.theta_deg = p.theta_deg;
    out.linkage.min_ray_angle_deg = p.min_ray_angle_deg;
  }
  out.window.duration = p.window_seconds;
  if constexpr (std::is_same_v<typename config_traits<Config>::resolution, AdaptiveResolution>) {
    out.resolution.max_multiplicity = p.max_multiplicity;
    out.resolution.target_gap = p.target_gap;
    out.resolution.target_density = p.target_density;
    out.resolution.gain_gap = p.gain_gap;
    out.resolution.gain_density = p.gain_density;
  }
  out.mask_size = p.mask_size;
  return out;
}

/// A C-ARC engine from flat parameters. Throws std::invalid_argument on a bad value.
inline CArcClusterer make_carc(const CArcParams& params = CArcParams{}) {
  return CArcClusterer(to_clusterer_params<CArcConfig>(params));
}

}  // namespace streamclust
