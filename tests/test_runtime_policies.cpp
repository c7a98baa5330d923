// SPDX-License-Identifier: MIT
// Run-time selectable policies and phase timing.

#include <doctest/doctest.h>

#include <streamclust/detail/sampled_timer.hpp>
#include <streamclust/ground/runtime_ground.hpp>
#include <streamclust/linkage/runtime_linkage.hpp>
#include <streamclust/resolution/runtime_resolution.hpp>
#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/streamclust.hpp>
#include <streamclust/window/runtime_window.hpp>

#include "support/partition.hpp"
#include "support/streams.hpp"

#include <random>

namespace sc = streamclust;

namespace {
struct RuntimeConfig {
  using projection = sc::SphericalProjection;
  using spatial_index = sc::BucketGrid;
  using linkage = sc::RuntimeLinkage;
  using window = sc::RuntimeWindow;
  using resolution = sc::RuntimeResolution;
  static constexpr bool timed = true;
};
struct StaticConfig {
  using projection = sc::SphericalProjection;
  using spatial_index = sc::BucketGrid;
  using linkage = sc::EuclideanLinkage;
  using window = sc::CountWindow;
  using resolution = sc::FixedResolution;
};

sc::Sample random_sample(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  const Eigen::Vector3f p(u(rng), u(rng), u(rng));
  return sc::make_sample(p, p.norm(), 0.0f, 0.0);
}
}  // namespace

TEST_CASE("RuntimeLinkage answers exactly as the linkage it selects") {
  std::mt19937 rng(3);
  sc::RuntimeLinkage::Params p;
  p.angular.theta_deg = 25.0f;
  p.euclidean.max_distance = 4.0f;
  const sc::RuntimeLinkage angular(p);
  p.kind = sc::RuntimeLinkage::Kind::euclidean;
  const sc::RuntimeLinkage euclidean(p);
  const sc::AngularLinkage a(p.angular);
  const sc::EuclideanLinkage e(p.euclidean);
  int linked = 0;
  for (int i = 0; i < 2000; ++i) {
    const auto s = random_sample(rng);
    const auto t = random_sample(rng);
    CHECK(angular(s, t) == a(s, t));
    CHECK(euclidean(s, t) == e(s, t));
    linked += e(s, t);
  }
  CHECK(linked > 0);
  CHECK(linked < 2000);
}

TEST_CASE("RuntimeWindow and RuntimeResolution forward to the chosen policy") {
  sc::RuntimeWindow::Params w;
  w.time.duration = 0.5;
  w.count.capacity = 3;
  CHECK(sc::RuntimeWindow(w).expired(0.0, 0.6, 1));
  CHECK_FALSE(sc::RuntimeWindow(w).expired(0.0, 0.5, 100));
  w.kind = sc::RuntimeWindow::Kind::count;
  CHECK(sc::RuntimeWindow(w).expired(0.0, 0.0, 4));
  CHECK_FALSE(sc::RuntimeWindow(w).expired(0.0, 9.0, 3));

  sc::RuntimeResolution::Params r;
  r.adaptive = false;
  r.fixed = {7, 9};
  const sc::RuntimeResolution fixed(r);
  CHECK_FALSE(fixed.needs_calibration());
  CHECK(fixed.grid() == sc::GridSize{7, 9});
  r.adaptive = true;
  sc::RuntimeResolution adaptive(r);
  CHECK(adaptive.needs_calibration());
  std::vector<sc::Projected> coords;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 5000; ++i) coords.push_back(sc::Projected{u(rng), u(rng), 5.0f, sc::RejectReason::accepted});
  const sc::GridSize g = adaptive.calibrate(coords, 4.0f);
  CHECK_FALSE(adaptive.needs_calibration());
  CHECK(adaptive.grid() == g);
  CHECK_FALSE(adaptive.trace().empty());
}

TEST_CASE("a run-time configuration gives the same partition as the static one") {
  sc::ClustererParams<RuntimeConfig> rp;
  rp.linkage.kind = sc::RuntimeLinkage::Kind::euclidean;
  rp.linkage.euclidean.max_distance = 0.7f;
  rp.window.kind = sc::RuntimeWindow::Kind::count;
  rp.window.count.capacity = 300;
  rp.resolution.adaptive = false;
  rp.resolution.fixed = {12, 48};
  rp.mask_size = 3;
  sc::ClustererParams<StaticConfig> sp;
  sp.linkage.max_distance = 0.7f;
  sp.window.capacity = 300;
  sp.resolution = {12, 48};
  sp.mask_size = 3;
  sc::StreamClusterer<RuntimeConfig> dynamic(rp);
  sc::StreamClusterer<StaticConfig> fixed(sp);
  const auto stream = sc::test::make_stream(sc::test::StreamKind::blobs, 1500, 11);
  for (std::size_t i = 0; i < stream.size(); ++i) {
    dynamic.insert(stream[i]);
    fixed.insert(stream[i]);
    if (i % 100 != 99) continue;
    std::vector<sc::ComponentId> a, b;
    for (const auto& p : dynamic.retrieve().points) a.push_back(p.label);
    for (const auto& p : fixed.retrieve().points) b.push_back(p.label);
    REQUIRE(sc::test::partition_mismatch(a, b) == "");
  }
}

TEST_CASE("a timed configuration measures its phases; an untimed one reports zeros") {
  sc::ClustererParams<RuntimeConfig> rp;
  rp.window.time.duration = 0.05;
  rp.resolution.adaptive = false;
  rp.resolution.fixed = {32, 256};
  sc::StreamClusterer<RuntimeConfig> timed(rp);
  sc::ClustererParams<StaticConfig> sp;
  sp.resolution = {32, 256};
  sp.window.capacity = 10000;
  sc::StreamClusterer<StaticConfig> untimed(sp);
  sc::SyntheticStream stream;
  while (stream.time() < 0.2) {
    const auto p = stream.next();
    timed.insert(p);
    untimed.insert(p);
  }
  timed.retrieve();
  untimed.retrieve();
  const sc::PhaseTimes& t = timed.last_stats().phase_us;
  CHECK(t.insertion > 0.0);
  CHECK(t.eviction > 0.0);
  CHECK(t.labelling > 0.0);
  CHECK(t.component_update >= 0.0);
  const sc::PhaseTimes& z = untimed.last_stats().phase_us;
  CHECK(z.insertion == 0.0);
  CHECK(z.eviction == 0.0);
  CHECK(z.labelling == 0.0);
}

TEST_CASE("SampledTimer times one call in 16, passes results through, and RuntimeGround forwards while timed") {
  sc::detail::SampledTimer timer;
  auto busy = [] {
    volatile double x = 0.0;
    for (int i = 0; i < 20000; ++i) x = x + 1.0;
    return static_cast<int>(x);
  };
  for (std::uint32_t i = 1; i < sc::detail::SampledTimer::kEvery; ++i) CHECK(timer.run(busy) == 20000);
  CHECK(timer.elapsed_us() == 0.0);  // no call timed yet
  int calls = 0;
  timer.run([&calls] { ++calls; });  // the 16th call: timed, void
  CHECK(calls == 1);
  const double after_sixteen = timer.elapsed_us();
  CHECK(after_sixteen > 0.0);
  for (std::uint32_t i = 1; i < sc::detail::SampledTimer::kEvery; ++i) timer.run(busy);
  CHECK(timer.elapsed_us() == after_sixteen);
  timer.run(busy);
  CHECK(timer.elapsed_us() > after_sixteen);

  // Timed or not, RuntimeGround decides as HeightMapGround does.
  sc::RuntimeGround::Params timed_params;
  timed_params.use_height_map = true;
  timed_params.timed = true;
  sc::RuntimeGround timed(timed_params);
  sc::HeightMapGround plain;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3f p(u(rng), u(rng), i % 3 == 0 ? 0.3f * u(rng) : -1.0f);
    REQUIRE(timed.classify(p, p) == plain.classify(p, p));
  }
  CHECK(timed.elapsed_us() > 0.0);
}
