// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The registrations of the policies streamclust ships, and StockRegistry,
/// the registry of the `streamclust` tool: the linkages angular, euclidean,
/// range-adaptive and scan-adaptive, the indexes bucket, capped and overwrite, the time
/// and count windows, the spherical and cylindrical projections and the
/// lazy-BFS and spanning-forest connectivities. A tool with its own
/// policies lists these and its own (cmake/StreamclustAddTool.cmake).
/// Option names, defaults and messages are the tool's (docs/cli.md).

#include <streamclust/registry/descriptor.hpp>
#include <streamclust/registry/option.hpp>
#include <streamclust/registry/registry.hpp>

#include <streamclust/connectivity/lazy_bfs.hpp>
#include <streamclust/connectivity/spanning_forest.hpp>
#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/index/overwrite_grid.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/linkage/range_adaptive.hpp>
#include <streamclust/linkage/scan_adaptive.hpp>
#include <streamclust/projection/cylindrical.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/window/count_window.hpp>
#include <streamclust/window/time_window.hpp>

#include <cstdio>
#include <string>
#include <vector>

namespace streamclust::registry {

template <>
struct PolicyDescriptor<AngularLinkage> {
  static constexpr Slot slot = Slot::linkage;
  static constexpr const char* name = "angular";
  static constexpr const char* summary = "C-ARC's criterion: link when the angle beta of the pair exceeds --theta";
  static std::vector<Option<AngularLinkage::Params>> options() {
    using P = AngularLinkage::Params;
    return {option("--theta", &P::theta_deg, "DEG", ValueKind::positive, "threshold on beta [deg], in (0, 90)",
                   "theta_deg"),
            option("--min-ray-angle", &P::min_ray_angle_deg, "DEG", ValueKind::number,
                   "floor on the angle between the rays [deg], 0: none", "min_ray_angle_deg")};
  }
  static std::string describe(const AngularLinkage::Params& p) {
    char line[64];
    std::snprintf(line, sizeof line, "angular theta %.3g deg", static_cast<double>(p.theta_deg));
    return line;
  }
};

template <>
struct PolicyDescriptor<EuclideanLinkage> {
  static constexpr Slot slot = Slot::linkage;
  static constexpr const char* name = "euclidean";
  static constexpr const char* summary = "link two points within --distance";
  static std::vector<Option<EuclideanLinkage::Params>> options() {
    using P = EuclideanLinkage::Params;
    return {option("--distance", &P::max_distance, "M", ValueKind::positive, "threshold [m]", "distance")};
  }
  static std::string describe(const EuclideanLinkage::Params& p) {
    char line[64];
    std::snprintf(line, sizeof line, "euclidean %.3g m", static_cast<double>(p.max_distance));
    return line;
  }
};

template <>
struct PolicyDescriptor<RangeAdaptiveLinkage> {
  static constexpr Slot slot = Slot::linkage;
  static constexpr const char* name = "range-adaptive";
  static constexpr const char* summary = "link within max(--min-distance, --range-factor x the nearer range)";
  static std::vector<Option<RangeAdaptiveLinkage::Params>> options() {
    using P = RangeAdaptiveLinkage::Params;
    return {option("--min-distance", &P::min_distance, "M", ValueKind::positive,
                   "radius near the sensor [m], in (0, 100]", "min_distance"),
            option("--range-factor", &P::range_factor, "F", ValueKind::number,
                   "growth of the radius per metre of range [m/m], in [0, 1]", "range_factor")};
  }
  static std::string describe(const RangeAdaptiveLinkage::Params& p) {
    char line[80];
    std::snprintf(line, sizeof line, "range-adaptive max(%.3g m, %.3g x range)", static_cast<double>(p.min_distance),
                  static_cast<double>(p.range_factor));
    return line;
  }
};

template <>
struct PolicyDescriptor<ScanAdaptiveLinkage> {
  static constexpr Slot slot = Slot::linkage;
  static constexpr const char* name = "scan-adaptive";
  static constexpr const char* summary =
      "link within max(--min-distance, --spacing-factor x the sensor's local spacing x range), the spacing "
      "table from the first window";
  static std::vector<Option<ScanAdaptiveLinkage::Params>> options() {
    using P = ScanAdaptiveLinkage::Params;
    return {option("--min-distance", &P::min_distance, "M", ValueKind::positive,
                   "radius near the sensor [m], in (0, 100]", "min_distance"),
            option("--spacing-factor", &P::spacing_factor, "F", ValueKind::positive,
                   "the radius in local spacings of the returns, in (0, 1000]", "spacing_factor"),
            option("--spacing-quantile", &P::spacing_quantile, "Q", ValueKind::number,
                   "the spacing: this quantile of the gaps between the first window's returns, in [0, 1]",
                   "spacing_quantile")};
  }
  static std::string describe(const ScanAdaptiveLinkage::Params& p) {
    char line[96];
    std::snprintf(line, sizeof line, "scan-adaptive max(%.3g m, %.3g x spacing x range)",
                  static_cast<double>(p.min_distance), static_cast<double>(p.spacing_factor));
    return line;
  }
};

template <>
struct PolicyDescriptor<BucketGrid> {
  static constexpr Slot slot = Slot::spatial_index;
  static constexpr const char* name = "bucket";
  static constexpr const char* summary = "every point of a cell kept (exact)";
  static std::vector<Option<BucketGrid::Params>> options() { return {}; }
};

template <>
struct PolicyDescriptor<CappedGrid> {
  static constexpr Slot slot = Slot::spatial_index;
  static constexpr const char* name = "capped";
  static constexpr const char* summary = "the newest --cap points of a cell kept";
  static std::vector<Option<CappedGrid::Params>> options() {
    return {option("--cap", &CappedGrid::Params::capacity, "K", ValueKind::count, "points per cell, 1 to 255", "cap")
                .at_most(255, "expected 1 to 255 points per cell")};
  }
};

template <>
struct PolicyDescriptor<OverwriteGrid> {
  static constexpr Slot slot = Slot::spatial_index;
  static constexpr const char* name = "overwrite";
  static constexpr const char* summary = "the newest point of a cell kept (the frame baseline's range image)";
  static std::vector<Option<OverwriteGrid::Params>> options() { return {}; }
};

template <>
struct PolicyDescriptor<TimeWindow> {
  static constexpr Slot slot = Slot::window;
  static constexpr const char* name = "time";
  static constexpr const char* summary = "the points of the last --window-time seconds";
  static std::vector<Option<TimeWindow::Params>> options() { return {}; }
};

template <>
struct PolicyDescriptor<CountWindow> {
  static constexpr Slot slot = Slot::window;
  static constexpr const char* name = "count";
  static constexpr const char* summary = "the last --window-count points";
  static std::vector<Option<CountWindow::Params>> options() { return {}; }
};

template <>
struct PolicyDescriptor<SphericalProjection> {
  static constexpr Slot slot = Slot::projection;
  static constexpr const char* name = "spherical";
  static constexpr const char* summary = "azimuth x elevation range image (C-ARC's)";
  static std::vector<Option<SphericalProjection::Params>> options() { return {}; }
};

template <>
struct PolicyDescriptor<CylindricalProjection> {
  static constexpr Slot slot = Slot::projection;
  static constexpr const char* name = "cylindrical";
  static constexpr const char* summary = "azimuth x height image (--fov-z)";
  static std::vector<Option<CylindricalProjection::Params>> options() { return {}; }
};

template <>
struct PolicyDescriptor<LazyBfsConnectivity> {
  static constexpr Slot slot = Slot::connectivity;
  static constexpr const char* name = "lazy-bfs";
  static constexpr const char* summary = "the paper's lazy BFS (same partition; its own stable ids)";
  static std::vector<Option<LazyBfsConnectivity::Params>> options() { return {}; }
};

template <>
struct PolicyDescriptor<SpanningForestConnectivity> {
  static constexpr Slot slot = Slot::connectivity;
  static constexpr const char* name = "forest";
  static constexpr const char* summary = "the spanning forest, the fastest exact strategy";
  static std::vector<Option<SpanningForestConnectivity::Params>> options() { return {}; }
};

/// The stock policies, each slot's in the order its choices are listed.
#define STREAMCLUST_STOCK_POLICIES                                                                            \
  ::streamclust::SphericalProjection, ::streamclust::CylindricalProjection, ::streamclust::BucketGrid,          \
      ::streamclust::CappedGrid, ::streamclust::OverwriteGrid, ::streamclust::AngularLinkage,                   \
      ::streamclust::EuclideanLinkage, ::streamclust::RangeAdaptiveLinkage, ::streamclust::ScanAdaptiveLinkage,   \
      ::streamclust::TimeWindow, ::streamclust::CountWindow, ::streamclust::LazyBfsConnectivity,                \
      ::streamclust::SpanningForestConnectivity

/// The registry of the `streamclust` tool.
using StockRegistry = PolicyRegistry<STREAMCLUST_STOCK_POLICIES>;

}  // namespace streamclust::registry
