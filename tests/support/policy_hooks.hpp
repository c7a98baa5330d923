// SPDX-License-Identifier: MIT
#pragma once
// Per-policy hooks of the generated tests (policy_lists.hpp): what each
// policy needs beyond its concept to be tested generically. Every hook has a
// default that fits a new policy with default Params, so a policy added to a
// list is tested at once; a specialisation here sharpens the test (random
// parameters for the oracle, pairs known to link at the defaults, the
// capacity model of an index).

#include <streamclust/connectivity/spanning_forest.hpp>
#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/index/overwrite_grid.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/combinators.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/linkage/range_adaptive.hpp>
#include <streamclust/linkage/runtime_linkage.hpp>
#include <streamclust/projection/cylindrical.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/resolution/fixed.hpp>
#include <streamclust/types.hpp>
#include <streamclust/window/count_window.hpp>
#include <streamclust/window/time_window.hpp>

#include "test_linkages.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <tuple>
#include <utility>

namespace streamclust::test {

// ------------------------------------------------------ oracle parameters

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

namespace detail {
template <class Rng>
float unit_float(Rng& rng) {
  return std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
}
}  // namespace detail

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
    p.max_distance = 0.2f + 2.0f * detail::unit_float(rng);
  }
};

template <>
struct RandomParams<AngularLinkage> {
  template <class Rng>
  static void draw(AngularLinkage::Params& p, Rng& rng) {
    p.theta_deg = 5.0f + 60.0f * detail::unit_float(rng);
    const float floors[] = {0.0f, 0.2f, 1.0f};
    p.min_ray_angle_deg = floors[rng() % 3];
  }
};

template <>
struct RandomParams<RangeAdaptiveLinkage> {
  template <class Rng>
  static void draw(RangeAdaptiveLinkage::Params& p, Rng& rng) {
    p.min_distance = 0.05f + 0.5f * detail::unit_float(rng);
    const float factor = 0.005f + 0.1f * detail::unit_float(rng);
    p.range_factor = rng() % 4 == 0 ? 0.0f : factor;  // 0: a fixed radius
  }
};

template <>
struct RandomParams<BoxLinkage> {
  template <class Rng>
  static void draw(BoxLinkage::Params& p, Rng& rng) {
    p.half_width = 0.1f + 1.5f * detail::unit_float(rng);
  }
};

namespace detail {
/// Draws every child's parameters in order (the combinators' Params tuple).
template <class... Ls, class Rng>
void draw_children(std::tuple<typename Ls::Params...>& p, Rng& rng) {
  std::apply([&](auto&... child) { (RandomParams<Ls>::draw(child, rng), ...); }, p);
}
}  // namespace detail

template <class... Ls>
struct RandomParams<AllOf<Ls...>> {
  template <class Rng>
  static void draw(typename AllOf<Ls...>::Params& p, Rng& rng) {
    detail::draw_children<Ls...>(p, rng);
  }
};

template <class... Ls>
struct RandomParams<AnyOf<Ls...>> {
  template <class Rng>
  static void draw(typename AnyOf<Ls...>::Params& p, Rng& rng) {
    detail::draw_children<Ls...>(p, rng);
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

// ------------------------------------------------- linkage known values

/// The Sample at `range` [m] along the ray of azimuth / elevation [deg]
/// (direction computed in double).
inline Sample sample_on_ray(double azimuth_deg, double elevation_deg, double range) {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  const double a = azimuth_deg * kDeg;
  const double e = elevation_deg * kDeg;
  const Eigen::Vector3f p(static_cast<float>(range * std::cos(e) * std::cos(a)),
                          static_cast<float>(range * std::cos(e) * std::sin(a)),
                          static_cast<float>(range * std::sin(e)));
  return make_sample(p, p.norm(), 0.0f, 0.0);
}

/// Pairs of Samples that linkage `L` must link (`linked()`) and must not
/// link (`split()`) at its DEFAULT parameters. The defaults fit a linkage
/// that joins a surface seen face-on and separates a depth jump: two points
/// 10 m away on rays 0.05 degrees apart (0.9 cm apart) at equal range
/// (linked), and at 10 m and 20 m (split). A linkage that decides otherwise
/// specialises this hook.
template <class L>
struct KnownPairs {
  static std::pair<Sample, Sample> linked() { return {sample_on_ray(0.0, 0.0, 10.0), sample_on_ray(0.05, 0.0, 10.0)}; }
  static std::pair<Sample, Sample> split() { return {sample_on_ray(0.0, 0.0, 10.0), sample_on_ray(0.05, 0.0, 20.0)}; }
};

template <>
struct KnownPairs<EuclideanLinkage> {
  // the default threshold is 0.5 m: 0.49 m links, 0.51 m does not
  static std::pair<Sample, Sample> linked() { return {sample_on_ray(0.0, 0.0, 10.0), sample_on_ray(0.0, 0.0, 10.49)}; }
  static std::pair<Sample, Sample> split() { return {sample_on_ray(0.0, 0.0, 10.0), sample_on_ray(0.0, 0.0, 10.51)}; }
};

template <>
struct KnownPairs<AngularLinkage> {
  // defaults theta 10 deg, floor 0.2 deg: a wall at 10 m with 2 cm of range
  // noise on rays 0.1 deg apart has beta = 41 deg (linked); a second wall
  // 1 m behind on rays 0.01 deg apart (floored to 0.2) has beta = 2 deg
  static std::pair<Sample, Sample> linked() { return {sample_on_ray(0.0, 0.0, 10.02), sample_on_ray(0.1, 0.0, 10.0)}; }
  static std::pair<Sample, Sample> split() { return {sample_on_ray(0.0, 0.0, 10.0), sample_on_ray(0.01, 0.0, 11.0)}; }
};

template <>
struct KnownPairs<RangeAdaptiveLinkage> {
  // defaults 0.2 m, 0.05 m per m: at 25 m (radius 1.25 m) two returns on
  // rays 2.5 deg apart, 1.09 m apart, link (a fixed 0.5 m would split them);
  // at 3 m (radius max(0.2, 0.15) = 0.2 m) rays 5 deg apart, 0.26 m, split
  static std::pair<Sample, Sample> linked() { return {sample_on_ray(0.0, 0.0, 25.0), sample_on_ray(2.5, 0.0, 25.0)}; }
  static std::pair<Sample, Sample> split() { return {sample_on_ray(0.0, 0.0, 3.0), sample_on_ray(5.0, 0.0, 3.0)}; }
};

// ------------------------------------------------------ index capacity model

/// How the index contract test builds index `I` and how many handles one of
/// its cells keeps (a full cell displaces its oldest handle). The default
/// builds `I` from default Params and models an unbounded cell; a bounded
/// index specialises it.
template <class I>
struct IndexModel {
  static I make() { return I{typename I::Params{}}; }
  static constexpr std::size_t capacity = std::numeric_limits<std::size_t>::max();
};
template <>
struct IndexModel<BucketGrid> {
  static BucketGrid make() { return BucketGrid{{2}}; }  // inline capacity 2: spills early
  static constexpr std::size_t capacity = std::numeric_limits<std::size_t>::max();
};
template <>
struct IndexModel<CappedGrid> {
  static CappedGrid make() { return CappedGrid{{3}}; }
  static constexpr std::size_t capacity = 3;
};
template <>
struct IndexModel<OverwriteGrid> {
  static OverwriteGrid make() { return OverwriteGrid{{}}; }
  static constexpr std::size_t capacity = 1;
};

}  // namespace streamclust::test
