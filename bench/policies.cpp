// SPDX-License-Identifier: MIT
// Microbenchmarks of the policies, one family at a time, each reporting
// points (or pairs) per second through SetItemsProcessed (items_per_second).
// Engine-level benchmarks (insertion per preset, retrieval) live in
// bench/engine.cpp; the end-to-end latency is bench/latency/.
//
// The policies measured are the lists of tests/support/policy_lists.hpp
// (Projections, SpatialIndexes, Linkages, Windows, Resolutions), each with its
// default Params: adding a policy to its list there adds its benchmark here
// (and its tests), with no line in this file. Benchmark names are
// BM_<family><PolicyType>, e.g. BM_Linkage<AngularLinkage>; a linkage with
// `link_many` also gets BM_LinkageMany<...> (the engine's one-call path). The
// motion policy PosedMotion is measured on its own (BM_PosedMotion, ns per point).
//
// Inputs are sensor ray patterns (no ray casting, so the set-up stays cheap
// for CTest's --benchmark_min_time=0.01 smoke run), built once and shared:
//   - realistic occupancy: 0.1 s of the analytic Mid-360 (20,000 rays) on the
//     grid the adaptive loop chooses for it (T_M = 2);
//   - pathological occupancy: the rays of 0.5 s of the Avia model (120,000)
//     that fall within 5 degrees of its axis, the dense centre of the
//     rosette, on the grid the adaptive loop chooses for the whole 0.5 s
//     window (what the engine uses at T_B = 0.5 s).
// Counters: `occupancy` is the mean number of points per occupied cell,
// `max_occupancy` the fullest cell's.
//
// Measure with (numbers: docs/benchmarks.md):
//   build/bench-run/bench/bench_policies --benchmark_min_time=0.5 --benchmark_repetitions=3
//       --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <streamclust/detail/mask.hpp>
#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/index/overwrite_grid.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/combinators.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/linkage/range_adaptive.hpp>
#include <streamclust/linkage/runtime_linkage.hpp>
#include <streamclust/motion/posed_motion.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/projection/cylindrical.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/resolution/adaptive.hpp>
#include <streamclust/sensors.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/avia_model.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/simulator.hpp>
#include <streamclust/types.hpp>
#include <streamclust/window/count_window.hpp>
#include <streamclust/window/time_window.hpp>

#include "../tests/support/policy_lists.hpp"
#include "../tests/support/type_name.hpp"
#include "../tests/support/type_product.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sc = streamclust;

namespace {

// ----------------------------------------------------------------- inputs

sc::SphericalProjection::Params mid360_fov() {
  sc::SphericalProjection::Params f;
  f.elevation_min_deg = sc::livox_mid360.projection_elevation_min_deg();
  f.elevation_max_deg = sc::livox_mid360.projection_elevation_max_deg();
  return f;
}

sc::SphericalProjection::Params avia_fov() {
  sc::SphericalProjection::Params f;
  f.azimuth_min_deg = sc::livox_avia.projection_azimuth_min_deg();
  f.azimuth_max_deg = sc::livox_avia.projection_azimuth_max_deg();
  f.elevation_min_deg = sc::livox_avia.projection_elevation_min_deg();
  f.elevation_max_deg = sc::livox_avia.projection_elevation_max_deg();
  return f;
}

/// The firings of `seconds` of a sensor model, projected at a 10 m range
/// (only the direction matters for the grid), accepted points only.
template <class Sensor>
std::vector<sc::Projected> project_rays(Sensor sensor, double seconds, const sc::SphericalProjection::Params& fov) {
  const sc::SphericalProjection projection(fov);
  std::vector<sc::Projected> out;
  for (;;) {
    const sc::sim::Ray r = sensor.next();
    if (r.time >= seconds) break;
    const sc::Projected q = projection.project(r.direction * 10.0f);
    if (q.accepted()) out.push_back(q);
  }
  return out;
}

/// A first window for the adaptive loop (calibrate's input).
struct Mid360FirstWindow {
  static const std::vector<sc::Projected>& coords() {
    static const auto c = project_rays(sc::sim::Mid360Model(sc::sim::Mid360Model::Params{}), 0.1, mid360_fov());
    return c;
  }
  static float fov_aspect() { return sc::SphericalProjection(mid360_fov()).fov_aspect(); }
};

struct AviaFirstWindow {
  static const std::vector<sc::Projected>& coords() {
    static const auto c = project_rays(sc::sim::AviaModel(sc::sim::AviaModel::Params{}), 0.1, avia_fov());
    return c;
  }
  static float fov_aspect() { return sc::SphericalProjection(avia_fov()).fov_aspect(); }
};

/// A sequence of cells (in firing order) on a grid, for the index benchmarks.
struct CellSequence {
  sc::GridShape grid;
  std::vector<sc::CellIndex> cells;
  double occupancy = 0.0;      ///< mean points per occupied cell
  std::uint32_t max_occupancy = 0;  ///< points in the fullest cell
};

CellSequence make_cells(const std::vector<sc::Projected>& calibration, float fov_aspect, bool wraps,
                        const std::vector<sc::Projected>& points) {
  sc::AdaptiveResolution resolution{sc::AdaptiveResolution::Params{}};
  const sc::GridSize size = resolution.calibrate(calibration, fov_aspect);
  CellSequence s;
  s.grid = sc::GridShape{size.rows, size.cols, wraps};
  std::vector<std::uint32_t> count(s.grid.cell_count(), 0);
  std::size_t occupied = 0;
  for (const sc::Projected& p : points) {
    const sc::CellIndex c = s.grid.cell_of(p.u, p.v);
    s.cells.push_back(c);
    if (count[c]++ == 0) ++occupied;
    s.max_occupancy = std::max(s.max_occupancy, count[c]);
  }
  s.occupancy = occupied == 0 ? 0.0 : static_cast<double>(points.size()) / static_cast<double>(occupied);
  return s;
}

/// Occupancy 0: the Mid-360's 0.1 s window on its own calibrated grid.
const CellSequence& realistic_cells() {
  static const CellSequence s = [] {
    const auto& c = Mid360FirstWindow::coords();
    return make_cells(c, Mid360FirstWindow::fov_aspect(), true, c);
  }();
  return s;
}

/// Occupancy 1: the Avia's dense centre (off-axis < 5 degrees) over 0.5 s,
/// on the grid calibrated from the whole 0.5 s window.
const CellSequence& pathological_cells() {
  static const CellSequence s = [] {
    const sc::SphericalProjection projection(avia_fov());
    sc::sim::AviaModel avia(sc::sim::AviaModel::Params{});
    std::vector<sc::Projected> all;
    std::vector<sc::Projected> centre;
    const float cos_5deg = std::cos(5.0f * 3.14159265f / 180.0f);
    for (;;) {
      const sc::sim::Ray r = avia.next();
      if (r.time >= 0.5) break;
      const sc::Projected q = projection.project(r.direction * 10.0f);
      if (!q.accepted()) continue;
      all.push_back(q);
      if (r.direction.x() >= cos_5deg * r.direction.norm()) centre.push_back(q);
    }
    return make_cells(all, projection.fov_aspect(), false, centre);
  }();
  return s;
}

const CellSequence& cells_for(std::int64_t occupancy) {
  return occupancy == 0 ? realistic_cells() : pathological_cells();
}

/// 0.1 s of the Mid-360 in the simulated office: realistic positions and
/// ranges (for projections and linkages).
const std::vector<sc::sim::SimPoint>& office_points() {
  static const std::vector<sc::sim::SimPoint> points = [] {
    sc::sim::Simulator<sc::sim::Mid360Model> simulator(sc::sim::Mid360Model(sc::sim::Mid360Model::Params{}),
                                                       sc::sim::office_scene(1),
                                                       sc::sim::Simulator<sc::sim::Mid360Model>::Params{});
    std::vector<sc::sim::SimPoint> out;
    while (simulator.time() < 0.1) out.push_back(simulator.next());
    return out;
  }();
  return points;
}

// -------------------------------------------------------------- projection

/// Projects every position of 0.1 s of a simulated Mid-360 stream.
template <class Projection>
void BM_Project(benchmark::State& state) {
  const auto& points = office_points();
  std::vector<Eigen::Vector3f> positions;
  positions.reserve(points.size());
  for (const auto& p : points) positions.emplace_back(p.x, p.y, p.z);
  const Projection projection{typename Projection::Params{}};
  for (auto _ : state) {
    float sum = 0.0f;
    for (const Eigen::Vector3f& x : positions) {
      const sc::Projected q = projection.project(x);
      sum += q.u + q.v;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(positions.size()));
}

// ------------------------------------------------------------ spatial index

/// Index operations. Arguments: op (0 insert, 1 remove, 2 mask query) and
/// occupancy (0 realistic Mid-360, 1 Avia dense centre); see the file comment.
/// - insert: all points in firing order into an empty index;
/// - remove: all points in insertion order (FIFO, as the engine evicts) from
///   a full index;
/// - mask query: for each point, visit every handle in its 5 x 5 mask in a
///   full index (what one insertion searches).
template <class Index>
void BM_Index(benchmark::State& state) {
  const std::int64_t op = state.range(0);
  const CellSequence& seq = cells_for(state.range(1));
  Index index{typename Index::Params{}};
  index.reset(seq.grid);
  const auto n = static_cast<sc::PointHandle>(seq.cells.size());
  auto fill = [&] {
    for (sc::PointHandle h = 0; h < n; ++h) benchmark::DoNotOptimize(index.insert(seq.cells[h], h));
  };
  std::size_t visited = 0;
  if (op == 2) fill();
  for (auto _ : state) {
    if (op == 0) {
      fill();
      state.PauseTiming();
      index.clear();
      state.ResumeTiming();
    } else if (op == 1) {
      state.PauseTiming();
      fill();
      state.ResumeTiming();
      for (sc::PointHandle h = 0; h < n; ++h) index.remove(seq.cells[h], h);
    } else {
      for (sc::PointHandle h = 0; h < n; ++h) {
        sc::detail::for_each_mask_cell(seq.grid, seq.cells[h], 2, [&](sc::CellIndex c) {
          index.for_each(c, [&](sc::PointHandle g) { visited += g; });
        });
      }
    }
  }
  benchmark::DoNotOptimize(visited);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(n));
  state.counters["occupancy"] = seq.occupancy;
  state.counters["max_occupancy"] = seq.max_occupancy;
  state.counters["cells"] = static_cast<double>(seq.grid.cell_count());
}

void index_cases(benchmark::internal::Benchmark* b) {
  b->ArgNames({"op", "occupancy"});
  b->ArgsProduct({{0, 1, 2}, {0, 1}});
  b->Unit(benchmark::kMicrosecond);
}

// ----------------------------------------------------------------- linkage

/// The linkage predicate over the pairs an insertion evaluates: each point
/// of 0.1 s of the simulated Mid-360 office stream against the 16 points
/// fired before it (neighbours on the same laser's recent sweep and the
/// adjacent lasers), both links and rejections.
template <class Linkage>
void BM_Linkage(benchmark::State& state) {
  const auto& points = office_points();
  std::vector<sc::Sample> samples;
  samples.reserve(points.size());
  for (const auto& p : points) {
    const Eigen::Vector3f pos(p.x, p.y, p.z);
    samples.push_back(sc::make_sample(pos, pos.norm(), p.intensity, p.t));
  }
  constexpr std::size_t kBack = 16;
  const Linkage linkage{typename Linkage::Params{}};
  std::size_t linked = 0;
  for (auto _ : state) {
    for (std::size_t i = kBack; i < samples.size(); ++i) {
      for (std::size_t j = i - kBack; j < i; ++j) linked += linkage(samples[i], samples[j]) ? 1u : 0u;
    }
  }
  benchmark::DoNotOptimize(linked);
  const auto pairs = static_cast<std::int64_t>((samples.size() - kBack) * kBack);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * pairs);
  state.counters["linked_share"] =
      static_cast<double>(linked) / (static_cast<double>(pairs) * static_cast<double>(state.iterations()));
}

/// The same pairs through the engine's path, for a linkage with `link_many`:
/// each point's payload against the payloads of the 16 points fired before
/// it, read from a payload ring through a slot list, in one call per point.
template <class Linkage>
void BM_LinkageMany(benchmark::State& state) {
  using Payload = sc::linkage_payload_t<Linkage>;
  const auto& points = office_points();
  std::vector<Payload> ring;
  ring.reserve(points.size());
  for (const auto& p : points) {
    const Eigen::Vector3f pos(p.x, p.y, p.z);
    ring.push_back(Linkage::make_payload(sc::make_sample(pos, pos.norm(), p.intensity, p.t)));
  }
  constexpr std::size_t kBack = 16;
  const Linkage linkage{typename Linkage::Params{}};
  std::uint32_t slots[kBack];
  std::uint8_t linked[kBack];
  std::size_t total = 0;
  for (auto _ : state) {
    for (std::size_t i = kBack; i < ring.size(); ++i) {
      for (std::size_t k = 0; k < kBack; ++k) slots[k] = static_cast<std::uint32_t>(i - kBack + k);
      linkage.link_many(ring[i], ring.data(), slots, kBack, linked);
      for (std::size_t k = 0; k < kBack; ++k) total += linked[k];
    }
  }
  benchmark::DoNotOptimize(total);
  const auto pairs = static_cast<std::int64_t>((ring.size() - kBack) * kBack);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * pairs);
  state.counters["linked_share"] =
      static_cast<double>(total) / (static_cast<double>(pairs) * static_cast<double>(state.iterations()));
}

// ------------------------------------------------------------------ window

/// Window bookkeeping as the engine does it: before each push, the oldest
/// points are popped while `expired(oldest, newest, size)` holds. One second
/// of a 200 kHz stream (timestamps every 5 us) through a FIFO of times.
template <class Window>
void BM_Window(benchmark::State& state) {
  constexpr std::size_t kPoints = 200000;
  const Window window{typename Window::Params{}};
  std::vector<double> fifo(kPoints);
  std::size_t evicted = 0;
  for (auto _ : state) {
    std::size_t oldest = 0;
    for (std::size_t i = 0; i < kPoints; ++i) {
      const double t = static_cast<double>(i) * 5e-6;
      while (oldest < i && window.expired(fifo[oldest], t, i - oldest + 1)) ++oldest;
      fifo[i] = t;
    }
    evicted += oldest;
  }
  benchmark::DoNotOptimize(evicted);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(kPoints));
}

// -------------------------------------------------------------- resolution

/// One calibration (the whole adaptive control loop) on a sensor's first
/// 0.1 s window; items are the window's points. Counters: the grid chosen.
template <class Resolution, class FirstWindow>
void BM_Calibrate(benchmark::State& state) {
  const auto& coords = FirstWindow::coords();
  const float aspect = FirstWindow::fov_aspect();
  sc::GridSize grid{};
  for (auto _ : state) {
    Resolution resolution{typename Resolution::Params{}};
    grid = resolution.calibrate(coords, aspect);
    benchmark::DoNotOptimize(grid);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(coords.size()));
  state.counters["rows"] = grid.rows;
  state.counters["cols"] = grid.cols;
}

// ------------------------------------------------------------------ motion

/// PosedMotion::place over one second of a 200 kHz stream (the positions of
/// the 0.1 s office stream, repeated, at times every 5 us) on a 100 Hz
/// trajectory driving at 10 m/s and yawing at 1 rad/s, the sensor pitched
/// 15 degrees on the vehicle. Argument: 0 a fixed mount (no trajectory),
/// 1 the trajectory, 2 the same pose per point from PoseTrajectory::at (a
/// slerp per point, double; what the per-segment cache saves).
void BM_PosedMotion(benchmark::State& state) {
  const auto& points = office_points();
  std::vector<sc::StampedPose> poses;
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.01 * i;
    sc::Pose pose = sc::mount_from_roll_pitch_yaw_deg(0.0, 0.0, t * 57.29577951308232);
    pose.translation = Eigen::Vector3d(10.0 * t, 0.5 * t * t, 0.0);
    poses.push_back(sc::StampedPose{1700000000.0 + t, pose});
  }
  sc::PosedMotion::Params params;
  params.mount = sc::mount_from_roll_pitch_yaw_deg(0.0, 15.0, 0.0);
  if (state.range(0) != 0) params.trajectory = std::make_shared<const sc::PoseTrajectory>(poses);
  constexpr std::size_t kPoints = 200000;
  std::vector<Eigen::Vector3f> positions(kPoints);
  std::vector<double> times(kPoints);
  for (std::size_t i = 0; i < kPoints; ++i) {
    const auto& p = points[i % points.size()];
    positions[i] = Eigen::Vector3f(p.x, p.y, p.z);
    times[i] = 1700000000.0 + static_cast<double>(i) * 5e-6;
  }
  float sum = 0.0f;
  for (auto _ : state) {
    sc::PosedMotion motion(params);  // a fresh cursor: the stream starts at the trajectory's start
    if (state.range(0) == 2) {
      sc::PoseTrajectory::Cursor cursor;
      for (std::size_t i = 0; i < kPoints; ++i) {
        const sc::Pose pose = *params.trajectory->at(times[i], cursor) * params.mount;
        sum += static_cast<float>((pose * positions[i].cast<double>()).x());
      }
    } else {
      sc::PlacedPoint placed;
      for (std::size_t i = 0; i < kPoints; ++i) {
        benchmark::DoNotOptimize(motion.place(positions[i], times[i], placed));
        sum += placed.world.x() + placed.ray.y();
      }
    }
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(kPoints));
}
BENCHMARK(BM_PosedMotion)->ArgName("trajectory")->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

/// Registers one benchmark per policy of each list (support/policy_lists.hpp).
bool register_policy_benchmarks() {
  namespace st = sc::test;
  // "BM_<family><Policy>", e.g. BM_Linkage<AngularLinkage>
  const auto name = [](const char* family, auto tag) {
    return std::string(family) + "<" + st::type_name<typename decltype(tag)::type>() + ">";
  };
  st::for_each_type<st::Projections>([&](auto tag) {
    benchmark::RegisterBenchmark(name("BM_Project", tag).c_str(), BM_Project<typename decltype(tag)::type>);
  });
  st::for_each_type<st::SpatialIndexes>([&](auto tag) {
    benchmark::RegisterBenchmark(name("BM_Index", tag).c_str(), BM_Index<typename decltype(tag)::type>)
        ->Apply(index_cases);
  });
  st::for_each_type<st::Linkages>([&](auto tag) {
    using L = typename decltype(tag)::type;
    benchmark::RegisterBenchmark(name("BM_Linkage", tag).c_str(), BM_Linkage<L>);
    if constexpr (sc::has_linkage_link_many_v<L>) {
      benchmark::RegisterBenchmark(name("BM_LinkageMany", tag).c_str(), BM_LinkageMany<L>);
    }
  });
  st::for_each_type<st::Windows>([&](auto tag) {
    benchmark::RegisterBenchmark(name("BM_Window", tag).c_str(), BM_Window<typename decltype(tag)::type>);
  });
  st::for_each_type<st::Resolutions>([&](auto tag) {
    using R = typename decltype(tag)::type;
    benchmark::RegisterBenchmark((name("BM_Calibrate", tag) + "/Mid360").c_str(), BM_Calibrate<R, Mid360FirstWindow>)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((name("BM_Calibrate", tag) + "/Avia").c_str(), BM_Calibrate<R, AviaFirstWindow>)
        ->Unit(benchmark::kMillisecond);
  });
  return true;
}

[[maybe_unused]] const bool registered = register_policy_benchmarks();

}  // namespace

BENCHMARK_MAIN();
