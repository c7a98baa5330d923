// SPDX-License-Identifier: MIT
// fuzz_engine's configuration off the presets' paths: the cylindrical
// projection, the Euclidean linkage, a count window and the lazy BFS
// (engine_configs.hpp).

#include "engine/engine_configs.hpp"
#include "engine/run_scenario.hpp"

namespace streamclust::fuzz {

void run_cylindrical_euclidean(const Scenario& s) {
  run_scenario<cli::CliConfig<CylindricalProjection, BucketGrid, EuclideanLinkage, CountWindow, LazyBfsConnectivity>>(s);
}

}  // namespace streamclust::fuzz
