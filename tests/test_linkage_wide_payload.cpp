// SPDX-License-Identifier: MIT
// Combinators of children with different payloads (policies/streamclust/
// linkage/combined_payload.hpp): the composed payload's layout, its decisions
// against the children's on Samples, and the engine on the wide (32-byte)
// payload path against the same linkage on the Sample path and the batch
// oracle. Also the near-miss detection (concepts/*.hpp): a member named like
// an optional capability is seen apart from its signature (the compile-time
// errors themselves are tests/compile_fail/near_miss_*.cpp).

#include <doctest/doctest.h>

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/connectivity/lazy_bfs.hpp>
#include <streamclust/connectivity/spanning_forest.hpp>
#include <streamclust/connectivity/union_find_rebuild.hpp>
#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/index/overwrite_grid.hpp>
#include <streamclust/linkage/combinators.hpp>
#include <streamclust/linkage/range_adaptive.hpp>
#include <streamclust/linkage/scan_adaptive.hpp>
#include <streamclust/linkage/runtime_linkage.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/resolution/fixed.hpp>
#include <streamclust/stream_clusterer.hpp>
#include <streamclust/window/time_window.hpp>

#include "support/last_labels.hpp"
#include "support/partition.hpp"
#include "support/streams.hpp"

#include <cmath>
#include <cstdint>
#include <random>
#include <type_traits>
#include <vector>

namespace sc = streamclust;
namespace st = streamclust::test;

namespace {

/// A linkage the library does not ship: linked when the two intensities
/// differ by at most `max_gap`. Its payload is the intensity: 4 bytes.
struct IntensityGate {
  struct Params {
    float max_gap = 20.0f;  ///< [intensity units]
  };
  struct Payload {
    float intensity;
  };
  explicit IntensityGate(const Params& p) : max_gap(p.max_gap) {}
  static Payload make_payload(const sc::Sample& s) { return Payload{s.intensity}; }
  bool operator()(const Payload& a, const Payload& b) const { return std::fabs(a.intensity - b.intensity) <= max_gap; }
  bool operator()(const sc::Sample& a, const sc::Sample& b) const { return (*this)(make_payload(a), make_payload(b)); }
  float max_gap;
};

/// `L` behind its Sample operator only: what the engine ran before a
/// combinator of different payloads had one.
template <class L>
struct SamplePathOnly {
  using Params = typename L::Params;
  explicit SamplePathOnly(const Params& p) : inner(p) {}
  bool operator()(const sc::Sample& a, const sc::Sample& b) const { return inner(a, b); }
  L inner;
};

using Gated = sc::AllOf<sc::RangeAdaptiveLinkage, IntensityGate>;
using GatedPayload = sc::linkage_payload_t<Gated>;

template <class Linkage>
struct ForestCfg {
  using projection = sc::SphericalProjection;
  using spatial_index = sc::CappedGrid;
  using linkage = Linkage;
  using window = sc::TimeWindow;
  using resolution = sc::FixedResolution;
  using connectivity = sc::SpanningForestConnectivity;
};

template <class Config>
sc::ClustererParams<Config> gated_params_for(std::uint64_t seed) {
  sc::ClustererParams<Config> p;
  p.mask_size = 3 + 2 * static_cast<int>(seed % 3);
  p.resolution = {12, 48};
  const double durations[] = {0.05, 0.3, 1.2};
  p.window.duration = durations[seed % 3];
  p.spatial_index.capacity = 2 + static_cast<std::uint32_t>(seed % 3);
  std::get<0>(p.linkage).min_distance = 0.3f + 0.2f * static_cast<float>(seed % 4);
  std::get<1>(p.linkage).max_gap = 10.0f + 10.0f * static_cast<float>(seed % 3);
  return p;
}

/// A test stream with intensities in [0, 100): clusters of a few levels,
/// so that the gate splits some neighbours and keeps others.
std::vector<sc::Point> gated_stream(st::StreamKind kind, std::size_t n, std::uint64_t seed) {
  auto stream = st::make_stream(kind, n, seed, 2000.0);
  std::mt19937 rng(static_cast<std::uint32_t>(seed) + 17u);
  for (auto& p : stream) p.intensity = 25.0f * static_cast<float>(rng() % 4) + static_cast<float>(rng() % 8);
  return stream;
}

using st::last_labels;

// Near misses: named like a capability, without its signature.
struct NonConstLinkMany : sc::RangeAdaptiveLinkage {
  using RangeAdaptiveLinkage::RangeAdaptiveLinkage;
  void link_many(const Payload&, const Payload*, const std::uint32_t*, std::size_t, std::uint8_t*) {}
};
struct MemberMakePayload {
  struct Params {};
  struct Payload {
    float range;
  };
  explicit MemberMakePayload(const Params&) {}
  Payload make_payload(const sc::Sample& s) { return Payload{s.range}; }  // neither static nor const
  bool operator()(const Payload& a, const Payload& b) const { return a.range == b.range; }
  bool operator()(const sc::Sample&, const sc::Sample&) const { return true; }
};

}  // namespace

// the composed payload: the 16-byte range-adaptive part and the 4-byte gate, 32 bytes, 32-aligned
static_assert(sc::has_linkage_payload_v<Gated> && sc::is_linkage_payload_valid_v<Gated>);
static_assert(sizeof(GatedPayload) == 32 && alignof(GatedPayload) == 32);
static_assert(std::is_trivially_copyable_v<GatedPayload>);
static_assert(!sc::has_linkage_ray_payload_v<Gated>);
// link_many from the first child's: the range-adaptive one, not the gate's (it has none)
static_assert(sc::has_linkage_link_many_v<Gated>);
static_assert(!sc::has_linkage_link_many_v<sc::AnyOf<IntensityGate, sc::RangeAdaptiveLinkage>>);
static_assert(sizeof(sc::linkage_payload_t<sc::AnyOf<IntensityGate, sc::RangeAdaptiveLinkage>>) == 32);
// a shared payload stays the children's own (16 bytes)
static_assert(std::is_same_v<sc::linkage_payload_t<sc::AllOf<sc::RangeAdaptiveLinkage, sc::RangeAdaptiveLinkage>>,
                             sc::RangeAdaptiveLinkage::Payload>);
// a nested combinator of one payload type shares it
static_assert(sizeof(sc::linkage_payload_t<sc::AllOf<IntensityGate, sc::AnyOf<IntensityGate>>>) == 4);
// the angular part carries the ray: the composed payload does too
static_assert(sc::has_linkage_ray_payload_v<sc::AngularOrEuclidean>);
// over 32 bytes together (16 + 16 + 4): the Sample path
static_assert(!sc::has_linkage_payload_v<sc::AllOf<sc::AngularLinkage, sc::EuclideanLinkage, IntensityGate>>);
static_assert(!sc::has_linkage_payload_v<sc::AllOf<sc::RangeAdaptiveLinkage, SamplePathOnly<IntensityGate>>>);
static_assert(sc::StreamClusterer<ForestCfg<Gated>>::uses_payload);
static_assert(!sc::StreamClusterer<ForestCfg<SamplePathOnly<Gated>>>::uses_payload);
// a const member make_payload is a bound payload: the engine's, not a combinator's
static_assert(sc::has_linkage_bound_payload_v<sc::ScanAdaptiveLinkage> &&
              !sc::has_linkage_static_payload_v<sc::ScanAdaptiveLinkage>);
static_assert(sc::has_linkage_static_payload_v<sc::RangeAdaptiveLinkage> &&
              !sc::has_linkage_bound_payload_v<sc::RangeAdaptiveLinkage>);
static_assert(!sc::has_linkage_payload_v<sc::AllOf<sc::RangeAdaptiveLinkage, sc::ScanAdaptiveLinkage>>);
static_assert(sc::StreamClusterer<ForestCfg<sc::ScanAdaptiveLinkage>>::uses_payload &&
              sc::StreamClusterer<ForestCfg<sc::ScanAdaptiveLinkage>>::tests_many);
// near misses are told apart from absent capabilities
static_assert(sc::detail::names_link_many<NonConstLinkMany> && !sc::has_linkage_link_many_v<NonConstLinkMany>);
static_assert(sc::detail::names_make_payload<MemberMakePayload> && !sc::has_linkage_payload_v<MemberMakePayload>);
static_assert(!sc::detail::names_link_many<sc::EuclideanLinkage> && !sc::detail::names_restore_ray<Gated>);
static_assert(sc::detail::names_Payload<Gated> && !sc::detail::names_Payload<SamplePathOnly<Gated>>);
static_assert(sc::detail::names_gather<sc::CappedGrid> && !sc::detail::names_youngest<sc::CappedGrid>);
// and every standard policy passes the near-miss checks
static_assert(sc::detail::check_linkage_capabilities<sc::EuclideanLinkage>() &&
              sc::detail::check_linkage_capabilities<sc::AngularLinkage>() &&
              sc::detail::check_linkage_capabilities<sc::RangeAdaptiveLinkage>() &&
              sc::detail::check_linkage_capabilities<sc::ScanAdaptiveLinkage>() &&
              sc::detail::check_linkage_capabilities<sc::RuntimeLinkage>() &&
              sc::detail::check_linkage_capabilities<sc::AngularOrEuclidean>() &&
              sc::detail::check_linkage_capabilities<Gated>());
static_assert(sc::detail::check_spatial_index_capabilities<sc::BucketGrid>() &&
              sc::detail::check_spatial_index_capabilities<sc::CappedGrid>() &&
              sc::detail::check_spatial_index_capabilities<sc::OverwriteGrid>());
static_assert(sc::detail::check_connectivity_capabilities<sc::LazyBfsConnectivity>() &&
              sc::detail::check_connectivity_capabilities<sc::UnionFindRebuildConnectivity>() &&
              sc::detail::check_connectivity_capabilities<sc::SpanningForestConnectivity>());

TEST_CASE("a composed payload decides as its children on Samples, bit for bit") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coord(-6.0f, 6.0f);
  std::uniform_real_distribution<float> level(0.0f, 60.0f);
  auto sample = [&] {
    const Eigen::Vector3f position(coord(rng), coord(rng), coord(rng));
    return sc::make_sample(position, position.norm(), level(rng), 0.0);
  };
  const sc::RangeAdaptiveLinkage::Params range{0.4f, 0.1f};
  const IntensityGate::Params gap{15.0f};
  const Gated all{{range, gap}};
  const sc::AnyOf<IntensityGate, sc::RangeAdaptiveLinkage> any{{gap, range}};
  const sc::RangeAdaptiveLinkage by_range{range};
  const IntensityGate by_gap{gap};
  std::size_t both = 0;
  std::size_t either = 0;
  for (int i = 0; i < 20000; ++i) {
    const sc::Sample a = sample();
    const sc::Sample b = i % 3 == 0 ? a : sample();  // some coincident pairs
    const bool r = by_range(a, b);
    const bool g = by_gap(a, b);
    const GatedPayload pa = Gated::make_payload(a);
    const GatedPayload pb = Gated::make_payload(b);
    REQUIRE(all(pa, pb) == (r && g));
    REQUIRE(all(a, b) == (r && g));
    REQUIRE(all(pb, pa) == all(pa, pb));
    const auto qa = decltype(any)::make_payload(a);
    const auto qb = decltype(any)::make_payload(b);
    REQUIRE(any(qa, qb) == (r || g));
    REQUIRE(any(a, b) == (r || g));
    both += r && g ? 1u : 0u;
    either += r != g ? 1u : 0u;
  }
  CHECK(both > 100);    // the two criteria agree often ...
  CHECK(either > 100);  // ... and disagree often: AND and OR both exercised
}

TEST_CASE("a combinator's link_many decides as its pairwise operator, across blocks of candidates") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coord(-0.5f, 0.5f);
  std::uniform_real_distribution<float> level(0.0f, 60.0f);
  std::vector<GatedPayload> ring;
  std::vector<sc::AngularOrEuclidean::Payload> hybrid_ring;
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector3f position(coord(rng), coord(rng), coord(rng) + 4.0f);
    const sc::Sample s = sc::make_sample(position, position.norm(), level(rng), 0.0);
    ring.push_back(Gated::make_payload(s));
    hybrid_ring.push_back(sc::AngularOrEuclidean::make_payload(s));
  }
  const Gated gated{{{0.5f, 0.1f}, {30.0f}}};
  const sc::AngularOrEuclidean hybrid{{{20.0f, 0.2f}, {0.4f}}};
  std::vector<std::uint32_t> slots;
  std::vector<std::uint8_t> linked;
  std::size_t ones = 0;
  std::size_t total = 0;
  for (std::size_t i = 0; i < ring.size(); i += 13) {
    const std::size_t count = 1 + rng() % 200;  // up to three blocks and a partial one
    slots.resize(count);
    for (auto& slot : slots) slot = static_cast<std::uint32_t>(rng() % ring.size());
    linked.assign(count + 1, 7);
    gated.link_many(ring[i], ring.data(), slots.data(), count, linked.data());
    for (std::size_t k = 0; k < count; ++k) REQUIRE(linked[k] == (gated(ring[i], ring[slots[k]]) ? 1u : 0u));
    REQUIRE(linked[count] == 7);  // nothing written past count
    for (std::size_t k = 0; k < count; ++k) ones += linked[k];
    total += count;
    linked.assign(count + 1, 7);
    hybrid.link_many(hybrid_ring[i], hybrid_ring.data(), slots.data(), count, linked.data());
    for (std::size_t k = 0; k < count; ++k)
      REQUIRE(linked[k] == (hybrid(hybrid_ring[i], hybrid_ring[slots[k]]) ? 1u : 0u));
    REQUIRE(linked[count] == 7);
  }
  CHECK(ones > total / 20);  // both outcomes occur
  CHECK(ones < total - total / 20);
}

TEST_CASE("the wide payload path gives the Sample path's partition, equal to the batch clusterer") {
  using Wide = ForestCfg<Gated>;
  using Plain = ForestCfg<SamplePathOnly<Gated>>;
  std::size_t compared = 0;
  std::size_t multi = 0;
  std::size_t gated = 0;
  for (std::uint64_t seed = 0; seed < 12; ++seed) {
    const auto kind = static_cast<st::StreamKind>(seed % static_cast<std::uint64_t>(st::StreamKind::count_));
    const auto stream = gated_stream(kind, seed % 4 < 2 ? 500 : 2600, seed);
    sc::StreamClusterer<Wide> wide(gated_params_for<Wide>(seed));
    sc::StreamClusterer<Plain> plain(gated_params_for<Plain>(seed));
    sc::BatchClusterer<Plain> batch(gated_params_for<Plain>(seed));
    const auto ungated_params = [&] {
      auto p = gated_params_for<Plain>(seed);
      std::get<1>(p.linkage).max_gap = 1000.0f;
      return p;
    }();
    sc::BatchClusterer<Plain> ungated(ungated_params);
    for (std::size_t i = 0; i < stream.size(); ++i) {
      wide.insert(stream[i]);
      plain.insert(stream[i]);
      if (i % 41 != 40) continue;
      wide.retrieve();
      plain.retrieve();
      INFO("seed " << seed << ", stream " << st::to_string(kind) << ", after point " << i);
      REQUIRE(wide.size() == plain.size());
      REQUIRE(last_labels(wide) == last_labels(plain));
      std::vector<sc::Sample> window;
      wide.for_each_point([&](const sc::Sample& s, std::uint64_t) { window.push_back(s); });
      batch.set_grid({wide.grid().rows, wide.grid().cols});
      REQUIRE(st::partition_mismatch(last_labels(wide), batch.cluster(window).labels) == "");
      // the ring holds the composed payload of every live sample
      for (std::size_t pos = 0; pos < wide.size(); pos += 7) {
        const sc::PointHandle h = wide.handle_at(pos);
        const GatedPayload& stored = wide.payload(h);
        const sc::Sample s = wide.sample(h);
        REQUIRE(stored.parts.head.range == s.range);
        REQUIRE(stored.parts.tail.head.intensity == s.intensity);
      }
      ungated.set_grid({wide.grid().rows, wide.grid().cols});
      gated += ungated.cluster(window).components < wide.last_result().components.size() ? 1u : 0u;
      ++compared;
      multi += wide.last_result().components.size() > 1 ? 1u : 0u;
    }
  }
  CHECK(compared > 100);
  CHECK(multi > compared / 4);  // not a trivial partition
  CHECK(gated > compared / 4);  // the gate's part of the payload matters
}

TEST_CASE("memory_usage counts 32 payload bytes per ring slot for the composed payload") {
  using Wide = ForestCfg<Gated>;
  using Plain = ForestCfg<SamplePathOnly<Gated>>;
  sc::StreamClusterer<Wide> wide(gated_params_for<Wide>(1));
  sc::StreamClusterer<Plain> plain(gated_params_for<Plain>(1));
  for (const auto& p : gated_stream(st::StreamKind::blobs, 3000, 3)) {
    wide.insert(p);
    plain.insert(p);
  }
  REQUIRE(wide.size() == plain.size());
  const std::size_t extra = wide.memory_usage().point_ring - plain.memory_usage().point_ring;
  CHECK(extra > 0);
  CHECK(extra % 32 == 0);
  CHECK(extra / 32 >= wide.size());
}
