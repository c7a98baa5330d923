// SPDX-License-Identifier: MIT
// Example 0, the demo (README: `bash scripts/run.sh`): a simulated Livox
// Mid-360 scans an office with people walking; the objects preset (C-ARC
// with ground and ceiling removal) clusters the stream continuously and is
// scored against the simulator's ground truth.
//
// The scan simulator fires the Mid-360's scan pattern into the office scene
// (the real firing table when ../shared/data/livox is present, else the
// analytic model fitted to it). The engine is objects_mid360_params() with
// the sensor 1 m above the floor (ObjectsConfig: HeightMapGround takes
// ground and ceiling out as points arrive, the range-adaptive linkage, the
// spanning forest), a sliding window of T_B = 0.5 s and a retrieval every
// 50 ms of stream time (20 Hz). Points arrive in packets of 96, as from a
// Livox driver.
//
// A cycle is what a 20 Hz driver does: insert the 50 ms of points that
// arrived, then retrieve the clusters of the whole window; its latency is the
// wall time of both (the simulation is not timed). Each window is scored
// against the ground truth (streamclust::eval::object_metrics): the
// adjusted Rand index over object points, the strict objects correct (one
// cluster holds 80 % of the object and is 80 % the object), the object
// points kept out of the ground, and the ground's F1.
//
// Usage: example_00_livox_demo [--seconds S] [--png FILE] [--every N]
//                              [--livox-data DIR]
//   --seconds S       stream time to simulate (default 10)
//   --png FILE        bird's-eye picture of the last window (default streamclust_demo.png)
//   --every N         print every N-th cycle (default 10: two lines per second)
//   --livox-data DIR  folder with patterns/mid360_u16le.bin (default
//                     $STREAMCLUST_LIVOX_DATA, else ../shared/data/livox)

#include <streamclust/eval/object_metrics.hpp>
#include <streamclust/io/birds_eye.hpp>
#include <streamclust/io/png_writer.hpp>
#include <streamclust/sensors.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/sensors/table_replay.hpp>
#include <streamclust/sim/simulator.hpp>
#include <streamclust/streamclust.hpp>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <exception>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace sc = streamclust;
namespace sim = streamclust::sim;

namespace {

struct Options {
  double seconds = 10.0;
  std::string png = "streamclust_demo.png";
  std::size_t every = 10;
  std::string livox_data;
};

constexpr double kWindow = 0.5;          // T_B [s]
constexpr double kCyclePeriod = 0.05;    // 20 Hz [s]
constexpr std::size_t kPacket = 96;      // points per Livox UDP packet
constexpr std::size_t kMinObjectPoints = 10;  // objects with fewer points in a window are not rated

/// The points of the stream still needed (the window's), by stream index.
class StreamLog {
 public:
  void push(const sim::SimPoint& p) { points_.push_back(p); }
  const sim::SimPoint& at(std::uint64_t stream_index) const {
    return points_[static_cast<std::size_t>(stream_index - first_)];
  }
  /// Forgets the points before `stream_index`.
  void drop_before(std::uint64_t stream_index) {
    while (first_ < stream_index && !points_.empty()) {
      points_.pop_front();
      ++first_;
    }
  }

 private:
  std::deque<sim::SimPoint> points_;
  std::uint64_t first_ = 0;
};

/// Nearest-rank percentile (p in [0, 100]) of `v`; 0 when empty.
double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(v.size())));
  return v[std::min(v.size() - 1, rank == 0 ? 0 : rank - 1)];
}

/// Bird's-eye view of a window (io/birds_eye.hpp): one colour per cluster
/// with its box, structure-sized clusters dimmed, fragments grey, a metre
/// scale and the sensor's origin. Ground-truth free.
sc::io::RgbImage birds_eye(const sc::Clustering& result, const StreamLog& log) {
  std::vector<sc::io::Record> points;
  std::vector<std::int64_t> labels;
  points.reserve(result.points.size());
  labels.reserve(result.points.size());
  for (const sc::PointLabel& pl : result.points) {
    const sim::SimPoint& p = log.at(pl.stream_index);
    points.push_back(sc::io::Record{p.x, p.y, p.z, 0.0f, 0.0, -1});
    labels.push_back(static_cast<std::int64_t>(pl.label));
  }
  return sc::io::render_birds_eye(points, labels);
}

template <class Sensor>
int run(Sensor sensor, const std::string& sensor_label, const Options& o) {
  using Config = sc::ObjectsConfig;
  sc::ObjectsSetup setup;
  setup.sensor_height = 1.0f;  // [m] the simulator's default sensor position
  setup.window_seconds = kWindow;
  const sc::ClustererParams<Config> params = sc::objects_mid360_params(setup);
  sc::StreamClusterer<Config> engine(params);
  engine.reserve(static_cast<std::size_t>(sc::livox_mid360.point_rate_hz * kWindow) + 1);

  sim::Simulator<Sensor> simulator(std::move(sensor), sim::office_scene(1), typename sim::Simulator<Sensor>::Params{});

  std::printf("streamclust demo: a %s scans a simulated office (20 x 12 x 3 m, desks, cabinets, people walking)\n",
              sensor_label.c_str());
  std::printf("objects_mid360_params: ground and ceiling out as points arrive, range-adaptive linkage, w %d, T_M %.0f,\n"
              "the spanning-forest connectivity;\n",
              params.mask_size, static_cast<double>(params.resolution.max_multiplicity));
  std::printf("window T_B = %.1f s, a cycle every %.0f ms: insert the new points (packets of %zu), retrieve all clusters\n\n",
              kWindow, kCyclePeriod * 1000.0, kPacket);
  std::printf("%8s %11s %9s %9s %10s %7s %9s\n", "time[s]", "window pts", "clusters", ">=20 pts", "cycle[ms]", "ARI",
              "objects");

  StreamLog log;
  std::vector<sim::SimPoint> slice;
  std::vector<double> latency_ms, cpu_ms;  // steady cycles (after the first)
  double first_cycle_ms = -1.0;
  std::vector<std::int64_t> truth, predicted;
  std::vector<sc::SurfaceClass> truth_class;
  double ari_sum = 0.0, coverage_sum = 0.0, ground_f1_sum = 0.0;
  std::size_t objects_rated = 0, objects_correct = 0, windows_scored = 0;
  const sc::Clustering* last = nullptr;
  const auto cycles = static_cast<std::size_t>(std::llround(o.seconds / kCyclePeriod));

  for (std::size_t cycle = 1; cycle <= cycles; ++cycle) {
    const double cycle_end = static_cast<double>(cycle) * kCyclePeriod;
    slice.clear();
    while (simulator.time() < cycle_end) slice.push_back(simulator.next());
    for (const sim::SimPoint& p : slice) log.push(p);

    const std::clock_t c0 = std::clock();
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < slice.size(); i += kPacket) {
      const auto first = slice.begin() + static_cast<std::ptrdiff_t>(i);
      engine.insert_batch(first, first + static_cast<std::ptrdiff_t>(std::min(kPacket, slice.size() - i)));
    }
    if (engine.calibrating()) continue;  // the adaptive grid is chosen on the first full window
    const sc::Clustering& result = engine.retrieve();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = 1000.0 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    // The first cycle after calibration inserts the whole first window: reported apart.
    if (first_cycle_ms < 0.0) {
      first_cycle_ms = ms;
    } else {
      latency_ms.push_back(ms);
      cpu_ms.push_back(cpu);
    }
    last = &result;
    if (!result.points.empty() || !result.structure.empty()) {
      std::uint64_t oldest = result.points.empty() ? result.structure.front().stream_index : result.points.front().stream_index;
      if (!result.structure.empty()) oldest = std::min(oldest, result.structure.front().stream_index);
      log.drop_before(oldest);
    }

    // Quality against the ground truth: every window point, object or structure.
    truth.clear();
    truth_class.clear();
    predicted.clear();
    for (const sc::PointLabel& pl : result.points) {
      truth.push_back(log.at(pl.stream_index).instance);
      truth_class.push_back(log.at(pl.stream_index).surface);
      predicted.push_back(static_cast<std::int64_t>(pl.label));
    }
    for (const sc::StructurePoint& sp : result.structure) {
      truth.push_back(log.at(sp.stream_index).instance);
      truth_class.push_back(log.at(sp.stream_index).surface);
      predicted.push_back(sp.surface == sc::SurfaceClass::ceiling ? sc::eval::kClassedCeiling
                          : sp.surface == sc::SurfaceClass::wall  ? sc::eval::kClassedWall
                                                                  : sc::eval::kClassedGround);
    }
    sc::eval::MetricOptions metric;
    metric.min_points = kMinObjectPoints;
    const sc::eval::ObjectMetrics m = sc::eval::object_metrics(truth, truth_class, predicted, metric);
    const double ari = m.adjusted_rand_index;
    ari_sum += ari;
    coverage_sum += m.object_point_coverage;
    ground_f1_sum += m.ground.f1;
    objects_rated += m.objects.objects;
    objects_correct += m.objects.correct_objects;
    ++windows_scored;

    if (o.every > 0 && (windows_scored - 1) % o.every == 0) {
      std::size_t big = 0;
      for (const auto& c : result.components_with_at_least(20)) big += c.size > 0;
      std::printf("%8.2f %11zu %9zu %9zu %10.2f %7.3f %5zu/%-3zu\n", result.time,
                  result.points.size() + result.structure.size(), result.components.size(), big, ms, ari,
                  m.objects.correct_objects, m.objects.objects);
    }
  }
  if (last == nullptr || latency_ms.empty()) {
    std::fprintf(stderr, "demo: the stream ended before the first window (--seconds must exceed %.1f)\n", kWindow);
    return 1;
  }

  const sc::io::RgbImage image = birds_eye(*last, log);
  sc::io::write_png(o.png, image);
  std::error_code ec;
  const std::filesystem::path png_path = std::filesystem::absolute(o.png, ec);

  const auto& grid = engine.grid();
  const double p50 = percentile(latency_ms, 50.0);
  const double p99 = percentile(latency_ms, 99.0);
  const double worst = *std::max_element(latency_ms.begin(), latency_ms.end());
  std::printf("\nsummary\n");
  std::printf("  stream   %llu points in %.1f s (%.0f kHz), grid %u x %u chosen on the first window\n",
              static_cast<unsigned long long>(engine.offered()), o.seconds,
              static_cast<double>(engine.offered()) / o.seconds / 1000.0, grid.rows, grid.cols);
  std::printf("  latency  %zu cycles: median %.2f ms, P99 %.2f ms, max %.2f ms (P99 = %.0f %% of the %.0f ms period)\n",
              latency_ms.size(), p50, p99, worst, 100.0 * p99 / (kCyclePeriod * 1000.0), kCyclePeriod * 1000.0);
  const double cpu_p50 = percentile(cpu_ms, 50.0);
  std::printf("           CPU time of the same cycles: median %.2f ms, P99 %.2f ms%s\n", cpu_p50, percentile(cpu_ms, 99.0),
              p50 > 1.3 * cpu_p50 ? " (wall well above CPU: other processes share the cores)" : "");
  std::printf("           first cycle %.1f ms (after calibration: the whole first window inserted), not counted\n",
              first_cycle_ms);
  const double n = static_cast<double>(windows_scored);
  std::printf("  quality  against the simulator's ground truth, mean over %zu windows: ARI %.3f (object points),\n"
              "           strict objects correct %.1f %% (%.1f of %.1f per window), object points kept %.1f %%,\n"
              "           ground F1 %.3f (a level Mid-360 sees the floor only from 8 m: little ground indoors)\n",
              windows_scored, ari_sum / n,
              objects_rated == 0 ? 100.0 : 100.0 * static_cast<double>(objects_correct) / static_cast<double>(objects_rated),
              static_cast<double>(objects_correct) / n, static_cast<double>(objects_rated) / n, 100.0 * coverage_sum / n,
              ground_f1_sum / n);
  std::printf("  picture  %s (%zu x %zu px: bird's-eye view of the last window, one colour per cluster)\n",
              (ec ? o.png : png_path.string()).c_str(), image.width(), image.height());
  return 0;
}

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) return false;
    const std::string v = argv[++i];
    if (a == "--seconds") {
      o.seconds = std::atof(v.c_str());
      if (!(o.seconds > kWindow) || o.seconds > 3600.0) return false;
    } else if (a == "--png") {
      o.png = v;
    } else if (a == "--every") {
      o.every = static_cast<std::size_t>(std::atol(v.c_str()));
    } else if (a == "--livox-data") {
      o.livox_data = v;
    } else {
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse(argc, argv, o)) {
    std::fprintf(stderr,
                 "usage: %s [--seconds S > %.1f] [--png FILE] [--every N] [--livox-data DIR]\n", argv[0], kWindow);
    return 2;
  }
  if (o.livox_data.empty()) {
    const char* env = std::getenv("STREAMCLUST_LIVOX_DATA");
    o.livox_data = env != nullptr ? env : "../shared/data/livox";
  }
  const std::string rate = std::to_string(static_cast<int>(sc::livox_mid360.point_rate_hz / 1000.0)) + " kHz";
  try {
    const std::filesystem::path table = std::filesystem::path(o.livox_data) / "patterns" / "mid360_u16le.bin";
    std::error_code ec;
    if (std::filesystem::is_regular_file(table, ec)) {
      return run(sim::TableReplay::mid360(table.string()), "Livox Mid-360 (its real firing table, " + rate + ")", o);
    }
    return run(sim::Mid360Model(), "Livox Mid-360 (analytic scan model, " + rate + ")", o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "demo: %s\n", e.what());
    return 1;
  }
}
