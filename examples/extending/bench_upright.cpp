// SPDX-License-Identifier: MIT
// UprightLinkage against EuclideanLinkage (0.3 m) on the pairs a 5 x 5 mask offers (Mid-360, Avia).
#include "upright_linkage.hpp"

#include <streamclust/benchmarking/kit.hpp>
#include <streamclust/linkage/euclidean.hpp>

[[maybe_unused]] const bool registered = [] {
  streamclust::benchmarking::register_linkage_comparison<upright::UprightLinkage, streamclust::EuclideanLinkage>(
      "upright", {}, {0.3f});
  return true;
}();

STREAMCLUST_BENCHMARK_MAIN();
