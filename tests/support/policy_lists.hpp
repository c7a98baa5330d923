// SPDX-License-Identifier: MIT
#pragma once
// The lists of policies that drive the generated tests and benchmarks.
//
// Adding a policy to its list is the only line it needs. The checks are the
// test kit's (<streamclust/testing/...>, docs/testing.md), the same a user
// runs on a policy of their own. A linkage added to `Linkages` gets, with no
// other change:
//   1. the oracle (tests/test_oracle.cpp): the kit's exactness check, the
//      continuous partition equals the batch partition of the same window,
//      for every combination of it with the other lists' policies
//      (Projections x SpatialIndexes x Linkages x Windows x Connectivities);
//   2. the kit's linkage laws (tests/test_policy_linkage.cpp): symmetry, no
//      state, the payload operator and `link_many` against the Sample
//      operator (when it has them), a pair that must link and one that must
//      not at its default parameters;
//   3. its microbenchmark (bench/policies.cpp, bench_policies).
// The same holds for the other families: a projection, index, window or
// resolution added to its list runs its family's laws
// (tests/test_policy_<family>.cpp) and its microbenchmark, and (except
// resolutions, see below) the oracle.
//
// What a policy may add in policy_hooks.hpp (each has a default):
// `streamclust::testing::RandomParams<P>` (random parameters for the oracle;
// default: P's defaults), `KnownPairs<L>` (a linkage's pairs at its
// defaults; default: a surface seen face-on links, a depth jump of 10 m
// splits), `IndexModel<I>` (the parameters an index's laws run with;
// default: I's defaults).
//
// The oracle runs on FixedResolution (it compares on a grid it draws); the
// adaptive resolution is compared through the C-ARC presets in
// test_oracle.cpp. BoxLinkage is a test-only linkage (test_linkages.hpp):
// no angle parameter, a payload without the ray, its own link_many. The run-time forwarders RuntimeWindow and
// RuntimeResolution are tested against the policies they select in
// test_runtime_policies.cpp; RuntimeLinkage is a linkage like any other here.

#include <streamclust/connectivity/lazy_bfs.hpp>
#include <streamclust/connectivity/spanning_forest.hpp>
#include <streamclust/connectivity/union_find_rebuild.hpp>
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
#include <streamclust/resolution/adaptive.hpp>
#include <streamclust/resolution/fixed.hpp>
#include <streamclust/window/count_window.hpp>
#include <streamclust/window/time_window.hpp>

#include "policy_hooks.hpp"
#include "test_linkages.hpp"

#include <tuple>

namespace streamclust::test {

using Projections = std::tuple<SphericalProjection, CylindricalProjection>;

using SpatialIndexes = std::tuple<BucketGrid, CappedGrid, OverwriteGrid>;

/// The combinators are represented by AngularOrEuclidean (AnyOf): AllOf
/// takes the same engine paths and has its own tests in
/// test_policy_linkage.cpp. Each linkage here adds 36 oracle
/// configurations (about a minute of compile time per build of the tests).
using Linkages = std::tuple<EuclideanLinkage, AngularLinkage, RangeAdaptiveLinkage, AngularOrEuclidean,
                            RuntimeLinkage, BoxLinkage>;

using Windows = std::tuple<TimeWindow, CountWindow>;

using Resolutions = std::tuple<FixedResolution, AdaptiveResolution>;

using Connectivities = std::tuple<LazyBfsConnectivity, UnionFindRebuildConnectivity, SpanningForestConnectivity>;

}  // namespace streamclust::test
