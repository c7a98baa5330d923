// SPDX-License-Identifier: MIT
// The oracle: after every retrieval the continuous partition equals the
// partition the batch clusterer computes from scratch on the same window.
// Here: the first slice of the generated product of the policy lists
// (support/oracle_product.hpp; the other slices are test_oracle_part2.cpp
// and test_oracle_part3.cpp), the spanning forest's retrieval schedules,
// the C-ARC presets with the adaptive resolution, and windows of many age
// bands.

#include <doctest/doctest.h>

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/detail/age_bands.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/stream_clusterer.hpp>

#include "support/oracle.hpp"
#include "support/oracle_product.hpp"
#include "support/presets.hpp"
#include "support/streams.hpp"

#include <algorithm>
#include <random>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

namespace sc = streamclust;
namespace st = streamclust::test;

TEST_CASE_TEMPLATE_APPLY(oracle_id, st::OracleSlice<0>);

using st::PolicyCombo;
using SphB = sc::SphericalProjection;
using Cyl = sc::CylindricalProjection;
using SpanningForest = sc::SpanningForestConnectivity;

// The spanning forest's own edge cases: a retrieval after every point (a
// fold per point, the forest never older than one point) and a single
// retrieval at the end (everything before it by folds without labelling,
// threshold 1: a fold whenever the new edges outnumber the window's points).
TEST_CASE_TEMPLATE("spanning forest: retrieval after every point and only at the end agree with the batch clusterer",
                   Config, PolicyCombo<SphB, sc::BucketGrid, sc::EuclideanLinkage, sc::TimeWindow, SpanningForest>,
                   PolicyCombo<SphB, sc::BucketGrid, sc::AngularLinkage, sc::CountWindow, SpanningForest>,
                   PolicyCombo<SphB, sc::CappedGrid, sc::AngularLinkage, sc::TimeWindow, SpanningForest>,
                   PolicyCombo<Cyl, sc::OverwriteGrid, sc::EuclideanLinkage, sc::CountWindow, SpanningForest>) {
  st::run_oracle<Config>(0, 100, st::Schedule::every_point, 1);
  const std::uint64_t folds = st::run_oracle<Config>(0, 100, st::Schedule::at_end, 1);
  CHECK(folds > 100);
}

TEST_CASE_TEMPLATE("the C-ARC presets with adaptive resolution agree with the batch clusterer on their calibrated grid",
                   Preset, sc::CArcConfig, sc::CArcFastConfig, sc::CArcCappedFastConfig, sc::CArcRebuildConfig,
                   sc::CArcCappedRebuildConfig) {
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const auto params = st::short_window_params<Preset>();
    sc::StreamClusterer<Preset> engine(params);
    sc::BatchClusterer<Preset> batch(params);
    const auto stream = st::make_stream(st::StreamKind::blobs, 600, seed, 4000.0);
    CHECK(engine.calibrating());
    std::size_t compared = 0;
    // Odd seeds feed insert_batch: packets of 1-120 points, one of which
    // completes the first window (the calibration ends inside it).
    std::mt19937_64 rng(seed);
    const std::size_t packet_max = seed % 2 == 1 ? 120 : 0;
    for (std::size_t offered = 0; offered < stream.size();) {
      const std::size_t stop = std::min(offered + 97, stream.size());
      st::offer(engine, stream, offered, stop, packet_max, rng);
      offered = stop;
      if (offered % 97 != 0) break;  // the tail: no retrieval
      const bool calibrating = engine.calibrating();
      const sc::Clustering& result = engine.retrieve();
      INFO("seed " << seed << " after point " << offered - 1);
      if (calibrating) {
        CHECK(result.points.empty());  // no labels before the grid is chosen
        CHECK(engine.calibrating());   // and a retrieval does not end the calibration
        continue;
      }
      REQUIRE(st::compare_with_batch(engine, batch) == "");
      ++compared;
    }
    CHECK_FALSE(engine.calibrating());
    CHECK(compared >= 4);
    CHECK(engine.grid().rows >= 1);
    CHECK(engine.grid().cols >= 1);
  }
}

TEST_CASE_TEMPLATE("spanning forest: windows of many age bands agree with the batch clusterer", Preset,
                   sc::CArcFastConfig, sc::CArcCappedFastConfig) {
  // The windows above fit in one or two age bands of the new edges (512
  // points each, detail::AgeBands); here 10,000 points span about 20, with
  // folds at retrievals and, with a low threshold, between them.
  for (const std::uint32_t min_fold_edges : {65536u, 3000u}) {
    auto params = sc::to_clusterer_params<Preset>(sc::CArcParams{});
    params.window.duration = 0.05;  // [s] 10,000 points at 200 kHz
    params.connectivity.min_fold_edges = min_fold_edges;
    params.connectivity.fold_edges_per_point = 1;
    sc::StreamClusterer<Preset> engine(params);
    sc::BatchClusterer<Preset> batch(params);
    sc::SyntheticStream stream;
    double next_retrieval = 0.06;
    std::size_t compared = 0;
    std::uint64_t folds = 0;
    while (stream.time() < 0.2) {
      const sc::SyntheticPoint p = stream.next();
      engine.insert(sc::Point{p.x, p.y, p.z, p.intensity, p.t});
      if (p.t >= next_retrieval) {
        engine.retrieve();
        folds += engine.last_stats().forest_folds;
        INFO("threshold " << min_fold_edges << ", t = " << p.t << ", window " << engine.size());
        REQUIRE(st::compare_with_batch(engine, batch) == "");
        ++compared;
        next_retrieval += 0.0137;  // not a multiple of the window: the expiry cuts bands anywhere
      }
    }
    CHECK(compared >= 8);
    CHECK(engine.size() > 8 * sc::detail::AgeBands::kBandPoints);
    if (min_fold_edges == 3000u) CHECK(folds > 0);
  }
}
