// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The exactness check of a configuration of your own: its continuous
/// partition equals the batch partition of the same window after every
/// retrieval, on random, adversarial and simulated Livox streams, many seeds
/// (the run, the seeds and the failure report: exactness_run.hpp).
///
/// \code
/// struct MyConfig : streamclust::CArcFastConfig { using linkage = MyLinkage; };
/// const auto r = streamclust::testing::check_exactness<MyConfig>();      // default parameters
/// const auto s = streamclust::testing::check_exactness<MyConfig>(params); // yours
/// // parameters drawn per seed (RandomParams hooks, random_params.hpp):
/// const auto t = streamclust::testing::check_exactness_drawn<MyConfig>(
///     [](std::mt19937_64& rng) { return streamclust::testing::random_params<MyConfig>(rng); });
/// if (!r) std::cerr << r.message;  // or STREAMCLUST_CHECK_LAW(r) (testing/doctest.hpp)
/// \endcode

#include <streamclust/testing/exactness_run.hpp>
#include <streamclust/testing/livox_streams.hpp>
#include <streamclust/testing/random_params.hpp>

#include <random>
#include <utility>

namespace streamclust::testing {

/// The exactness check with parameters from `draw(std::mt19937_64&)` per
/// seed; `options.streams` empty: the random and the Livox sources.
template <class Config, class Draw>
ExactnessReport check_exactness_drawn(Draw&& draw, ExactnessOptions options = {}) {
  if (options.streams.empty()) options.streams = random_and_livox_stream_sources();
  return check_exactness_on<Config>(std::forward<Draw>(draw), options);
}

/// The exactness check with the same `params` for every seed.
template <class Config>
ExactnessReport check_exactness(const ClustererParams<Config>& params = {}, ExactnessOptions options = {}) {
  return check_exactness_drawn<Config>([&params](std::mt19937_64&) { return params; }, std::move(options));
}

}  // namespace streamclust::testing
