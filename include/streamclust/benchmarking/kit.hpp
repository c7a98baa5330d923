// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The benchmark kit (CMake: streamclust::benchmarking, package component
/// `benchmarking`): Google Benchmark helpers that measure a policy against
/// a reference on realistic inputs from simulated Livox streams, and the
/// whole engine's 20 Hz cycle latency for any configuration.
///   linkage_benchmarks.hpp  a linkage's paths; a linkage against a reference
///   policy_benchmarks.hpp   projection, spatial index, window, resolution
///   cycle_latency.hpp       insert 50 ms + retrieve: median and P99 per cycle
///   candidate_pairs.hpp     the pairs a w x w mask offers the linkage
///   simulated_streams.hpp   the simulated Mid-360 and Avia scenes
///   main.hpp                STREAMCLUST_BENCHMARK_MAIN(): main with a smoke mode
/// `#include <streamclust/benchmarking/kit.hpp>` for all of it. Documentation:
/// docs/performance.md ("Benchmark your own policy").

#include <streamclust/benchmarking/candidate_pairs.hpp>
#include <streamclust/benchmarking/cycle_latency.hpp>
#include <streamclust/benchmarking/linkage_benchmarks.hpp>
#include <streamclust/benchmarking/main.hpp>
#include <streamclust/benchmarking/policy_benchmarks.hpp>
#include <streamclust/benchmarking/simulated_streams.hpp>
