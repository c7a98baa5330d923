// SPDX-License-Identifier: MIT
// What a linkage's compact payload is worth to the whole engine: the 20 Hz
// cycle (50 ms of stream inserted, evictions, retrieve) of configurations
// that differ only in the linkage's path, run in lockstep on the same slices
// of a simulated Livox office (sim::Simulator, sensor at rest 1 m above the
// floor), each cycle timed on its own in the thread's CPU time (a shared
// machine's time slices stay out), the order rotated every iteration.
// Same-run medians and their ratios, so that the noise left (caches shared
// with other processes) falls on every configuration alike.
//
//   BM_GatedObjects<Scenario>  ObjectsConfig (range-adaptive, 16-byte payload,
//                              link_many), and ObjectsConfig with
//                              AllOf<RangeAdaptiveLinkage, IntensityGate>: on
//                              the Sample path (`sample`, what a combinator of
//                              different payloads ran before it composed one)
//                              and on its composed 32-byte payload (`wide`)
//   BM_AngularOrEuclidean<Scenario>  CArcFastConfig with AngularOrEuclidean
//                              (theta of the sensor, 10 cm) on the Sample path
//                              and on its composed 32-byte ray payload
//
// Counters: <config>_p50_ms per cycle (thread CPU time) and the ratios of
// the medians (wide_over_sample < 1: the payload is cheaper). The reported
// time is the sum of an iteration's cycles.
//
//   build/bench/bench_payload --benchmark_min_time=20
// Streams: STREAMCLUST_BENCH_SECONDS seconds (default 3; cycles wrap around
// the stream, each wrap restarts every engine with a full window).

#include <benchmark/benchmark.h>

#include <time.h>

#include <streamclust/linkage/combinators.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/avia_model.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/simulator.hpp>
#include <streamclust/streamclust.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace sc = streamclust;
namespace sim = streamclust::sim;

namespace {

/// Linked when two intensities differ by at most `max_gap` (a linkage the
/// library does not ship). Payload: the intensity, 4 bytes.
struct IntensityGate {
  struct Params {
    float max_gap = 40.0f;  ///< [intensity units, 0-255]
  };
  struct Payload {
    float intensity;
  };
  explicit IntensityGate(const Params& p) : max_gap_(p.max_gap) {}
  static Payload make_payload(const sc::Sample& s) { return Payload{s.intensity}; }
  bool operator()(const Payload& a, const Payload& b) const { return std::fabs(a.intensity - b.intensity) <= max_gap_; }
  bool operator()(const sc::Sample& a, const sc::Sample& b) const { return (*this)(make_payload(a), make_payload(b)); }

 private:
  float max_gap_;
};

/// `L` behind its Sample operator only: the engine's Sample path.
template <class L>
struct SamplePathOnly {
  using Params = typename L::Params;
  explicit SamplePathOnly(const Params& p) : inner_(p) {}
  bool operator()(const sc::Sample& a, const sc::Sample& b) const { return inner_(a, b); }

 private:
  L inner_;
};

using Gated = sc::AllOf<sc::RangeAdaptiveLinkage, IntensityGate>;
struct GatedWideConfig : sc::ObjectsConfig {
  using linkage = Gated;
};
struct GatedSampleConfig : sc::ObjectsConfig {
  using linkage = SamplePathOnly<Gated>;
};
struct HybridWideConfig : sc::CArcFastConfig {
  using linkage = sc::AngularOrEuclidean;
};
struct HybridSampleConfig : sc::CArcFastConfig {
  using linkage = SamplePathOnly<sc::AngularOrEuclidean>;
};

/// `from` with another linkage: every other slot and engine parameter kept.
template <class To, class From, class LinkageParams>
sc::ClustererParams<To> rebind(const sc::ClustererParams<From>& from, const LinkageParams& linkage) {
  sc::ClustererParams<To> to;
  to.projection = from.projection;
  to.spatial_index = from.spatial_index;
  to.linkage = linkage;
  to.window = from.window;
  to.resolution = from.resolution;
  to.mask_size = from.mask_size;
  to.crowded_cell_chains = from.crowded_cell_chains;
  to.connectivity = from.connectivity;
  to.motion = from.motion;
  to.ground = from.ground;
  to.time_order = from.time_order;
  to.first_stream_index = from.first_stream_index;
  return to;
}

/// CPU time of the calling thread [ms].
double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

double stream_seconds() {
  const char* env = std::getenv("STREAMCLUST_BENCH_SECONDS");
  const double s = env != nullptr ? std::atof(env) : 3.0;
  return std::max(s, 0.8);
}

template <class Sensor>
std::vector<sim::SimPoint> simulate(Sensor sensor) {
  sim::Simulator<Sensor> simulator(std::move(sensor), sim::office_scene(3), typename sim::Simulator<Sensor>::Params{});
  std::vector<sim::SimPoint> out;
  while (simulator.time() < stream_seconds()) out.push_back(simulator.next());
  return out;
}

constexpr double kWindow = 0.5;  // T_B [s]

/// The sensor's objects preset at rest, 1 m above the floor (the
/// simulator's start height), T_B = 0.5 s.
sc::ObjectsSetup objects_setup() {
  sc::ObjectsSetup setup;
  setup.sensor_height = sim::Simulator<sim::Mid360Model>::Params{}.start_position.z();
  setup.window_seconds = kWindow;
  return setup;
}

struct Mid360Office {
  static const char* name() { return "mid360_office"; }
  static const std::vector<sim::SimPoint>& points() {
    static const auto pts = simulate(sim::Mid360Model{});
    return pts;
  }
  static sc::ClustererParams<sc::ObjectsConfig> objects() { return sc::objects_mid360_params(objects_setup()); }
  static sc::CArcParams carc() { return sc::carc_mid360_params(); }
};
struct AviaOffice {
  static const char* name() { return "avia_office"; }
  static const std::vector<sim::SimPoint>& points() {
    static const auto pts = simulate(sim::AviaModel{});
    return pts;
  }
  static sc::ClustererParams<sc::ObjectsConfig> objects() { return sc::objects_avia_params(objects_setup()); }
  static sc::CArcParams carc() { return sc::carc_avia_params(); }
};

/// One engine fed 50 ms slices of a stream; a fresh engine with a full
/// window (untimed) whenever the stream would run out.
template <class Config>
class Driver {
 public:
  Driver(const std::vector<sim::SimPoint>& points, sc::ClustererParams<Config> params)
      : points_(points), params_(std::move(params)), engine_(params_) {
    restart();
  }
  /// One timed cycle [ms of thread CPU time]: the next slice inserted, then
  /// a retrieval.
  double cycle() {
    if (slice_end_ > points_.back().t) restart();
    std::size_t last = i_;
    while (last < points_.size() && points_[last].t < slice_end_) ++last;
    const double t0 = thread_cpu_ms();
    for (; i_ < last; ++i_) engine_.insert(points_[i_]);
    benchmark::DoNotOptimize(engine_.retrieve().components.size());
    const double t1 = thread_cpu_ms();
    slice_end_ += 0.05;
    return t1 - t0;
  }

 private:
  void restart() {
    engine_ = sc::StreamClusterer<Config>(params_);
    i_ = 0;
    const double fill = kWindow + 0.1;
    for (; i_ < points_.size() && points_[i_].t < fill; ++i_) engine_.insert(points_[i_]);
    engine_.retrieve();
    slice_end_ = fill + 0.05;
  }

  const std::vector<sim::SimPoint>& points_;
  sc::ClustererParams<Config> params_;
  sc::StreamClusterer<Config> engine_;
  std::size_t i_ = 0;
  double slice_end_ = 0.0;
};

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

/// Runs drivers in lockstep, one cycle each per iteration, the order
/// rotated; returns each driver's median cycle [ms]. The iteration's time is
/// the sum of the cycles.
template <class... Drivers, std::size_t... I>
std::array<double, sizeof...(Drivers)> lockstep(benchmark::State& state, std::tuple<Drivers...>& drivers,
                                                std::index_sequence<I...>) {
  constexpr std::size_t n = sizeof...(Drivers);
  std::array<std::vector<double>, n> ms;
  std::size_t turn = 0;
  for (auto _ : state) {
    double total = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t which = (turn + k) % n;
      ((which == I ? (ms[I].push_back(std::get<I>(drivers).cycle()), total += ms[I].back(), 0) : 0), ...);
    }
    ++turn;
    state.SetIterationTime(total / 1000.0);
  }
  return {median(ms[I])...};
}

template <class Scenario>
void BM_GatedObjects(benchmark::State& state) {
  const auto objects = Scenario::objects();
  const IntensityGate::Params gate{};
  std::tuple<Driver<sc::ObjectsConfig>, Driver<GatedSampleConfig>, Driver<GatedWideConfig>> drivers{
      {Scenario::points(), objects},
      {Scenario::points(), rebind<GatedSampleConfig>(objects, Gated::Params{objects.linkage, gate})},
      {Scenario::points(), rebind<GatedWideConfig>(objects, Gated::Params{objects.linkage, gate})}};
  const auto m = lockstep(state, drivers, std::index_sequence_for<int, int, int>{});
  state.counters["range_adaptive_p50_ms"] = m[0];
  state.counters["gated_sample_p50_ms"] = m[1];
  state.counters["gated_wide_p50_ms"] = m[2];
  state.counters["wide_over_sample"] = m[2] / m[1];
  state.counters["sample_over_range_adaptive"] = m[1] / m[0];
  state.counters["wide_over_range_adaptive"] = m[2] / m[0];
  state.SetLabel(Scenario::name());
}

template <class Scenario>
void BM_AngularOrEuclidean(benchmark::State& state) {
  sc::CArcParams carc = Scenario::carc();
  carc.window_seconds = kWindow;
  const auto fast = sc::to_clusterer_params<sc::CArcFastConfig>(carc);
  const sc::AngularOrEuclidean::Params hybrid{fast.linkage, {0.1f}};
  std::tuple<Driver<HybridSampleConfig>, Driver<HybridWideConfig>> drivers{
      {Scenario::points(), rebind<HybridSampleConfig>(fast, hybrid)},
      {Scenario::points(), rebind<HybridWideConfig>(fast, hybrid)}};
  const auto m = lockstep(state, drivers, std::index_sequence_for<int, int>{});
  state.counters["sample_p50_ms"] = m[0];
  state.counters["wide_p50_ms"] = m[1];
  state.counters["wide_over_sample"] = m[1] / m[0];
  state.SetLabel(Scenario::name());
}

}  // namespace

BENCHMARK_TEMPLATE(BM_GatedObjects, Mid360Office)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_GatedObjects, AviaOffice)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_AngularOrEuclidean, Mid360Office)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_AngularOrEuclidean, AviaOffice)->UseManualTime()->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
