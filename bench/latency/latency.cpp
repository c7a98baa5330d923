// SPDX-License-Identifier: MIT
// bench_latency: the paper's end-to-end metric, with peers in the same run.
//
// For each scenario (sensor x scene x configuration x T_B) a raw stream is
// simulated on the fly (no downsampling; ground removal only by the objects
// presets' own ground policy) and drives the continuous engine
// single-threaded, with a retrieval every 50 ms of stream time (20 Hz). The
// cycle latency is the wall time around the inserts of everything that
// arrived in the 50 ms slice plus the retrieve() (placement + ground +
// insertion + eviction + validation + component update + labelling); the
// simulation of the slice is not timed. The objects scenarios run
// ObjectsConfig (objects_mid360_params / objects_avia_params) with the
// scene's sensor height, at rest or moving with the simulator's 100 Hz
// sensor poses (the engine's PosedMotion places every point by them). On every k-th cycle the peers cluster the same
// window (the engine's window at that cycle, read back from the engine):
//   batch  BatchClusterer<Config> in insertion_order (from scratch, same grid)
//   frame  the overwrite-grid frame baseline: FrameClusterer<Config with
//          OverwriteGrid> (range_image mode) clustering the engine's window
//          on the same grid
//   (with a motion policy both get the window's points in the sensor frame
//   and place them as the engine does; the engine's ground decisions are
//   replayed: they cluster its object points)
//   pcl    pcl::EuclideanClusterExtraction (kd-tree), tolerance = the
//          Euclidean linkage distance; Euclidean configurations only, built
//          only when PCL is found
// and the adjusted Rand index of the engine (and of the frame baseline)
// against the simulator's ground truth is computed (streamclust::eval,
// object points only).
//
// Memory: the engine's footprint per windowed point from
// StreamClusterer::memory_usage() (heap capacities by part: point ring, edge
// storage, spatial index, clusters/bridges, scratch, result; divided by the
// window's points at that cycle), and as a cross-check the live engine heap
// bytes per windowed point from a counting global operator new/delete
// (alloc_counter.hpp: only the engine's calls attributed, malloc usable
// sizes); heap allocations per cycle after warm-up; the process's peak RSS
// (VmHWM, reset per scenario through /proc/self/clear_refs; getrusage's
// ru_maxrss, never reset, when /proc is unavailable). --trace-allocs prints
// the call stack of every steady-state allocation (see alloc_counter.hpp).
// The phase split (RetrievalStats::phase_us) comes from a second, shorter
// pass with a timed copy of the configuration (T_B = 0.5 s scenarios only),
// so that the totals are measured without the timer overhead.
//
// Usage: bench_latency [--cycles N] [--peer-every K] [--pcl-every K]
//                      [--timed-cycles N] [--filter TEXT] [--out DIR]
//                      [--scenario NAME] [--data DIR] [--smoke] [--list]
//                      [--trace-allocs] [--spin-up SECONDS] [--prune-witnesses N]
//                      [--capacity K] [--reserve POINTS] [--packet POINTS]
// (--scenario: exactly one scenario, by its --list name; bench/run.sh runs
// every scenario as its own process, two at a time, and merges the outputs
// with merge_summaries.py.)
// Output in DIR (default latency-results):
//   cycles.csv    every measured cycle: scenario, cycle, latency_us, cpu_us,
//                 inserted, window, allocations (engine heap allocations)
//   summary.json  per scenario: percentiles, peers, ratios, ARI, memory, phases
//   summary.md    the same as markdown tables
//   cdf/<scenario>.dat, pct/<scenario>.dat  sorted latencies (ms, fraction)
//                 and the percentile points, for bench/latency/plot_cdf.gp
//
// Adding a configuration is one line in kConfigs below.

#include "alloc_counter.hpp"
#include "pcl_peer.hpp"

#include <streamclust/eval/rand_index.hpp>
#include <streamclust/frame_clusterer.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/avia_model.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/sensors/table_replay.hpp>
#include <streamclust/sim/simulator.hpp>
#include <streamclust/percentiles.hpp>
#include <streamclust/streamclust.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <time.h>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace sc = streamclust;
namespace sim = streamclust::sim;
namespace fs = std::filesystem;
using sc::summarize;
using sc::LatencySummary;

namespace {

constexpr double kCyclePeriod = 0.05;  // 20 Hz retrieval [s]

// ------------------------------------------------------------- configuration

enum class Sensor { mid360, avia };
const char* to_string(Sensor s) { return s == Sensor::mid360 ? "mid360" : "avia"; }

/// A configuration with a timed copy (phase split) and its overwrite-grid
/// frame baseline.
template <class Config>
struct Timed : Config {
  static constexpr bool timed = true;
};
template <class Config>
struct WithOverwrite : Config {
  using spatial_index = sc::OverwriteGrid;
};
/// EuclideanConfig with the fast presets' spanning-forest connectivity (no
/// preset of its own): the fast strategy against the PCL peer, which only
/// runs on Euclidean linkage.
struct EuclideanFastConfig : sc::EuclideanConfig {
  using connectivity = sc::SpanningForestConnectivity;
};

struct Options;
struct Scenario;
struct ScenarioResult;
using Runner = ScenarioResult (*)(const Scenario&, const Options&);

/// One configuration under test: a name, on which sensors it runs, and the
/// runner instantiated for it.
struct ConfigEntry {
  const char* name;         ///< short id used in scenario names
  const char* description;  ///< for the report
  bool mid360;              ///< run on the Mid-360
  bool avia;                ///< run on the Avia
  unsigned windows;         ///< bit i: run at kWindows[i]
  Runner run;
  bool moving;              ///< the sensor moves (the engine gets its poses); false: at rest
};

constexpr unsigned kAllWindows = 0x1Fu;     // T_B = 0.1 ... 0.5 s
constexpr unsigned kLongestWindow = 0x10u;  // T_B = 0.5 s only
constexpr unsigned kShortestWindow = 0x01u; // T_B = 0.1 s only

template <class Config>
ScenarioResult run_scenario(const Scenario& s, const Options& o);

// Adding a configuration (e.g. a new preset of the perf work) is one line:
const ConfigEntry kConfigs[] = {
    {"carc", "C-ARC preset (bucket grid, angular)", true, true, kAllWindows, &run_scenario<sc::CArcConfig>, false},
    {"capped", "CArcCappedConfig (capped grid K = 4, angular)", false, true, kAllWindows,
     &run_scenario<sc::CArcCappedConfig>, false},
    {"fast", "CArcFastConfig (bucket grid, angular, spanning forest)", true, true, kAllWindows,
     &run_scenario<sc::CArcFastConfig>, false},
    {"capfast", "CArcCappedFastConfig (capped grid K = 4, angular, spanning forest)", false, true, kAllWindows,
     &run_scenario<sc::CArcCappedFastConfig>, false},
    // The capped fast preset (target 6's memory figure) on the Mid-360 too, at the window ends only.
    {"capfast", "CArcCappedFastConfig (capped grid K = 4, angular, spanning forest)", true, false,
     kShortestWindow | kLongestWindow, &run_scenario<sc::CArcCappedFastConfig>, false},
    {"rebuild", "CArcRebuildConfig (bucket grid, angular, union-find rebuild)", true, true, kLongestWindow,
     &run_scenario<sc::CArcRebuildConfig>, false},
    {"caprebuild", "CArcCappedRebuildConfig (capped grid K = 4, angular, union-find rebuild)", false, true,
     kLongestWindow, &run_scenario<sc::CArcCappedRebuildConfig>, false},
    {"euclid", "EuclideanConfig (bucket grid, Euclidean 0.5 m)", true, true, kLongestWindow,
     &run_scenario<sc::EuclideanConfig>, false},
    {"euclidfast", "EuclideanConfig + spanning forest (bench-local)", true, true, kLongestWindow,
     &run_scenario<EuclideanFastConfig>, false},
    // The objects presets (objects_mid360_params / objects_avia_params with the scene's sensor height): ground and
    // ceiling out, range-adaptive linkage, spanning forest, PosedMotion; at rest, and moving with the poses.
    {"objects", "ObjectsConfig (height-map ground, range-adaptive, spanning forest, PosedMotion), at rest", true, true,
     kLongestWindow, &run_scenario<sc::ObjectsConfig>, false},
    {"objects-moving", "ObjectsConfig, moving (back and forth along x at 0.8 m/s, yawing +-0.4 rad/s; 100 Hz poses)",
     true, true, kLongestWindow, &run_scenario<sc::ObjectsConfig>, true},
};

const double kWindows[] = {0.1, 0.2, 0.3, 0.4, 0.5};
const char* const kScenes[] = {"office", "forest"};

struct Scenario {
  Sensor sensor = Sensor::mid360;
  std::string scene;
  const ConfigEntry* config = nullptr;
  double window = 0.1;  ///< T_B [s]

  std::string name() const {
    std::ostringstream os;
    os << to_string(sensor) << '-' << scene << '-' << config->name << "-tb" << std::fixed << std::setprecision(1)
       << window;
    return os.str();
  }
};

struct Options {
  std::size_t cycles = 1000;       ///< measured cycles per scenario
  std::size_t peer_every = 20;     ///< batch and frame peers (and ARI) on every k-th measured cycle
  std::size_t pcl_every = 100;     ///< PCL peer on every k-th measured cycle
  std::size_t timed_cycles = 200;  ///< cycles of the timed (phase split) pass, 0 = none
  std::string filter;              ///< run scenarios whose name contains this
  std::string scenario;            ///< run only the scenario of exactly this name
  std::string out = "latency-results";
  std::string data;                ///< ../shared/data/livox (Mid-360 table); empty = default lookup
  bool smoke = false;
  bool list = false;
  bool trace_allocs = false;       ///< print the stacks of steady-state engine allocations to stderr
  std::size_t spin_up_s = 3;       ///< busy seconds before each scenario (CPU frequency ramp), 0 = none
  std::size_t packet = 96;         ///< points per insert_batch call (a Livox packet), 0 = insert() per point
};

// ------------------------------------------------------------------- inputs

/// <repo>/../shared/data/livox, or $STREAMCLUST_LIVOX_DATA, or --data.
fs::path livox_dir(const Options& o) {
  if (!o.data.empty()) return fs::path(o.data);
  if (const char* env = std::getenv("STREAMCLUST_LIVOX_DATA")) return fs::path(env);
  return fs::path(STREAMCLUST_SOURCE_DIR) / ".." / "shared" / "data" / "livox";
}

sc::CArcParams sensor_params(Sensor s, double window) {
  sc::CArcParams p = s == Sensor::mid360 ? sc::carc_mid360_params() : sc::carc_avia_params();
  p.window_seconds = window;
  return p;
}

/// Engine parameters: the paper's (w = 5, T_M = 2, theta 30 / 80 degrees,
/// adaptive grid) for angular configurations; the same FOV, window, mask and
/// calibration with the linkage's default Params otherwise.
/// --prune-witnesses N: SpanningForestConnectivity::Params::prune_witnesses
/// of the spanning-forest configurations (-1: the default), for A/B runs.
long g_prune_witnesses = -1;
/// --capacity K: CappedGrid::Params::capacity of the capped configurations
/// (-1: the default), for A/B runs.
long g_capacity = -1;
/// --reserve POINTS: StreamClusterer::reserve(POINTS) right after
/// construction (0: none, the default), to measure a pre-sized engine.
std::size_t g_reserve = 0;

sim::Scene make_scene(const std::string& name) {
  return name == "forest" ? sim::forest_scene(1) : sim::office_scene(1);
}

/// The simulator's settings: the defaults (sensor level at 1 m above the
/// origin, 2 cm range noise, seed 1), at rest; a moving scenario goes back
/// and forth along x (+-1 m at 0.8 m/s, turning every 2.5 s) while yawing
/// (+-0.5 rad at 0.4 rad/s), up to `seconds` of stream.
template <class SensorModel>
typename sim::Simulator<SensorModel>::Params sim_params(const Scenario& s, double seconds) {
  typename sim::Simulator<SensorModel>::Params p;
  if (!s.config->moving) return p;
  constexpr float kSpeed = 0.8f;     // [m/s]
  constexpr float kYawRate = 0.4f;   // [rad/s]
  constexpr double kLeg = 2.5;       // [s] one leg: 2 m, 1 rad
  p.velocity = Eigen::Vector3f(kSpeed, 0.0f, 0.0f);
  p.yaw_rate = kYawRate;
  float sign = -1.0f;
  for (double t = 0.5 * kLeg; t < seconds; t += kLeg, sign = -sign) {
    p.motion_profile.push_back(sim::MotionSegment{t, Eigen::Vector3f(sign * kSpeed, 0.0f, 0.0f), sign * kYawRate});
  }
  return p;
}

/// The sensor's height above the scene's ground under its start position
/// [m] (the simulator's start height; floors and the forest's ground pass
/// through z = 0 at the origin when the scene has no terrain).
float scene_sensor_height(const Scenario& s) {
  const Eigen::Vector3f start = sim::Simulator<sim::Mid360Model>::Params{}.start_position;
  return start.z() - make_scene(s.scene).ground_height(start.x(), start.y()).value_or(0.0f);
}

/// The sensor's poses over the first `seconds` of a moving scenario (100 Hz,
/// as odometry would give them), null at rest.
template <class SensorModel>
std::shared_ptr<const sc::PoseTrajectory> scenario_trajectory(const Scenario& s, const SensorModel& sensor,
                                                              double seconds) {
  if (!s.config->moving) return nullptr;
  const sim::Simulator<SensorModel> simulator(sensor, make_scene(s.scene), sim_params<SensorModel>(s, seconds));
  return std::make_shared<const sc::PoseTrajectory>(simulator.trajectory(0.0, seconds, 100.0));
}

template <class Config>
sc::ClustererParams<Config> engine_params(const Scenario& s,
                                          const std::shared_ptr<const sc::PoseTrajectory>& trajectory = nullptr) {
  sc::ClustererParams<Config> params;
  if constexpr (std::is_same_v<Config, sc::ObjectsConfig>) {
    sc::ObjectsSetup setup;
    setup.trajectory = trajectory;  // the simulator's sensor poses: the mount stays the identity
    setup.sensor_height = scene_sensor_height(s);
    setup.window_seconds = s.window;
    params = s.sensor == Sensor::mid360 ? sc::objects_mid360_params(setup) : sc::objects_avia_params(setup);
  } else {
    params = sc::to_clusterer_params<Config>(sensor_params(s.sensor, s.window));
  }
  if constexpr (std::is_same_v<typename sc::config_traits<Config>::connectivity, sc::SpanningForestConnectivity>) {
    if (g_prune_witnesses >= 0) params.connectivity.prune_witnesses = static_cast<std::uint32_t>(g_prune_witnesses);
  }
  if constexpr (std::is_same_v<typename sc::config_traits<Config>::spatial_index, sc::CappedGrid>) {
    if (g_capacity >= 0) params.spatial_index.capacity = static_cast<std::uint32_t>(g_capacity);
  }
  return params;
}

/// The same parameters for a configuration derived from another: every slot
/// is copied, the index's only when both use the same index policy.
template <class To, class From>
sc::ClustererParams<To> rebind_params(const sc::ClustererParams<From>& from) {
  sc::ClustererParams<To> to;
  to.projection = from.projection;
  to.linkage = from.linkage;
  to.window = from.window;
  to.resolution = from.resolution;
  to.mask_size = from.mask_size;
  if constexpr (std::is_same_v<decltype(to.connectivity), decltype(from.connectivity)>) {
    to.connectivity = from.connectivity;
  }
  if constexpr (std::is_same_v<decltype(to.spatial_index), decltype(from.spatial_index)>) {
    to.spatial_index = from.spatial_index;
  }
  if constexpr (std::is_same_v<decltype(to.motion), decltype(from.motion)>) to.motion = from.motion;
  if constexpr (std::is_same_v<decltype(to.ground), decltype(from.ground)>) to.ground = from.ground;
  return to;
}

/// Slices of a simulated stream: every point with time < t_end not yet given.
template <class SensorModel>
class SliceSource {
 public:
  SliceSource(SensorModel sensor, sim::Scene scene, const typename sim::Simulator<SensorModel>::Params& params)
      : sim_(std::move(sensor), std::move(scene), params),
        pending_(sim_.next()) {}

  void fill(double t_end, std::vector<sim::SimPoint>& out) {
    out.clear();
    while (pending_.t < t_end) {
      out.push_back(pending_);
      pending_ = sim_.next();
    }
  }

 private:
  sim::Simulator<SensorModel> sim_;
  sim::SimPoint pending_;
};

// ------------------------------------------------------------------ results

struct PeerResult {
  std::vector<double> us;          ///< peer wall time per evaluated cycle
  std::vector<double> engine_us;   ///< the engine's cycle latency on those cycles
  LatencySummary summary() const { return summarize(us); }
};

struct ScenarioResult {
  std::string name;
  std::string sensor_source;  ///< which Mid-360 pattern (table or analytic) or Avia model
  sc::GridSize grid{};
  std::vector<double> latency_us;
  std::vector<double> cpu_us;  ///< thread CPU time of the same cycles
  std::vector<std::uint32_t> inserted;
  std::vector<std::uint32_t> window;     ///< window points: object points + structure points
  std::vector<std::uint32_t> structure;  ///< of those, structure points (ground policy; 0 without one)
  std::vector<std::uint32_t> allocations;  ///< engine heap allocations of each cycle
  PeerResult batch, frame, pcl;
  std::vector<double> ari_engine, ari_frame;
  std::vector<double> bytes_per_point;       ///< memory_usage().total() / window points
  std::vector<double> heap_bytes_per_point;  ///< live engine heap (counting allocator) / window points
  /// memory_usage() parts / window points: ring, edges, index, clusters, scratch, result, structure.
  std::vector<double> part_bytes_per_point[7];
  bool index_memory_known = true;
  std::uint64_t steady_allocations = 0;
  std::size_t cycles_with_allocations = 0;
  double peak_rss_mb = 0.0;
  bool rss_reset = false;
  // timed pass
  std::size_t timed_cycles = 0;
  sc::PhaseTimes phase_mean{};
  double edges_found_mean = 0.0;  // spanning_forest: new edges found per cycle
  double edges_kept_mean = 0.0;   // of those, kept after pruning
  double edges_folded_mean = 0.0;    // spanning_forest: new edges the folds read per cycle
  double edges_accepted_mean = 0.0;  // of those, accepted into the forest
  double forest_edges_mean = 0.0;    // the forest after the retrieval [edges]
  double timed_median_us = 0.0;
  double wall_seconds = 0.0;
};

/// Names of MemoryUsage's parts, in ScenarioResult::part_bytes_per_point order.
const char* const kMemoryParts[7] = {"point_ring", "edge_storage", "spatial_index", "clusters",
                                     "scratch",    "result",       "structure"};

double mean(const std::vector<double>& v) {
  if (v.empty()) return 0.0;
  double s = 0.0;
  for (const double x : v) s += x;
  return s / static_cast<double>(v.size());
}

// -------------------------------------------------------------------- memory

/// Resets the process's peak RSS (VmHWM) so that getrusage reports this
/// scenario's peak; false when the kernel refuses.
bool reset_peak_rss() {
  std::ofstream f("/proc/self/clear_refs");
  if (!f) return false;
  f << "5";
  f.flush();
  return static_cast<bool>(f);
}

/// Peak RSS [MiB]: VmHWM of /proc/self/status (which clear_refs resets),
/// else getrusage's ru_maxrss (the peak over the process's whole life).
double peak_rss_mb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::strtod(line.c_str() + 6, nullptr) / 1024.0;  // in kB
  }
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

// -------------------------------------------------------------------- runner

using Clock = std::chrono::steady_clock;
double micros(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::micro>(b - a).count(); }

/// CPU time of this thread [us]: unlike the wall clock, not inflated when
/// other processes take the core (a noise check on a shared machine).
double thread_cpu_us() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) * 1e-3;
}

std::size_t warmup_cycles(double window) { return static_cast<std::size_t>(std::ceil(2.0 * window / kCyclePeriod)) + 10; }

/// Ground truth (or the raw points) of the offered stream, by stream index
/// (rejected points included).
template <class T>
class StreamLog {
 public:
  void push(const T& value) { ids_.push_back(value); }
  /// Forget everything older than stream index `first_kept`.
  void trim(std::uint64_t first_kept) {
    while (base_ < first_kept && !ids_.empty()) {
      ids_.pop_front();
      ++base_;
    }
  }
  const T& at(std::uint64_t stream_index) const { return ids_.at(static_cast<std::size_t>(stream_index - base_)); }

 private:
  std::deque<T> ids_;
  std::uint64_t base_ = 0;
};

/// Feeds one slice to the engine as a driver would: insert_batch on packets
/// of `packet` points (96: a Livox packet), or insert() per point when
/// `packet` is 0.
template <class Engine>
void feed(Engine& engine, const std::vector<sim::SimPoint>& slice, std::size_t packet) {
  if (packet == 0) {
    for (const auto& p : slice) engine.insert(p);
    return;
  }
  for (std::size_t i = 0; i < slice.size(); i += packet) {
    const auto first = slice.begin() + static_cast<std::ptrdiff_t>(i);
    engine.insert_batch(first, first + static_cast<std::ptrdiff_t>(std::min(packet, slice.size() - i)));
  }
}

/// Drives one configuration over one scenario's stream. The engine calibrates
/// its grid on the first complete window (T_B), as in the paper; retrievals
/// start once it has.
///
/// With a motion policy (the objects presets) the peers get the window's
/// points as the sensor gave them (sensor frame, in stream order) and place
/// them as the engine does; the ground policy is not applied: they cluster
/// the engine's object points.
template <class Config, class SensorModel>
void drive(const Scenario& s, const Options& o, SensorModel sensor,
           const std::shared_ptr<const sc::PoseTrajectory>& trajectory, double seconds, ScenarioResult& r) {
  using Engine = sc::StreamClusterer<Config>;
  constexpr bool placed = !Engine::motion_type::identity;
  const auto params = engine_params<Config>(s, trajectory);
  SliceSource<SensorModel> source(std::move(sensor), make_scene(s.scene), sim_params<SensorModel>(s, seconds));
  std::optional<Engine> engine;
  // The counters are process-wide: the engine's live bytes are the growth
  // from here on (construction included).
  const std::int64_t live_base = sc::bench::alloc_counters().live_bytes;
  {
    sc::bench::AllocScope scope;
    engine.emplace(params);
    if (g_reserve > 0) engine->reserve(g_reserve);
  }
  sc::BatchClusterer<Config> batch(params, sc::BatchMode::insertion_order);
  using Frame = WithOverwrite<Config>;
  sc::FrameClusterer<Frame> frame(rebind_params<Frame>(params), sc::BatchMode::range_image);
  constexpr bool euclidean = std::is_same_v<typename sc::config_traits<Config>::linkage, sc::EuclideanLinkage>;

  StreamLog<int> truth_log;
  StreamLog<sim::SimPoint> raw_log;  // with a motion policy: the peers' input
  std::vector<sim::SimPoint> slice, window_raw;
  std::vector<sc::Sample> window_samples;
  std::vector<std::int64_t> truth, predicted;
  std::vector<float> xyz;
  const std::size_t warmup = warmup_cycles(s.window);
  const std::size_t total = warmup + o.cycles;
  r.latency_us.reserve(o.cycles);
  r.inserted.reserve(o.cycles);
  r.window.reserve(o.cycles);

  for (std::size_t cycle = 0; cycle < total; ++cycle) {
    source.fill(static_cast<double>(cycle + 1) * kCyclePeriod, slice);
    for (const auto& p : slice) truth_log.push(p.instance);
    if constexpr (placed) {
      for (const auto& p : slice) raw_log.push(p);
    }
    const bool measured = cycle >= warmup;
    if (o.trace_allocs && cycle == warmup) sc::bench::set_alloc_tracing(true);
    const sc::bench::AllocCounters before = sc::bench::alloc_counters();

    const double c0 = thread_cpu_us();
    const auto t0 = Clock::now();
    const sc::Clustering* result = nullptr;
    {
      sc::bench::AllocScope scope;
      feed(*engine, slice, o.packet);
      // No retrieval while the first window is buffered (it would return an
      // empty result and measure nothing).
      if (!engine->calibrating()) result = &engine->retrieve();
    }
    const auto t1 = Clock::now();
    const double cpu = thread_cpu_us() - c0;
    const double us = micros(t0, t1);
    const sc::bench::AllocCounters after = sc::bench::alloc_counters();
    if (!measured) continue;
    if (result == nullptr) throw std::runtime_error(r.name + ": still calibrating after the warm-up");

    const std::size_t m = cycle - warmup;
    r.latency_us.push_back(us);
    r.cpu_us.push_back(cpu);
    r.inserted.push_back(static_cast<std::uint32_t>(slice.size()));
    r.window.push_back(static_cast<std::uint32_t>(engine->size() + engine->structure_size()));
    r.structure.push_back(static_cast<std::uint32_t>(engine->structure_size()));
    const std::uint64_t allocs = after.allocations - before.allocations;
    r.steady_allocations += allocs;
    r.allocations.push_back(static_cast<std::uint32_t>(allocs));
    if (allocs > 0) ++r.cycles_with_allocations;
    if (engine->size() > 0) {
      const auto n = static_cast<double>(engine->size() + engine->structure_size());
      const sc::MemoryUsage mu = engine->memory_usage();
      r.index_memory_known = mu.spatial_index_known;
      r.bytes_per_point.push_back(static_cast<double>(mu.total()) / n);
      r.heap_bytes_per_point.push_back(static_cast<double>(after.live_bytes - live_base) / n);
      const std::size_t parts[7] = {mu.point_ring, mu.edge_storage, mu.spatial_index, mu.clusters,
                                    mu.scratch,    mu.result,       mu.structure};
      for (std::size_t k = 0; k < 7; ++k) r.part_bytes_per_point[k].push_back(static_cast<double>(parts[k]) / n);
    }
    if (m == 0) r.grid = sc::GridSize{engine->grid().rows, engine->grid().cols};

    const bool peers = m % o.peer_every == 0;
    const bool pcl = euclidean && sc::bench::pcl_peer_available() && m % o.pcl_every == 0;
    if (!peers && !pcl) continue;

    // The engine's window, oldest first, and its ground truth.
    window_samples.clear();
    window_raw.clear();
    truth.clear();
    engine->for_each_point([&](const sc::Sample& sample, std::uint64_t stream_index) {
      if constexpr (placed) {
        window_raw.push_back(raw_log.at(stream_index));
      } else {
        window_samples.push_back(sample);
      }
      truth.push_back(truth_log.at(stream_index));
    });
    if (!result->points.empty()) {
      truth_log.trim(result->points.front().stream_index);
      raw_log.trim(result->points.front().stream_index);
    }
    // The peers' input: the window's points as stored (world), or as the sensor gave them.
    auto peer_cluster = [&](auto& peer) -> const sc::BatchResult& {
      if constexpr (placed) {
        return peer.cluster(window_raw);
      } else {
        return peer.cluster(window_samples);
      }
    };

    if (peers) {
      predicted.clear();
      for (const sc::PointLabel& pl : result->points) predicted.push_back(static_cast<std::int64_t>(pl.label));
      r.ari_engine.push_back(sc::eval::adjusted_rand_index(truth, predicted));

      batch.set_grid(r.grid);
      const auto b0 = Clock::now();
      const sc::BatchResult& br = peer_cluster(batch);
      const auto b1 = Clock::now();
      r.batch.us.push_back(micros(b0, b1));
      r.batch.engine_us.push_back(us);
      if (br.components == 0 && !truth.empty()) throw std::runtime_error("batch peer labelled nothing");

      frame.set_grid(r.grid);
      const auto f0 = Clock::now();
      const sc::BatchResult& fr = peer_cluster(frame);  // the engine's window, from scratch
      const auto f1 = Clock::now();
      r.frame.us.push_back(micros(f0, f1));
      r.frame.engine_us.push_back(us);
      r.ari_frame.push_back(sc::eval::adjusted_rand_index(truth, fr.labels));
    }
    if (pcl) {
      xyz.clear();
      for (const sc::Sample& smp : window_samples) {  // (no motion policy: the Euclidean presets)
        xyz.push_back(smp.position.x());
        xyz.push_back(smp.position.y());
        xyz.push_back(smp.position.z());
      }
      std::size_t clusters = 0;
      float tolerance = 0.0f;
      if constexpr (euclidean) tolerance = params.linkage.max_distance;
      r.pcl.us.push_back(sc::bench::pcl_euclidean_us(xyz, tolerance, clusters));
      r.pcl.engine_us.push_back(us);
    }
  }
  if (o.trace_allocs) {
    sc::bench::set_alloc_tracing(false);
    std::cerr << "=== " << r.name << ": stacks of the steady-state engine allocations" << std::endl;
    const std::uint64_t traced = sc::bench::dump_alloc_traces(2);
    std::cerr << "=== " << r.name << ": " << traced << " traced allocation(s)" << std::endl;
  }
  sc::bench::AllocScope scope;  // the engine's frees balance its allocations
  engine.reset();
}

/// The timed pass: phase split averaged over `cycles` cycles after warm-up.
template <class Config, class SensorModel>
void drive_timed(const Scenario& s, std::size_t cycles, std::size_t packet, SensorModel sensor,
                 const std::shared_ptr<const sc::PoseTrajectory>& trajectory, double seconds, ScenarioResult& r) {
  using T = Timed<Config>;
  sc::StreamClusterer<T> engine(rebind_params<T>(engine_params<Config>(s, trajectory)));
  SliceSource<SensorModel> source(std::move(sensor), make_scene(s.scene), sim_params<SensorModel>(s, seconds));
  std::vector<sim::SimPoint> slice;
  std::vector<double> lat;
  sc::PhaseTimes sum{};
  double edges_found = 0.0;
  double edges_kept = 0.0;
  double edges_folded = 0.0;
  double edges_accepted = 0.0;
  double forest_edges = 0.0;
  const std::size_t warmup = warmup_cycles(s.window);
  for (std::size_t cycle = 0; cycle < warmup + cycles; ++cycle) {
    source.fill(static_cast<double>(cycle + 1) * kCyclePeriod, slice);
    const auto t0 = Clock::now();
    feed(engine, slice, packet);
    if (!engine.calibrating()) engine.retrieve();
    const auto t1 = Clock::now();
    if (cycle < warmup) continue;
    lat.push_back(micros(t0, t1));
    const sc::RetrievalStats& stats = engine.last_stats();
    const sc::PhaseTimes& ph = stats.phase_us;
    edges_found += static_cast<double>(stats.edges_found);
    edges_kept += static_cast<double>(stats.edges_found - stats.edges_pruned);
    edges_folded += static_cast<double>(stats.edges_folded);
    edges_accepted += static_cast<double>(stats.edges_accepted);
    forest_edges += static_cast<double>(stats.forest_edges);
    sum.placement += ph.placement;
    sum.ground += ph.ground;
    sum.insertion += ph.insertion;
    sum.eviction += ph.eviction;
    sum.validation += ph.validation;
    sum.component_update += ph.component_update;
    sum.labelling += ph.labelling;
  }
  const auto n = static_cast<double>(cycles);
  r.timed_cycles = cycles;
  r.phase_mean.placement = sum.placement / n;
  r.phase_mean.ground = sum.ground / n;
  r.phase_mean.insertion = sum.insertion / n;
  r.phase_mean.eviction = sum.eviction / n;
  r.phase_mean.validation = sum.validation / n;
  r.phase_mean.component_update = sum.component_update / n;
  r.phase_mean.labelling = sum.labelling / n;
  r.timed_median_us = summarize(lat).median;
  r.edges_found_mean = edges_found / n;
  r.edges_kept_mean = edges_kept / n;
  r.edges_folded_mean = edges_folded / n;
  r.edges_accepted_mean = edges_accepted / n;
  r.forest_edges_mean = forest_edges / n;
}

/// Calls f(sensor model, description) with this scenario's sensor.
template <class F>
void with_sensor(const Scenario& s, const Options& o, F&& f) {
  if (s.sensor == Sensor::avia) {
    f(sim::AviaModel(sim::AviaModel::Params{}), std::string("AviaModel (analytic, 240 kHz)"));
    return;
  }
  const fs::path table = livox_dir(o) / "patterns" / "mid360_u16le.bin";
  std::error_code ec;
  if (fs::is_regular_file(table, ec)) {
    f(sim::TableReplay::mid360(table.string()), "TableReplay of the real table " + table.lexically_normal().string());
  } else {
    f(sim::Mid360Model(sim::Mid360Model::Params{}), std::string("Mid360Model (analytic; real table not found)"));
  }
}

/// Keeps the core busy for `seconds` [s]. On this VM a process's first
/// seconds of work run up to 1.4x slower than the rest (a step, not a
/// drift: measured on avia-office-capfast-tb0.5, about 45 measured cycles
/// at 21 ms then 15 ms; a 4 s busy loop before the run removed the step),
/// which put start-up, not the engine, into the P99 of the slower scenarios.
void spin_up(std::size_t seconds) {
  const auto end = Clock::now() + std::chrono::seconds(seconds);
  volatile std::uint64_t sink = 0;
  while (Clock::now() < end) {
    for (int i = 0; i < 4096; ++i) sink = sink + static_cast<std::uint64_t>(i);
  }
}

template <class Config>
ScenarioResult run_scenario(const Scenario& s, const Options& o) {
  spin_up(o.spin_up_s);
  ScenarioResult r;
  r.name = s.name();
  r.rss_reset = reset_peak_rss();
  const auto w0 = Clock::now();
  with_sensor(s, o, [&](auto sensor, const std::string& source) {
    r.sensor_source = source;
    // Stream time of the longer pass, plus a slice of margin: the poses must cover every point.
    const std::size_t longest = warmup_cycles(s.window) + std::max(o.cycles, o.timed_cycles) + 2;
    const double seconds = static_cast<double>(longest) * kCyclePeriod;
    const auto trajectory = scenario_trajectory(s, sensor, seconds);
    drive<Config>(s, o, sensor, trajectory, seconds, r);
    r.peak_rss_mb = peak_rss_mb();
    if (o.timed_cycles > 0 && (s.window > 0.45 || o.smoke)) {
      drive_timed<Config>(s, o.timed_cycles, o.packet, sensor, trajectory, seconds, r);
    }
  });
  r.wall_seconds = std::chrono::duration<double>(Clock::now() - w0).count();
  return r;
}

// ------------------------------------------------------------------- output

std::string fmt(double v, int precision = 2) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(precision) << v;
  return os.str();
}

void write_json_summary(std::ostream& os, const LatencySummary& s, double scale) {
  os << "{\"count\": " << s.count << ", \"p1\": " << s.p1 * scale << ", \"q1\": " << s.q1 * scale
     << ", \"median\": " << s.median * scale << ", \"q3\": " << s.q3 * scale << ", \"p95\": " << s.p95 * scale
     << ", \"p99\": " << s.p99 * scale << ", \"p999\": " << s.p999 * scale << ", \"max\": " << s.max * scale
     << ", \"mean\": " << s.mean * scale << "}";
}

void write_peer_json(std::ostream& os, const char* name, const PeerResult& p, const LatencySummary& engine) {
  const LatencySummary ps = p.summary();
  os << "    \"" << name << "\": ";
  if (ps.count == 0) {
    os << "null";
    return;
  }
  os << "{\"ms\": ";
  write_json_summary(os, ps, 1e-3);
  os << ", \"engine_same_cycles_ms\": ";
  write_json_summary(os, summarize(p.engine_us), 1e-3);
  os << ", \"median_ratio\": " << ps.median / engine.median << ", \"p99_ratio\": " << ps.p99 / engine.p99 << "}";
}

struct Written {
  std::vector<std::pair<Scenario, ScenarioResult>> all;
};

void write_outputs(const Options& o, const Written& w) {
  const fs::path out(o.out);
  fs::create_directories(out / "cdf");
  fs::create_directories(out / "pct");

  std::ofstream csv(out / "cycles.csv");
  csv << "scenario,cycle,latency_us,cpu_us,inserted,window,allocations\n";
  for (const auto& [s, r] : w.all) {
    for (std::size_t i = 0; i < r.latency_us.size(); ++i) {
      csv << r.name << ',' << i << ',' << fmt(r.latency_us[i], 1) << ',' << fmt(r.cpu_us[i], 1) << ',' << r.inserted[i]
          << ',' << r.window[i] << ',' << r.allocations[i] << '\n';
    }
    std::vector<double> sorted = r.latency_us;
    std::sort(sorted.begin(), sorted.end());
    std::ofstream cdf(out / "cdf" / (r.name + ".dat"));
    cdf << "# latency_ms fraction\n";
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      cdf << sorted[i] * 1e-3 << ' ' << static_cast<double>(i + 1) / static_cast<double>(sorted.size()) << '\n';
    }
    const LatencySummary ls = summarize(r.latency_us);
    std::ofstream pct(out / "pct" / (r.name + ".dat"));
    pct << "# latency_ms fraction label\n";
    const std::pair<const char*, std::pair<double, double>> marks[] = {
        {"P1", {ls.p1, 0.01}},     {"Q1", {ls.q1, 0.25}},   {"median", {ls.median, 0.5}}, {"Q3", {ls.q3, 0.75}},
        {"P95", {ls.p95, 0.95}}, {"P99", {ls.p99, 0.99}}, {"P999", {ls.p999, 0.999}}};
    for (const auto& mk : marks) pct << mk.second.first * 1e-3 << ' ' << mk.second.second << ' ' << mk.first << '\n';
  }

  std::ofstream json(out / "summary.json");
  json << "{\n  \"cycle_period_ms\": " << kCyclePeriod * 1e3 << ", \"cycles\": " << o.cycles
       << ", \"peer_every\": " << o.peer_every << ", \"pcl_every\": " << o.pcl_every
       << ", \"pcl_available\": " << (sc::bench::pcl_peer_available() ? "true" : "false")
       << ", \"timed_cycles\": " << o.timed_cycles << ",\n  \"scenarios\": [\n";
  for (std::size_t k = 0; k < w.all.size(); ++k) {
    const auto& [s, r] = w.all[k];
    const LatencySummary ls = summarize(r.latency_us);
    json << "  {\n    \"name\": \"" << r.name << "\", \"sensor\": \"" << to_string(s.sensor) << "\", \"scene\": \""
         << s.scene << "\", \"config\": \"" << s.config->name << "\", \"window_s\": " << s.window
         << ", \"sensor_source\": \"" << r.sensor_source << "\", \"grid\": [" << r.grid.rows << ", " << r.grid.cols
         << "],\n    \"latency_ms\": ";
    write_json_summary(json, ls, 1e-3);
    json << ",\n    \"cpu_ms\": ";
    write_json_summary(json, summarize(r.cpu_us), 1e-3);
    json << ",\n    \"points_per_cycle_mean\": " << mean(std::vector<double>(r.inserted.begin(), r.inserted.end()))
         << ", \"window_points_mean\": " << mean(std::vector<double>(r.window.begin(), r.window.end()))
         << ", \"structure_points_mean\": " << mean(std::vector<double>(r.structure.begin(), r.structure.end()))
         << ",\n";
    write_peer_json(json, "batch", r.batch, ls);
    json << ",\n";
    write_peer_json(json, "frame", r.frame, ls);
    json << ",\n";
    write_peer_json(json, "pcl", r.pcl, ls);
    json << ",\n    \"ari_engine_mean\": " << mean(r.ari_engine) << ", \"ari_frame_mean\": " << mean(r.ari_frame)
         << ", \"ari_samples\": " << r.ari_engine.size() << ",\n    \"bytes_per_point\": ";
    write_json_summary(json, summarize(r.bytes_per_point), 1.0);
    json << ",\n    \"heap_bytes_per_point\": ";
    write_json_summary(json, summarize(r.heap_bytes_per_point), 1.0);
    json << ",\n    \"memory_parts_bytes_per_point_median\": {";
    for (std::size_t part = 0; part < 7; ++part) {
      json << (part ? ", " : "") << '"' << kMemoryParts[part] << "\": " << summarize(r.part_bytes_per_point[part]).median;
    }
    json << "}, \"index_memory_known\": " << (r.index_memory_known ? "true" : "false");
    json << ",\n    \"steady_allocations\": " << r.steady_allocations
         << ", \"cycles_with_allocations\": " << r.cycles_with_allocations << ", \"peak_rss_mb\": " << r.peak_rss_mb
         << ", \"peak_rss_reset\": " << (r.rss_reset ? "true" : "false") << ",\n    \"timed_cycles\": " << r.timed_cycles
         << ", \"phase_mean_ms\": {\"placement\": " << r.phase_mean.placement * 1e-3
         << ", \"ground\": " << r.phase_mean.ground * 1e-3 << ", \"insertion\": " << r.phase_mean.insertion * 1e-3
         << ", \"eviction\": " << r.phase_mean.eviction * 1e-3 << ", \"validation\": " << r.phase_mean.validation * 1e-3
         << ", \"component_update\": " << r.phase_mean.component_update * 1e-3
         << ", \"labelling\": " << r.phase_mean.labelling * 1e-3 << "}, \"new_edges_per_cycle\": " << r.edges_found_mean
         << ", \"kept_edges_per_cycle\": " << r.edges_kept_mean << ", \"folded_edges_per_cycle\": " << r.edges_folded_mean
         << ", \"accepted_edges_per_cycle\": " << r.edges_accepted_mean << ", \"forest_edges\": " << r.forest_edges_mean
         << ", \"timed_median_ms\": " << r.timed_median_us * 1e-3
         << ", \"wall_seconds\": " << r.wall_seconds << "\n  }" << (k + 1 < w.all.size() ? "," : "") << '\n';
  }
  json << "  ]\n}\n";

  std::ofstream md(out / "summary.md");
  md << "# bench_latency summary\n\n";
  md << "Cycle = inserts of one 50 ms slice + retrieve() (20 Hz), single thread; " << o.cycles
     << " measured cycles per scenario after a warm-up of 2 T_B + 0.5 s (wall clock; CPU = the thread's CPU time of the same cycles). Peers (batch, frame) and ARI on every "
     << o.peer_every << "-th cycle, PCL on every " << o.pcl_every << "-th ("
     << (sc::bench::pcl_peer_available() ? "PCL found" : "PCL not built") << "). Times in ms.\n\n";
  if (!w.all.empty()) md << "Mid-360 pattern: " << [&] {
      for (const auto& e : w.all) {
        if (e.first.sensor == Sensor::mid360) return e.second.sensor_source;
      }
      return std::string("(not run)");
    }() << ".\n\n";
  md << "## Continuous engine: cycle latency [ms]\n\n";
  md << "| scenario | grid | pts/cycle | window pts | P1 | Q1 | median | Q3 | P95 | P99 | P999 | max | P99 / 50 ms | CPU "
        "median | CPU P99 |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [s, r] : w.all) {
    const LatencySummary ls = summarize(r.latency_us);
    md << "| " << r.name << " | " << r.grid.rows << "x" << r.grid.cols << " | "
       << fmt(mean(std::vector<double>(r.inserted.begin(), r.inserted.end())), 0) << " | "
       << fmt(mean(std::vector<double>(r.window.begin(), r.window.end())), 0) << " | " << fmt(ls.p1 * 1e-3) << " | "
       << fmt(ls.q1 * 1e-3) << " | " << fmt(ls.median * 1e-3) << " | " << fmt(ls.q3 * 1e-3) << " | "
       << fmt(ls.p95 * 1e-3) << " | " << fmt(ls.p99 * 1e-3) << " | " << fmt(ls.p999 * 1e-3) << " | "
       << fmt(ls.max * 1e-3) << " | " << fmt(100.0 * ls.p99 * 1e-3 / 50.0, 0) << " % | " << fmt(summarize(r.cpu_us).median * 1e-3) << " | "
       << fmt(summarize(r.cpu_us).p99 * 1e-3) << " |\n";
  }
  md << "\n## Peers on the same windows [ms] (ratio = peer / engine, engine over all measured cycles)\n\n";
  md << "| scenario | engine median | batch median | batch P99 | batch/engine median | frame median | frame P99 | "
        "frame/engine median | PCL median | PCL P99 | PCL/engine median |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [s, r] : w.all) {
    const LatencySummary ls = summarize(r.latency_us);
    const LatencySummary b = r.batch.summary(), f = r.frame.summary(), p = r.pcl.summary();
    auto cell = [&](const LatencySummary& x, double v) { return x.count == 0 ? std::string("-") : fmt(v * 1e-3); };
    auto ratio = [&](const LatencySummary& x) {
      return x.count == 0 ? std::string("-") : fmt(x.median / ls.median, 2) + "x";
    };
    md << "| " << r.name << " | " << fmt(ls.median * 1e-3) << " | " << cell(b, b.median) << " | " << cell(b, b.p99)
       << " | " << ratio(b) << " | " << cell(f, f.median) << " | " << cell(f, f.p99) << " | " << ratio(f) << " | "
       << cell(p, p.median) << " | " << cell(p, p.p99) << " | " << ratio(p) << " |\n";
  }
  md << "\n## Quality and memory\n\n";
  md << "Bytes / window point = StreamClusterer::memory_usage().total() (heap capacities: point ring, edge "
        "storage, spatial index, clusters and bridges, scratch, result, structure) / points in the window (object and "
        "structure points), median over the "
        "measured cycles; live heap = the engine's live heap bytes counted by the allocator (malloc usable sizes, "
        "the same parts plus allocator rounding and policies' small buffers) / window points.\n\n";
  md << "| scenario | ARI engine | ARI frame baseline | bytes / window point (median) | live heap / window point "
        "(median) | steady allocations (cycles with any) | peak RSS [MB] |\n";
  md << "|---|---|---|---|---|---|---|\n";
  for (const auto& [s, r] : w.all) {
    md << "| " << r.name << " | " << fmt(mean(r.ari_engine), 4) << " | " << fmt(mean(r.ari_frame), 4) << " | "
       << fmt(summarize(r.bytes_per_point).median, 1) << (r.index_memory_known ? "" : " (index unknown)") << " | "
       << fmt(summarize(r.heap_bytes_per_point).median, 1) << " | " << r.steady_allocations << " ("
       << r.cycles_with_allocations << ") | " << fmt(r.peak_rss_mb, 0) << " |\n";
  }
  md << "\n## Engine memory by part [bytes per window point, median over the measured cycles]\n\n";
  md << "| scenario | window pts | point ring | edge storage | spatial index | clusters + bridges | scratch | result "
        "| structure | total |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [s, r] : w.all) {
    md << "| " << r.name << " | " << fmt(mean(std::vector<double>(r.window.begin(), r.window.end())), 0);
    for (const auto& part : r.part_bytes_per_point) md << " | " << fmt(summarize(part).median, 1);
    md << " | " << fmt(summarize(r.bytes_per_point).median, 1) << " |\n";
  }
  md << "\n## Phase split (timed configuration, mean per cycle) [ms]\n\n";
  md << "| scenario | cycles | placement | ground | insertion | eviction | validation | component update | labelling "
        "| timed median | new edges / cycle (kept) | folded (accepted) | forest edges |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [s, r] : w.all) {
    if (r.timed_cycles == 0) continue;
    const sc::PhaseTimes& ph = r.phase_mean;
    md << "| " << r.name << " | " << r.timed_cycles << " | " << fmt(ph.placement * 1e-3) << " | "
       << fmt(ph.ground * 1e-3) << " | " << fmt(ph.insertion * 1e-3) << " | "
       << fmt(ph.eviction * 1e-3) << " | " << fmt(ph.validation * 1e-3) << " | " << fmt(ph.component_update * 1e-3)
       << " | " << fmt(ph.labelling * 1e-3) << " | " << fmt(r.timed_median_us * 1e-3) << " | "
       << fmt(r.edges_found_mean, 0) << " (" << fmt(r.edges_kept_mean, 0) << ") | " << fmt(r.edges_folded_mean, 0)
       << " (" << fmt(r.edges_accepted_mean, 0) << ") | " << fmt(r.forest_edges_mean, 0) << " |\n";
  }
}

// -------------------------------------------------------------------- main

std::vector<Scenario> all_scenarios() {
  std::vector<Scenario> out;
  for (const Sensor sensor : {Sensor::mid360, Sensor::avia}) {
    for (const ConfigEntry& c : kConfigs) {
      if (!(sensor == Sensor::mid360 ? c.mid360 : c.avia)) continue;
      for (const char* scene : kScenes) {
        for (std::size_t i = 0; i < std::size(kWindows); ++i) {
          if ((c.windows >> i) & 1u) out.push_back(Scenario{sensor, scene, &c, kWindows[i]});
        }
      }
    }
  }
  return out;
}

std::size_t parse_count(const std::string& flag, const std::string& value, std::size_t min) {
  char* end = nullptr;
  const unsigned long long v = std::strtoull(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || v < min) {
    throw std::invalid_argument(flag + " = '" + value + "' is invalid: expected an integer >= " + std::to_string(min));
  }
  return static_cast<std::size_t>(v);
}

Options parse(int argc, char** argv) {
  Options o;
  bool cycles_given = false, timed_given = false, peer_given = false, pcl_given = false, spin_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--cycles") {
      o.cycles = parse_count(a, value(), 1);
      cycles_given = true;
    } else if (a == "--peer-every") {
      o.peer_every = parse_count(a, value(), 1);
      peer_given = true;
    } else if (a == "--pcl-every") {
      o.pcl_every = parse_count(a, value(), 1);
      pcl_given = true;
    } else if (a == "--timed-cycles") {
      o.timed_cycles = parse_count(a, value(), 0);
      timed_given = true;
    } else if (a == "--filter") {
      o.filter = value();
    } else if (a == "--scenario") {
      o.scenario = value();
    } else if (a == "--out") {
      o.out = value();
    } else if (a == "--data") {
      o.data = value();
    } else if (a == "--smoke") {
      o.smoke = true;
    } else if (a == "--list") {
      o.list = true;
    } else if (a == "--trace-allocs") {
      o.trace_allocs = true;
    } else if (a == "--prune-witnesses") {
      g_prune_witnesses = static_cast<long>(parse_count(a, value(), 0));
    } else if (a == "--capacity") {
      g_capacity = static_cast<long>(parse_count(a, value(), 1));
      if (g_capacity > 255) throw std::invalid_argument("--capacity: expected 1 to 255 points per cell");
    } else if (a == "--reserve") {
      g_reserve = parse_count(a, value(), 0);
    } else if (a == "--packet") {
      o.packet = parse_count(a, value(), 0);
    } else if (a == "--spin-up") {
      o.spin_up_s = parse_count(a, value(), 0);
      spin_given = true;
    } else if (a == "--help" || a == "-h") {
      std::cout << "usage: bench_latency [--cycles N] [--peer-every K] [--pcl-every K] [--timed-cycles N]\n"
                   "                     [--filter TEXT] [--scenario NAME] [--out DIR] [--data DIR] [--smoke]\n"
                   "                     [--list] [--trace-allocs] [--spin-up SECONDS] [--prune-witnesses N]\n"
                   "                     [--capacity K] [--reserve POINTS] [--packet POINTS]\n";
      std::exit(0);
    } else {
      throw std::invalid_argument("unknown option '" + a + "' (try --help)");
    }
  }
  if (o.smoke) {  // a few cycles of one scenario, every peer on every cycle
    if (!cycles_given) o.cycles = 6;
    if (!timed_given) o.timed_cycles = 3;
    if (!peer_given) o.peer_every = 2;
    if (!pcl_given) o.pcl_every = 3;
    if (!spin_given) o.spin_up_s = 0;
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    std::vector<Scenario> scenarios;
    if (o.smoke && o.filter.empty()) {
      // Smoke: the Euclidean configuration (all three peers) at T_B = 0.1 s, and the objects preset moving
      // with poses (placement, ground, the peers on sensor-frame points) at T_B = 0.5 s.
      auto entry = [](const char* name) {
        return std::find_if(std::begin(kConfigs), std::end(kConfigs),
                            [name](const ConfigEntry& c) { return std::string(c.name) == name; });
      };
      scenarios.push_back(Scenario{Sensor::mid360, "office", entry("euclid"), 0.1});
      scenarios.push_back(Scenario{Sensor::avia, "office", entry("objects-moving"), 0.5});
    } else {
      for (const Scenario& s : all_scenarios()) {
        const std::string name = s.name();
        if (!o.scenario.empty() && name != o.scenario) continue;
        if (o.filter.empty() || name.find(o.filter) != std::string::npos) scenarios.push_back(s);
      }
    }
    if (o.list) {
      for (const Scenario& s : scenarios) std::cout << s.name() << '\n';
      return 0;
    }
    if (scenarios.empty()) {
      throw std::invalid_argument("--filter '" + o.filter + "' / --scenario '" + o.scenario +
                                  "' match no scenario (see --list)");
    }
    std::cout << "bench_latency: " << scenarios.size() << " scenario(s), " << o.cycles << " cycles each, peers every "
              << o.peer_every << ", PCL every " << o.pcl_every << " ("
              << (sc::bench::pcl_peer_available() ? "available" : "not built") << ")\n";
    Written w;
    for (const Scenario& s : scenarios) {
      ScenarioResult r = s.config->run(s, o);
      const LatencySummary ls = summarize(r.latency_us);
      std::cout << std::left << std::setw(30) << r.name << " grid " << r.grid.rows << "x" << r.grid.cols << "  median "
                << fmt(ls.median * 1e-3) << " ms  P99 " << fmt(ls.p99 * 1e-3) << " ms  P999 " << fmt(ls.p999 * 1e-3)
                << " ms  max " << fmt(ls.max * 1e-3) << " ms  batch " << fmt(r.batch.summary().median * 1e-3) << "  frame "
                << fmt(r.frame.summary().median * 1e-3) << "  pcl " << fmt(r.pcl.summary().median * 1e-3)
                << "  ARI " << fmt(mean(r.ari_engine), 3) << "  allocs " << r.steady_allocations << "  ("
                << fmt(r.wall_seconds, 0) << " s)  [" << r.sensor_source << "]" << std::endl;
      w.all.emplace_back(s, std::move(r));
    }
    write_outputs(o, w);
    std::cout << "results: " << fs::absolute(o.out).lexically_normal().string() << "/{summary.md,summary.json,cycles.csv}\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "bench_latency: " << e.what() << '\n';
    return 1;
  }
}
