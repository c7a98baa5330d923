// SPDX-License-Identifier: MIT
// bench_soak: ten minutes of a simulated Livox Mid-360 in an office, as
// fast as it goes, through the engines `streamclust cluster` runs for
// `--preset carc` (its default) and `--preset objects-mid360`
// (cli_presets.hpp), with a retrieval every 50 ms of stream time (20 Hz).
// The objects preset gets the simulated sensor's mount and height
// (`--mount 0,0,0 --sensor-height 1`); --estimate-setup leaves them to the
// tool's first-window estimate instead.
//
// The stream is simulated slice by slice (50 ms, about 10,000 points) and
// never held whole; the engine is reserved up front for the sensor's rate x
// T_B plus 5 %. A cycle is a driver's work for one slice: insert_batch in
// 96-point packets (a Livox packet), advance_to the slice's end, retrieve;
// its latency is the wall time of that work (steady_clock), the simulation
// of the slice not included. Every second of stream time the soak samples
// the resident set (/proc/self/status: VmRSS, anonymous and file-backed),
// the engine's heap capacities, the machine's load, the window, the
// second's 20 cycle latencies, the engine's heap allocations
// (bench/latency/alloc_counter: a counting global operator new, attributing
// only the calls made inside the engine), the engine's work (edges found:
// the same on every run of the stream) and two probes of the host, fixed
// CPU work and a fixed walk through 16 MiB of memory (proc_stats.hpp),
// timed outside the cycles: a latency that moves with them is the host's.
//
// Targets (soak_verdict.hpp): RSS growth after the first window under 1 %;
// the last minute's P99 at most 1.2 x the first minute's; no engine
// allocation after the warm-up (default 10 s). Each preset runs in its own
// process, so one preset's heap does not shape the other's resident set.
//
// Output in --out-dir: soak_<preset>.csv (one row per second) and
// soak_<preset>_cycles.csv (one row per cycle); bench/soak/plot_soak.py
// draws them. Usage: bench_soak --help. docs/performance.md#soak has the
// record and the command that reproduces it.

#include "../latency/alloc_counter.hpp"
#include "cli_presets.hpp"
#include "mid360_source.hpp"
#include "proc_stats.hpp"
#include "soak_options.hpp"
#include "soak_series.hpp"
#include "soak_verdict.hpp"

#include <streamclust/percentiles.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/simulator.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <execinfo.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace sc = streamclust;
namespace sim = streamclust::sim;
using sc::bench::SoakOptions;

namespace {

constexpr double kCyclePeriod = 0.05;         // 20 Hz retrievals [s]
constexpr std::size_t kCyclesPerSecond = 20;  // of stream time
constexpr std::size_t kPacket = 96;           // points per insert_batch (a Livox UDP packet)
constexpr double kReserveMargin = 0.05;       // reserve rate x T_B x (1 + margin) + 1 points

enum ExitCode : int { kPass = 0, kMissed = 1, kUsage = 2, kError = 3 };

using Clock = std::chrono::steady_clock;

/// This thread's CPU time [us].
double thread_cpu_us() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) * 1e-3;
}

/// The configuration's name as cli_presets.hpp's table spells it.
template <class Config>
const char* config_name() {
  return std::is_same_v<Config, sc::bench::CarcCliConfig>
             ? "CliConfig<SphericalProjection, BucketGrid, AngularLinkage, TimeWindow> (spanning forest)"
             : "CliConfig<SphericalProjection, CappedGrid, RangeAdaptiveLinkage, TimeWindow> (spanning forest)";
}

/// Sensor-frame points of the stream's first `window` seconds, from a
/// simulator of its own (the same stream): what the tool reads for its
/// first-window estimate.
std::vector<Eigen::Vector3f> first_window(const SoakOptions& o, const sim::Scene& scene,
                                          const sim::Simulator<sc::bench::Mid360Source>::Params& params,
                                          double window) {
  sim::Simulator<sc::bench::Mid360Source> simulator(sc::bench::Mid360Source(o.livox_data), scene, params);
  std::vector<Eigen::Vector3f> points;
  const sim::SimPoint first = simulator.next();
  for (sim::SimPoint p = first; p.t - first.t < window; p = simulator.next()) points.emplace_back(p.x, p.y, p.z);
  return points;
}

/// Soaks one preset; returns its exit code.
template <class Config>
int soak_preset(const std::string& preset, const SoakOptions& o) {
  sc::cli::ClusterOptions cli = sc::bench::cli_preset_options(preset);
  sc::bench::require_cli_config<Config>(cli);
  const double window = cli.window_seconds;

  const sim::Scene scene = sim::office_scene(1);
  const sim::Simulator<sc::bench::Mid360Source>::Params sim_params{};  // at rest, level, 1 m above the floor, seed 1
  if (cli.ground && !o.estimate_setup) {  // --mount 0,0,0 --sensor-height 1: the simulated sensor's
    cli.mount_deg = std::array<double, 3>{0.0, 0.0, 0.0};
    cli.sensor_height = sim_params.start_position.z();
  }
  {
    // The tool reads the first window only to estimate what is not given.
    const bool estimates = cli.ground && (!sc::cli::has_motion_options(cli) || !cli.sensor_height);
    const std::vector<Eigen::Vector3f> first =
        estimates ? first_window(o, scene, sim_params, window) : std::vector<Eigen::Vector3f>{};
    sc::bench::resolve_cli_setup(cli, first);
  }
  const sc::ClustererParams<Config> params = sc::cli::make_params<Config>(cli);

  sc::bench::Mid360Source sensor(o.livox_data);
  const std::string sensor_description = sensor.description();
  const double rate = sensor.point_rate();
  sim::Simulator<sc::bench::Mid360Source> simulator(std::move(sensor), scene, sim_params);

  const auto reserve_points = static_cast<std::size_t>(std::ceil(rate * window * (1.0 + kReserveMargin))) + 1;
  std::optional<sc::StreamClusterer<Config>> engine;
  {
    sc::bench::AllocScope scope;
    engine.emplace(params);
    engine->reserve(reserve_points);
  }

  const auto cycles = static_cast<std::size_t>(std::llround(o.seconds / kCyclePeriod));
  sc::bench::SoakSeries series(cycles, cycles / kCyclesPerSecond, kCyclesPerSecond);
  std::vector<sim::SimPoint> slice(static_cast<std::size_t>(2.0 * rate * kCyclePeriod) + 4096);  // pages touched now
  slice.clear();

  std::printf("== soak: streamclust cluster --preset %s\n", preset.c_str());
  std::printf("  engine       %s\n", config_name<Config>());
  if (cli.linkage == "angular") {
    std::printf("               theta %.0f deg, w %d, T_M %.0f, T_B %.2f s\n",
                static_cast<double>(cli.params.get<sc::AngularLinkage>().theta_deg),
                cli.mask, static_cast<double>(cli.max_multiplicity), window);
  } else {
    std::printf(
        "               range-adaptive %.2f m + %.2f x range, K %u, w %d, T_M %.0f, T_B %.2f s, "
        "ground and ceiling out\n",
        static_cast<double>(cli.params.get<sc::RangeAdaptiveLinkage>().min_distance),
        static_cast<double>(cli.params.get<sc::RangeAdaptiveLinkage>().range_factor),
        cli.params.get<sc::CappedGrid>().capacity, cli.mask,
        static_cast<double>(cli.max_multiplicity), window);
  }
  if (cli.setup && cli.setup->estimate) {
    const auto& e = *cli.setup->estimate;
    std::printf(
        "  setup        the tool's first-window estimate: roll %.2f deg, pitch %.2f deg, "
        "sensor %.3f m above the ground (simulated: level, %.1f m)\n",
        e.roll_deg, e.pitch_deg, e.height, static_cast<double>(sim_params.start_position.z()));
  } else if (cli.ground && cli.sensor_height) {
    std::printf("  setup        --mount 0,0,0 --sensor-height %.1f (the simulated sensor: level, at rest)\n",
                static_cast<double>(*cli.sensor_height));
  } else if (cli.ground) {
    std::printf("  setup        no ground in the first window: a level sensor, height unknown (as the tool)\n");
  }
  std::printf("  stream       %s, %.0f kHz; office scene, seed 1; %.0f s, retrieval every %.0f ms, packets of %zu\n",
              sensor_description.c_str(), rate / 1000.0, o.seconds, kCyclePeriod * 1000.0, kPacket);
  std::printf("  reserve      %zu points (rate x T_B + %.0f %%)\n", reserve_points, 100.0 * kReserveMargin);
  std::fflush(stdout);

  if (o.trace_allocs) {
    // glibc's first backtrace() loads libgcc_s: about 0.3 MiB of file-backed
    // pages that would show as RSS growth when the first steady allocation
    // is traced. Load it before the baseline.
    void* frame[1];
    backtrace(frame, 1);
  }
  bool tracing = false;
  std::uint64_t offered = 0;
  double engine_s = 0.0;
  sc::bench::MemoryProbe memory_probe;  // built before the clock starts
  const auto start = Clock::now();
  for (std::size_t k = 1; k <= cycles; ++k) {
    const double cycle_end = static_cast<double>(k) * kCyclePeriod;
    slice.clear();
    while (simulator.time() < cycle_end) slice.push_back(simulator.next());
    offered += slice.size();
    if (o.trace_allocs && !tracing && cycle_end > o.warmup + 1e-9) {
      sc::bench::set_alloc_tracing(true);
      tracing = true;
    }

    const sc::bench::AllocCounters before = sc::bench::alloc_counters();
    const double c0 = thread_cpu_us();
    const auto t0 = Clock::now();
    bool retrieved = false;
    {
      sc::bench::AllocScope scope;
      for (std::size_t i = 0; i < slice.size(); i += kPacket) {
        const auto first = slice.begin() + static_cast<std::ptrdiff_t>(i);
        engine->insert_batch(first, first + static_cast<std::ptrdiff_t>(std::min(kPacket, slice.size() - i)));
      }
      engine->advance_to(cycle_end);
      if (!engine->calibrating()) {  // as the tool: no cycle while the first window is buffered for the grid
        engine->retrieve();
        retrieved = true;
      }
    }
    const auto t1 = Clock::now();
    const double cpu = thread_cpu_us() - c0;
    const sc::bench::AllocCounters after = sc::bench::alloc_counters();
    const double us = std::chrono::duration<double, std::micro>(t1 - t0).count();
    engine_s += us * 1e-6;
    const auto edges = static_cast<std::uint32_t>(retrieved ? engine->last_stats().edges_found : 0u);
    series.add_cycle({cycle_end, us, cpu, static_cast<std::uint32_t>(slice.size()),
                      static_cast<std::uint32_t>(after.allocations - before.allocations), edges, retrieved});

    if (k % kCyclesPerSecond != 0) continue;
    sc::bench::SecondSample s;
    s.second = static_cast<std::uint32_t>(k / kCyclesPerSecond);
    s.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
    const sc::bench::ResidentSet rss = sc::bench::resident_set();
    s.rss_kib = rss.total_kib;
    s.rss_anon_kib = rss.anon_kib;
    s.rss_file_kib = rss.file_kib;
    s.engine_kib = engine->memory_usage().total() / 1024u;
    s.load1 = sc::bench::load_average_1min();
    s.window_points = engine->size() + engine->structure_size();
    s.host_probe_us = sc::bench::host_probe_us();  // outside the timed cycles
    s.memory_probe_us = memory_probe.run_us();
    series.close_second(s);
    if (s.second % 60 == 0) {
      const sc::bench::SecondSample& last = *(series.seconds_end() - 1);
      std::printf(
          "  minute %3u   wall %6.1f s, RSS %.2f MiB, window %llu points, last second: median %.2f ms, max %.2f ms\n",
          s.second / 60, last.wall_s, static_cast<double>(last.rss_kib) / 1024.0,
          static_cast<unsigned long long>(last.window_points), last.median_ms, last.max_ms);
      std::fflush(stdout);
    }
  }
  const double wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  if (tracing) sc::bench::set_alloc_tracing(false);

  std::filesystem::create_directories(o.out_dir);
  const std::string stem = (std::filesystem::path(o.out_dir) / ("soak_" + preset)).string();
  series.write_seconds_csv(stem + ".csv");
  series.write_cycles_csv(stem + "_cycles.csv");

  std::vector<double> steady;
  for (const sc::bench::CycleRecord* c = series.cycles_begin(); c != series.cycles_end(); ++c) {
    if (c->retrieved && c->time > o.warmup + 1e-9) steady.push_back(c->latency_us / 1000.0);
  }
  const sc::LatencySummary all = sc::summarize(steady);
  double load_min = 1e9, load_max = -1e9;
  for (const sc::bench::SecondSample* s = series.seconds_begin(); s != series.seconds_end(); ++s) {
    load_min = std::min(load_min, s->load1);
    load_max = std::max(load_max, s->load1);
  }
  std::printf(
      "  ran          %llu points (%.1f kHz) in %.1f s of wall time (engine %.1f s: %.2f M points/s), grid %u x %u\n",
      static_cast<unsigned long long>(offered), static_cast<double>(offered) / o.seconds / 1000.0, wall_s, engine_s,
      static_cast<double>(offered) / engine_s / 1e6, engine->grid().rows, engine->grid().cols);
  std::printf(
      "  latency      %zu steady cycles: median %.2f ms, P99 %.2f ms, P99.9 %.2f ms, max %.2f ms; "
      "load average %.2f-%.2f on %ld cores\n",
      all.count, all.median, all.p99, all.p999, all.max, load_min, load_max, ::sysconf(_SC_NPROCESSORS_ONLN));
  const sc::bench::SoakTargets targets;
  const sc::bench::SoakVerdict verdict = sc::bench::judge_soak(series, o.seconds, window, o.warmup, targets);
  sc::bench::print_verdict(stdout, verdict, targets);
  std::printf("  files        %s.csv, %s_cycles.csv\n", stem.c_str(), stem.c_str());
  std::printf("  verdict      %s%s\n", verdict.pass() ? "every target met" : "a target MISSED",
              o.smoke ? " (smoke run: not enforced)" : "");
  std::fflush(stdout);
  if (tracing && verdict.steady_allocations > 0) {
    std::fprintf(stderr, "stacks of the steady-state engine allocations (addr2line -Cfie <binary> <offset>):\n");
    sc::bench::dump_alloc_traces(2);
  }
  return verdict.pass() || o.smoke ? kPass : kMissed;
}

int run_preset(const std::string& preset, const SoakOptions& o) {
  try {
    if (preset == "carc") return soak_preset<sc::bench::CarcCliConfig>(preset, o);
    return soak_preset<sc::bench::ObjectsCliConfig>(preset, o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_soak: %s: %s\n", preset.c_str(), e.what());
    return kError;
  }
}

/// Runs `preset` in a child process; returns its exit code.
int run_preset_in_child(const std::string& preset, const SoakOptions& o) {
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) return run_preset(preset, o);  // no fork: run here
  if (pid == 0) {
    const int code = run_preset(preset, o);
    std::fflush(nullptr);
    ::_exit(code);
  }
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return kError;
  return WEXITSTATUS(status);
}

}  // namespace

int main(int argc, char** argv) {
  SoakOptions o;
  try {
    const std::vector<std::string> args(argv + 1, argv + argc);
    for (const std::string& a : args) {
      if (a == "--help" || a == "-h") {
        std::fputs(sc::bench::kSoakUsage, stdout);
        return kPass;
      }
    }
    o = sc::bench::parse_soak_options(args);
  } catch (const sc::bench::SoakUsageError& e) {
    std::fprintf(stderr, "bench_soak: %s\n%s", e.what(), sc::bench::kSoakUsage);
    return kUsage;
  }
  if (o.livox_data.empty()) {
    const char* env = std::getenv("STREAMCLUST_LIVOX_DATA");
    o.livox_data = env != nullptr ? env : STREAMCLUST_SOURCE_DIR "/../shared/data/livox";
  }
  if (o.presets.size() == 1) return run_preset(o.presets.front(), o);
  int worst = kPass;
  for (const std::string& preset : o.presets) worst = std::max(worst, run_preset_in_child(preset, o));
  return worst;
}
