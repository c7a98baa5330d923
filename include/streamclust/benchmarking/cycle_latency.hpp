// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The whole engine's cycle latency, as a 20 Hz client sees it: insert the
/// next 50 ms of a simulated Livox stream, then retrieve; one benchmark
/// iteration per cycle, timed manually, reported as the median and P99 per
/// cycle (counters `cycle_p50_ms`, `cycle_p99_ms`).
///
/// ```cpp
/// namespace bk = streamclust::benchmarking;
/// [[maybe_unused]] const bool registered = [] {
///   // any Config; its parameters per scenario (T_B = 0.5 s by default) ...
///   bk::register_cycle_latency<MyConfig>("MyConfig", [](const bk::CycleSetup& setup) {
///     streamclust::ClustererParams<MyConfig> p;
///     p.projection = setup.field_of_view;
///     p.window.duration = setup.window_seconds;
///     return p;
///   });
///   // ... or one parameter set for every scenario
///   bk::register_cycle_latency<streamclust::CArcConfig>(
///       "carc", streamclust::to_clusterer_params<streamclust::CArcConfig>(streamclust::carc_mid360_params()),
///       {{bk::Sensor::mid360, "office"}});
///   return true;
/// }();
/// ```
/// Streams: cycle_stream_seconds() of each scenario (2 s; 0.8 s in a smoke
/// run; or $STREAMCLUST_BENCH_SECONDS), cycles wrap around to a fresh engine, whose
/// first full window is inserted untimed before the first timed cycle.
/// Thread-safety: as linkage_benchmarks.hpp.

#include <streamclust/benchmarking/simulated_streams.hpp>
#include <streamclust/percentiles.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace streamclust::benchmarking {

/// [s] one cycle: a retrieval every 50 ms of stream time (20 Hz).
inline constexpr double kCyclePeriod = 0.05;

/// Drives an engine over a stream in 50 ms slices, wrapping around.
/// Not thread-safe; holds a reference to the stream.
template <class Config>
class CycleDriver {
 public:
  CycleDriver(const std::vector<sim::SimPoint>& points, const ClustererParams<Config>& params)
      : points_(points), params_(params), engine_(params) {
    restart();
  }

  /// Inserts the next 50 ms slice and retrieves; returns the slice's points.
  std::size_t cycle() {
    const std::size_t n = insert_slice();
    engine_.retrieve();
    return n;
  }
  /// Inserts the next 50 ms slice without retrieving: point by point with
  /// insert(), or with insert_batch on packets of `packet` points (96: a
  /// Livox packet). Returns the slice's points.
  std::size_t insert_slice(std::size_t packet = 0) {
    const double end = slice_end_;
    std::size_t last = i_;
    while (last < points_.size() && points_[last].t < end) ++last;
    const std::size_t n = last - i_;
    if (packet == 0) {
      for (; i_ < last; ++i_) engine_.insert(points_[i_]);
    } else {
      for (; i_ < last; i_ = std::min(last, i_ + packet)) {
        engine_.insert_batch(points_.begin() + static_cast<std::ptrdiff_t>(i_),
                             points_.begin() + static_cast<std::ptrdiff_t>(std::min(last, i_ + packet)));
      }
    }
    slice_end_ += kCyclePeriod;
    return n;
  }
  /// True when the next slice would run past the stream.
  bool exhausted() const { return slice_end_ > points_.back().t; }
  /// A fresh engine with one full window inserted before the first
  /// retrieval (untimed warm-up: the adaptive resolution calibrates on it).
  void restart() {
    engine_ = StreamClusterer<Config>(params_);
    i_ = 0;
    slice_end_ = kCyclePeriod;
    const double fill = params_.window.duration + 0.1;
    for (; i_ < points_.size() && points_[i_].t < fill; ++i_) engine_.insert(points_[i_]);
    while (slice_end_ < fill) slice_end_ += kCyclePeriod;
    cycle();
  }
  StreamClusterer<Config>& engine() { return engine_; }

 private:
  const std::vector<sim::SimPoint>& points_;
  ClustererParams<Config> params_;
  StreamClusterer<Config> engine_;
  std::size_t i_ = 0;
  double slice_end_ = kCyclePeriod;
};

/// What a configuration's parameters may depend on, per scenario.
struct CycleSetup {
  Scenario scenario;
  SphericalProjection::Params field_of_view;   ///< the sensor's (projection parameters)
  std::shared_ptr<const PoseTrajectory> trajectory;  ///< the sensor's 100 Hz poses over the stream
  float sensor_height = 0.0f;  ///< [m] above the floor or ground at the start
  double window_seconds = 0.5;  ///< T_B [s]
};

/// [s] the stream simulated per scenario unless $STREAMCLUST_BENCH_SECONDS
/// says otherwise: 2 s, 0.8 s in a smoke run (run_benchmarks, main.hpp).
/// Set it before the benchmarks run. Not thread-safe.
inline double& default_stream_seconds() {
  static double seconds = 2.0;
  return seconds;
}

/// [s] the stream simulated per scenario: $STREAMCLUST_BENCH_SECONDS when
/// set, else default_stream_seconds(); at least T_B + 0.3 s (one window and
/// a few cycles).
inline double cycle_stream_seconds(double window_seconds) {
  const char* env = std::getenv("STREAMCLUST_BENCH_SECONDS");
  const double s = env != nullptr ? std::atof(env) : default_stream_seconds();
  return std::max(s, window_seconds + 0.3);
}

/// The benchmark body: one cycle per iteration (UseManualTime).
template <class Config>
void run_cycle_latency(benchmark::State& state, const std::vector<sim::SimPoint>& points,
                       const ClustererParams<Config>& params) {
  CycleDriver<Config> driver(points, params);
  std::vector<double> cycle_ms;
  std::size_t processed = 0;
  double window_points = 0.0;
  for (auto _ : state) {
    if (driver.exhausted()) driver.restart();
    const auto t0 = std::chrono::steady_clock::now();
    processed += driver.cycle();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    cycle_ms.push_back(s * 1e3);
    window_points += static_cast<double>(driver.engine().size());
    state.SetIterationTime(s);
  }
  const LatencySummary summary = summarize(cycle_ms);
  state.counters["cycle_p50_ms"] = summary.median;
  state.counters["cycle_p99_ms"] = summary.p99;
  state.counters["window_pts"] = cycle_ms.empty() ? 0.0 : window_points / static_cast<double>(cycle_ms.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(processed));
}

/// Registers `<name>/<scenario>/T_B:<ms>` for each scenario (default: the
/// Mid-360 and the Avia in the office). `params` is a ClustererParams<Config>
/// used on every scenario, or a function of the scenario's CycleSetup
/// returning one. `window_seconds` is T_B (the setup's, and the stream's
/// warm-up; the parameters set the engine's). The stream is simulated when
/// the benchmark first runs. Returns the benchmarks (milliseconds, manual time).
template <class Config, class ParamsOrMaker>
std::vector<benchmark::internal::Benchmark*> register_cycle_latency(const std::string& name, const ParamsOrMaker& params,
                                                                    const std::vector<Scenario>& scenarios = office_scenarios(),
                                                                    double window_seconds = 0.5) {
  constexpr bool is_maker = std::is_invocable_v<const ParamsOrMaker&, const CycleSetup&>;
  static_assert(is_maker || std::is_same_v<ParamsOrMaker, ClustererParams<Config>>,
                "STREAMCLUST_CYCLE_PARAMS_INVALID: give a ClustererParams<Config> or a function of "
                "const CycleSetup& returning one");
  std::vector<benchmark::internal::Benchmark*> out;
  for (const Scenario& s : scenarios) {
    const std::string bench_name =
        name + "/" + s.name() + "/T_B:" + std::to_string(static_cast<long>(window_seconds * 1000.0 + 0.5));
    out.push_back(benchmark::RegisterBenchmark(bench_name.c_str(),
                                               [s, window_seconds, params](benchmark::State& state) {
                                                 const double seconds = cycle_stream_seconds(window_seconds);
                                                 CycleSetup setup;
                                                 setup.scenario = s;
                                                 setup.field_of_view = field_of_view(s.sensor);
                                                 setup.trajectory = simulated_trajectory(s, seconds);
                                                 setup.sensor_height = simulated_sensor_height();
                                                 setup.window_seconds = window_seconds;
                                                 if constexpr (is_maker) {
                                                   const ClustererParams<Config> p = params(setup);
                                                   run_cycle_latency<Config>(state, simulated_points(s, seconds), p);
                                                 } else {
                                                   run_cycle_latency<Config>(state, simulated_points(s, seconds), params);
                                                 }
                                               })
                      ->UseManualTime()
                      ->Unit(benchmark::kMillisecond));
  }
  return out;
}

}  // namespace streamclust::benchmarking
