// SPDX-License-Identifier: MIT
// Microbenchmarks per policy and per configuration, on the built-in synthetic
// Livox-like stream (200 kHz). Each reports points per second
// (items_per_second). Measure with:
//   build/gcc/bench/bench_policies --benchmark_min_time=1 --benchmark_repetitions=5
// CTest only smoke-runs it.

#include <benchmark/benchmark.h>

#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/streamclust.hpp>

#include <vector>

namespace sc = streamclust;

namespace {

// One second of stream, generated once.
const std::vector<sc::SyntheticPoint>& stream_points() {
  static const std::vector<sc::SyntheticPoint> points = [] {
    std::vector<sc::SyntheticPoint> out;
    sc::SyntheticStream stream;
    while (stream.time() < 1.0) out.push_back(stream.next());
    return out;
  }();
  return points;
}

template <class Index, class Linkage>
struct BenchConfig {
  using projection = sc::SphericalProjection;
  using spatial_index = Index;
  using linkage = Linkage;
  using window = sc::TimeWindow;
  using resolution = sc::FixedResolution;
};

template <class Config>
sc::ClustererParams<Config> bench_params() {
  sc::ClustererParams<Config> p;
  p.resolution = {64, 512};
  p.window.duration = 0.1;
  if constexpr (std::is_same_v<typename Config::linkage, sc::AngularLinkage>) p.linkage.theta_deg = 30.0f;
  return p;
}

// Sustained insertion (with eviction) at the sensor's pace.
template <class Config>
void BM_Insert(benchmark::State& state) {
  const auto& points = stream_points();
  const auto params = bench_params<Config>();
  std::size_t processed = 0;
  for (auto _ : state) {
    state.PauseTiming();
    sc::StreamClusterer<Config> engine(params);
    state.ResumeTiming();
    for (const auto& p : points) engine.insert(p);
    processed += points.size();
    benchmark::DoNotOptimize(engine.size());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(processed));
}

// A 20 Hz retrieval cycle: 10,000 insertions plus one retrieve().
template <class Config>
void BM_Cycle(benchmark::State& state) {
  const auto& points = stream_points();
  const auto params = bench_params<Config>();
  sc::StreamClusterer<Config> engine(params);
  std::size_t i = 0;
  for (; i < 40000; ++i) engine.insert(points[i]);  // fill the window first
  std::size_t processed = 0;
  for (auto _ : state) {
    for (int k = 0; k < 10000; ++k, ++i) {
      if (i == points.size()) {
        state.PauseTiming();
        engine = sc::StreamClusterer<Config>(params);
        for (i = 0; i < 40000; ++i) engine.insert(points[i]);
        state.ResumeTiming();
      }
      engine.insert(points[i]);
    }
    benchmark::DoNotOptimize(engine.retrieve().components.size());
    processed += 10000;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(processed));
}

// The batch clusterer on one 0.1 s window.
template <class Config>
void BM_Batch(benchmark::State& state) {
  const auto& points = stream_points();
  const std::vector<sc::SyntheticPoint> window(points.begin(), points.begin() + 20000);
  sc::BatchClusterer<Config> batch(bench_params<Config>());
  for (auto _ : state) benchmark::DoNotOptimize(batch.cluster(window).components);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(window.size()));
}

// One linkage predicate over neighbouring pairs of the stream.
template <class Linkage>
void BM_Linkage(benchmark::State& state) {
  const auto& points = stream_points();
  std::vector<sc::Sample> samples;
  for (std::size_t i = 0; i < 4096; ++i) {
    const auto& p = points[i];
    const Eigen::Vector3f pos(p.x, p.y, p.z);
    samples.push_back(sc::make_sample(pos, pos.norm(), p.intensity, p.t));
  }
  const Linkage linkage{typename Linkage::Params{}};
  std::size_t linked = 0;
  for (auto _ : state) {
    for (std::size_t i = 1; i < samples.size(); ++i) linked += linkage(samples[i - 1], samples[i]);
  }
  benchmark::DoNotOptimize(linked);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * 4095);
}

using BucketAngular = BenchConfig<sc::BucketGrid, sc::AngularLinkage>;
using CappedAngular = BenchConfig<sc::CappedGrid, sc::AngularLinkage>;
using OverwriteAngular = BenchConfig<sc::OverwriteGrid, sc::AngularLinkage>;
using BucketEuclidean = BenchConfig<sc::BucketGrid, sc::EuclideanLinkage>;

}  // namespace

BENCHMARK_TEMPLATE(BM_Insert, BucketAngular)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Insert, CappedAngular)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Insert, OverwriteAngular)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Insert, BucketEuclidean)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Cycle, BucketAngular)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Cycle, CappedAngular)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Batch, BucketAngular)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Batch, CappedAngular)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Linkage, sc::EuclideanLinkage);
BENCHMARK_TEMPLATE(BM_Linkage, sc::AngularLinkage);
BENCHMARK_TEMPLATE(BM_Linkage, sc::AngularOrEuclidean);

BENCHMARK_MAIN();
