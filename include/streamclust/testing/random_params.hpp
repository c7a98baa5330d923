// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Random parameters of the standard policies for the exactness check: the
/// `RandomParams<P>` hook (default: P's defaults; specialise it in namespace
/// streamclust::testing for a policy of your own) and `random_params<Config>`,
/// a whole ClustererParams drawn from them. The draws favour small, crowded
/// and extreme settings: the check's streams are a few hundred points.

#include <streamclust/config.hpp>
#include <streamclust/connectivity/spanning_forest.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/combinators.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/linkage/range_adaptive.hpp>
#include <streamclust/linkage/runtime_linkage.hpp>
#include <streamclust/projection/cylindrical.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/resolution/fixed.hpp>
#include <streamclust/window/count_window.hpp>
#include <streamclust/window/time_window.hpp>

#include <cstddef>
#include <cstdint>
#include <random>
#include <tuple>
#include <utility>

namespace streamclust::testing {

/// Random parameters of policy `P` for one oracle seed: `draw(params, rng)`
/// overwrites some fields of `params` (a `P::Params`) from `rng`. The
/// default keeps P's defaults. Specialisations favour small, crowded and
/// extreme settings (the oracle's streams are a few hundred points).
/// `rng` is a std::mt19937_64; the draws of one seed follow a fixed order
/// (ClustererParams: mask, resolution, projection, index, linkage, window,
/// connectivity), so a seed always gives the same parameters.
template <class P>
struct RandomParams {
  template <class Params, class Rng>
  static void draw(Params&, Rng&) {}
};

namespace internal {
template <class Rng>
float unit_float(Rng& rng) {
  return std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
}
}  // namespace internal

template <>
struct RandomParams<FixedResolution> {
  template <class Rng>
  static void draw(FixedResolution::Params& p, Rng& rng) {
    p.rows = 1 + static_cast<std::uint32_t>(rng() % 24);
    p.cols = 1 + static_cast<std::uint32_t>(rng() % 64);
  }
};

template <>
struct RandomParams<SphericalProjection> {
  template <class Rng>
  static void draw(SphericalProjection::Params& p, Rng& rng) {
    if (rng() % 2) {
      p.azimuth_min_deg = -60.0f;
      p.azimuth_max_deg = 60.0f;
    }
    if (rng() % 2) {
      p.elevation_min_deg = -30.0f;
      p.elevation_max_deg = 50.0f;
    }
  }
};

template <>
struct RandomParams<CylindricalProjection> {
  template <class Rng>
  static void draw(CylindricalProjection::Params& p, Rng& rng) {
    if (rng() % 2) {
      p.azimuth_min_deg = -60.0f;
      p.azimuth_max_deg = 60.0f;
    }
    p.z_min = -2.0f;
    p.z_max = 4.0f;
  }
};

template <>
struct RandomParams<CappedGrid> {
  template <class Rng>
  static void draw(CappedGrid::Params& p, Rng& rng) {
    p.capacity = 1 + static_cast<std::uint32_t>(rng() % 4);
  }
};

template <>
struct RandomParams<EuclideanLinkage> {
  template <class Rng>
  static void draw(EuclideanLinkage::Params& p, Rng& rng) {
    p.max_distance = 0.2f + 2.0f * internal::unit_float(rng);
  }
};

template <>
struct RandomParams<AngularLinkage> {
  template <class Rng>
  static void draw(AngularLinkage::Params& p, Rng& rng) {
    p.theta_deg = 5.0f + 60.0f * internal::unit_float(rng);
    const float floors[] = {0.0f, 0.2f, 1.0f};
    p.min_ray_angle_deg = floors[rng() % 3];
  }
};

template <>
struct RandomParams<RangeAdaptiveLinkage> {
  template <class Rng>
  static void draw(RangeAdaptiveLinkage::Params& p, Rng& rng) {
    p.min_distance = 0.05f + 0.5f * internal::unit_float(rng);
    const float factor = 0.005f + 0.1f * internal::unit_float(rng);
    p.range_factor = rng() % 4 == 0 ? 0.0f : factor;  // 0: a fixed radius
  }
};

namespace internal {
/// Draws every child's parameters in order (the combinators' Params tuple).
template <class... Ls, class Rng>
void draw_children(std::tuple<typename Ls::Params...>& p, Rng& rng) {
  std::apply([&](auto&... child) { (RandomParams<Ls>::draw(child, rng), ...); }, p);
}
}  // namespace internal

template <class... Ls>
struct RandomParams<AllOf<Ls...>> {
  template <class Rng>
  static void draw(typename AllOf<Ls...>::Params& p, Rng& rng) {
    internal::draw_children<Ls...>(p, rng);
  }
};

template <class... Ls>
struct RandomParams<AnyOf<Ls...>> {
  template <class Rng>
  static void draw(typename AnyOf<Ls...>::Params& p, Rng& rng) {
    internal::draw_children<Ls...>(p, rng);
  }
};

template <>
struct RandomParams<RuntimeLinkage> {
  template <class Rng>
  static void draw(RuntimeLinkage::Params& p, Rng& rng) {
    const RuntimeLinkage::Kind kinds[] = {RuntimeLinkage::Kind::angular, RuntimeLinkage::Kind::euclidean,
                                          RuntimeLinkage::Kind::range_adaptive};
    p.kind = kinds[rng() % 3];
    RandomParams<AngularLinkage>::draw(p.angular, rng);
    RandomParams<EuclideanLinkage>::draw(p.euclidean, rng);
    RandomParams<RangeAdaptiveLinkage>::draw(p.range_adaptive, rng);
  }
};

template <>
struct RandomParams<TimeWindow> {
  template <class Rng>
  static void draw(TimeWindow::Params& p, Rng& rng) {
    const double durations[] = {0.0, 0.0005, 0.01, 0.05, 0.2, 1.0};  // [s]
    p.duration = durations[rng() % 6];
  }
};

template <>
struct RandomParams<CountWindow> {
  template <class Rng>
  static void draw(CountWindow::Params& p, Rng& rng) {
    const std::size_t capacities[] = {1, 2, 7, 40, 150};
    p.capacity = capacities[rng() % 5];
  }
};

template <>
struct RandomParams<SpanningForestConnectivity> {
  template <class Rng>
  static void draw(SpanningForestConnectivity::Params& p, Rng& rng) {
    // The default threshold (65536 edges) never folds on the oracle's short
    // streams: mostly tiny ones, so that the fold runs between retrievals.
    const std::uint32_t thresholds[] = {1, 1, 3, 20, 65536};
    p.min_fold_edges = thresholds[rng() % 5];
    p.fold_edges_per_point = 1 + static_cast<std::uint32_t>(rng() % 2);
    p.prune_witnesses = static_cast<std::uint32_t>(rng() % 4);  // 0: every edge kept
  }
};

/// True for a connectivity strategy that folds its new edges without a
/// retrieval once they pass a threshold (counted in
/// RetrievalStats::forest_folds); the oracle then requires that such folds
/// happened. False by default: the oracle requires that none happened.
template <class Connectivity>
inline constexpr bool folds_between_retrievals_v = false;
template <>
inline constexpr bool folds_between_retrievals_v<SpanningForestConnectivity> = true;

/// Random parameters of every slot of `Config` for one seed, drawn by the
/// policies' hooks in a fixed order (mask, resolution, projection, index,
/// linkage, window, connectivity), so that a seed always gives the same
/// parameters. Small grids and wide masks on purpose: crowded cells, masks
/// wider than the grid, seams. The ground and motion slots keep the values
/// of `base`.
template <class Config>
ClustererParams<Config> random_params(std::mt19937_64& rng, ClustererParams<Config> base = {}) {
  ClustererParams<Config> p = std::move(base);
  p.mask_size = 1 + 2 * static_cast<int>(rng() % 4);
  RandomParams<typename config_traits<Config>::resolution>::draw(p.resolution, rng);
  RandomParams<typename config_traits<Config>::projection>::draw(p.projection, rng);
  RandomParams<typename config_traits<Config>::spatial_index>::draw(p.spatial_index, rng);
  RandomParams<typename config_traits<Config>::linkage>::draw(p.linkage, rng);
  RandomParams<typename config_traits<Config>::window>::draw(p.window, rng);
  RandomParams<typename config_traits<Config>::connectivity>::draw(p.connectivity, rng);
  return p;
}

}  // namespace streamclust::testing
