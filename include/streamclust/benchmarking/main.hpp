// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A benchmark program's main: Google Benchmark's, plus the kit's smoke
/// mode. A run with --benchmark_min_time below 0.05 s (a CTest smoke run,
/// e.g. 0.01) simulates 0.8 s streams for the cycle latency (one 0.5 s
/// window and a few cycles) instead of 2 s. Full runs are unchanged. The
/// exit code is 1 when a kit check failed (a linkage whose paths disagree).
///
/// ```cpp
/// STREAMCLUST_BENCHMARK_MAIN();   // instead of BENCHMARK_MAIN()
/// ```

#include <streamclust/benchmarking/cycle_latency.hpp>
#include <streamclust/benchmarking/linkage_benchmarks.hpp>

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <string>

namespace streamclust::benchmarking {

/// True when the arguments ask for a smoke run (--benchmark_min_time < 0.05 s).
inline bool smoke_run(int argc, char** argv) {
  const std::string key = "--benchmark_min_time=";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.compare(0, key.size(), key) == 0 && std::atof(a.c_str() + key.size()) < 0.05) return true;
  }
  return false;
}

/// Google Benchmark's main with the smoke mode; returns the exit code: 1
/// for unrecognised arguments or when a kit check failed (failed_checks()).
inline int run_benchmarks(int argc, char** argv) {
  if (smoke_run(argc, argv)) default_stream_seconds() = 0.8;
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return failed_checks() == 0 ? 0 : 1;
}

}  // namespace streamclust::benchmarking

/// Defines main() as streamclust::benchmarking::run_benchmarks.
#define STREAMCLUST_BENCHMARK_MAIN() \
  int main(int argc, char** argv) { return streamclust::benchmarking::run_benchmarks(argc, argv); } \
  int main(int, char**)
