// SPDX-License-Identifier: MIT
// fuzz_engine's configurations with C-ARC's projection and linkage and a
// count window (engine_configs.hpp).

#include "engine/engine_configs.hpp"
#include "engine/run_scenario.hpp"

namespace streamclust::fuzz {

template <class Connectivity>
using CarcCount = cli::CliConfig<SphericalProjection, BucketGrid, AngularLinkage, CountWindow, Connectivity>;

void run_carc_count(const Scenario& s) { run_scenario<CarcCount<SpanningForestConnectivity>>(s); }
void run_carc_count_lazy_bfs(const Scenario& s) { run_scenario<CarcCount<LazyBfsConnectivity>>(s); }

}  // namespace streamclust::fuzz
