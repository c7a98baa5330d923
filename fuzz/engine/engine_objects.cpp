// SPDX-License-Identifier: MIT
// fuzz_engine's configurations of the objects presets: spherical, capped
// grid, range-adaptive linkage (engine_configs.hpp).

#include "engine/engine_configs.hpp"
#include "engine/run_scenario.hpp"

namespace streamclust::fuzz {

template <class Window, class Connectivity = SpanningForestConnectivity>
using Objects = cli::CliConfig<SphericalProjection, CappedGrid, RangeAdaptiveLinkage, Window, Connectivity>;

void run_objects(const Scenario& s) { run_scenario<Objects<TimeWindow>>(s); }
void run_objects_lazy_bfs(const Scenario& s) { run_scenario<Objects<TimeWindow, LazyBfsConnectivity>>(s); }
void run_objects_count(const Scenario& s) { run_scenario<Objects<CountWindow>>(s); }

}  // namespace streamclust::fuzz
