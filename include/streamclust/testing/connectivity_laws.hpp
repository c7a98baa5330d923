// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The law the engine relies on for a connectivity strategy
/// (concepts/connectivity.hpp): whatever it keeps, every retrieval's
/// partition is the batch partition of the window. Checked with the
/// exactness run (exactness_run.hpp) on the random and adversarial streams,
/// under two configurations that take different engine paths (bucket grid,
/// Euclidean linkage, time window; capped grid, angular linkage, count
/// window; FixedResolution grids and masks drawn per seed), with a random
/// retrieval schedule, a retrieval after every point and one at the end.
/// An edge forgotten, a component not split on eviction, a stale label: each
/// shows as a mismatch, reported with its seed and shrunk.
/// Cost: about 3 x seeds runs of a few hundred points per configuration.

#include <streamclust/concepts/connectivity.hpp>
#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/testing/exactness_run.hpp>
#include <streamclust/testing/policy_combo.hpp>
#include <streamclust/testing/random_params.hpp>
#include <streamclust/testing/type_product.hpp>
#include <streamclust/window/count_window.hpp>
#include <streamclust/window/time_window.hpp>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace streamclust::testing {

template <class C>
struct ConnectivityLawOptions {
  /// Parameter sets, used in turn by the seeds; empty: RandomParams<C>
  /// draws them (default: C's defaults).
  std::vector<typename C::Params> params;
  std::uint64_t seeds = 40;  ///< per configuration and schedule
};

/// The connectivity law (see the file comment); the first failure.
template <class C>
LawResult check_connectivity(const ConnectivityLawOptions<C>& options = {}) {
  static_assert(is_connectivity_policy_v<C>,
                "check_connectivity: C does not model the connectivity concept (concepts/connectivity.hpp)");
  std::uint64_t compared = 0;
  const auto run = [&](auto config_tag) -> LawResult {
    using Config = typename decltype(config_tag)::type;
    for (const ExactnessSchedule schedule :
         {ExactnessSchedule::random, ExactnessSchedule::every_point, ExactnessSchedule::at_end}) {
      ExactnessOptions exactness;
      exactness.seeds = options.seeds;
      exactness.schedule = schedule;
      std::uint64_t drawn = 0;
      const ExactnessReport r = check_exactness_on<Config>(
          [&](std::mt19937_64& rng) {
            ClustererParams<Config> p = random_params<Config>(rng);
            if (!options.params.empty()) p.connectivity = options.params[drawn++ % options.params.size()];
            return p;
          },
          exactness);
      if (!r) return r;
      compared += r.comparisons;
    }
    return law_passed();
  };
  LawResult r = run(type_tag<PolicyCombo<SphericalProjection, BucketGrid, EuclideanLinkage, TimeWindow, C>>{});
  if (!r) return r;
  r = run(type_tag<PolicyCombo<SphericalProjection, CappedGrid, AngularLinkage, CountWindow, C>>{});
  if (!r) return r;
  return law_passed("connectivity " + type_name<C>() + ": " + std::to_string(compared) + " retrievals compared");
}

}  // namespace streamclust::testing
