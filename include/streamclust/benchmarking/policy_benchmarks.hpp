// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Google Benchmark helpers for the policy families other than the linkage
/// (linkage_benchmarks.hpp): projection, spatial index, window, resolution.
/// Each `register_<family><P>(name, params)` registers P with its Params
/// under `name` and returns the benchmark; items_per_second counts points.
///
/// ```cpp
/// namespace bk = streamclust::benchmarking;
/// [[maybe_unused]] const bool registered = [] {
///   bk::register_index<MyIndex>("MyIndex");
///   bk::register_index<streamclust::BucketGrid>("BucketGrid");  // the reference, same inputs
///   return true;
/// }();
/// ```
///
/// Inputs are sensor ray patterns (no ray casting, so set-up stays cheap),
/// built once and shared:
///   - realistic occupancy: 0.1 s of the analytic Mid-360 (20,000 rays) on
///     the grid the adaptive loop chooses for it (T_M = 2);
///   - pathological occupancy: the rays of 0.5 s of the Avia model (120,000)
///     that fall within 5 degrees of its axis, the dense centre of the
///     rosette, on the grid the adaptive loop chooses for the whole 0.5 s
///     window (what the engine uses at T_B = 0.5 s);
/// and, for projections, 0.1 s of the simulated Mid-360 office stream.
/// Thread-safety: as linkage_benchmarks.hpp.

#include <streamclust/benchmarking/simulated_streams.hpp>
#include <streamclust/detail/mask.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/resolution/adaptive.hpp>
#include <streamclust/types.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace streamclust::benchmarking {

// ------------------------------------------------------------------ inputs

/// The firings of `seconds` of a sensor model, projected at a 10 m range
/// (only the direction matters for the grid), accepted points only.
template <class Model>
std::vector<Projected> project_rays(Model model, double seconds, const SphericalProjection::Params& fov) {
  const SphericalProjection projection(fov);
  std::vector<Projected> out;
  for (;;) {
    const sim::Ray r = model.next();
    if (r.time >= seconds) break;
    const Projected q = projection.project(r.direction * 10.0f);
    if (q.accepted()) out.push_back(q);
  }
  return out;
}

/// A sensor's first 0.1 s window as the adaptive loop sees it (calibrate's input).
struct FirstWindow {
  std::vector<Projected> coords;
  float fov_aspect = 1.0f;
};

/// The first window of sensor `s`, built once.
inline const FirstWindow& first_window(Sensor s) {
  static const FirstWindow mid360{
      project_rays(sim::Mid360Model(sim::Mid360Model::Params{}), 0.1, field_of_view(Sensor::mid360)),
      SphericalProjection(field_of_view(Sensor::mid360)).fov_aspect()};
  static const FirstWindow avia{project_rays(sim::AviaModel(sim::AviaModel::Params{}), 0.1, field_of_view(Sensor::avia)),
                                SphericalProjection(field_of_view(Sensor::avia)).fov_aspect()};
  return s == Sensor::mid360 ? mid360 : avia;
}

/// A sequence of cells (in firing order) on a grid, for the index benchmarks.
struct CellSequence {
  GridShape grid;
  std::vector<CellIndex> cells;
  double occupancy = 0.0;           ///< mean points per occupied cell
  std::uint32_t max_occupancy = 0;  ///< points in the fullest cell
};

/// The cells of `points` on the grid the adaptive loop calibrates on `calibration`.
inline CellSequence make_cells(const std::vector<Projected>& calibration, float fov_aspect, bool wraps,
                               const std::vector<Projected>& points) {
  AdaptiveResolution resolution{AdaptiveResolution::Params{}};
  const GridSize size = resolution.calibrate(calibration, fov_aspect);
  CellSequence s;
  s.grid = GridShape{size.rows, size.cols, wraps};
  std::vector<std::uint32_t> count(s.grid.cell_count(), 0);
  std::size_t occupied = 0;
  for (const Projected& p : points) {
    const CellIndex c = s.grid.cell_of(p.u, p.v);
    s.cells.push_back(c);
    if (count[c]++ == 0) ++occupied;
    s.max_occupancy = std::max(s.max_occupancy, count[c]);
  }
  s.occupancy = occupied == 0 ? 0.0 : static_cast<double>(points.size()) / static_cast<double>(occupied);
  return s;
}

/// Occupancy 0: the Mid-360's 0.1 s window on its own calibrated grid.
inline const CellSequence& realistic_cells() {
  static const CellSequence s = [] {
    const FirstWindow& w = first_window(Sensor::mid360);
    return make_cells(w.coords, w.fov_aspect, true, w.coords);
  }();
  return s;
}

/// Occupancy 1: the Avia's dense centre (off-axis < 5 degrees) over 0.5 s,
/// on the grid calibrated from the whole 0.5 s window.
inline const CellSequence& pathological_cells() {
  static const CellSequence s = [] {
    const SphericalProjection projection(field_of_view(Sensor::avia));
    sim::AviaModel avia(sim::AviaModel::Params{});
    std::vector<Projected> all;
    std::vector<Projected> centre;
    const float cos_5deg = std::cos(5.0f * 3.14159265f / 180.0f);
    for (;;) {
      const sim::Ray r = avia.next();
      if (r.time >= 0.5) break;
      const Projected q = projection.project(r.direction * 10.0f);
      if (!q.accepted()) continue;
      all.push_back(q);
      if (r.direction.x() >= cos_5deg * r.direction.norm()) centre.push_back(q);
    }
    return make_cells(all, projection.fov_aspect(), false, centre);
  }();
  return s;
}

// -------------------------------------------------------------- projection

/// Projects every position of 0.1 s of the simulated Mid-360 office stream.
template <class Projection>
void run_projection(benchmark::State& state, const typename Projection::Params& params) {
  const auto& points = simulated_points({Sensor::mid360, "office"}, 0.1);
  std::vector<Eigen::Vector3f> positions;
  positions.reserve(points.size());
  for (const auto& p : points) positions.emplace_back(p.x, p.y, p.z);
  const Projection projection{params};
  for (auto _ : state) {
    float sum = 0.0f;
    for (const Eigen::Vector3f& x : positions) {
      const Projected q = projection.project(x);
      sum += q.u + q.v;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(positions.size()));
}

template <class Projection>
benchmark::internal::Benchmark* register_projection(const std::string& name,
                                                    const typename Projection::Params& params = {}) {
  return benchmark::RegisterBenchmark(name.c_str(),
                                      [params](benchmark::State& state) { run_projection<Projection>(state, params); });
}

// ------------------------------------------------------------ spatial index

/// Index operations. Arguments: op (0 insert, 1 remove, 2 mask query) and
/// occupancy (0 realistic Mid-360, 1 Avia dense centre); see the file comment.
/// - insert: all points in firing order into an empty index;
/// - remove: all points in insertion order (FIFO, as the engine evicts) from
///   a full index;
/// - mask query: for each point, visit every handle in its 5 x 5 mask in a
///   full index (what one insertion searches).
/// Counters: `occupancy` the mean points per occupied cell, `max_occupancy`
/// the fullest cell's, `cells` the grid's.
template <class Index>
void run_index(benchmark::State& state, const typename Index::Params& params) {
  const std::int64_t op = state.range(0);
  const CellSequence& seq = state.range(1) == 0 ? realistic_cells() : pathological_cells();
  Index index{params};
  index.reset(seq.grid);
  const auto n = static_cast<PointHandle>(seq.cells.size());
  auto fill = [&] {
    for (PointHandle h = 0; h < n; ++h) benchmark::DoNotOptimize(index.insert(seq.cells[h], h));
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
      for (PointHandle h = 0; h < n; ++h) index.remove(seq.cells[h], h);
    } else {
      for (PointHandle h = 0; h < n; ++h) {
        streamclust::detail::for_each_mask_cell(seq.grid, seq.cells[h], 2, [&](CellIndex c) {
          index.for_each(c, [&](PointHandle g) { visited += g; });
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

/// Registers the six cases (op x occupancy) of run_index, in microseconds.
template <class Index>
benchmark::internal::Benchmark* register_index(const std::string& name, const typename Index::Params& params = {}) {
  return benchmark::RegisterBenchmark(name.c_str(),
                                      [params](benchmark::State& state) { run_index<Index>(state, params); })
      ->ArgNames({"op", "occupancy"})
      ->ArgsProduct({{0, 1, 2}, {0, 1}})
      ->Unit(benchmark::kMicrosecond);
}

// ------------------------------------------------------------------ window

/// Window bookkeeping as the engine does it: before each push, the oldest
/// points are popped while `expired(oldest, newest, size)` holds. One second
/// of a 200 kHz stream (timestamps every 5 us) through a FIFO of times.
template <class Window>
void run_window(benchmark::State& state, const typename Window::Params& params) {
  constexpr std::size_t kPoints = 200000;
  const Window window{params};
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

template <class Window>
benchmark::internal::Benchmark* register_window(const std::string& name, const typename Window::Params& params = {}) {
  return benchmark::RegisterBenchmark(name.c_str(),
                                      [params](benchmark::State& state) { run_window<Window>(state, params); });
}

// -------------------------------------------------------------- resolution

/// One calibration (the whole adaptive control loop) on a sensor's first
/// 0.1 s window; items are the window's points. Counters: the grid chosen.
template <class Resolution>
void run_calibrate(benchmark::State& state, const typename Resolution::Params& params, Sensor sensor) {
  const FirstWindow& w = first_window(sensor);
  GridSize grid{};
  for (auto _ : state) {
    Resolution resolution{params};
    grid = resolution.calibrate(w.coords, w.fov_aspect);
    benchmark::DoNotOptimize(grid);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(w.coords.size()));
  state.counters["rows"] = grid.rows;
  state.counters["cols"] = grid.cols;
}

/// Registers `<name>/Mid360` and `<name>/Avia`, in milliseconds.
template <class Resolution>
std::vector<benchmark::internal::Benchmark*> register_resolution(const std::string& name,
                                                                 const typename Resolution::Params& params = {}) {
  std::vector<benchmark::internal::Benchmark*> out;
  for (const Sensor s : {Sensor::mid360, Sensor::avia}) {
    out.push_back(benchmark::RegisterBenchmark((name + (s == Sensor::mid360 ? "/Mid360" : "/Avia")).c_str(),
                                               [params, s](benchmark::State& state) {
                                                 run_calibrate<Resolution>(state, params, s);
                                               })
                      ->Unit(benchmark::kMillisecond));
  }
  return out;
}

}  // namespace streamclust::benchmarking
