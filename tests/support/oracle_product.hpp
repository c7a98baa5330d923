// SPDX-License-Identifier: MIT
#pragma once
// The generated oracle property test: after every retrieval the continuous
// partition equals the partition the batch clusterer computes from scratch
// on the same window, for every combination of the policy lists
// (policy_lists.hpp: Projections x SpatialIndexes x Linkages x Windows x
// Connectivities, on a FixedResolution grid drawn per seed), over random and
// adversarial streams (streams.hpp).
//
// The test is defined here (`oracle_id`) and applied to three interleaved
// slices of the product, one per file (test_oracle.cpp, test_oracle_part2.cpp,
// test_oracle_part3.cpp), so that the slices compile and run in parallel:
//   TEST_CASE_TEMPLATE_APPLY(oracle_id, OracleSlice<0>);
//
// Seeds per combination (seed k: stream kind k mod 8, insert_batch when
// k / 8 is odd, 120 + k mod 200 points, retrievals at random intervals):
// every combination runs kProductSeeds seeds, so every stream kind both
// ways five times, on streams of 120-199 points; the combinations of the
// deep linkages (OracleDeepLinkages: the two criteria of the presets, whose
// payload, compact-sample and link_many paths the engine takes) run
// kDeepSeeds seeds, on streams of up to 319 points.

#include <doctest/doctest.h>

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/stream_clusterer.hpp>

#include "oracle.hpp"
#include "policy_hooks.hpp"
#include "policy_lists.hpp"
#include "streams.hpp"
#include "type_name.hpp"
#include "type_product.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <tuple>
#include <type_traits>

namespace streamclust::test {

/// A configuration of the oracle: the five listed policies on a FixedResolution grid.
template <class Projection, class Index, class Linkage, class Window, class Connectivity>
struct Combo {
  using projection = Projection;
  using spatial_index = Index;
  using linkage = Linkage;
  using window = Window;
  using resolution = FixedResolution;
  using connectivity = Connectivity;
};

/// Every combination of the policy lists.
using OracleCombos =
    apply_each_t<Combo, tuple_product_t<Projections, SpatialIndexes, Linkages, Windows, Connectivities>>;

/// The slice `K` (0, 1 or 2) of OracleCombos.
template <std::size_t K>
using OracleSlice = tuple_stride_t<OracleCombos, K, 3>;

/// The linkages whose combinations run kDeepSeeds seeds.
using OracleDeepLinkages = std::tuple<EuclideanLinkage, AngularLinkage>;
constexpr std::uint64_t kProductSeeds = 80;
constexpr std::uint64_t kDeepSeeds = 200;

template <class Config>
constexpr std::uint64_t oracle_seeds() {
  return tuple_contains_v<typename Config::linkage, OracleDeepLinkages> ? kDeepSeeds : kProductSeeds;
}

/// Random parameters for one seed, drawn by the policies' hooks
/// (policy_hooks.hpp). Small grids and wide masks on purpose: crowded
/// cells, masks wider than the grid, seams.
template <class Config>
ClustererParams<Config> random_params(std::mt19937_64& rng) {
  ClustererParams<Config> p;
  p.mask_size = 1 + 2 * static_cast<int>(rng() % 4);
  RandomParams<typename Config::resolution>::draw(p.resolution, rng);
  RandomParams<typename Config::projection>::draw(p.projection, rng);
  RandomParams<typename Config::spatial_index>::draw(p.spatial_index, rng);
  RandomParams<typename Config::linkage>::draw(p.linkage, rng);
  RandomParams<typename Config::window>::draw(p.window, rng);
  RandomParams<typename Config::connectivity>::draw(p.connectivity, rng);
  return p;
}

/// When the oracle retrieves: after a random 1-40 points, after every
/// point, or only once at the end of the stream.
enum class Schedule { random, every_point, at_end };

/// Runs one seed; returns the folds without retrieval (RetrievalStats::
/// forest_folds, zero for a strategy that does not fold between retrievals).
/// `min_fold_edges`, when not 0, replaces the drawn fold threshold of the
/// spanning forest.
template <class Config>
std::uint64_t run_oracle(std::uint64_t seed, Schedule schedule = Schedule::random,
                         std::uint32_t min_fold_edges = 0) {
  std::mt19937_64 rng(seed * 7919 + 13);
  auto params = random_params<Config>(rng);
  if constexpr (std::is_same_v<typename Config::connectivity, SpanningForestConnectivity>) {
    if (min_fold_edges != 0) params.connectivity.min_fold_edges = min_fold_edges;
  }
  const auto kind = static_cast<StreamKind>(seed % static_cast<std::uint64_t>(StreamKind::count_));
  const auto stream = make_stream(kind, 120 + seed % 200, seed);
  StreamClusterer<Config> engine(params);
  BatchClusterer<Config> batch(params);
  std::size_t next_retrieval = schedule == Schedule::every_point ? 1 : 1 + rng() % 40;
  // Half of the seeds (alternating blocks of eight, so every stream kind
  // both ways) feed the stream through insert_batch, in packets of 1-100
  // points cut at the retrievals.
  const std::size_t packet_max = (seed >> 3) % 2 == 1 ? 100 : 0;
  int retrievals = 0;
  std::uint64_t folds = 0;
  for (std::size_t offered = 0; offered < stream.size();) {
    const std::size_t stop = schedule == Schedule::at_end ? stream.size() : std::min(next_retrieval, stream.size());
    offer(engine, stream, offered, stop, packet_max, rng);
    offered = stop;
    engine.retrieve();
    ++retrievals;
    folds += engine.last_stats().forest_folds;
    const std::string mismatch = compare_with_batch(engine, batch);
    INFO("seed " << seed << ", stream " << to_string(kind) << ", after point " << offered - 1 << ", retrieval "
                 << retrievals << ", grid " << engine.grid().rows << "x" << engine.grid().cols << ", mask "
                 << params.mask_size << ", window size " << engine.size() << ", packets of at most " << packet_max);
    REQUIRE(mismatch == "");
    next_retrieval += schedule == Schedule::every_point ? 1 : 1 + rng() % 40;
  }
  CHECK(retrievals > 0);
  return folds;
}

}  // namespace streamclust::test

TEST_CASE_TEMPLATE_DEFINE("continuous partition equals the batch partition of the same window", Config, oracle_id) {
  namespace st = streamclust::test;
  std::uint64_t folds = 0;
  for (std::uint64_t seed = 0; seed < st::oracle_seeds<Config>(); ++seed) folds += st::run_oracle<Config>(seed);
  if constexpr (st::folds_between_retrievals_v<typename Config::connectivity>) {
    CHECK(folds > 0);  // the fold without retrieval ran
  } else {
    CHECK(folds == 0);
  }
}
