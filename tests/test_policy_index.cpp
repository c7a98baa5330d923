// SPDX-License-Identifier: MIT
// Unit tests of the spatial-index policies: every index of the
// SpatialIndexes list (support/policy_lists.hpp) against a brute-force model
// and with its optional prefetch hint, then each index's own behaviour.

#include <doctest/doctest.h>

#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/index/overwrite_grid.hpp>

#include <streamclust/testing/doctest.hpp>
#include <streamclust/testing/index_laws.hpp>

#include "support/policy_hooks.hpp"
#include "support/policy_lists.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

using streamclust::BucketGrid;
using streamclust::CappedGrid;
using streamclust::CellIndex;
using streamclust::GridShape;
using streamclust::kNoPoint;
using streamclust::OverwriteGrid;
using streamclust::PointHandle;

namespace {

/// The parameters each index is tested with: support/policy_hooks.hpp.
using streamclust::test::IndexModel;

template <class I>
std::vector<PointHandle> contents(const I& index, CellIndex c) {
  std::vector<PointHandle> out;
  index.for_each(c, [&](PointHandle h) { out.push_back(h); });
  return out;
}

/// The cell as `gather` hands it over, asked with several rooms: exactly
/// the count, one more, the index's own copy width and plenty; and, for a
/// non-empty cell, one less than the count (it must then report the count
/// and nothing else). A guard entry right after the room must stay untouched.
template <class I>
std::vector<PointHandle> gathered(const I& index, CellIndex c) {
  constexpr PointHandle kGuard = 0xDEADBEEFu;
  const std::size_t n = index.cell_size(c);
  std::vector<PointHandle> first;
  for (const std::size_t room : {n, n + 1, std::size_t{4}, std::size_t{6}, std::size_t{64}}) {
    if (room < n) continue;
    std::vector<PointHandle> buffer(room + 1, kGuard);
    REQUIRE(index.gather(c, buffer.data(), room) == n);
    REQUIRE(buffer.back() == kGuard);
    buffer.resize(n);
    if (room == n) first = buffer;
    REQUIRE(buffer == first);
  }
  if (n > 0) {
    std::vector<PointHandle> short_buffer(n, kGuard);  // room n - 1, guard at [n - 1]
    REQUIRE(index.gather(c, short_buffer.data(), n - 1) == n);
    REQUIRE(short_buffer.back() == kGuard);
  }
  return first;
}

}  // namespace

// The test kit's index laws (<streamclust/testing/index_laws.hpp>): the
// brute-force model on random operation sequences (its capacity the index's
// max_cell_size), gather, youngest / gather_older and prefetch against
// for_each, on the hooks' parameters (a bucket grid that spills early).
TEST_CASE_TEMPLATE_DEFINE("spatial index: the test kit's index laws hold", I, index_laws_id) {
  streamclust::testing::IndexLawOptions<I> options;
  options.params = {IndexModel<I>::params()};
  STREAMCLUST_CHECK_LAW(streamclust::testing::check_index<I>(options));
}

TEST_CASE("CappedGrid: a full cell's newest point displaces the oldest") {
  CappedGrid grid{{3}};
  grid.reset(GridShape{2, 2, false});
  CHECK(grid.insert(1, 10) == kNoPoint);
  CHECK(grid.insert(1, 11) == kNoPoint);
  CHECK(grid.insert(1, 12) == kNoPoint);
  CHECK(grid.size() == 3);
  CHECK(grid.insert(1, 13) == 10u);
  CHECK(grid.insert(1, 14) == 11u);
  CHECK(grid.size() == 3);
  CHECK(contents(grid, 1) == std::vector<PointHandle>{12, 13, 14});
  CHECK(contents(grid, 0).empty());
  grid.remove(1, 10);  // displaced earlier: no-op
  CHECK(grid.size() == 3);
  grid.remove(1, 13);  // middle
  CHECK(contents(grid, 1) == std::vector<PointHandle>{12, 14});
  CHECK(grid.insert(1, 15) == kNoPoint);
  CHECK(grid.insert(1, 16) == 12u);
  CHECK(contents(grid, 1) == std::vector<PointHandle>{14, 15, 16});
  grid.remove(1, 14);  // head
  CHECK(contents(grid, 1) == std::vector<PointHandle>{15, 16});
  CHECK(grid.size() == 2);
  CappedGrid single{{1}};
  single.reset(GridShape{1, 1, false});
  CHECK(single.insert(0, 5) == kNoPoint);
  CHECK(single.insert(0, 6) == 5u);
  CHECK(contents(single, 0) == std::vector<PointHandle>{6});
  CappedGrid widest{{255}};
  widest.reset(GridShape{1, 2, false});
  for (PointHandle h = 0; h < 255; ++h) REQUIRE(widest.insert(1, h) == kNoPoint);
  CHECK(widest.insert(1, 1000) == 0u);
  CHECK(widest.size() == 255);
}

TEST_CASE("CappedGrid: capacity outside [1, 255] throws") {
  CHECK_THROWS_AS(CappedGrid{{0}}, std::invalid_argument);
  CHECK_THROWS_AS(CappedGrid{{256}}, std::invalid_argument);
  try {
    CappedGrid bad{{300}};
    FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    CHECK(what.find("capacity") != std::string::npos);
    CHECK(what.find("300") != std::string::npos);
    CHECK(what.find("[1, 255]") != std::string::npos);
  }
}

TEST_CASE("OverwriteGrid: the newest point wins") {
  OverwriteGrid grid{{}};
  grid.reset(GridShape{3, 3, true});
  CHECK(grid.insert(4, 10) == kNoPoint);
  CHECK(grid.insert(4, 11) == 10u);
  CHECK(grid.insert(5, 12) == kNoPoint);
  CHECK(grid.size() == 2);
  grid.remove(4, 10);  // overwritten: no-op
  CHECK(contents(grid, 4) == std::vector<PointHandle>{11});
  grid.remove(5, 11);  // wrong cell: no-op
  CHECK(grid.size() == 2);
  grid.remove(4, 11);
  CHECK(contents(grid, 4).empty());
  CHECK(grid.size() == 1);
  grid.clear();
  CHECK(grid.size() == 0);
  CHECK(contents(grid, 5).empty());
}

TEST_CASE("BucketGrid: keeps every point, FIFO removal, compaction keeps order") {
  BucketGrid grid{{}};
  grid.reset(GridShape{1, 2, false});
  std::vector<PointHandle> expected;
  for (PointHandle h = 0; h < 100; ++h) {
    REQUIRE(grid.insert(0, h) == kNoPoint);
    expected.push_back(h);
  }
  CHECK(grid.size() == 100);
  // interleave oldest-first removal with insertion: crosses the compaction threshold many times
  for (PointHandle h = 100; h < 1000; ++h) {
    grid.remove(0, expected.front());
    expected.erase(expected.begin());
    REQUIRE(grid.insert(0, h) == kNoPoint);
    expected.push_back(h);
    if (h % 11 == 0) {  // 81 extra removals: the bucket shrinks from 100 to 19
      grid.remove(0, expected.front());
      expected.erase(expected.begin());
    }
    REQUIRE(contents(grid, 0) == expected);
  }
  CHECK(grid.cell_size(0) == expected.size());
  CHECK(contents(grid, 1).empty());
}

TEST_CASE("BucketGrid: overflow of the inline capacity keeps insertion order and recycles spill buckets") {
  constexpr PointHandle inline_cap = BucketGrid::kInlineCapacity;
  BucketGrid grid{{}};
  grid.reset(GridShape{2, 2, false});
  std::vector<PointHandle> expected;
  for (PointHandle h = 0; h < inline_cap; ++h) {
    REQUIRE(grid.insert(3, h) == kNoPoint);
    expected.push_back(h);
  }
  CHECK(grid.spilled_cells() == 0);
  CHECK(grid.insert(3, inline_cap) == kNoPoint);  // the first handle beyond the inline capacity
  expected.push_back(inline_cap);
  CHECK(grid.spilled_cells() == 1);
  CHECK(contents(grid, 3) == expected);
  CHECK(grid.cell_size(3) == expected.size());
  // the oldest leaves: the spilled handle moves inline, the spill bucket is released
  grid.remove(3, 0);
  expected.erase(expected.begin());
  CHECK(contents(grid, 3) == expected);
  CHECK(grid.spilled_cells() == 0);
  // spill again, then remove a middle inline handle: the oldest spilled one moves inline
  for (PointHandle h = 100; h < 103; ++h) {
    grid.insert(3, h);
    expected.push_back(h);
  }
  CHECK(grid.spilled_cells() == 1);
  grid.remove(3, 3);
  expected.erase(std::find(expected.begin(), expected.end(), PointHandle{3}));
  CHECK(contents(grid, 3) == expected);
  // remove the newest (in the spill, not its head), then the spill's head
  grid.remove(3, 102);
  expected.pop_back();
  CHECK(contents(grid, 3) == expected);
  grid.remove(3, expected[inline_cap]);  // the spill's oldest handle
  expected.erase(expected.begin() + inline_cap);
  CHECK(contents(grid, 3) == expected);
  CHECK(grid.spilled_cells() == 0);
  CHECK(grid.cell_size(3) == inline_cap);
  // absent handles, and a present handle asked of the wrong cell: no-ops
  grid.remove(3, 999);
  grid.remove(2, expected.front());
  grid.remove(0, 5);
  CHECK(contents(grid, 3) == expected);
  CHECK(grid.size() == expected.size());
  // other cells are untouched
  CHECK(contents(grid, 0).empty());
  CHECK(contents(grid, 2).empty());
  // clear and reset empty every cell and return the spill buckets to the pool
  for (PointHandle h = 200; h < 220; ++h) grid.insert(1, h);
  CHECK(grid.spilled_cells() == 1);
  grid.clear();
  CHECK(grid.size() == 0);
  CHECK(grid.spilled_cells() == 0);
  CHECK(contents(grid, 1).empty());
  CHECK(contents(grid, 3).empty());
  for (PointHandle h = 300; h < 320; ++h) grid.insert(h % 4, h);  // 5 per cell: inline only
  CHECK(grid.spilled_cells() == 0);
  for (PointHandle h = 320; h < 328; ++h) grid.insert(h % 4, h);  // 7 per cell: 4 spills
  CHECK(grid.spilled_cells() == 4);
  CHECK(contents(grid, 2) == std::vector<PointHandle>{302, 306, 310, 314, 318, 322, 326});
  grid.reset(GridShape{3, 1, false});
  CHECK(grid.size() == 0);
  CHECK(grid.spilled_cells() == 0);
  for (CellIndex c = 0; c < 3; ++c) CHECK(contents(grid, c).empty());
  // a crowded cell with reserve_per_cell: same contents
  BucketGrid reserved{{64}};
  reserved.reset(GridShape{1, 1, false});
  std::vector<PointHandle> all;
  for (PointHandle h = 0; h < 100; ++h) {
    reserved.insert(0, h);
    all.push_back(h);
  }
  CHECK(contents(reserved, 0) == all);
}

TEST_CASE("the capped and bucket grids offer gather; stale slots are never handed over") {
  static_assert(streamclust::has_spatial_index_gather_v<CappedGrid>);
  static_assert(streamclust::has_spatial_index_gather_v<BucketGrid>);
  static_assert(!streamclust::has_spatial_index_gather_v<OverwriteGrid>);
  CappedGrid grid{{3}};
  grid.reset(GridShape{1, 2, false});
  CHECK(gathered(grid, 0).empty());
  grid.insert(0, 7);
  grid.insert(0, 8);
  CHECK(gathered(grid, 0) == std::vector<PointHandle>{7, 8});
  grid.remove(0, 7);  // the stale slot behind the count is not handed over
  CHECK(gathered(grid, 0) == std::vector<PointHandle>{8});
  for (PointHandle h = 9; h < 13; ++h) grid.insert(0, h);  // full: the oldest are displaced
  CHECK(gathered(grid, 0) == std::vector<PointHandle>{10, 11, 12});
  CHECK(gathered(grid, 1).empty());
  // A bucket cell past its six inline handles: the spill follows them, in order.
  BucketGrid buckets{{}};
  buckets.reset(GridShape{1, 1, false});
  std::vector<PointHandle> all;
  for (PointHandle h = 100; h < 111; ++h) {
    buckets.insert(0, h);
    all.push_back(h);
    CHECK(gathered(buckets, 0) == all);
  }
  buckets.remove(0, 100);  // the oldest spilled handle moves inline
  all.erase(all.begin());
  CHECK(gathered(buckets, 0) == all);
}

TEST_CASE("BucketGrid: a cell that spills takes the largest pooled bucket") {
  constexpr PointHandle inline_cap = BucketGrid::kInlineCapacity;
  BucketGrid grid{{}};
  grid.reset(GridShape{1, 3, false});
  PointHandle next = 0;
  const auto fill = [&](CellIndex cell, PointHandle n) {
    std::vector<PointHandle> handles;
    for (PointHandle k = 0; k < n; ++k, ++next) {
      grid.insert(cell, next);
      handles.push_back(next);
    }
    return handles;
  };
  const std::vector<PointHandle> big = fill(0, inline_cap + 100);
  const std::vector<PointHandle> small = fill(1, inline_cap + 3);
  for (const PointHandle h : big) grid.remove(0, h);  // the large bucket is pooled first,
  for (const PointHandle h : small) grid.remove(1, h);  // the small one last
  REQUIRE(grid.spilled_cells() == 0);
  const std::size_t pooled = grid.heap_bytes();
  fill(2, inline_cap + 100);  // takes the large bucket: nothing grows
  CHECK(grid.spilled_cells() == 1);
  CHECK(grid.heap_bytes() == pooled);
}

TEST_CASE("BucketGrid: a full spill bucket moves into a larger pooled one instead of growing") {
  constexpr PointHandle inline_cap = BucketGrid::kInlineCapacity;
  BucketGrid grid{{}};
  grid.reset(GridShape{1, 2, false});
  std::vector<PointHandle> big, small;
  PointHandle next = 0;
  for (PointHandle k = 0; k < inline_cap + 100; ++k, ++next) {
    grid.insert(0, next);
    big.push_back(next);
  }
  for (PointHandle k = 0; k < inline_cap + 3; ++k, ++next) {
    grid.insert(1, next);
    small.push_back(next);
  }
  for (const PointHandle h : big) grid.remove(0, h);  // the large bucket is pooled; cell 1 keeps the small one
  const std::size_t before = grid.heap_bytes();
  for (PointHandle k = 0; k < 90; ++k, ++next) {  // cell 1 outgrows its bucket
    grid.insert(1, next);
    small.push_back(next);
  }
  CHECK(grid.heap_bytes() == before);  // no bucket grew: cell 1 moved into the large one
  CHECK(contents(grid, 1) == small);
  CHECK(grid.spilled_cells() == 1);
}

TEST_CASE("BucketGrid: youngest and gather_older read a crowded cell by its chain start") {
  static_assert(streamclust::has_spatial_index_chain_v<BucketGrid>);
  static_assert(!streamclust::has_spatial_index_chain_v<CappedGrid>);
  static_assert(!streamclust::has_spatial_index_chain_v<OverwriteGrid>);
  BucketGrid grid{{}};
  grid.reset(GridShape{1, 2, false});
  std::vector<PointHandle> cell;  // handles near the wrap of PointHandle: the order is by difference
  for (PointHandle h = 0xFFFFFFF0u; h != 12u; ++h) {
    if (h % 3 == 0) continue;  // gaps: other cells' points
    grid.insert(0, h);
    cell.push_back(h);
    CHECK(grid.youngest(0) == h);
  }
  REQUIRE(cell.size() > 2 * BucketGrid::kInlineCapacity);
  std::vector<PointHandle> out(cell.size());
  for (std::size_t k = 0; k <= cell.size(); ++k) {
    const PointHandle bound = k < cell.size() ? cell[k] : 12u;  // a bound past the youngest: all are older
    CAPTURE(k);
    CHECK(grid.gather_older(0, bound, out.data(), out.size()) == k);
    CHECK(std::vector<PointHandle>(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(k)) ==
          std::vector<PointHandle>(cell.begin(), cell.begin() + static_cast<std::ptrdiff_t>(k)));
    std::vector<PointHandle> small(3, kNoPoint);  // room for 3: the count is whole, nothing past the room
    CHECK(grid.gather_older(0, bound, small.data(), 2) == k);
    CHECK(small[2] == kNoPoint);
  }
  // Removing the oldest (the engine's order) keeps both in step.
  for (std::size_t k = 0; k + 1 < cell.size(); ++k) {
    grid.remove(0, cell[k]);
    CHECK(grid.youngest(0) == cell.back());
    CHECK(grid.gather_older(0, cell[k + 1], out.data(), out.size()) == 0);
    CHECK(grid.gather_older(0, cell.back(), out.data(), out.size()) == cell.size() - k - 2);
  }
}

static_assert(streamclust::has_spatial_index_prefetch_v<BucketGrid> &&
              streamclust::has_spatial_index_prefetch_v<CappedGrid> &&
              streamclust::has_spatial_index_prefetch_v<OverwriteGrid>);

TEST_CASE_TEMPLATE_APPLY(index_laws_id, streamclust::test::SpatialIndexes);
