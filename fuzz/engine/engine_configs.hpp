// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The compiled configurations fuzz_engine runs: those the tool's presets
/// select (cli/presets.hpp apply_preset, cli/engine_config.hpp), each with
/// the default connectivity (spanning forest) and `--connectivity
/// lazy-bfs`, a time window and `--window-count`, plus the capped and the
/// overwrite index under C-ARC's linkage and one Euclidean, cylindrical
/// configuration. Each is `cli::CliConfig<...>` (run-time resolution,
/// motion and ground, as the tool builds them). The runners are compiled in
/// four translation units (engine_*.cpp) so that they build in parallel.

#include "engine/scenario.hpp"

#include <array>
#include <cstddef>

namespace streamclust::fuzz {

// engine_carc_time.cpp: spherical, angular, time window.
void run_carc(const Scenario& s);               // bucket, forest: carc, carc-mid360, carc-avia
void run_carc_lazy_bfs(const Scenario& s);      // bucket, lazy BFS: the same with --connectivity lazy-bfs
void run_carc_capped(const Scenario& s);        // capped, forest: --index capped
void run_carc_overwrite(const Scenario& s);     // overwrite, forest: the baseline's index, continuous
// engine_carc_count.cpp: spherical, angular, count window.
void run_carc_count(const Scenario& s);         // bucket, forest: --window-count
void run_carc_count_lazy_bfs(const Scenario& s);
// engine_objects.cpp: spherical, capped, range-adaptive.
void run_objects(const Scenario& s);            // time, forest: objects, objects-mid360, objects-avia
void run_objects_lazy_bfs(const Scenario& s);   // time, lazy BFS
void run_objects_count(const Scenario& s);      // count, forest
// engine_other.cpp
void run_cylindrical_euclidean(const Scenario& s);  // cylindrical, bucket, Euclidean, count, lazy BFS

/// A configuration: its name, its runner and the presets whose parameters
/// it runs with (the scenario picks one; the header's overrides follow).
struct EngineConfig {
  const char* name;
  void (*run)(const Scenario&);
  std::array<const char*, 3> presets;
};

inline constexpr std::array<const char*, 3> kCarcPresets = {"carc", "carc-mid360", "carc-avia"};
inline constexpr std::array<const char*, 3> kObjectsPresets = {"objects", "objects-mid360", "objects-avia"};

inline constexpr EngineConfig kEngineConfigs[] = {
    {"carc", &run_carc, kCarcPresets},
    {"carc lazy-bfs", &run_carc_lazy_bfs, kCarcPresets},
    {"carc capped", &run_carc_capped, kCarcPresets},
    {"carc overwrite", &run_carc_overwrite, kCarcPresets},
    {"carc count", &run_carc_count, kCarcPresets},
    {"carc count lazy-bfs", &run_carc_count_lazy_bfs, kCarcPresets},
    {"objects", &run_objects, kObjectsPresets},
    {"objects lazy-bfs", &run_objects_lazy_bfs, kObjectsPresets},
    {"objects count", &run_objects_count, kObjectsPresets},
    {"cylindrical euclidean", &run_cylindrical_euclidean, {"carc", "carc", "carc"}},
};
inline constexpr std::size_t kEngineConfigCount = sizeof kEngineConfigs / sizeof kEngineConfigs[0];

}  // namespace streamclust::fuzz
