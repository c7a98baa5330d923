// SPDX-License-Identifier: MIT
// The optional compact linkage payload (concepts/linkage.hpp, optimization
// log section 10): detection, the engine's payload path against its Sample
// path (a linkage without the capability) on the same streams, and the
// memory of the payload ring.

#include <doctest/doctest.h>

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/connectivity/lazy_bfs.hpp>
#include <streamclust/connectivity/union_find_rebuild.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/combinators.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/linkage/runtime_linkage.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/resolution/fixed.hpp>
#include <streamclust/stream_clusterer.hpp>
#include <streamclust/window/time_window.hpp>

#include "support/last_labels.hpp"
#include "support/partition.hpp"
#include "support/streams.hpp"

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

namespace sc = streamclust;
namespace st = streamclust::test;

namespace {

/// A linkage WITHOUT the payload capability: AngularLinkage behind the
/// Sample operator only. The engine must take its Sample path and decide the
/// same as with AngularLinkage (whose Sample operator is its payload one).
struct SampleOnlyAngular {
  using Params = sc::AngularLinkage::Params;
  explicit SampleOnlyAngular(const Params& p) : inner(p) {}
  bool operator()(const sc::Sample& a, const sc::Sample& b) const { return inner(a, b); }
  sc::AngularLinkage inner;
};

/// AngularLinkage's payload WITHOUT `restore_ray`: the engine keeps a payload
/// ring and full 40-byte Samples (no compact samples).
struct PayloadNoRayAngular {
  using Params = sc::AngularLinkage::Params;
  using Payload = sc::AngularLinkage::Payload;
  explicit PayloadNoRayAngular(const Params& p) : inner(p) {}
  static Payload make_payload(const sc::Sample& s) { return sc::AngularLinkage::make_payload(s); }
  bool operator()(const Payload& a, const Payload& b) const { return inner(a, b); }
  bool operator()(const sc::Sample& a, const sc::Sample& b) const { return inner(a, b); }
  sc::AngularLinkage inner;
};

/// Fields of two Samples equal bit for bit (as floats: -0 == +0 aside).
void require_same_sample(const sc::Sample& a, const sc::Sample& b) {
  for (int c = 0; c < 3; ++c) {
    REQUIRE(a.position[c] == b.position[c]);
    REQUIRE(a.direction[c] == b.direction[c]);
  }
  REQUIRE(a.range == b.range);
  REQUIRE(a.intensity == b.intensity);
  REQUIRE(a.time == b.time);
}

/// A payload over the 32-byte limit: detected, but invalid.
struct WidePayloadLinkage {
  struct Params {};
  struct Payload {
    float v[9];
  };
  explicit WidePayloadLinkage(const Params&) {}
  static Payload make_payload(const sc::Sample& s) { return Payload{{s.position.x()}}; }
  bool operator()(const Payload& a, const Payload& b) const { return a.v[0] == b.v[0]; }
  bool operator()(const sc::Sample& a, const sc::Sample& b) const { return (*this)(make_payload(a), make_payload(b)); }
};

/// make_payload returning another type than Payload: not the capability.
struct MismatchedPayloadLinkage {
  struct Params {};
  struct Payload {
    float x;
  };
  explicit MismatchedPayloadLinkage(const Params&) {}
  static float make_payload(const sc::Sample& s) { return s.range; }
  bool operator()(const Payload&, const Payload&) const { return true; }
  bool operator()(const sc::Sample&, const sc::Sample&) const { return true; }
};

template <class Linkage, class Connectivity = sc::LazyBfsConnectivity>
struct Cfg {
  using projection = sc::SphericalProjection;
  using spatial_index = sc::CappedGrid;
  using linkage = Linkage;
  using window = sc::TimeWindow;
  using resolution = sc::FixedResolution;
  using connectivity = Connectivity;
};

template <class Config>
sc::ClustererParams<Config> params_for(std::uint64_t seed) {
  sc::ClustererParams<Config> p;
  p.mask_size = 3 + 2 * static_cast<int>(seed % 3);
  p.resolution = {12, 48};
  const double durations[] = {0.05, 0.2, 0.6, 1.2};  // the longer ones grow the rings with live points
  p.window.duration = durations[seed % 4];
  p.spatial_index.capacity = 2 + static_cast<std::uint32_t>(seed % 3);
  p.linkage.theta_deg = 10.0f + 5.0f * static_cast<float>(seed % 5);
  p.linkage.min_ray_angle_deg = seed % 2 ? 0.2f : 0.0f;
  return p;
}

using st::last_labels;

}  // namespace

static_assert(sc::has_linkage_payload_v<sc::AngularLinkage>);
static_assert(sc::has_linkage_payload_v<sc::EuclideanLinkage>);
static_assert(std::is_same_v<sc::linkage_payload_t<sc::AngularLinkage>, sc::AngularLinkage::Payload>);
static_assert(sizeof(sc::AngularLinkage::Payload) == 16 && alignof(sc::AngularLinkage::Payload) == 16);
static_assert(sizeof(sc::EuclideanLinkage::Payload) == 16 && alignof(sc::EuclideanLinkage::Payload) == 16);
static_assert(std::is_trivially_copyable_v<sc::AngularLinkage::Payload>);
static_assert(std::is_trivially_copyable_v<sc::EuclideanLinkage::Payload>);
// combinators: children sharing one payload type, or different ones composed
// (tests/test_linkage_wide_payload.cpp)
static_assert(sc::has_linkage_payload_v<sc::AllOf<sc::AngularLinkage, sc::AngularLinkage>>);
static_assert(sc::has_linkage_payload_v<sc::AnyOf<sc::EuclideanLinkage>>);
static_assert(sc::has_linkage_payload_v<sc::AngularOrEuclidean>);
static_assert(!sc::has_linkage_payload_v<sc::AllOf<sc::AngularLinkage, SampleOnlyAngular>>);
static_assert(!sc::has_linkage_payload_v<sc::AllOf<>>);
static_assert(!sc::has_linkage_payload_v<sc::RuntimeLinkage>);
// without the capability: the Sample path, NoPayload, no ring
static_assert(!sc::has_linkage_payload_v<SampleOnlyAngular>);
static_assert(std::is_same_v<sc::linkage_payload_t<SampleOnlyAngular>, sc::detail::NoPayload>);
static_assert(sc::is_linkage_payload_valid_v<SampleOnlyAngular>);
static_assert(!sc::has_linkage_payload_v<MismatchedPayloadLinkage>);
// detected but too wide: the engine's config check rejects it
static_assert(sc::has_linkage_payload_v<WidePayloadLinkage>);
static_assert(!sc::is_linkage_payload_valid_v<WidePayloadLinkage>);
static_assert(sc::StreamClusterer<Cfg<sc::AngularLinkage>>::uses_payload);
static_assert(!sc::StreamClusterer<Cfg<SampleOnlyAngular>>::uses_payload);
// the ray refinement: angular payloads carry it, Euclidean's (a position) does not
static_assert(sc::has_linkage_ray_payload_v<sc::AngularLinkage>);
static_assert(sc::has_linkage_ray_payload_v<sc::AllOf<sc::AngularLinkage, sc::AngularLinkage>>);
static_assert(!sc::has_linkage_ray_payload_v<sc::EuclideanLinkage>);
static_assert(!sc::has_linkage_ray_payload_v<sc::AnyOf<sc::EuclideanLinkage>>);
static_assert(!sc::has_linkage_ray_payload_v<PayloadNoRayAngular>);
static_assert(!sc::has_linkage_ray_payload_v<SampleOnlyAngular>);
static_assert(sc::StreamClusterer<Cfg<sc::AngularLinkage>>::compact_samples);
static_assert(!sc::StreamClusterer<Cfg<PayloadNoRayAngular>>::compact_samples);
static_assert(sc::StreamClusterer<Cfg<PayloadNoRayAngular>>::uses_payload);

TEST_CASE_TEMPLATE("payload path and Sample path give the same partition, equal to the batch clusterer", Conn,
                   sc::LazyBfsConnectivity, sc::UnionFindRebuildConnectivity) {
  using Fast = Cfg<sc::AngularLinkage, Conn>;
  using Plain = Cfg<SampleOnlyAngular, Conn>;
  std::size_t compared = 0;
  std::size_t multi = 0;
  std::size_t grown = 0;
  for (std::uint64_t seed = 0; seed < 24; ++seed) {
    const auto kind = static_cast<st::StreamKind>(seed % static_cast<std::uint64_t>(st::StreamKind::count_));
    const auto stream = st::make_stream(kind, seed % 4 < 2 ? 400 : 2600, seed, 2000.0);
    sc::StreamClusterer<Fast> fast(params_for<Fast>(seed));
    sc::StreamClusterer<Plain> plain(params_for<Plain>(seed));
    sc::BatchClusterer<Plain> batch(params_for<Plain>(seed));
    for (std::size_t i = 0; i < stream.size(); ++i) {
      fast.insert(stream[i]);
      plain.insert(stream[i]);
      if (i % 37 != 36) continue;
      fast.retrieve();
      plain.retrieve();
      INFO("seed " << seed << ", stream " << st::to_string(kind) << ", after point " << i);
      REQUIRE(fast.size() == plain.size());
      // the same point ids and the same labels: ids follow the same history
      REQUIRE(last_labels(fast) == last_labels(plain));
      const auto& fp = fast.last_result().points;
      const auto& pp = plain.last_result().points;
      for (std::size_t k = 0; k < fp.size(); ++k) REQUIRE(fp[k].stream_index == pp[k].stream_index);
      // and the partition of the Sample-path batch oracle
      std::vector<sc::Sample> window;
      fast.for_each_point([&](const sc::Sample& s, std::uint64_t) { window.push_back(s); });
      batch.set_grid({fast.grid().rows, fast.grid().cols});
      REQUIRE(st::partition_mismatch(last_labels(fast), batch.cluster(window).labels) == "");
      // the payload ring holds make_payload of every live sample
      for (std::size_t pos = 0; pos < fast.size(); ++pos) {
        const sc::PointHandle h = fast.handle_at(pos);
        const sc::AngularLinkage::Payload expected = sc::AngularLinkage::make_payload(fast.sample(h));
        const sc::AngularLinkage::Payload& stored = fast.payload(h);
        for (int c = 0; c < 3; ++c) REQUIRE(stored.direction[c] == expected.direction[c]);
        REQUIRE(stored.range == expected.range);
        // the Sample rebuilt from the compact ring and the payload is the
        // one the Sample path stored
        require_same_sample(fast.sample(h), plain.sample(plain.handle_at(pos)));
      }
      ++compared;
      multi += fast.last_result().components.size() > 1 ? 1u : 0u;
      grown += fast.size() > 1024 ? 1u : 0u;
    }
  }
  CHECK(compared > 100);
  CHECK(multi > compared / 4);  // not a trivial partition
  CHECK(grown > 0);             // rings grew (1024 -> 2048 slots or more) with live points
}

TEST_CASE("memory_usage counts the payload ring (16 bytes per slot) and the compact samples (16 fewer)") {
  using Compact = Cfg<sc::AngularLinkage>;  // payload with the ray: 24-byte samples
  using NoRay = Cfg<PayloadNoRayAngular>;   // payload without it: 40-byte samples
  using Plain = Cfg<SampleOnlyAngular>;     // no payload ring
  sc::StreamClusterer<Compact> compact(params_for<Compact>(3));
  sc::StreamClusterer<NoRay> noray(params_for<NoRay>(3));
  sc::StreamClusterer<Plain> plain(params_for<Plain>(3));
  CHECK(compact.memory_usage().point_ring == 0);
  const auto stream = st::make_stream(st::StreamKind::blobs, 3000, 5, 2000.0);
  for (const auto& p : stream) {
    compact.insert(p);
    noray.insert(p);
    plain.insert(p);
  }
  REQUIRE(compact.size() == plain.size());
  REQUIRE(noray.size() == plain.size());
  const sc::MemoryUsage mc = compact.memory_usage();
  const sc::MemoryUsage mn = noray.memory_usage();
  const sc::MemoryUsage mp = plain.memory_usage();
  REQUIRE(mp.point_ring > 0);
  // the same ring capacity (>= 1024 slots): the difference is the payload ring
  REQUIRE(mn.point_ring > mp.point_ring);
  const std::size_t extra = mn.point_ring - mp.point_ring;
  CHECK(extra % sizeof(sc::AngularLinkage::Payload) == 0);
  const std::size_t ring_slots = extra / sizeof(sc::AngularLinkage::Payload);
  CHECK(ring_slots >= compact.size());
  CHECK(ring_slots >= 1024);               // the smallest ring
  CHECK(mp.point_ring % ring_slots == 0);  // the Sample and record rings have as many slots
  CHECK(mn.total() == mp.total() + extra);
  // compact samples: 24 bytes instead of 40 per slot, so the payload ring is free
  CHECK(mn.point_ring - mc.point_ring == ring_slots * (sizeof(sc::Sample) - 24));
  CHECK(mc.point_ring == mp.point_ring);
  // and every rebuilt Sample equals the stored one of the Sample path
  for (std::size_t pos = 0; pos < compact.size(); ++pos)
    require_same_sample(compact.sample(compact.handle_at(pos)), plain.sample(plain.handle_at(pos)));
}
