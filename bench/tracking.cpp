// SPDX-License-Identifier: MIT
// The cost of tracking per retrieval: the objects engine (objects_mid360_params
// / objects_avia_params, with the simulated poses and the sensor height) runs
// the kit's office stream at 20 Hz; after each retrieval (once the first window
// is full) ObjectBoxes fits the boxes and in-window velocities of the
// components of 10 points or more and KalmanTracker updates its tracks. Only
// that part is timed (manual time, per retrieval). The counters: its median
// and P99 [us] over the retrievals of a running stream (from 1 s of stream
// on: the stream restarts every few seconds, and its first window is no
// running stream's), the median of a stream's first retrieval (`first_us`:
// every component new, ground and ceiling looked up for all), the objects
// and tracks per retrieval, and the points boxed. The *_unlinked runs leave
// a fast mover's pieces unlinked: the difference is what linking costs.
//
// Measure with (numbers: docs/performance.md):
//   build/bench-run/bench/bench_tracking --benchmark_min_time=2 --benchmark_repetitions=3
//       --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <streamclust/benchmarking/main.hpp>
#include <streamclust/benchmarking/simulated_streams.hpp>
#include <streamclust/objects_presets.hpp>
#include <streamclust/percentiles.hpp>
#include <streamclust/stream_clusterer.hpp>
#include <streamclust/tracking/kalman_tracker.hpp>
#include <streamclust/tracking/object_boxes.hpp>

#include <chrono>
#include <cstddef>
#include <memory>
#include <vector>

namespace sc = streamclust;
namespace bk = streamclust::benchmarking;

namespace {

/// The engine over the scenario's stream, restarted when the stream ends.
class ObjectsRun {
 public:
  ObjectsRun(const bk::Scenario& s, double seconds)
      : points_(bk::simulated_points(s, seconds)), scenario_(s), seconds_(seconds) {
    restart();
  }

  /// Inserts the next 50 ms and retrieves; false while the first window fills.
  bool next_cycle() {
    if (next_ >= points_.size()) restart();
    const double until = cycle_time_ + 0.05;
    while (next_ < points_.size() && points_[next_].t < until) {
      const sc::sim::SimPoint& p = points_[next_++];
      engine_->insert(sc::Point{p.x, p.y, p.z, p.intensity, p.t});
    }
    cycle_time_ = until;
    result_ = &engine_->retrieve();
    return cycle_time_ > 0.55;
  }
  const sc::StreamClusterer<sc::ObjectsConfig>& engine() const { return *engine_; }
  const sc::Clustering& result() const { return *result_; }
  /// [s] the stream's time of the last retrieval.
  double cycle_time() const { return cycle_time_; }

 private:
  void restart() {
    sc::ObjectsSetup setup;
    setup.sensor_height = bk::simulated_sensor_height();
    setup.trajectory = bk::simulated_trajectory(scenario_, seconds_);
    const auto params = scenario_.sensor == bk::Sensor::mid360 ? sc::objects_mid360_params(setup)
                                                               : sc::objects_avia_params(setup);
    engine_ = std::make_unique<sc::StreamClusterer<sc::ObjectsConfig>>(params);
    next_ = 0;
    cycle_time_ = 0.0;
  }

  const std::vector<sc::sim::SimPoint>& points_;
  bk::Scenario scenario_;
  double seconds_;
  std::unique_ptr<sc::StreamClusterer<sc::ObjectsConfig>> engine_;
  const sc::Clustering* result_ = nullptr;
  std::size_t next_ = 0;
  double cycle_time_ = 0.0;
};

/// `link_pieces` false: without linking a fast mover's pieces (its cost).
void BM_Tracking(benchmark::State& state, bk::Scenario scenario, bool link_pieces) {
  ObjectsRun run(scenario, bk::cycle_stream_seconds(0.5));
  sc::tracking::ObjectBoxParams params;
  params.link_pieces = link_pieces;
  sc::tracking::ObjectBoxes boxes(params);
  auto tracker = std::make_unique<sc::KalmanTracker>();
  std::vector<double> us, running_us, first_us;
  double objects = 0.0, tracks = 0.0, points = 0.0;
  for (auto _ : state) {
    bool first = false;
    while (!run.next_cycle()) {  // a new stream: new tracks
      tracker = std::make_unique<sc::KalmanTracker>();
      first = true;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const auto& observed = boxes.update(run.engine(), run.result());
    const auto& kept = tracker->update(observed, run.result().time);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(seconds);
    us.push_back(seconds * 1e6);
    if (first) first_us.push_back(seconds * 1e6);
    if (run.cycle_time() >= 1.0) running_us.push_back(seconds * 1e6);
    objects += static_cast<double>(observed.size());
    tracks += static_cast<double>(kept.size());
    for (const auto& o : observed) points += static_cast<double>(o.box.points);
    benchmark::DoNotOptimize(kept.data());
  }
  const double n = static_cast<double>(us.size());
  if (!running_us.empty()) us.swap(running_us);  // else a stream shorter than 1 s (a smoke run): all
  state.counters["median_us"] = sc::percentile(us, 50.0);
  state.counters["p99_us"] = sc::percentile(us, 99.0);
  state.counters["first_us"] = sc::percentile(first_us, 50.0);
  state.counters["objects"] = objects / n;
  state.counters["tracks"] = tracks / n;
  state.counters["boxed_points"] = points / n;
}

}  // namespace

BENCHMARK_CAPTURE(BM_Tracking, mid360_office, bk::Scenario{bk::Sensor::mid360, "office"}, true)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Tracking, avia_office, bk::Scenario{bk::Sensor::avia, "office"}, true)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Tracking, mid360_street, bk::Scenario{bk::Sensor::mid360, "street"}, true)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Tracking, mid360_office_unlinked, bk::Scenario{bk::Sensor::mid360, "office"}, false)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Tracking, mid360_street_unlinked, bk::Scenario{bk::Sensor::mid360, "street"}, false)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

STREAMCLUST_BENCHMARK_MAIN();
