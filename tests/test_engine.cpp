// SPDX-License-Identifier: MIT
// Behaviour of the continuous engine on hand-made streams: the three
// insertion cases, bridge multiplicity, lazy deletion and splits, stable ids,
// rejected input, windows, the mask, visitors and result summaries.

#include <doctest/doctest.h>

#include <streamclust/detail/mask.hpp>
#include <streamclust/streamclust.hpp>

#include "support/partition.hpp"
#include "support/points.hpp"
#include "support/presets.hpp"
#include "support/streams.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <random>
#include <set>
#include <vector>

namespace sc = streamclust;

namespace {

// One cell holds everything, so the Euclidean linkage alone decides.
struct OneCellConfig {
  using projection = sc::SphericalProjection;
  using spatial_index = sc::BucketGrid;
  using linkage = sc::EuclideanLinkage;
  using window = sc::TimeWindow;
  using resolution = sc::FixedResolution;
};

struct Events {
  std::vector<sc::ClusterId> created, evicted;
  std::vector<std::pair<sc::ClusterId, sc::ClusterId>> merged, split;
};
struct RecordingVisitor : sc::NullVisitor {
  Events* events = nullptr;
  void cluster_created(sc::ClusterId c) { events->created.push_back(c); }
  void clusters_merged(sc::ClusterId a, sc::ClusterId b) { events->merged.emplace_back(a, b); }
  void cluster_split(sc::ClusterId a, sc::ClusterId b) { events->split.emplace_back(a, b); }
  void cluster_evicted(sc::ClusterId c) { events->evicted.push_back(c); }
};
struct RecordingConfig : OneCellConfig {
  using visitor = RecordingVisitor;
};

sc::ClustererParams<OneCellConfig> one_cell_params(double window = 10.0) {
  sc::ClustererParams<OneCellConfig> p;
  p.resolution = {1, 1};
  p.linkage.max_distance = 1.0f;
  p.window.duration = window;
  p.mask_size = 1;
  return p;
}

using streamclust::test::at;

template <class Engine>
sc::ComponentId label_of(const Engine& e, std::uint64_t stream_index) {
  for (const auto& p : e.last_result().points) {
    if (p.stream_index == stream_index) return p.label;
  }
  return sc::kNoComponent;
}

/// The two results are the same: every point's stream index and label, and
/// every component's id, size, centroid and time span.
void check_same_result(const sc::Clustering& a, const sc::Clustering& b) {
  REQUIRE(b.points.size() == a.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    REQUIRE(b.points[i].stream_index == a.points[i].stream_index);
    REQUIRE(b.points[i].label == a.points[i].label);
  }
  REQUIRE(b.components.size() == a.components.size());
  for (std::size_t k = 0; k < a.components.size(); ++k) {
    CHECK(b.components[k].id == a.components[k].id);
    CHECK(b.components[k].size == a.components[k].size);
    CHECK(b.components[k].centroid == a.components[k].centroid);
    CHECK(b.components[k].time_begin == a.components[k].time_begin);
    CHECK(b.components[k].time_end == a.components[k].time_end);
  }
}

}  // namespace

TEST_CASE("isolation, expansion and bridging into the most recently created cluster") {
  Events events;
  sc::ClustererParams<RecordingConfig> params;
  params.resolution = {1, 1};
  params.linkage.max_distance = 1.0f;
  params.window.duration = 10.0;
  params.mask_size = 1;
  sc::StreamClusterer<RecordingConfig> engine(params, RecordingVisitor{sc::NullVisitor{}, &events});

  engine.insert(at(5.0f, 0.0f, 0.0));  // isolation: cluster A
  engine.insert(at(5.5f, 0.0f, 0.1));  // expansion of A
  engine.insert(at(7.0f, 0.0f, 0.2));  // isolation: cluster B (1.5 m from A's nearest point)
  REQUIRE(events.created.size() == 2);
  const sc::ClusterId a = engine.cluster_of(engine.handle_at(0));
  const sc::ClusterId b = engine.cluster_of(engine.handle_at(2));
  CHECK(engine.cluster_of(engine.handle_at(1)) == a);
  CHECK(a != b);
  CHECK(engine.bridges(a).empty());

  engine.insert(at(6.3f, 0.0f, 0.3));  // links 5.5 (A) and 7.0 (B): bridging
  CHECK(events.created.size() == 2);   // no new cluster
  CHECK(engine.cluster_of(engine.handle_at(3)) == b);  // joins the newer cluster
  REQUIRE(engine.bridges(a).size() == 1);
  CHECK(engine.bridges(a)[0].other == b);
  CHECK(engine.bridges(a)[0].multiplicity == 1);
  REQUIRE(events.merged.size() == 1);

  const auto& result = engine.retrieve();
  CHECK(result.components.size() == 1);
  CHECK(result.points.size() == 4);
}

TEST_CASE("a bridge carries a multiplicity and disappears with its last point-level link") {
  sc::StreamClusterer<OneCellConfig> engine(one_cell_params(1.0));
  engine.insert(at(5.2f, 0.0f, 0.0));   // A
  engine.insert(at(6.8f, 0.0f, 0.1));   // B, 1.6 m away
  engine.insert(at(6.0f, 0.0f, 0.2));   // bridge: joins B, one link to A
  engine.insert(at(6.0f, 0.1f, 0.6));   // second bridge point: links A, B and the first bridge
  const sc::ClusterId a = engine.cluster_of(engine.handle_at(0));
  REQUIRE(engine.bridges(a).size() == 1);
  CHECK(engine.bridges(a)[0].multiplicity == 2);
  CHECK(engine.retrieve().components.size() == 1);

  engine.advance_to(1.05);  // A (t = 0) leaves: both links to A go
  CHECK(engine.size() == 3);
  const auto& result = engine.retrieve();
  CHECK(result.components.size() == 1);
  for (sc::ClusterId c = 0; c < engine.cluster_slots(); ++c) {
    if (engine.cluster_alive(c)) CHECK(engine.bridges(c).empty());
  }
}

TEST_CASE("a bridge goes when the bridging points leave, and the components separate") {
  sc::StreamClusterer<OneCellConfig> engine(one_cell_params(1.0));
  engine.insert(at(6.0f, 0.0f, 0.0));  // the bridge first, so it is evicted first
  engine.insert(at(5.2f, 0.0f, 0.5));  // joins the bridge's cluster
  engine.insert(at(6.8f, 0.0f, 0.5));  // joins it too
  CHECK(engine.retrieve().components.size() == 1);
  engine.advance_to(1.2);  // the bridge leaves: 5.2 and 6.8 are 1.6 m apart
  const auto& result = engine.retrieve();
  CHECK(result.points.size() == 2);
  CHECK(result.components.size() == 2);
  CHECK(engine.last_stats().clusters_split == 1);
}

TEST_CASE("lazy deletion: eviction marks a cluster pending only when it can split, and retrieve() splits it") {
  Events events;
  sc::ClustererParams<RecordingConfig> params;
  params.resolution = {1, 1};
  params.linkage.max_distance = 1.0f;
  params.window.duration = 1.0;
  params.mask_size = 1;
  sc::StreamClusterer<RecordingConfig> engine(params, RecordingVisitor{sc::NullVisitor{}, &events});
  engine.insert(at(5.0f, 0.0f, 0.0));  // middle of a chain
  engine.insert(at(4.2f, 0.0f, 0.5));
  engine.insert(at(3.4f, 0.0f, 0.5));
  engine.insert(at(5.8f, 0.0f, 0.5));
  engine.insert(at(6.6f, 0.0f, 0.5));
  const auto& before = engine.retrieve();
  REQUIRE(before.components.size() == 1);
  const sc::ComponentId id = before.components[0].id;

  engine.advance_to(1.01);  // the middle point leaves
  const sc::ClusterId c = engine.cluster_of(engine.handle_at(0));
  CHECK(engine.cluster_pending(c));
  const auto& after = engine.retrieve();
  CHECK(after.components.size() == 2);
  CHECK(events.split.size() == 1);
  // Two parts of two points each: one keeps the id, the other gets a new one.
  std::set<sc::ComponentId> ids;
  for (const auto& comp : after.components) ids.insert(comp.id);
  CHECK(ids.count(id) == 1);
  CHECK(*ids.rbegin() > id);
}

TEST_CASE("a leaf leaving does not mark its cluster pending") {
  sc::StreamClusterer<OneCellConfig> engine(one_cell_params(1.0));
  engine.insert(at(5.0f, 0.0f, 0.0));  // end of a chain
  engine.insert(at(5.8f, 0.0f, 0.5));
  engine.insert(at(6.6f, 0.0f, 0.5));
  engine.retrieve();
  engine.advance_to(1.01);
  CHECK_FALSE(engine.cluster_pending(engine.cluster_of(engine.handle_at(0))));
  CHECK(engine.retrieve().components.size() == 1);
  CHECK(engine.last_stats().clusters_validated == 0);
}

TEST_CASE("stable ids survive, merge to the larger part and split to the larger part") {
  sc::StreamClusterer<OneCellConfig> engine(one_cell_params(1.0));
  // Big object (3 points) near x = 5, small one (2 points) near x = 8.
  engine.insert(at(4.0f, 0.0f, 0.0));
  engine.insert(at(4.5f, 0.0f, 0.0));
  engine.insert(at(5.0f, 0.0f, 0.0));
  engine.insert(at(8.0f, 0.0f, 0.0));
  engine.insert(at(8.5f, 0.0f, 0.0));
  const auto& r1 = engine.retrieve();
  REQUIRE(r1.components.size() == 2);
  const sc::ComponentId big = label_of(engine, 0);
  const sc::ComponentId small = label_of(engine, 3);
  CHECK(big != small);

  engine.insert(at(5.8f, 0.0f, 0.1));  // joins big
  const auto& r2 = engine.retrieve();
  CHECK(r2.components.size() == 2);
  CHECK(label_of(engine, 5) == big);
  CHECK(label_of(engine, 3) == small);

  engine.insert(at(6.6f, 0.0f, 0.6));
  engine.insert(at(7.3f, 0.0f, 0.6));  // links 6.6 and 8.0: everything merges
  engine.retrieve();
  CHECK(engine.last_result().components.size() == 1);
  CHECK(label_of(engine, 3) == big);  // the merged component keeps the heavier id

  engine.advance_to(1.05);  // the five points at t = 0 leave; 5.8, 6.6 and 7.3 stay
  const auto& r4 = engine.retrieve();
  CHECK(r4.points.size() == 3);
  CHECK(r4.components.size() == 1);
  CHECK(label_of(engine, 6) == big);
}

TEST_CASE("rejected input is counted by reason and never inserted; stream indices count every record") {
  sc::StreamClusterer<OneCellConfig> engine(one_cell_params());
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  CHECK(engine.insert(at(5.0f, 0.0f, 1.0)) == sc::RejectReason::accepted);
  CHECK(engine.insert(at(nan, 0.0f, 1.1)) == sc::RejectReason::non_finite);
  CHECK(engine.insert(at(inf, 0.0f, 1.1)) == sc::RejectReason::non_finite);
  CHECK(engine.insert(at(5.0f, 0.0f, 1.1), std::numeric_limits<double>::quiet_NaN()) == sc::RejectReason::non_finite);
  CHECK(engine.insert(at(0.0f, 0.0f, 1.1)) == sc::RejectReason::too_close);
  CHECK(engine.insert(at(0.05f, 0.0f, 1.1)) == sc::RejectReason::too_close);
  CHECK(engine.insert(at(5.0f, 0.0f, 0.5)) == sc::RejectReason::time_backwards);
  CHECK(engine.insert(at(5.5f, 0.0f, 1.2)) == sc::RejectReason::accepted);
  CHECK(engine.offered() == 8);
  CHECK(engine.size() == 2);
  const auto& counts = engine.rejections();
  CHECK(counts[sc::RejectReason::accepted] == 2);
  CHECK(counts[sc::RejectReason::non_finite] == 3);
  CHECK(counts[sc::RejectReason::too_close] == 2);
  CHECK(counts[sc::RejectReason::time_backwards] == 1);
  CHECK(counts.rejected() == 6);
  const auto& result = engine.retrieve();
  REQUIRE(result.points.size() == 2);
  CHECK(result.points[0].stream_index == 0);
  CHECK(result.points[1].stream_index == 7);
  CHECK(result.points[0].label == result.points[1].label);
}

TEST_CASE_TEMPLATE("insert_batch gives exactly what insert gives: rejections, stream indexes, labels, summaries",
                   Preset, sc::CArcConfig, sc::CArcCappedFastConfig) {
  // Bad records of every kind among good points; the adaptive resolution's
  // calibration ends inside a packet. Packets of 1 to 130 points, cut at the
  // retrievals; the reference engine gets the same points one by one.
  for (std::uint64_t seed = 0; seed < 12; ++seed) {
    const auto params = sc::test::short_window_params<Preset>();
    sc::StreamClusterer<Preset> single(params);
    sc::StreamClusterer<Preset> batched(params);
    const auto kind = seed % 2 == 0 ? sc::test::StreamKind::invalid_mixed : sc::test::StreamKind::blobs;
    const auto stream = sc::test::make_stream(kind, 1500, seed, 4000.0);
    std::mt19937_64 rng(seed);
    std::size_t retrievals_with_labels = 0;
    for (std::size_t offered = 0; offered < stream.size();) {
      const std::size_t stop = std::min(stream.size(), offered + 1 + static_cast<std::size_t>(rng() % 300));
      // Seeds 2, 3, 6, 7, 10, 11 also compare each point's reason (the reporting overload).
      const bool with_reasons = seed % 4 >= 2;
      std::vector<sc::RejectReason> reasons_single, reasons_batched;
      const std::size_t accepted_single =
          sc::test::offer(single, stream, offered, stop, 0, rng, with_reasons ? &reasons_single : nullptr);
      const std::size_t accepted_batched =
          sc::test::offer(batched, stream, offered, stop, 130, rng, with_reasons ? &reasons_batched : nullptr);
      INFO("seed " << seed << ", after point " << stop - 1);
      if (with_reasons) {
        REQUIRE(reasons_single.size() == stop - offered);
        CHECK(reasons_batched == reasons_single);
      }
      offered = stop;
      CHECK(accepted_batched == accepted_single);
      REQUIRE(batched.offered() == single.offered());
      CHECK(batched.rejections().by_reason == single.rejections().by_reason);
      CHECK(batched.calibrating() == single.calibrating());
      CHECK(batched.size() == single.size());
      const sc::Clustering& a = single.retrieve();
      const sc::Clustering& b = batched.retrieve();
      check_same_result(a, b);
      retrievals_with_labels += a.points.empty() ? 0 : 1;
    }
    CHECK(retrievals_with_labels > 3);
    if (kind == sc::test::StreamKind::invalid_mixed) CHECK(single.rejections().rejected() > 0);
  }
}

TEST_CASE_TEMPLATE("reserve() changes nothing a result shows, wherever the stream is when it is called", Preset,
                   sc::CArcConfig, sc::CArcCappedFastConfig, sc::CArcRebuildConfig) {
  // 3,000 points at 4 kHz through a 50 ms window (about 200 points): the
  // rings' first 1,024 slots wrap, so a reservation after point 1,024 moves
  // a window that straddles the wrap. Reservations before the first point,
  // during the calibration (point 50), mid-stream (point 1,500), and one
  // smaller than the rings (point 2,200: a no-op); a retrieval every 100
  // points, compared with an engine that never reserves.
  struct Call {
    std::size_t at;      // points offered before the call
    std::size_t points;  // reserve(points)
  };
  const Call calls[] = {{0, 4000}, {50, 5000}, {1500, 34000}, {2200, 100}};
  for (std::uint64_t seed = 0; seed < 4; ++seed) {
    const auto params = sc::test::short_window_params<Preset>();
    sc::StreamClusterer<Preset> plain(params);
    sc::StreamClusterer<Preset> reserved(params);
    const auto stream = sc::test::make_stream(sc::test::StreamKind::blobs, 3000, seed, 4000.0);
    std::mt19937_64 rng(seed);
    std::size_t retrievals_with_labels = 0;
    std::size_t offered = 0;
    const auto offer_until = [&](std::size_t end) {
      while (offered < end) {
        const std::size_t stop = std::min(end, offered + 100);
        sc::test::offer(plain, stream, offered, stop, 0, rng);
        sc::test::offer(reserved, stream, offered, stop, 0, rng);
        offered = stop;
        const sc::Clustering& a = plain.retrieve();
        const sc::Clustering& b = reserved.retrieve();
        INFO("seed " << seed << ", after point " << stop - 1);
        check_same_result(a, b);
        retrievals_with_labels += a.points.empty() ? 0 : 1;
      }
    };
    std::size_t most = 0;  // the largest reservation so far
    for (const Call& call : calls) {
      offer_until(call.at);
      const std::size_t ring_before = reserved.memory_usage().point_ring;
      reserved.reserve(call.points);
      const std::size_t ring_after = reserved.memory_usage().point_ring;
      INFO("seed " << seed << ", reserve(" << call.points << ") after point " << call.at);
      if (call.points > most) {
        CHECK(ring_after >= call.points * 16);  // at least a 16-byte record per slot
        most = call.points;
      } else {
        CHECK(ring_after == ring_before);  // never shrinks
      }
    }
    offer_until(stream.size());
    CHECK(retrievals_with_labels > 20);
  }
}

TEST_CASE("insert_batch: an empty batch changes nothing; a range overload takes containers") {
  sc::StreamClusterer<OneCellConfig> engine(one_cell_params());
  const std::vector<sc::Point> none;
  CHECK(engine.insert_batch(none) == 0);
  CHECK(engine.insert_batch(none.begin(), none.end()) == 0);
  CHECK(engine.offered() == 0);
  const std::vector<sc::Point> two{at(5.0f, 0.0f, 1.0), at(std::numeric_limits<float>::quiet_NaN(), 0.0f, 1.1),
                                   at(5.5f, 0.0f, 1.2)};
  CHECK(engine.insert_batch(two) == 2);
  CHECK(engine.offered() == 3);
  CHECK(engine.rejections()[sc::RejectReason::non_finite] == 1);
  const auto& result = engine.retrieve();
  REQUIRE(result.points.size() == 2);
  CHECK(result.points[1].stream_index == 2);
  CHECK(result.points[0].label == result.points[1].label);
}

TEST_CASE("insert_batch with reasons: one reason per point, in order, into any output iterator") {
  sc::StreamClusterer<OneCellConfig> engine(one_cell_params());
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<sc::Point> points{at(5.0f, 0.0f, 1.0), at(nan, 0.0f, 1.1), at(0.0f, 0.0f, 1.1),
                                      at(5.0f, 0.0f, 0.5), at(5.5f, 0.0f, 1.2)};
  std::array<sc::RejectReason, 6> room;
  room.fill(sc::RejectReason::accepted);
  room[5] = sc::RejectReason::non_finite;  // a guard: nothing is written past the batch
  sc::RejectReason* const end = engine.insert_batch(points.begin(), points.end(), room.data());
  CHECK(end == room.data() + 5);
  CHECK(room[0] == sc::RejectReason::accepted);
  CHECK(room[1] == sc::RejectReason::non_finite);
  CHECK(room[2] == sc::RejectReason::too_close);
  CHECK(room[3] == sc::RejectReason::time_backwards);
  CHECK(room[4] == sc::RejectReason::accepted);
  CHECK(room[5] == sc::RejectReason::non_finite);
  CHECK(engine.size() == 2);
  std::vector<sc::RejectReason> none;
  engine.insert_batch(points.end(), points.end(), std::back_inserter(none));
  CHECK(none.empty());
  CHECK(engine.offered() == 5);
}

TEST_CASE("points outside the field of view are rejected") {
  auto params = one_cell_params();
  params.projection.azimuth_min_deg = -30.0f;
  params.projection.azimuth_max_deg = 30.0f;
  sc::StreamClusterer<OneCellConfig> engine(params);
  CHECK(engine.insert(at(5.0f, 0.0f, 0.0)) == sc::RejectReason::accepted);
  CHECK(engine.insert(at(-5.0f, 0.0f, 0.1)) == sc::RejectReason::outside_fov);
  CHECK(engine.rejections()[sc::RejectReason::outside_fov] == 1);
}

TEST_CASE("an empty engine retrieves an empty result, repeatedly") {
  sc::StreamClusterer<OneCellConfig> engine(one_cell_params());
  CHECK(engine.retrieve().points.empty());
  CHECK(engine.retrieve().components.empty());
  CHECK(engine.last_result().cycle == 2);
  auto carc = sc::make_carc();
  CHECK(carc.retrieve().points.empty());
  CHECK(carc.calibrating());  // nothing to calibrate on yet
}

TEST_CASE("the time window keeps exactly the points within T_B of the newest") {
  sc::StreamClusterer<OneCellConfig> engine(one_cell_params(0.25));
  for (int i = 0; i < 10; ++i) engine.insert(at(5.0f + 0.01f * static_cast<float>(i), 0.0f, 0.1 * i));
  // newest t = 0.9: keeps t >= 0.65 -> 0.7, 0.8, 0.9
  CHECK(engine.size() == 3);
  std::vector<std::uint64_t> kept;
  engine.for_each_point([&](const sc::Sample&, std::uint64_t i) { kept.push_back(i); });
  CHECK(kept == std::vector<std::uint64_t>{7, 8, 9});
  engine.advance_to(100.0);  // a long quiet gap empties the window
  CHECK(engine.empty());
  CHECK(engine.retrieve().components.empty());
}

TEST_CASE("a zero-length time window keeps only the points of the newest timestamp") {
  sc::StreamClusterer<OneCellConfig> engine(one_cell_params(0.0));
  engine.insert(at(5.0f, 0.0f, 1.0));
  engine.insert(at(5.1f, 0.0f, 1.0));
  CHECK(engine.size() == 2);
  engine.insert(at(5.2f, 0.0f, 1.5));
  CHECK(engine.size() == 1);
}

TEST_CASE("the count window keeps the N newest points") {
  struct CountConfig : OneCellConfig {
    using window = sc::CountWindow;
  };
  sc::ClustererParams<CountConfig> params;
  params.resolution = {1, 1};
  params.window.capacity = 4;
  params.mask_size = 1;
  sc::StreamClusterer<CountConfig> engine(params);
  for (int i = 0; i < 9; ++i) engine.insert(at(5.0f + 0.1f * static_cast<float>(i), 0.0f, 0.0));
  std::vector<std::uint64_t> kept;
  engine.for_each_point([&](const sc::Sample&, std::uint64_t i) { kept.push_back(i); });
  CHECK(kept == std::vector<std::uint64_t>{5, 6, 7, 8});
}

TEST_CASE("the mask wraps around the azimuth seam and visits each cell once") {
  const sc::GridShape wrapping{4, 10, true};
  std::vector<sc::CellIndex> cells;
  sc::detail::for_each_mask_cell(wrapping, wrapping.cell_of(0.0f, 0.0f), 1, [&](sc::CellIndex c) { cells.push_back(c); });
  CHECK(cells == std::vector<sc::CellIndex>{9, 0, 1, 19, 10, 11});
  cells.clear();
  const sc::GridShape clamped{4, 10, false};
  sc::detail::for_each_mask_cell(clamped, clamped.cell_of(0.0f, 0.0f), 1, [&](sc::CellIndex c) { cells.push_back(c); });
  CHECK(cells == std::vector<sc::CellIndex>{0, 1, 10, 11});
  cells.clear();
  const sc::GridShape narrow{1, 3, true};
  sc::detail::for_each_mask_cell(narrow, 1, 3, [&](sc::CellIndex c) { cells.push_back(c); });
  CHECK(cells == std::vector<sc::CellIndex>{0, 1, 2});
}

TEST_CASE("MaskMembership agrees with the cells the mask visits, on every pair of cells") {
  // Wrapping and clamped grids, wide and narrower than the mask, at every
  // half width up to 3: b is in a's mask iff for_each_mask_cell_at around a
  // visits b, and the coordinates it reports are b's.
  for (const bool wrap : {true, false}) {
    for (const std::uint32_t cols : {1u, 2u, 3u, 5u, 7u, 9u, 16u}) {
      const sc::GridShape grid{5, cols, wrap};
      for (int half = 0; half <= 3; ++half) {
        const sc::detail::MaskMembership in_mask(grid, half);
        for (sc::CellIndex a = 0; a < grid.cell_count(); ++a) {
          std::vector<bool> visited(grid.cell_count(), false);
          sc::detail::for_each_mask_cell_at(grid, a, half, [&](sc::CellIndex c, std::int64_t row, std::int64_t col) {
            REQUIRE(row == static_cast<std::int64_t>(grid.row_of(c)));
            REQUIRE(col == static_cast<std::int64_t>(grid.col_of(c)));
            visited[c] = true;
          });
          for (sc::CellIndex b = 0; b < grid.cell_count(); ++b) {
            CAPTURE(wrap);
            CAPTURE(cols);
            CAPTURE(half);
            CAPTURE(a);
            CAPTURE(b);
            const auto ra = static_cast<std::int32_t>(grid.row_of(a));
            const auto ca = static_cast<std::int32_t>(grid.col_of(a));
            const auto rb = static_cast<std::int32_t>(grid.row_of(b));
            const auto cb = static_cast<std::int32_t>(grid.col_of(b));
            REQUIRE(in_mask(ra, ca, rb, cb) == visited[b]);
          }
        }
      }
    }
  }
}

TEST_CASE("points on both sides of the azimuth seam link through the wrap") {
  struct SeamConfig : OneCellConfig {};
  sc::ClustererParams<SeamConfig> params;
  params.resolution = {4, 360};
  params.linkage.max_distance = 0.5f;
  params.mask_size = 3;
  params.window.duration = 10.0;
  sc::StreamClusterer<SeamConfig> engine(params);
  engine.insert(sc::Point{-5.0f, 0.01f, 0.0f, 0.0f, 0.0});   // azimuth just below +180
  engine.insert(sc::Point{-5.0f, -0.01f, 0.0f, 0.0f, 0.0});  // just above -180
  CHECK(engine.grid().wrap_columns);
  CHECK(engine.retrieve().components.size() == 1);
}

TEST_CASE("invalid engine parameters are refused with a message") {
  auto params = one_cell_params();
  params.mask_size = 4;
  CHECK_THROWS_AS(sc::StreamClusterer<OneCellConfig>{params}, std::invalid_argument);
  params.mask_size = 0;
  CHECK_THROWS_AS(sc::StreamClusterer<OneCellConfig>{params}, std::invalid_argument);
  params.mask_size = -3;
  CHECK_THROWS_WITH_AS(sc::StreamClusterer<OneCellConfig>{params},
                       doctest::Contains("mask_size = -3"), std::invalid_argument);
}

TEST_CASE("component summaries: size, centroid, box, time span; range-v3 views") {
  sc::StreamClusterer<OneCellConfig> engine(one_cell_params());
  engine.insert(sc::Point{4.0f, 0.0f, 0.0f, 0.0f, 1.0});
  engine.insert(sc::Point{4.5f, 0.5f, 0.0f, 0.0f, 1.5});
  engine.insert(sc::Point{5.0f, 0.0f, 0.3f, 0.0f, 2.0});
  engine.insert(sc::Point{-9.0f, 0.0f, 0.0f, 0.0f, 2.5});
  const auto& result = engine.retrieve();
  REQUIRE(result.components.size() == 2);
  const auto big = std::find_if(result.components.begin(), result.components.end(),
                                [](const sc::ComponentSummary& c) { return c.size == 3; });
  REQUIRE(big != result.components.end());
  CHECK(big->centroid.x() == doctest::Approx(4.5));
  CHECK(big->centroid.y() == doctest::Approx(1.0 / 6.0));
  CHECK(big->centroid.z() == doctest::Approx(0.1));
  CHECK(big->min.x() == 4.0f);
  CHECK(big->max.x() == 5.0f);
  CHECK(big->max.z() == doctest::Approx(0.3));
  CHECK(big->time_begin == 1.0);
  CHECK(big->time_end == 2.0);
  int large = 0;
  for (const auto& c : result.components_with_at_least(2)) {
    CHECK(c.size >= 2);
    ++large;
  }
  CHECK(large == 1);
  std::vector<sc::ComponentId> labels;
  for (const auto l : result.labels()) labels.push_back(l);
  CHECK(labels.size() == 4);
  CHECK(labels[0] == labels[2]);
  CHECK(labels[0] != labels[3]);
}

TEST_CASE("a user's own point type with a `time` member, and an explicit time") {
  struct MyPoint {
    double x, y, z;
    double time;
  };
  sc::StreamClusterer<OneCellConfig> engine(one_cell_params(0.5));
  engine.insert(MyPoint{5.0, 0.0, 0.0, 1.0});
  engine.insert(MyPoint{5.2, 0.0, 0.0, 2.0});  // t = 2 evicts the first
  CHECK(engine.size() == 1);
  struct Untimed {
    float x, y, z;
  };
  engine.insert(Untimed{5.4f, 0.0f, 0.0f}, 2.1);
  CHECK(engine.size() == 2);
  CHECK(engine.retrieve().components.size() == 1);
}

TEST_CASE("visitor hooks: created, merged, split and evicted") {
  Events events;
  sc::ClustererParams<RecordingConfig> params;
  params.resolution = {1, 1};
  params.linkage.max_distance = 1.0f;
  params.window.duration = 1.0;
  params.mask_size = 1;
  sc::StreamClusterer<RecordingConfig> engine(params, RecordingVisitor{sc::NullVisitor{}, &events});
  engine.insert(at(5.0f, 0.0f, 0.0));
  engine.insert(at(9.0f, 0.0f, 0.0));
  CHECK(events.created.size() == 2);
  engine.advance_to(2.0);
  CHECK(events.evicted.size() == 2);
  CHECK(engine.cluster_count() == 0);
  engine.insert(at(5.0f, 0.0f, 2.0));  // reuses a recycled cluster slot
  CHECK(engine.cluster_slots() == 2);
  CHECK(engine.cluster_count() == 1);
}

TEST_CASE("batch range-image mode: displaced points are unlabelled, bucket grids lose nothing") {
  struct OverwriteConfig : OneCellConfig {
    using spatial_index = sc::OverwriteGrid;
  };
  sc::ClustererParams<OverwriteConfig> params;
  params.resolution = {1, 4};
  params.projection.azimuth_min_deg = -40.0f;
  params.projection.azimuth_max_deg = 40.0f;
  params.linkage.max_distance = 3.0f;
  params.mask_size = 3;
  std::vector<sc::Point> points = {at(5.0f, -3.0f, 0.0), at(5.0f, -2.9f, 0.0), at(5.0f, 3.0f, 0.0), at(5.0f, 0.2f, 0.0)};
  sc::BatchClusterer<OverwriteConfig> image(params, sc::BatchMode::range_image);
  const auto& r = image.cluster(points);
  REQUIRE(r.labels.size() == 4);
  CHECK(r.labels[0] == -1);  // overwritten by the second point in the same cell
  CHECK(r.labels[1] >= 0);
  CHECK(r.labels[2] >= 0);
  CHECK(r.labels[3] >= 0);

  sc::ClustererParams<OneCellConfig> bucket_params;
  bucket_params.resolution = {1, 4};
  bucket_params.projection = params.projection;
  bucket_params.linkage = params.linkage;
  bucket_params.mask_size = 3;
  sc::BatchClusterer<OneCellConfig> replay(bucket_params, sc::BatchMode::insertion_order);
  sc::BatchClusterer<OneCellConfig> snapshot(bucket_params, sc::BatchMode::range_image);
  const std::vector<std::int64_t> a = replay.cluster(points).labels;
  const std::vector<std::int64_t> b = snapshot.cluster(points).labels;
  CHECK(sc::test::partition_mismatch(a, b) == "");
  for (auto l : b) CHECK(l >= 0);
}

TEST_CASE("adaptive calibration: the first complete window chooses the grid, retrievals do not cut it short") {
  sc::CArcParams carc;
  carc.window_seconds = 0.1;
  // Irregular timestamps: no point lands exactly T_B after the first one.
  const std::vector<double> times = {0.0, 0.013, 0.031, 0.046, 0.058, 0.072, 0.089, 0.097, 0.1043, 0.12, 0.2};
  const auto point_at = [](std::size_t i, double t) {
    const float a = 0.05f * static_cast<float>(i);
    return sc::Point{5.0f * std::cos(a), 5.0f * std::sin(a), 1.0f, 0.0f, t};
  };
  SUBCASE("a retrieval at 20 Hz during the first window returns nothing and keeps buffering") {
    auto engine = sc::make_carc(carc);
    for (std::size_t i = 0; i < 5; ++i) engine.insert(point_at(i, times[i]));
    const sc::Clustering& early = engine.retrieve();  // t = 0.058 < T_B
    CHECK(early.points.empty());
    CHECK(early.cycle == 1);
    CHECK(engine.calibrating());
    CHECK(engine.size() == 5);
    for (std::size_t i = 5; i < 8; ++i) engine.insert(point_at(i, times[i]));
    CHECK(engine.calibrating());  // t = 0.097: still inside the first window
    engine.insert(point_at(8, times[8]));  // 0.1043 - 0.0 >= T_B: completes it
    CHECK_FALSE(engine.calibrating());
    // Calibrated on the 8 buffered points, then the 9th was inserted and the
    // first (t = 0) evicted: the window is (0.0043, 0.1043].
    CHECK(engine.size() == 8);
    const sc::Clustering& result = engine.retrieve();
    CHECK(result.points.size() == 8);
    CHECK(result.points.front().stream_index == 1);
  }
  SUBCASE("advance_to past the first window ends the calibration too") {
    auto engine = sc::make_carc(carc);
    for (std::size_t i = 0; i < 4; ++i) engine.insert(point_at(i, times[i]));
    engine.advance_to(0.05);
    CHECK(engine.calibrating());
    engine.advance_to(0.11);  // completes the window (0.11 - 0.0 >= T_B), then evicts t < 0.01
    CHECK_FALSE(engine.calibrating());
    CHECK(engine.retrieve().points.size() == 3);
  }
  SUBCASE("complete_calibration: a stream shorter than one window still gets labels") {
    auto engine = sc::make_carc(carc);
    for (std::size_t i = 0; i < 4; ++i) engine.insert(point_at(i, times[i]));
    CHECK(engine.retrieve().points.empty());
    engine.complete_calibration();
    CHECK_FALSE(engine.calibrating());
    CHECK(engine.retrieve().points.size() == 4);
    engine.complete_calibration();  // no-op afterwards
    CHECK(engine.size() == 4);
  }
  SUBCASE("the grid equals the resolution policy's choice on exactly the first window") {
    auto engine = sc::make_carc(carc);
    std::vector<sc::Projected> first;
    const sc::SphericalProjection projection(carc.field_of_view);
    for (std::size_t i = 0; i < times.size(); ++i) {
      engine.insert(point_at(i, times[i]));
      if (times[i] < 0.1) first.push_back(projection.project(sc::position(point_at(i, times[i]))));
    }
    sc::AdaptiveResolution reference{sc::to_clusterer_params<sc::CArcConfig>(carc).resolution};
    const sc::GridSize g = reference.calibrate(first, projection.fov_aspect());
    CHECK(engine.grid().rows == g.rows);
    CHECK(engine.grid().cols == g.cols);
  }
}
