// SPDX-License-Identifier: MIT
// fuzz_engine's configurations with C-ARC's projection and linkage and a
// time window (engine_configs.hpp).

#include "engine/engine_configs.hpp"
#include "engine/run_scenario.hpp"

namespace streamclust::fuzz {

template <class Index, class Connectivity = SpanningForestConnectivity>
using CarcTime = cli::CliConfig<SphericalProjection, Index, AngularLinkage, TimeWindow, Connectivity>;

void run_carc(const Scenario& s) { run_scenario<CarcTime<BucketGrid>>(s); }
void run_carc_lazy_bfs(const Scenario& s) { run_scenario<CarcTime<BucketGrid, LazyBfsConnectivity>>(s); }
void run_carc_capped(const Scenario& s) { run_scenario<CarcTime<CappedGrid>>(s); }
void run_carc_overwrite(const Scenario& s) { run_scenario<CarcTime<OverwriteGrid>>(s); }

}  // namespace streamclust::fuzz
