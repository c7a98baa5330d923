// SPDX-License-Identifier: MIT
// Crowded cells: a cell holding many points is read by its chain of linked
// points (engine/cell_chains.hpp). The partition must stay the batch
// partition of the window under every strategy, with the chains on or off,
// on streams that build, break and outlive chains; a cell of duplicates must
// cost O(1) candidates and edges per point; the adaptive grid stays bounded
// by the points it is calibrated on.

#include <doctest/doctest.h>

#include <streamclust/streamclust.hpp>

#include "support/oracle.hpp"
#include "support/partition.hpp"
#include "support/streams.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

namespace sc = streamclust;

namespace {

template <class Linkage, class Connectivity, class Window = sc::TimeWindow, class Resolution = sc::FixedResolution>
struct CrowdedConfig {
  using projection = sc::SphericalProjection;
  using spatial_index = sc::BucketGrid;
  using linkage = Linkage;
  using window = Window;
  using resolution = Resolution;
  using connectivity = Connectivity;
};

using CrowdedConfigs = std::tuple<
    CrowdedConfig<sc::EuclideanLinkage, sc::LazyBfsConnectivity>,
    CrowdedConfig<sc::EuclideanLinkage, sc::UnionFindRebuildConnectivity>,
    CrowdedConfig<sc::EuclideanLinkage, sc::SpanningForestConnectivity>,
    CrowdedConfig<sc::AngularLinkage, sc::LazyBfsConnectivity>,
    CrowdedConfig<sc::AngularLinkage, sc::SpanningForestConnectivity>,
    CrowdedConfig<sc::RangeAdaptiveLinkage, sc::SpanningForestConnectivity, sc::CountWindow>,
    CrowdedConfig<sc::EuclideanLinkage, sc::LazyBfsConnectivity, sc::CountWindow, sc::AdaptiveResolution>>;

/// Streams that crowd a few cells of a 4 x 16 grid.
enum class Crowd {
  identical,       // one position, again and again
  near_identical,  // one position with 0.1 mm of jitter
  two_ranges,      // one direction at 3 m and 9 m: the chain breaks at every switch
  drift,           // one direction, the range creeping on: a chain whose ends do not link
  mixed,           // all of the above in a few directions, plus scattered points
  count_,
};

const char* to_string(Crowd c) {
  static const char* names[] = {"identical", "near_identical", "two_ranges", "drift", "mixed"};
  return names[static_cast<int>(c)];
}

std::vector<sc::Point> crowded_stream(Crowd kind, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> jitter(0.0f, 1e-4f);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<sc::Point> out;
  double t = 0.0;
  float drift_range = 2.0f;
  for (std::size_t i = 0; i < n; ++i) {
    t += 1e-3 * (0.5 + unit(rng));
    Crowd k = kind;
    float az = 10.0f;
    if (kind == Crowd::mixed) {
      const std::uint64_t r = rng() % 10;
      if (r == 9) {  // scattered
        out.push_back(sc::test::point_at(-170.0f + 340.0f * unit(rng), -20.0f + 60.0f * unit(rng), 1.0f + 10.0f * unit(rng), t));
        continue;
      }
      k = static_cast<Crowd>(r % 4);
      az = 10.0f + 30.0f * static_cast<float>(r % 3);
    }
    sc::Point p = sc::test::point_at(az, 5.0f, 4.0f, t);
    switch (k) {
      case Crowd::identical: break;
      case Crowd::near_identical:
        p.x += jitter(rng);
        p.y += jitter(rng);
        p.z += jitter(rng);
        break;
      case Crowd::two_ranges: p = sc::test::point_at(az, 5.0f, rng() % 3 == 0 ? 9.0f : 3.0f, t); break;
      case Crowd::drift:
        drift_range += 0.02f;
        if (drift_range > 8.0f) drift_range = 2.0f;
        p = sc::test::point_at(az, 5.0f, drift_range, t);
        break;
      default: break;
    }
    out.push_back(p);
  }
  return out;
}

template <class Config>
sc::ClustererParams<Config> crowded_params(bool chains) {
  sc::ClustererParams<Config> p;
  p.crowded_cell_chains = chains;
  p.mask_size = 3;
  if constexpr (std::is_same_v<typename Config::resolution, sc::FixedResolution>) p.resolution = {4, 16};
  if constexpr (std::is_same_v<typename Config::window, sc::TimeWindow>) p.window.duration = 0.25;  // ~250 points
  if constexpr (std::is_same_v<typename Config::window, sc::CountWindow>) p.window.capacity = 300;
  if constexpr (std::is_same_v<typename Config::linkage, sc::EuclideanLinkage>) p.linkage.max_distance = 0.3f;
  if constexpr (std::is_same_v<typename Config::linkage, sc::AngularLinkage>) p.linkage.theta_deg = 30.0f;
  return p;
}

}  // namespace

TEST_CASE_TEMPLATE_DEFINE("crowded cells: the partition is the batch partition, chains on or off", Config,
                          crowded_oracle_id) {
  for (int k = 0; k < static_cast<int>(Crowd::count_); ++k) {
    const auto kind = static_cast<Crowd>(k);
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const std::vector<sc::Point> stream = crowded_stream(kind, 1500, seed);
      sc::StreamClusterer<Config> chained(crowded_params<Config>(true));
      sc::StreamClusterer<Config> unchained(crowded_params<Config>(false));
      sc::BatchClusterer<Config> batch(crowded_params<Config>(true));
      std::mt19937_64 rng(seed);
      std::uint64_t skipped = 0;
      std::uint64_t retrievals = 0;
      for (std::size_t i = 0; i < stream.size(); ++i) {
        chained.insert(stream[i]);
        unchained.insert(stream[i]);
        if (rng() % 25 != 0 && i + 1 != stream.size()) continue;
        if (i + 1 == stream.size()) {
          chained.complete_calibration();
          unchained.complete_calibration();
        }
        const sc::Clustering& with = chained.retrieve();
        skipped += chained.last_stats().candidates_skipped;
        const sc::Clustering& without = unchained.retrieve();
        if (chained.calibrating()) continue;  // the first window is still buffered: nothing labelled yet
        ++retrievals;
        const std::string stream_kind = to_string(kind);
        CAPTURE(stream_kind);
        CAPTURE(seed);
        CAPTURE(i);
        REQUIRE(sc::test::compare_with_batch(chained, batch) == "");
        REQUIRE(with.points.size() == without.points.size());
        std::vector<sc::ComponentId> a, b;
        for (std::size_t j = 0; j < with.points.size(); ++j) {
          REQUIRE(with.points[j].stream_index == without.points[j].stream_index);
          a.push_back(with.points[j].label);
          b.push_back(without.points[j].label);
        }
        REQUIRE(sc::test::partition_mismatch(a, b) == "");
      }
      CHECK(retrievals > 10);
      if (kind == Crowd::identical) CHECK(skipped > 0);  // the chains were read
    }
  }
}

TEST_CASE_TEMPLATE_APPLY(crowded_oracle_id, CrowdedConfigs);

TEST_CASE("crowded cells: a cell of duplicates costs O(1) candidates and edges per point") {
  using Config = CrowdedConfig<sc::EuclideanLinkage, sc::LazyBfsConnectivity>;  // every found edge is stored
  constexpr std::size_t kPoints = 20000;
  const std::vector<sc::Point> stream = crowded_stream(Crowd::identical, kPoints, 1);
  for (const bool chains : {true, false}) {
    auto params = crowded_params<Config>(chains);
    params.window.duration = 1e6;  // every point stays: one cell of 20,000
    sc::StreamClusterer<Config> engine(params);
    const std::size_t measured = chains ? kPoints : 2000;  // without chains: quadratic, a prefix shows it
    for (std::size_t i = 0; i < measured; ++i) engine.insert(stream[i]);
    const sc::Clustering& result = engine.retrieve();
    CHECK(result.components.size() == 1);
    const sc::RetrievalStats& stats = engine.last_stats();
    CAPTURE(chains);
    if (chains) {
      // Before the cell is crowded every pair links; after, the youngest and
      // the points older than the chain start: the first kCrowdedCell - 1.
      CHECK(stats.edges_found <= measured * sc::CellChains::kCrowdedCell);
      CHECK(stats.candidates_skipped > measured * (measured / 4));
      CHECK(engine.memory_usage().edge_storage < measured * 64 * 12);  // bytes: about 16 edges of 12 bytes a point
    } else {
      CHECK(stats.edges_found == measured * (measured - 1) / 2);
      CHECK(stats.candidates_skipped == 0);
    }
  }
}

TEST_CASE("adaptive resolution: the grid holds at most max_cells_per_point cells per point") {
  // 25,000 points within 0.1 mm of one position 5 m away: finer cells keep
  // separating them, so without the bound the loop ran to max_cells.
  const std::vector<sc::Point> stream = crowded_stream(Crowd::near_identical, 25000, 7);
  sc::SphericalProjection projection{{}};
  std::vector<sc::Projected> coords;
  for (const sc::Point& p : stream) coords.push_back(projection.project(Eigen::Vector3f(p.x, p.y, p.z)));
  for (const float per_point : {64.0f, 4.0f}) {
    sc::AdaptiveResolution::Params params;
    params.max_cells_per_point = per_point;
    sc::AdaptiveResolution resolution(params);
    const sc::GridSize g = resolution.calibrate(coords, projection.fov_aspect());
    CAPTURE(per_point);
    for (const sc::AdaptiveStep& step : resolution.trace()) {
      CHECK(double(step.grid.rows) * step.grid.cols <= per_point * 25000.0);
    }
    CHECK(double(g.rows) * g.cols <= per_point * 25000.0);
  }
  // Few points: never below the initial grid.
  std::vector<sc::Projected> few(coords.begin(), coords.begin() + 10);
  sc::AdaptiveResolution small{{}};
  small.calibrate(few, projection.fov_aspect());
  CHECK(small.trace().front().grid.rows * small.trace().front().grid.cols == 32u * 256u);
  CHECK_THROWS_AS(sc::AdaptiveResolution({32, 256, 0.1f, 0.9f, 0.2f, 0.2f, 2.0f, 4.0f, 50, 1u << 24, 0.5f}),
                  std::invalid_argument);
}
