// SPDX-License-Identifier: MIT
#pragma once
// Per-policy hooks of the generated tests (policy_lists.hpp): what each
// policy needs beyond its concept to be tested generically. Every hook has a
// default that fits a new policy with default Params, so a policy added to a
// list is tested at once; a specialisation here sharpens the test (random
// parameters for the oracle, pairs known to link at the defaults, the
// parameters of an index's laws).

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

#include "constants.hpp"
#include "test_linkages.hpp"

#include <streamclust/testing/random_params.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <tuple>
#include <utility>

namespace streamclust::test {

// ------------------------------------------------------ oracle parameters

// RandomParams and random_params are the test kit's
// (<streamclust/testing/random_params.hpp>): a specialisation for a
// test-only policy goes into namespace streamclust::testing.

}  // namespace streamclust::test

namespace streamclust::testing {

template <>
struct RandomParams<test::BoxLinkage> {
  template <class Rng>
  static void draw(test::BoxLinkage::Params& p, Rng& rng) {
    p.half_width = 0.1f + 1.5f * internal::unit_float(rng);
  }
};

}  // namespace streamclust::testing

namespace streamclust::test {

using ::streamclust::testing::folds_between_retrievals_v;
using ::streamclust::testing::RandomParams;

// ------------------------------------------------- linkage known values

/// The Sample at `range` [m] along the ray of azimuth / elevation [deg]
/// (direction computed in double).
inline Sample sample_on_ray(double azimuth_deg, double elevation_deg, double range) {
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

// ------------------------------------------------------ index parameters

/// The parameters the index laws (test kit, check_index) test index `I`
/// with; the model's capacity is the index's max_cell_size. The default is
/// I's defaults.
template <class I>
struct IndexModel {
  static typename I::Params params() { return {}; }
};
template <>
struct IndexModel<BucketGrid> {
  static BucketGrid::Params params() { return {2}; }  // inline capacity 2: spills early
};
template <>
struct IndexModel<CappedGrid> {
  static CappedGrid::Params params() { return {3}; }
};

}  // namespace streamclust::test
