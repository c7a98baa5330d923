// SPDX-License-Identifier: MIT
// Heap allocations of the engine in steady state (docs/performance.md, target 6): once a
// window of the same size has been through it, the capped-grid presets
// allocate nothing, however crowded the masks become (the capped grid bounds
// the neighbour search: w^2 x K candidates, reserved when the grid is set).
//
// This file replaces the global operator new/delete of the test program with
// a counting version (malloc-based; it counts only inside `CountingScope`).

#include <doctest/doctest.h>

#include <streamclust/streamclust.hpp>

#include "support/streams.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace {
bool g_counting = false;         // single-threaded tests: no atomics needed
std::uint64_t g_allocations = 0;  // operator new calls while counting

void* counted_allocation(std::size_t n) {
  if (g_counting) ++g_allocations;
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t n) { return counted_allocation(n); }
void* operator new[](std::size_t n) { return counted_allocation(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  if (g_counting) ++g_allocations;
  return std::malloc(n == 0 ? 1 : n);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace sc = streamclust;

namespace {

/// Counts the operator new calls made while it lives.
class CountingScope {
 public:
  CountingScope() : start_(g_allocations) { g_counting = true; }
  ~CountingScope() { g_counting = false; }
  CountingScope(const CountingScope&) = delete;
  CountingScope& operator=(const CountingScope&) = delete;
  std::uint64_t allocations() const { return g_allocations - start_; }

 private:
  std::uint64_t start_;
};

/// Capped grid, fixed 32 x 256 grid, a count window, Euclidean linkage: the
/// stream below decides exactly how crowded each mask is.
template <class Connectivity>
struct CappedCountConfig : sc::CArcFixedConfig {
  using spatial_index = sc::CappedGrid;
  using linkage = sc::EuclideanLinkage;
  using window = sc::CountWindow;
  using connectivity = Connectivity;
};

constexpr std::uint32_t kGridRows = 32;   // 5.625 degrees of elevation per row
constexpr std::uint32_t kGridCols = 256;  // 1.40625 degrees of azimuth per column
constexpr std::size_t kWindow = 256;  // [points]
constexpr std::size_t kPerCycle = 64;  // points between retrievals

template <class Config>
sc::ClustererParams<Config> params() {
  sc::ClustererParams<Config> p;
  p.resolution = {kGridRows, kGridCols};
  p.window.capacity = kWindow;
  p.spatial_index.capacity = 4;
  p.linkage.max_distance = 0.05f;  // [m]: below the 0.12 m between neighbouring cells at 5 m
  p.mask_size = 5;
  return p;
}

/// The centre of cell (row, col) [deg].
float azimuth_of(std::uint32_t col) { return -180.0f + (static_cast<float>(col) + 0.5f) * 1.40625f; }
float elevation_of(std::uint32_t row) { return -90.0f + (static_cast<float>(row) + 0.5f) * 5.625f; }

/// Point i of the sparse pattern: 256 cells four rows and four columns
/// apart, one point each per window: every mask holds at most the point itself.
sc::Point sparse_point(std::size_t i, double t) {
  const std::size_t k = i % 256;
  const auto row = static_cast<std::uint32_t>(8 + 4 * (k / 64));
  const auto col = static_cast<std::uint32_t>(4 * (k % 64));
  return sc::test::point_at(azimuth_of(col), elevation_of(row), 5.0f, t);
}

/// Point i of the crowded pattern: a 5 x 5 block of cells, every cell full
/// (K = 4), so the centre cell's mask lists 100 candidates. Ranges step by
/// 1 m per visit of a cell and repeat only after 16 visits (400 points, more
/// than the window): no two points link, every point stays a singleton, and
/// the window's components, edges and result keep their sizes.
sc::Point crowded_point(std::size_t i, double t) {
  const std::size_t cell = i % 25;
  const auto row = static_cast<std::uint32_t>(14 + cell / 5);
  const auto col = static_cast<std::uint32_t>(100 + cell % 5);
  const float range = 5.0f + static_cast<float>((i / 25) % 16);
  return sc::test::point_at(azimuth_of(col), elevation_of(row), range, t);
}

template <class Engine, class Pattern>
void run_cycles(Engine& engine, Pattern pattern, std::size_t cycles, std::size_t& i, double& t) {
  for (std::size_t c = 0; c < cycles; ++c) {
    for (std::size_t k = 0; k < kPerCycle; ++k, ++i) {
      t += 1e-5;
      engine.insert(pattern(i, t));
    }
    engine.retrieve();
  }
}

template <class Config>
void check_no_steady_allocations() {
  sc::StreamClusterer<Config> engine(params<Config>());
  std::size_t i = 0;
  double t = 0.0;
  run_cycles(engine, sparse_point, 40, i, t);  // warm-up: every structure at its window size
  REQUIRE(engine.size() == kWindow);
  REQUIRE(engine.last_result().components.size() == kWindow);  // the sparse points never link

  CountingScope scope;
  run_cycles(engine, sparse_point, 20, i, t);
  const std::uint64_t sparse = scope.allocations();
  run_cycles(engine, crowded_point, 40, i, t);  // the masks fill up: 100 candidates
  const std::uint64_t crowded = scope.allocations() - sparse;
  CHECK(sparse == 0);
  CHECK(crowded == 0);
  CHECK(engine.size() == kWindow);
  CHECK(engine.last_result().components.size() == kWindow);  // still singletons: nothing else grew
}

/// The same grid with the presets' time window: the window's size follows
/// the point rate.
template <class Connectivity>
struct CappedTimeConfig : sc::CArcFixedConfig {
  using spatial_index = sc::CappedGrid;
  using linkage = sc::EuclideanLinkage;
  using connectivity = Connectivity;
};

/// Point i of the blocks pattern: a 5 x 5 block of cells, all at 5 m, so
/// the points of a cell link (distance 0) and those of neighbouring cells
/// do not (0.12 m apart): 25 components whatever the rate.
sc::Point block_point(std::size_t i, double t) {
  const std::size_t cell = i % 25;
  return sc::test::point_at(azimuth_of(static_cast<std::uint32_t>(100 + cell % 5)),
                            elevation_of(static_cast<std::uint32_t>(14 + cell / 5)), 5.0f, t);
}

/// Inserts block points for `seconds` [s] at `rate` [points/s], retrieving
/// every 20 ms when `retrieve` is set.
template <class Engine>
void run_blocks(Engine& engine, double rate, double seconds, bool retrieve, std::size_t& i, double& t) {
  const double end = t + seconds;
  double next_retrieval = t + 0.02;
  while (t < end) {
    t += 1.0 / rate;
    engine.insert(block_point(i++, t));
    if (retrieve && t >= next_retrieval) {
      engine.retrieve();
      next_retrieval += 0.02;
    }
  }
}

/// The fixed grid with a 0.1 s time window, K handles per cell and the
/// Euclidean linkage at 0.05 m.
template <class Config>
sc::ClustererParams<Config> time_params(std::uint32_t capacity) {
  sc::ClustererParams<Config> p;
  p.resolution = {kGridRows, kGridCols};
  p.window.duration = 0.1;  // [s]
  p.spatial_index.capacity = capacity;
  p.linkage.max_distance = 0.05f;  // [m]
  p.mask_size = 5;
  return p;
}

/// A window that grows back to a size its point rings have held already
/// (a sensor whose rate dips and recovers) allocates nothing: the per-point
/// vectors of the retrieval (labels, union-find) follow the rings'
/// capacity, not the largest window retrieved so far.
template <class Config>
void check_window_regrowth() {
  sc::StreamClusterer<Config> engine(time_params<Config>(4));
  std::size_t i = 0;
  double t = 0.0;
  run_blocks(engine, 3000.0, 0.3, false, i, t);  // the rings grow to about 300 points
  run_blocks(engine, 2000.0, 0.3, true, i, t);   // the first retrievals see about 200
  REQUIRE(engine.size() < 220);
  REQUIRE(engine.last_result().components.size() == 25);

  CountingScope scope;
  run_blocks(engine, 3000.0, 0.3, true, i, t);  // back to about 300
  CHECK(engine.size() > 280);
  CHECK(engine.last_result().points.size() == engine.size());
  CHECK(engine.last_result().components.size() == 25);
  CHECK(scope.allocations() == 0);
}

/// A window that grows past every size it has had (a scene that opens up:
/// the Avia forest's window grows from 71,000 to 80,000 points long after
/// start-up) allocates nothing when `reserve` covered it: the rings, the
/// per-point vectors of the retrieval and the band table were sized up
/// front. Without the reservation the same stream allocates. What grows
/// with the edges stays the same: one point per cell (K = 1), so each point
/// links to its cell's previous point only, and a retrieval every 300
/// points, so each fold takes as many new edges at any rate. Returns the
/// allocations counted while the window grows from about 1,500 to about
/// 2,500 points.
template <class Config>
std::uint64_t allocations_while_the_window_grows(std::size_t reserve_points) {
  sc::StreamClusterer<Config> engine(time_params<Config>(1));
  if (reserve_points > 0) engine.reserve(reserve_points);
  std::size_t i = 0;
  double t = 0.0;
  const auto run = [&](double rate, std::size_t points) {  // [points/s], points
    for (std::size_t k = 1; k <= points; ++k) {
      t += 1.0 / rate;
      engine.insert(block_point(i++, t));
      if (k % 300 == 0) engine.retrieve();
    }
  };
  run(15000.0, 7500);  // 0.5 s, about 1,500 points in the window: rings of about 1,690
  REQUIRE(engine.size() < 1600);
  REQUIRE(engine.last_result().components.size() == 25);

  CountingScope scope;
  run(25000.0, 7500);  // 0.3 s, about 2,500: past those rings
  CHECK(engine.size() > 2400);
  CHECK(engine.last_result().points.size() == engine.size());
  CHECK(engine.last_result().components.size() == 25);
  return scope.allocations();
}

}  // namespace

TEST_CASE("the counting allocator counts") {
  CountingScope scope;
  void* p = ::operator new(16);  // a call, not a new-expression: never elided
  ::operator delete(p);
  CHECK(scope.allocations() == 1);
}

TEST_CASE("capped-grid presets allocate nothing in steady state, even when the masks fill up") {
  static_assert(sc::has_spatial_index_cell_bound_v<sc::CappedGrid>);
  static_assert(sc::has_spatial_index_cell_bound_v<sc::OverwriteGrid>);
  static_assert(!sc::has_spatial_index_cell_bound_v<sc::BucketGrid>);
  SUBCASE("spanning forest (CArcCappedFastConfig's connectivity)") {
    check_no_steady_allocations<CappedCountConfig<sc::SpanningForestConnectivity>>();
  }
  SUBCASE("union-find rebuild (CArcCappedRebuildConfig's connectivity)") {
    check_no_steady_allocations<CappedCountConfig<sc::UnionFindRebuildConnectivity>>();
  }
}

TEST_CASE("a window growing back within its rings allocates nothing") {
  SUBCASE("spanning forest") { check_window_regrowth<CappedTimeConfig<sc::SpanningForestConnectivity>>(); }
  SUBCASE("union-find rebuild") { check_window_regrowth<CappedTimeConfig<sc::UnionFindRebuildConnectivity>>(); }
}

TEST_CASE("reserve(): a window growing to a new maximum within the reservation allocates nothing") {
  using Config = CappedTimeConfig<sc::SpanningForestConnectivity>;  // CArcCappedFastConfig's strategy
  CHECK(allocations_while_the_window_grows<Config>(3000) == 0);
  CHECK(allocations_while_the_window_grows<Config>(0) > 0);  // the control: the rings had to grow
}

TEST_CASE("bucket grid: a spill bucket is born with room for a cell of 16 handles") {
  using Grid = sc::BucketGrid;
  static_assert(Grid::kInlineCapacity + Grid::kMinSpillCapacity == 16);
  Grid grid{{}};
  grid.reset(sc::GridShape{1, 4, false});
  sc::PointHandle next = 0;
  for (std::uint32_t i = 0; i < Grid::kInlineCapacity; ++i) grid.insert(1, next++);
  std::uint64_t first_spill = 0;
  {
    CountingScope scope;
    grid.insert(1, next++);  // the cell's 7th handle: the first spill bucket
    first_spill = scope.allocations();
  }
  CHECK(first_spill > 0);
  CHECK(grid.spilled_cells() == 1);
  CountingScope scope;
  while (grid.cell_size(1) < 16) grid.insert(1, next++);  // climbing to 16: the bucket does not grow
  CHECK(scope.allocations() == 0);
  // A sliding cell of 16 (remove the oldest, insert the newest) for a long
  // while, and a second crowded cell taking the pooled bucket: nothing new.
  for (int i = 0; i < 1000; ++i) {
    grid.remove(1, next - 16);
    grid.insert(1, next++);
  }
  while (grid.cell_size(1) > 0) grid.remove(1, next - static_cast<sc::PointHandle>(grid.cell_size(1)));
  CHECK(grid.spilled_cells() == 0);
  for (int i = 0; i < 16; ++i) grid.insert(3, next++);
  CHECK(grid.spilled_cells() == 1);
  CHECK(scope.allocations() == 0);
  grid.insert(3, next++);  // the 17th handle: past the reserved room, the bucket grows
  CHECK(scope.allocations() == 1);
}
