// SPDX-License-Identifier: MIT
#pragma once
// The generated oracle property test: after every retrieval the continuous
// partition equals the partition the batch clusterer computes from scratch
// on the same window, for every combination of the policy lists
// (policy_lists.hpp: Projections x SpatialIndexes x Linkages x Windows x
// Connectivities, on a FixedResolution grid drawn per seed), over random and
// adversarial streams (streams.hpp).
//
// The run, the streams and the report (seed, stream, first mismatching
// retrieval, shrunk stream) are the test kit's
// (<streamclust/testing/exactness_run.hpp>), as for a user's configuration.
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

#include <streamclust/testing/doctest.hpp>
#include <streamclust/testing/exactness_run.hpp>
#include <streamclust/testing/policy_combo.hpp>
#include <streamclust/testing/random_params.hpp>

#include "policy_hooks.hpp"
#include "policy_lists.hpp"
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
using ::streamclust::testing::PolicyCombo;

/// Every combination of the policy lists; built with
/// STREAMCLUST_TEST_ORACLE_PAIRWISE (the sanitizer stage of scripts/test.sh),
/// a pairwise cover of them (tuple_pairwise_t: every two policies of two
/// lists together at least once, 19 of the 216 combinations), whose memory
/// and undefined-behaviour faults the sanitizers look for, at a tenth of the
/// compile time; the full product's exactness is the optimised stage's.
#ifdef STREAMCLUST_TEST_ORACLE_PAIRWISE
using OracleCombos =
    apply_each_t<PolicyCombo, tuple_pairwise_t<Projections, SpatialIndexes, Linkages, Windows, Connectivities>>;
#else
using OracleCombos =
    apply_each_t<PolicyCombo, tuple_product_t<Projections, SpatialIndexes, Linkages, Windows, Connectivities>>;
#endif

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

using ::streamclust::testing::random_params;
using Schedule = ::streamclust::testing::ExactnessSchedule;

/// Runs the exactness check of the test kit on seeds [first_seed,
/// first_seed + seeds) with random_params<Config> (the policies' RandomParams
/// hooks) and the given retrieval schedule; a mismatch fails the test case
/// with the kit's report (seed, stream, retrieval, shrunk stream). Returns
/// the folds without retrieval (RetrievalStats::forest_folds, zero for a
/// strategy that does not fold between retrievals). `min_fold_edges`, when
/// not 0, replaces the drawn fold threshold of the spanning forest.
template <class Config>
std::uint64_t run_oracle(std::uint64_t first_seed, std::uint64_t seeds, Schedule schedule = Schedule::random,
                         std::uint32_t min_fold_edges = 0) {
  ::streamclust::testing::ExactnessOptions options;
  options.first_seed = first_seed;
  options.seeds = seeds;
  options.schedule = schedule;
  const ::streamclust::testing::ExactnessReport report =
      ::streamclust::testing::check_exactness_on<Config>(
          [min_fold_edges](std::mt19937_64& rng) {
            auto params = random_params<Config>(rng);
            if constexpr (std::is_same_v<typename Config::connectivity, SpanningForestConnectivity>) {
              if (min_fold_edges != 0) params.connectivity.min_fold_edges = min_fold_edges;
            }
            (void)min_fold_edges;
            return params;
          },
          options);
  STREAMCLUST_REQUIRE_LAW(report);
  CHECK(report.comparisons > 0);
  return report.folds;
}

}  // namespace streamclust::test

TEST_CASE_TEMPLATE_DEFINE("continuous partition equals the batch partition of the same window", Config, oracle_id) {
  namespace st = streamclust::test;
  const std::uint64_t folds = st::run_oracle<Config>(0, st::oracle_seeds<Config>());
  if constexpr (st::folds_between_retrievals_v<typename Config::connectivity>) {
    CHECK(folds > 0);  // the fold without retrieval ran
  } else {
    CHECK(folds == 0);
  }
}
