// SPDX-License-Identifier: MIT
// StreamClusterer::memory_usage() and the optional heap_bytes() capability of
// spatial indexes.

#include <doctest/doctest.h>

#include <streamclust/memory_usage.hpp>
#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/streamclust.hpp>

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace sc = streamclust;

namespace {

/// A user index WITHOUT heap_bytes() (a BucketGrid behind the concept's
/// operations only): the engine must compile and report its memory unknown.
struct PlainIndex {
  struct Params {};
  explicit PlainIndex(const Params&) {}
  void reset(const sc::GridShape& g) { grid.reset(g); }
  void clear() { grid.clear(); }
  sc::PointHandle insert(sc::CellIndex c, sc::PointHandle h) { return grid.insert(c, h); }
  void remove(sc::CellIndex c, sc::PointHandle h) { grid.remove(c, h); }
  template <class F>
  void for_each(sc::CellIndex c, F&& f) const {
    grid.for_each(c, std::forward<F>(f));
  }
  std::size_t size() const { return grid.size(); }
  sc::BucketGrid grid{{}};
};

struct ReportingIndex : PlainIndex {
  using PlainIndex::PlainIndex;
  std::size_t heap_bytes() const { return 12345; }
};
struct WrongTypeIndex : PlainIndex {
  using PlainIndex::PlainIndex;
  void heap_bytes() const {}
};

struct PlainIndexConfig : sc::CArcFixedConfig {
  using spatial_index = PlainIndex;
};
struct ReportingIndexConfig : sc::CArcFixedConfig {
  using spatial_index = ReportingIndex;
};
struct CappedFixedConfig : sc::CArcFixedConfig {
  using spatial_index = sc::CappedGrid;
};
struct OverwriteFixedConfig : sc::CArcFixedConfig {
  using spatial_index = sc::OverwriteGrid;
};
struct FastFixedConfig : sc::CArcFixedConfig {
  using connectivity = sc::UnionFindRebuildConnectivity;
};

constexpr std::uint32_t kRows = 32;
constexpr std::uint32_t kCols = 256;

template <class Config>
sc::ClustererParams<Config> fixed_params(double window_seconds) {
  sc::ClustererParams<Config> p;
  p.resolution = {kRows, kCols};
  p.window.duration = window_seconds;
  p.linkage.theta_deg = 30.0f;
  return p;
}

/// Inserts `n` points of the 200 kHz synthetic stream.
template <class Engine>
void feed(Engine& engine, sc::SyntheticStream& stream, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) engine.insert(stream.next());
}

template <class Engine>
std::size_t live_edges(const Engine& engine) {
  std::size_t ends = 0;
  for (std::size_t pos = 0; pos < engine.size(); ++pos) {
    engine.for_each_neighbor(engine.handle_at(pos), [&](sc::PointHandle) { ++ends; });
  }
  return ends / 2;
}

std::size_t sum_of_parts(const sc::MemoryUsage& m) {
  return m.point_ring + m.edge_storage + m.spatial_index + m.clusters + m.scratch + m.result;
}

}  // namespace

static_assert(sc::is_spatial_index_heap_reporting_v<sc::BucketGrid>);
static_assert(sc::is_spatial_index_heap_reporting_v<sc::CappedGrid>);
static_assert(sc::is_spatial_index_heap_reporting_v<sc::OverwriteGrid>);
static_assert(sc::is_spatial_index_heap_reporting_v<ReportingIndex>);
static_assert(!sc::is_spatial_index_heap_reporting_v<PlainIndex>);
static_assert(!sc::is_spatial_index_heap_reporting_v<WrongTypeIndex>);
static_assert(sc::is_spatial_index_policy_v<PlainIndex>);

TEST_CASE("capacity_bytes is capacity x element size") {
  std::vector<std::uint64_t> v;
  CHECK(sc::capacity_bytes(v) == 0);
  v.reserve(37);
  CHECK(sc::capacity_bytes(v) == v.capacity() * 8);
  CHECK(sc::capacity_bytes(v) >= 37 * 8);
}

TEST_CASE("heap_bytes of the standard grids") {
  const sc::GridShape shape{kRows, kCols, true};
  const std::size_t cells = shape.cell_count();

  SUBCASE("capped grid: cells x (4 K + 1), fixed at reset") {
    sc::CappedGrid grid{{4}};
    CHECK(grid.heap_bytes() == 0);
    grid.reset(shape);
    CHECK(grid.heap_bytes() == cells * (4 * 4 + 1));
    for (sc::PointHandle h = 0; h < 100; ++h) grid.insert(h % 7, h);
    CHECK(grid.heap_bytes() == cells * (4 * 4 + 1));
    sc::CappedGrid k9{{9}};
    k9.reset(shape);
    CHECK(k9.heap_bytes() == cells * (4 * 9 + 1));
  }
  SUBCASE("overwrite grid: 4 bytes per cell") {
    sc::OverwriteGrid grid{{}};
    CHECK(grid.heap_bytes() == 0);
    grid.reset(shape);
    CHECK(grid.heap_bytes() == cells * sizeof(sc::PointHandle));
  }
  SUBCASE("bucket grid: the cell table plus the spill buckets' capacity, kept after removal") {
    sc::BucketGrid grid{{}};
    CHECK(grid.heap_bytes() == 0);
    grid.reset(shape);
    const std::size_t empty = grid.heap_bytes();
    CHECK(empty >= cells * 32);  // 32-byte cells with kInlineCapacity handles inline
    const auto inline_cap = sc::BucketGrid::kInlineCapacity;
    for (sc::PointHandle h = 0; h < inline_cap; ++h) grid.insert(3, h);
    CHECK(grid.heap_bytes() == empty);  // inline: no heap
    for (sc::PointHandle h = inline_cap; h < 1000; ++h) grid.insert(3, h);
    const std::size_t full = grid.heap_bytes();
    CHECK(full >= empty + (1000 - inline_cap) * sizeof(sc::PointHandle));
    for (sc::PointHandle h = 0; h < 1000; ++h) grid.remove(3, h);
    CHECK(grid.size() == 0);
    CHECK(grid.heap_bytes() >= full);  // capacity, not size: the spill bucket is pooled
    // A sliding window of 16 live handles in one cell (insert newest, remove
    // oldest): 6 inline, 10 spilled; the spill compacts its removed front
    // instead of growing, so the memory stops changing once the window slid.
    sc::BucketGrid sliding{{}};
    sliding.reset(shape);
    for (sc::PointHandle h = 0; h < 16; ++h) sliding.insert(5, h);
    std::size_t settled = 0;
    for (sc::PointHandle h = 16; h < 10000; ++h) {
      sliding.remove(5, h - 16);
      sliding.insert(5, h);
      REQUIRE(sliding.cell_size(5) == 16);
      if (h == 100) settled = sliding.heap_bytes();
    }
    CHECK(sliding.heap_bytes() == settled);
    CHECK(settled - empty <= 64 * sizeof(sc::PointHandle) + 64);  // bounded: not the 9,984 handles that passed
    std::vector<sc::PointHandle> seen;
    sliding.for_each(5, [&](sc::PointHandle h) { seen.push_back(h); });
    REQUIRE(seen.size() == 16);
    for (std::size_t i = 0; i < seen.size(); ++i) CHECK(seen[i] == 10000 - 16 + i);  // oldest first
    sc::BucketGrid reserved{{8}};  // a spill bucket reserves 8 - 6 handles when created
    reserved.reset(shape);
    for (sc::PointHandle h = 0; h <= inline_cap; ++h) reserved.insert(7, h);
    CHECK(reserved.heap_bytes() >= empty + 2 * sizeof(sc::PointHandle));
  }
}

TEST_CASE("memory_usage of an engine: parts, rings, growth with the window") {
  sc::StreamClusterer<sc::CArcFixedConfig> engine(fixed_params<sc::CArcFixedConfig>(10.0));  // nothing expires
  const sc::MemoryUsage empty = engine.memory_usage();
  CHECK(empty.spatial_index_known);
  CHECK(empty.point_ring == 0);
  CHECK(empty.edge_storage == 0);
  CHECK(empty.spatial_index >= std::size_t{kRows} * kCols * sizeof(std::vector<sc::PointHandle>));  // reset at construction
  CHECK(empty.total() == sum_of_parts(empty));

  sc::SyntheticStream stream;
  feed(engine, stream, 1);
  const std::size_t ring_one = engine.memory_usage().point_ring;
  // The ring starts at 1024 slots: the bytes per slot follow.
  REQUIRE(ring_one > 0);
  REQUIRE(ring_one % 1024 == 0);
  const std::size_t record = ring_one / 1024;
  CHECK(record >= sizeof(sc::Sample));

  feed(engine, stream, 4999);
  REQUIRE(engine.size() == 5000);
  const sc::MemoryUsage m = engine.memory_usage();
  CHECK(m.point_ring >= 5000 * record);  // holds every windowed point
  // Exact-size rings: grown to needed + needed / 8 slots, not to the next
  // power of two (8,192 slots for 5,000 points).
  CHECK(m.point_ring <= (5000 + 5000 / 8) * record);
  CHECK(m.point_ring < 8192 * record);
  const std::size_t edges = live_edges(engine);
  REQUIRE(edges > 0);
  CHECK(m.edge_storage >= edges * sizeof(sc::PointHandle));
  // The bucket grid holds up to kInlineCapacity handles per cell in its cell
  // table; only the handles beyond spill to the heap.
  CHECK(m.spatial_index >= empty.spatial_index);
  CHECK(m.spatial_index == engine.spatial_index().heap_bytes());
  CHECK(m.clusters > 0);
  CHECK(m.scratch > 0);  // candidate / neighbour buffers of the insertions
  CHECK(m.result == 0);  // no retrieval yet
  CHECK(m.total() == sum_of_parts(m));
  CHECK(m.total() > empty.total());

  const sc::Clustering& r = engine.retrieve();
  REQUIRE(r.points.size() == 5000);
  const sc::MemoryUsage after = engine.memory_usage();
  CHECK(after.result >= 5000 * sizeof(sc::PointLabel) + r.components.size() * sizeof(sc::ComponentSummary));
  CHECK(after.point_ring == m.point_ring);
  // memory_usage itself neither allocates nor changes anything.
  const sc::MemoryUsage again = engine.memory_usage();
  CHECK(again.total() == after.total());
}

TEST_CASE("memory_usage grows with the window and is stable in steady state") {
  auto run = [](double window, std::size_t points) {
    sc::StreamClusterer<FastFixedConfig> engine(fixed_params<FastFixedConfig>(window));
    sc::SyntheticStream stream;
    for (std::size_t i = 0; i < points; ++i) {
      engine.insert(stream.next());
      if (i % 10000 == 9999) engine.retrieve();
    }
    return engine.memory_usage();
  };
  // 200 kHz: 0.02 s = about 4,000 points, 0.1 s = about 20,000 points.
  const sc::MemoryUsage small = run(0.02, 60000);
  const sc::MemoryUsage large = run(0.1, 60000);
  CHECK(large.point_ring > small.point_ring);
  CHECK(large.edge_storage > small.edge_storage);
  CHECK(large.result > small.result);
  CHECK(large.total() > small.total());
  // Twice as many points in a steady window: the rings do not grow again.
  const sc::MemoryUsage longer = run(0.02, 120000);
  CHECK(longer.point_ring == small.point_ring);
  CHECK(longer.edge_storage == small.edge_storage);
}

TEST_CASE("memory_usage: index part per standard grid, unknown without heap_bytes") {
  sc::SyntheticStream s1, s2, s3, s4;
  const std::size_t cells = std::size_t{kRows} * kCols;

  sc::StreamClusterer<CappedFixedConfig> capped(fixed_params<CappedFixedConfig>(0.05));
  feed(capped, s1, 20000);
  const sc::MemoryUsage mc = capped.memory_usage();
  CHECK(mc.spatial_index_known);
  CHECK(mc.spatial_index == cells * (4 * capped.params().spatial_index.capacity + 1));

  sc::StreamClusterer<OverwriteFixedConfig> overwrite(fixed_params<OverwriteFixedConfig>(0.05));
  feed(overwrite, s2, 20000);
  CHECK(overwrite.memory_usage().spatial_index == cells * sizeof(sc::PointHandle));

  sc::StreamClusterer<PlainIndexConfig> plain(fixed_params<PlainIndexConfig>(0.05));
  feed(plain, s3, 20000);
  plain.retrieve();
  const sc::MemoryUsage mp = plain.memory_usage();
  CHECK_FALSE(mp.spatial_index_known);
  CHECK(mp.spatial_index == 0);
  CHECK(mp.point_ring > 0);
  CHECK(mp.result > 0);
  CHECK(mp.total() == sum_of_parts(mp));

  sc::StreamClusterer<ReportingIndexConfig> reporting(fixed_params<ReportingIndexConfig>(0.05));
  feed(reporting, s4, 100);
  CHECK(reporting.memory_usage().spatial_index_known);
  CHECK(reporting.memory_usage().spatial_index == 12345);
}
