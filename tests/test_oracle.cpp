// SPDX-License-Identifier: MIT
// The oracle: after every retrieval the continuous partition equals the
// partition the batch clusterer computes from scratch on the same window,
// for every combination of standard policies, over random and adversarial
// streams.

#include <doctest/doctest.h>

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/connectivity/lazy_bfs.hpp>
#include <streamclust/detail/age_bands.hpp>
#include <streamclust/connectivity/spanning_forest.hpp>
#include <streamclust/connectivity/union_find_rebuild.hpp>
#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/index/overwrite_grid.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/projection/cylindrical.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/resolution/fixed.hpp>
#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/stream_clusterer.hpp>
#include <streamclust/window/count_window.hpp>
#include <streamclust/window/time_window.hpp>

#include "support/oracle.hpp"
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

namespace {

template <class Projection, class Index, class Linkage, class Window,
          class Connectivity = sc::LazyBfsConnectivity>
struct Combo {
  using projection = Projection;
  using spatial_index = Index;
  using linkage = Linkage;
  using window = Window;
  using resolution = sc::FixedResolution;
  using connectivity = Connectivity;
};

// Random parameters for one seed. Small grids and wide masks on purpose:
// crowded cells, masks wider than the grid, seams.
template <class Config>
sc::ClustererParams<Config> random_params(std::mt19937_64& rng) {
  using Proj = typename Config::projection;
  using Index = typename Config::spatial_index;
  using Link = typename Config::linkage;
  using Win = typename Config::window;
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  sc::ClustererParams<Config> p;
  p.mask_size = 1 + 2 * static_cast<int>(rng() % 4);
  p.resolution.rows = 1 + static_cast<std::uint32_t>(rng() % 24);
  p.resolution.cols = 1 + static_cast<std::uint32_t>(rng() % 64);
  if (rng() % 2) {
    p.projection.azimuth_min_deg = -60.0f;
    p.projection.azimuth_max_deg = 60.0f;
  }
  if constexpr (std::is_same_v<Proj, sc::SphericalProjection>) {
    if (rng() % 2) {
      p.projection.elevation_min_deg = -30.0f;
      p.projection.elevation_max_deg = 50.0f;
    }
  } else {
    p.projection.z_min = -2.0f;
    p.projection.z_max = 4.0f;
  }
  if constexpr (std::is_same_v<Index, sc::CappedGrid>) p.spatial_index.capacity = 1 + static_cast<std::uint32_t>(rng() % 4);
  if constexpr (std::is_same_v<Link, sc::EuclideanLinkage>) {
    p.linkage.max_distance = 0.2f + 2.0f * unit(rng);
  } else {
    p.linkage.theta_deg = 5.0f + 60.0f * unit(rng);
    const float floors[] = {0.0f, 0.2f, 1.0f};
    p.linkage.min_ray_angle_deg = floors[rng() % 3];
  }
  if constexpr (std::is_same_v<Win, sc::TimeWindow>) {
    const double durations[] = {0.0, 0.0005, 0.01, 0.05, 0.2, 1.0};
    p.window.duration = durations[rng() % 6];
  } else {
    const std::size_t capacities[] = {1, 2, 7, 40, 150};
    p.window.capacity = capacities[rng() % 5];
  }
  return p;
}

/// When the oracle retrieves: after a random 1-40 points, after every
/// point, or only once at the end of the stream.
enum class Schedule { random, every_point, at_end };

/// Runs one seed; returns the spanning forest's folds without retrieval
/// (zero for the other strategies).
template <class Config>
std::uint64_t run_oracle(std::uint64_t seed, Schedule schedule = Schedule::random,
                         std::uint32_t forest_min_fold_edges = 0) {
  std::mt19937_64 rng(seed * 7919 + 13);
  auto params = random_params<Config>(rng);
  if constexpr (std::is_same_v<typename sc::config_traits<Config>::connectivity, sc::SpanningForestConnectivity>) {
    // The default threshold (65536 edges) never folds on these short streams:
    // mostly tiny ones, so the fold path runs between retrievals.
    const std::uint32_t thresholds[] = {1, 1, 3, 20, 65536};
    params.connectivity.min_fold_edges =
        forest_min_fold_edges != 0 ? forest_min_fold_edges : thresholds[rng() % 5];
    params.connectivity.fold_edges_per_point = 1 + static_cast<std::uint32_t>(rng() % 2);
    params.connectivity.prune_witnesses = static_cast<std::uint32_t>(rng() % 4);  // 0: every edge kept
  }
  const auto kind = static_cast<st::StreamKind>(seed % static_cast<std::uint64_t>(st::StreamKind::count_));
  const auto stream = st::make_stream(kind, 120 + seed % 200, seed);
  sc::StreamClusterer<Config> engine(params);
  sc::BatchClusterer<Config> batch(params);
  std::size_t next_retrieval = schedule == Schedule::every_point ? 1 : 1 + rng() % 40;
  // Half of the seeds (alternating blocks of eight, so every stream kind
  // both ways) feed the stream through insert_batch, in packets of 1-100
  // points cut at the retrievals.
  const std::size_t packet_max = (seed >> 3) % 2 == 1 ? 100 : 0;
  int retrievals = 0;
  std::uint64_t folds = 0;
  for (std::size_t offered = 0; offered < stream.size();) {
    const std::size_t stop = schedule == Schedule::at_end ? stream.size() : std::min(next_retrieval, stream.size());
    st::offer(engine, stream, offered, stop, packet_max, rng);
    offered = stop;
    engine.retrieve();
    ++retrievals;
    folds += engine.last_stats().forest_folds;
    const std::string mismatch = st::compare_with_batch(engine, batch);
    INFO("seed " << seed << ", stream " << st::to_string(kind) << ", after point " << offered - 1 << ", retrieval "
                 << retrievals << ", grid " << engine.grid().rows << "x" << engine.grid().cols << ", mask "
                 << params.mask_size << ", window size " << engine.size() << ", packets of at most " << packet_max);
    REQUIRE(mismatch == "");
    next_retrieval += schedule == Schedule::every_point ? 1 : 1 + rng() % 40;
  }
  CHECK(retrievals > 0);
  return folds;
}

constexpr std::uint64_t kSeeds = 200;

}  // namespace

TEST_CASE_TEMPLATE_DEFINE("continuous partition equals the batch partition of the same window", Config, oracle_id) {
  std::uint64_t folds = 0;
  for (std::uint64_t seed = 0; seed < kSeeds; ++seed) folds += run_oracle<Config>(seed);
  if constexpr (std::is_same_v<typename sc::config_traits<Config>::connectivity, sc::SpanningForestConnectivity>) {
    CHECK(folds > 0);  // the fold without retrieval ran
  } else {
    CHECK(folds == 0);
  }
}

using SphB = sc::SphericalProjection;
using Cyl = sc::CylindricalProjection;
TEST_CASE_TEMPLATE_APPLY(
    oracle_id,
    std::tuple<Combo<SphB, sc::BucketGrid, sc::AngularLinkage, sc::TimeWindow>,
               Combo<SphB, sc::BucketGrid, sc::AngularLinkage, sc::CountWindow>,
               Combo<SphB, sc::BucketGrid, sc::EuclideanLinkage, sc::TimeWindow>,
               Combo<SphB, sc::BucketGrid, sc::EuclideanLinkage, sc::CountWindow>,
               Combo<SphB, sc::CappedGrid, sc::AngularLinkage, sc::TimeWindow>,
               Combo<SphB, sc::CappedGrid, sc::AngularLinkage, sc::CountWindow>,
               Combo<SphB, sc::CappedGrid, sc::EuclideanLinkage, sc::TimeWindow>,
               Combo<SphB, sc::CappedGrid, sc::EuclideanLinkage, sc::CountWindow>,
               Combo<SphB, sc::OverwriteGrid, sc::AngularLinkage, sc::TimeWindow>,
               Combo<SphB, sc::OverwriteGrid, sc::AngularLinkage, sc::CountWindow>,
               Combo<SphB, sc::OverwriteGrid, sc::EuclideanLinkage, sc::TimeWindow>,
               Combo<SphB, sc::OverwriteGrid, sc::EuclideanLinkage, sc::CountWindow>,
               Combo<Cyl, sc::BucketGrid, sc::AngularLinkage, sc::TimeWindow>,
               Combo<Cyl, sc::BucketGrid, sc::AngularLinkage, sc::CountWindow>,
               Combo<Cyl, sc::BucketGrid, sc::EuclideanLinkage, sc::TimeWindow>,
               Combo<Cyl, sc::BucketGrid, sc::EuclideanLinkage, sc::CountWindow>,
               Combo<Cyl, sc::CappedGrid, sc::AngularLinkage, sc::TimeWindow>,
               Combo<Cyl, sc::CappedGrid, sc::AngularLinkage, sc::CountWindow>,
               Combo<Cyl, sc::CappedGrid, sc::EuclideanLinkage, sc::TimeWindow>,
               Combo<Cyl, sc::CappedGrid, sc::EuclideanLinkage, sc::CountWindow>,
               Combo<Cyl, sc::OverwriteGrid, sc::AngularLinkage, sc::TimeWindow>,
               Combo<Cyl, sc::OverwriteGrid, sc::AngularLinkage, sc::CountWindow>,
               Combo<Cyl, sc::OverwriteGrid, sc::EuclideanLinkage, sc::TimeWindow>,
               Combo<Cyl, sc::OverwriteGrid, sc::EuclideanLinkage, sc::CountWindow>>);

// Every combination again with the union-find rebuild connectivity.
using UF = sc::UnionFindRebuildConnectivity;
TEST_CASE_TEMPLATE_APPLY(
    oracle_id,
    std::tuple<Combo<SphB, sc::BucketGrid, sc::AngularLinkage, sc::TimeWindow, UF>,
               Combo<SphB, sc::BucketGrid, sc::AngularLinkage, sc::CountWindow, UF>,
               Combo<SphB, sc::BucketGrid, sc::EuclideanLinkage, sc::TimeWindow, UF>,
               Combo<SphB, sc::BucketGrid, sc::EuclideanLinkage, sc::CountWindow, UF>,
               Combo<SphB, sc::CappedGrid, sc::AngularLinkage, sc::TimeWindow, UF>,
               Combo<SphB, sc::CappedGrid, sc::AngularLinkage, sc::CountWindow, UF>,
               Combo<SphB, sc::CappedGrid, sc::EuclideanLinkage, sc::TimeWindow, UF>,
               Combo<SphB, sc::CappedGrid, sc::EuclideanLinkage, sc::CountWindow, UF>,
               Combo<SphB, sc::OverwriteGrid, sc::AngularLinkage, sc::TimeWindow, UF>,
               Combo<SphB, sc::OverwriteGrid, sc::AngularLinkage, sc::CountWindow, UF>,
               Combo<SphB, sc::OverwriteGrid, sc::EuclideanLinkage, sc::TimeWindow, UF>,
               Combo<SphB, sc::OverwriteGrid, sc::EuclideanLinkage, sc::CountWindow, UF>,
               Combo<Cyl, sc::BucketGrid, sc::AngularLinkage, sc::TimeWindow, UF>,
               Combo<Cyl, sc::BucketGrid, sc::AngularLinkage, sc::CountWindow, UF>,
               Combo<Cyl, sc::BucketGrid, sc::EuclideanLinkage, sc::TimeWindow, UF>,
               Combo<Cyl, sc::BucketGrid, sc::EuclideanLinkage, sc::CountWindow, UF>,
               Combo<Cyl, sc::CappedGrid, sc::AngularLinkage, sc::TimeWindow, UF>,
               Combo<Cyl, sc::CappedGrid, sc::AngularLinkage, sc::CountWindow, UF>,
               Combo<Cyl, sc::CappedGrid, sc::EuclideanLinkage, sc::TimeWindow, UF>,
               Combo<Cyl, sc::CappedGrid, sc::EuclideanLinkage, sc::CountWindow, UF>,
               Combo<Cyl, sc::OverwriteGrid, sc::AngularLinkage, sc::TimeWindow, UF>,
               Combo<Cyl, sc::OverwriteGrid, sc::AngularLinkage, sc::CountWindow, UF>,
               Combo<Cyl, sc::OverwriteGrid, sc::EuclideanLinkage, sc::TimeWindow, UF>,
               Combo<Cyl, sc::OverwriteGrid, sc::EuclideanLinkage, sc::CountWindow, UF>>);

// Every combination again with the spanning forest (random fold thresholds, see run_oracle).
using SF = sc::SpanningForestConnectivity;
TEST_CASE_TEMPLATE_APPLY(
    oracle_id,
    std::tuple<Combo<SphB, sc::BucketGrid, sc::AngularLinkage, sc::TimeWindow, SF>,
               Combo<SphB, sc::BucketGrid, sc::AngularLinkage, sc::CountWindow, SF>,
               Combo<SphB, sc::BucketGrid, sc::EuclideanLinkage, sc::TimeWindow, SF>,
               Combo<SphB, sc::BucketGrid, sc::EuclideanLinkage, sc::CountWindow, SF>,
               Combo<SphB, sc::CappedGrid, sc::AngularLinkage, sc::TimeWindow, SF>,
               Combo<SphB, sc::CappedGrid, sc::AngularLinkage, sc::CountWindow, SF>,
               Combo<SphB, sc::CappedGrid, sc::EuclideanLinkage, sc::TimeWindow, SF>,
               Combo<SphB, sc::CappedGrid, sc::EuclideanLinkage, sc::CountWindow, SF>,
               Combo<SphB, sc::OverwriteGrid, sc::AngularLinkage, sc::TimeWindow, SF>,
               Combo<SphB, sc::OverwriteGrid, sc::AngularLinkage, sc::CountWindow, SF>,
               Combo<SphB, sc::OverwriteGrid, sc::EuclideanLinkage, sc::TimeWindow, SF>,
               Combo<SphB, sc::OverwriteGrid, sc::EuclideanLinkage, sc::CountWindow, SF>,
               Combo<Cyl, sc::BucketGrid, sc::AngularLinkage, sc::TimeWindow, SF>,
               Combo<Cyl, sc::BucketGrid, sc::AngularLinkage, sc::CountWindow, SF>,
               Combo<Cyl, sc::BucketGrid, sc::EuclideanLinkage, sc::TimeWindow, SF>,
               Combo<Cyl, sc::BucketGrid, sc::EuclideanLinkage, sc::CountWindow, SF>,
               Combo<Cyl, sc::CappedGrid, sc::AngularLinkage, sc::TimeWindow, SF>,
               Combo<Cyl, sc::CappedGrid, sc::AngularLinkage, sc::CountWindow, SF>,
               Combo<Cyl, sc::CappedGrid, sc::EuclideanLinkage, sc::TimeWindow, SF>,
               Combo<Cyl, sc::CappedGrid, sc::EuclideanLinkage, sc::CountWindow, SF>,
               Combo<Cyl, sc::OverwriteGrid, sc::AngularLinkage, sc::TimeWindow, SF>,
               Combo<Cyl, sc::OverwriteGrid, sc::AngularLinkage, sc::CountWindow, SF>,
               Combo<Cyl, sc::OverwriteGrid, sc::EuclideanLinkage, sc::TimeWindow, SF>,
               Combo<Cyl, sc::OverwriteGrid, sc::EuclideanLinkage, sc::CountWindow, SF>>);

// The spanning forest's own edge cases: a retrieval after every point (a
// fold per point, the forest never older than one point) and a single
// retrieval at the end (everything before it by folds without labelling,
// threshold 1: a fold whenever the new edges outnumber the window's points).
TEST_CASE_TEMPLATE("spanning forest: retrieval after every point and only at the end agree with the batch clusterer",
                   Config, Combo<SphB, sc::BucketGrid, sc::EuclideanLinkage, sc::TimeWindow, SF>,
                   Combo<SphB, sc::BucketGrid, sc::AngularLinkage, sc::CountWindow, SF>,
                   Combo<SphB, sc::CappedGrid, sc::AngularLinkage, sc::TimeWindow, SF>,
                   Combo<Cyl, sc::OverwriteGrid, sc::EuclideanLinkage, sc::CountWindow, SF>) {
  std::uint64_t folds = 0;
  for (std::uint64_t seed = 0; seed < 100; ++seed) {
    run_oracle<Config>(seed, Schedule::every_point, 1);
    folds += run_oracle<Config>(seed, Schedule::at_end, 1);
  }
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
