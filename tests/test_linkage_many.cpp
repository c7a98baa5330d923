// SPDX-License-Identifier: MIT
// The optional one-against-many linkage test (`link_many`,
// concepts/linkage.hpp): detection, and AngularLinkage's vectorised version
// against its pairwise operator, decision by decision, on random pairs, on
// pairs a few ulps either side of the threshold, on ties and on the floor.

#include <doctest/doctest.h>

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/combinators.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/linkage/range_adaptive.hpp>
#include <streamclust/linkage/runtime_linkage.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/resolution/fixed.hpp>
#include <streamclust/window/time_window.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace sc = streamclust;

namespace {

using Payload = sc::AngularLinkage::Payload;

/// A payload with unit direction (azimuth, elevation) [rad] and range [m].
Payload ray_payload(double azimuth, double elevation, float range) {
  const auto x = static_cast<float>(std::cos(elevation) * std::cos(azimuth));
  const auto y = static_cast<float>(std::cos(elevation) * std::sin(azimuth));
  const auto z = static_cast<float>(std::sin(elevation));
  return Payload{{x, y, z}, range};
}

/// Tests `a` against every payload of `ring` through link_many, in a shuffled
/// slot order (and with every count from 0 up, so that each SIMD tail length
/// is taken), and requires the pairwise operator's decision for each.
/// Returns how many of the decisions were "linked".
template <class Link, class P>
std::size_t require_same_decisions(const Link& link, const P& a, const std::vector<P>& ring, std::mt19937& rng) {
  std::vector<std::uint32_t> slots(ring.size());
  for (std::uint32_t i = 0; i < slots.size(); ++i) slots[i] = i;
  std::shuffle(slots.begin(), slots.end(), rng);
  std::vector<std::uint8_t> linked(ring.size() + 1, 7);
  std::size_t positive = 0;
  std::vector<std::size_t> counts;  // every length up to 9, then some, then all
  for (std::size_t count = 0; count < ring.size(); count += count < 9 ? 1 : 5) counts.push_back(count);
  counts.push_back(ring.size());
  for (const std::size_t count : counts) {
    std::fill(linked.begin(), linked.end(), std::uint8_t{7});
    link.link_many(a, ring.data(), slots.data(), count, linked.data());
    for (std::size_t k = 0; k < count; ++k) {
      const bool pairwise = link(a, ring[slots[k]]);
      INFO("count " << count << ", candidate " << k << ", slot " << slots[k]);
      REQUIRE(linked[k] == (pairwise ? 1u : 0u));
      REQUIRE(link(ring[slots[k]], a) == pairwise);  // and symmetric
      positive += pairwise && count == ring.size() ? 1u : 0u;
    }
    REQUIRE(linked[count] == 7);  // nothing written past count
  }
  return positive;
}

}  // namespace

static_assert(sc::has_linkage_link_many_v<sc::AngularLinkage>);
static_assert(sc::has_linkage_link_many_v<sc::RangeAdaptiveLinkage>);
static_assert(!sc::has_linkage_link_many_v<sc::EuclideanLinkage>);
// combinators: when their first child has it (tests/test_linkage_wide_payload.cpp)
static_assert(sc::has_linkage_link_many_v<sc::AllOf<sc::AngularLinkage, sc::AngularLinkage>>);
static_assert(sc::has_linkage_link_many_v<sc::AngularOrEuclidean>);
static_assert(!sc::has_linkage_link_many_v<sc::AnyOf<sc::EuclideanLinkage, sc::AngularLinkage>>);
static_assert(!sc::has_linkage_link_many_v<sc::RuntimeLinkage>);

TEST_CASE("AngularLinkage::link_many decides as the pairwise operator on random rays") {
  std::mt19937 rng(20261125);
  std::uniform_real_distribution<double> angle(-0.01, 0.01);  // [rad]: neighbours in a mask, ~0.6 degrees
  std::uniform_real_distribution<float> range(0.3f, 40.0f);
  std::uniform_real_distribution<float> depth(-0.02f, 0.02f);  // relative depth noise of a surface
  std::size_t positive = 0;
  std::size_t total = 0;
  for (const float theta : {5.0f, 10.0f, 30.0f, 80.0f}) {
    for (const float floor : {0.0f, 0.2f, 2.0f}) {
      const sc::AngularLinkage link{{theta, floor}};
      for (int trial = 0; trial < 40; ++trial) {
        const double az = angle(rng) * 200.0;
        const double el = angle(rng) * 50.0;
        const float r = range(rng);
        const Payload a = ray_payload(az, el, r);
        std::vector<Payload> ring;
        for (int k = 0; k < 37; ++k) {
          // near rays at ranges near r (surfaces) and anywhere (depth jumps)
          const float rb = k % 3 == 0 ? range(rng) : r * (1.0f + depth(rng));
          ring.push_back(ray_payload(az + angle(rng), el + angle(rng), rb));
        }
        positive += require_same_decisions(link, a, ring, rng);
        total += ring.size();
      }
    }
  }
  // both outcomes well represented
  CHECK(positive > total / 10);
  CHECK(positive < total - total / 10);
}

TEST_CASE("AngularLinkage::link_many decides as the pairwise operator a few ulps either side of the threshold") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-0.02, 0.02);
  std::size_t flips = 0;
  for (const float theta : {10.0f, 30.0f, 80.0f}) {
    for (const float floor : {0.0f, 0.2f}) {
      const sc::AngularLinkage link{{theta, floor}};
      for (int trial = 0; trial < 60; ++trial) {
        const double az = angle(rng) * 50.0;
        const double el = angle(rng) * 20.0;
        const Payload a = ray_payload(az, el, 10.0f);
        const double daz = angle(rng);
        const double del = angle(rng);
        // Bisect the nearer range d2 of b until the decision flips between
        // two adjacent floats: linked near d2 = 10 (a surface), not near 0.
        float lo = 1e-3f;
        float hi = 10.0f;
        const auto at = [&](float d2) { return ray_payload(az + daz, el + del, d2); };
        if (link(a, at(lo)) == link(a, at(hi))) continue;
        while (std::nextafter(lo, hi) < hi) {
          const float mid = lo + (hi - lo) / 2.0f;
          if (mid <= lo || mid >= hi) break;
          (link(a, at(mid)) == link(a, at(lo)) ? lo : hi) = mid;
        }
        std::vector<Payload> ring;
        float d = lo;
        for (int step = 0; step < 6; ++step) d = std::nextafter(d, 0.0f);
        for (int step = 0; step < 14; ++step, d = std::nextafter(d, 20.0f)) ring.push_back(at(d));
        require_same_decisions(link, a, ring, rng);
        ++flips;
      }
    }
  }
  CHECK(flips > 100);  // the bisection found the threshold on most trials
}

TEST_CASE("AngularLinkage::link_many on ties: equal ranges, equal rays, the same payload, signed zeros") {
  std::mt19937 rng(3);
  for (const float floor : {0.0f, 0.2f}) {
    const sc::AngularLinkage link{{30.0f, floor}};
    const Payload a = ray_payload(0.01, 0.0, 5.0f);  // y ~ 0.01, z = +0
    std::vector<Payload> ring;
    ring.push_back(a);                               // itself
    ring.push_back(ray_payload(0.01, 0.0, 4.0f));            // same ray, nearer
    ring.push_back(ray_payload(0.01, 0.0, 6.0f));            // same ray, farther
    ring.push_back(ray_payload(0.012, 0.0, 5.0f));           // equal range, other ray
    ring.push_back(ray_payload(0.008, 0.0, 5.0f));           // equal range, other side
    ring.push_back(ray_payload(0.01, 0.001, 5.0f));          // equal range, tie broken by z
    Payload negative_zero = a;
    negative_zero.direction[2] = -0.0f;              // -0 against +0
    ring.push_back(negative_zero);
    ring.push_back(ray_payload(0.01 + 1e-6, 0.0, 5.0f));     // below the floor
    ring.push_back(ray_payload(3.0, 0.0, 5.0f));             // rays more than 90 degrees apart
    require_same_decisions(link, a, ring, rng);
    require_same_decisions(link, negative_zero, ring, rng);
  }
}

TEST_CASE("the batch clusterer with link_many gives the partition of its pairwise twin") {
  // AngularLinkage's batch run takes link_many; a wrapper without it the
  // pairwise operator. Same grid, same points: the same labels.
  struct PairwiseAngular {
    using Params = sc::AngularLinkage::Params;
    explicit PairwiseAngular(const Params& p) : inner(p) {}
    bool operator()(const sc::Sample& a, const sc::Sample& b) const { return inner(a, b); }
    sc::AngularLinkage inner;
  };
  struct Many {
    using projection = sc::SphericalProjection;
    using spatial_index = sc::BucketGrid;
    using linkage = sc::AngularLinkage;
    using window = sc::TimeWindow;
    using resolution = sc::FixedResolution;
  };
  struct Pairwise : Many {
    using linkage = PairwiseAngular;
  };
  static_assert(sc::BatchClusterer<Many>::tests_many && !sc::BatchClusterer<Pairwise>::tests_many);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coord(-8.0f, 8.0f);
  std::vector<sc::Sample> points;
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector3f p(coord(rng), coord(rng), 0.3f * coord(rng));
    sc::Sample s;
    s.position = p;
    s.range = p.norm();
    s.direction = p / s.range;
    s.time = 1e-4 * i;
    points.push_back(s);
  }
  for (const float theta : {10.0f, 30.0f}) {
    sc::ClustererParams<Many> pm;
    pm.linkage.theta_deg = theta;
    pm.resolution = {24, 96};
    sc::ClustererParams<Pairwise> pp;
    pp.linkage.theta_deg = theta;
    pp.resolution = {24, 96};
    sc::BatchClusterer<Many> many(pm);
    sc::BatchClusterer<Pairwise> pairwise(pp);
    const std::vector<std::int64_t> a = many.cluster(points).labels;
    const std::vector<std::int64_t> b = pairwise.cluster(points).labels;
    REQUIRE(a == b);
    CHECK(many.last_result().components > 10);
    CHECK(many.last_result().components < points.size() / 2);
  }
}

// ------------------------------------------------------- RangeAdaptiveLinkage

namespace {

using RangePayload = sc::RangeAdaptiveLinkage::Payload;

/// The payload of the point at `range` [m] on the ray (azimuth, elevation)
/// [rad], its position computed in double: range and position agree as a
/// sensor at rest measures them.
RangePayload point(double azimuth, double elevation, double range) {
  return RangePayload{{static_cast<float>(range * std::cos(elevation) * std::cos(azimuth)),
                       static_cast<float>(range * std::cos(elevation) * std::sin(azimuth)),
                       static_cast<float>(range * std::sin(elevation))},
                      static_cast<float>(range)};
}

}  // namespace

TEST_CASE("RangeAdaptiveLinkage::link_many decides as the pairwise operator on random points") {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> angle(-0.03, 0.03);  // [rad]: a mask's neighbourhood, ~1.7 degrees
  std::uniform_real_distribution<double> range(0.3, 60.0);
  std::uniform_real_distribution<double> depth(-0.05, 0.05);  // [m] range noise and surface relief
  std::size_t positive = 0;
  std::size_t total = 0;
  for (const float min_distance : {0.05f, 0.2f, 0.5f}) {
    for (const float factor : {0.0f, 0.01f, 0.03f, 0.1f}) {
      const sc::RangeAdaptiveLinkage link{{min_distance, factor}};
      for (int trial = 0; trial < 40; ++trial) {
        const double az = angle(rng) * 100.0;
        const double el = angle(rng) * 20.0;
        const double r = range(rng);
        const RangePayload a = point(az, el, r);
        std::vector<RangePayload> ring;
        for (int k = 0; k < 37; ++k) {
          // the same surface (range r plus noise) or anything along nearby rays
          const double rb = k % 3 == 0 ? range(rng) : r + depth(rng);
          ring.push_back(point(az + angle(rng), el + angle(rng), rb));
        }
        positive += require_same_decisions(link, a, ring, rng);
        total += ring.size();
      }
    }
  }
  CHECK(positive > total / 10);
  CHECK(positive < total - total / 10);
}

TEST_CASE("RangeAdaptiveLinkage::link_many decides as the pairwise operator a few ulps either side of the radius") {
  // b on the line from a along a random direction: bisect its distance until
  // the decision flips between two adjacent floats, then test the 14 floats
  // around the flip. The nearer range is a's or b's, so both the floor and
  // the proportional part of the radius are met.
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> range(1.0, 40.0);
  std::size_t flips = 0;
  for (const float min_distance : {0.1f, 0.3f}) {
    for (const float factor : {0.0f, 0.02f, 0.05f}) {
      const sc::RangeAdaptiveLinkage link{{min_distance, factor}};
      for (int trial = 0; trial < 50; ++trial) {
        const RangePayload a = point(0.3 * unit(rng), 0.2 * unit(rng), range(rng));
        Eigen::Vector3f step(static_cast<float>(unit(rng)), static_cast<float>(unit(rng)),
                             static_cast<float>(unit(rng)));
        step.normalize();
        const float range_b = a.range * static_cast<float>(1.0 + 0.05 * unit(rng));
        const auto at = [&](float distance) {
          return RangePayload{{a.position[0] + distance * step.x(), a.position[1] + distance * step.y(),
                               a.position[2] + distance * step.z()},
                              range_b};
        };
        float lo = 0.0f;
        float hi = 5.0f;
        if (!link(a, at(lo)) || link(a, at(hi))) continue;
        while (std::nextafter(lo, hi) < hi) {
          const float mid = lo + (hi - lo) / 2.0f;
          if (mid <= lo || mid >= hi) break;
          (link(a, at(mid)) ? lo : hi) = mid;
        }
        std::vector<RangePayload> ring;
        float d = lo;
        for (int s = 0; s < 6; ++s) d = std::nextafter(d, 0.0f);
        for (int s = 0; s < 14; ++s, d = std::nextafter(d, 10.0f)) ring.push_back(at(d));
        const std::size_t linked = require_same_decisions(link, a, ring, rng);
        CHECK(linked > 0);             // the flip lies inside the 14 floats
        CHECK(linked < ring.size());
        ++flips;
      }
    }
  }
  CHECK(flips == 300);
}

TEST_CASE("RangeAdaptiveLinkage::link_many on ties: the same payload, equal ranges, signed zeros") {
  std::mt19937 rng(5);
  const sc::RangeAdaptiveLinkage link{{0.2f, 0.03f}};
  const RangePayload a = point(0.0, 0.0, 10.0);  // y = z = +0
  std::vector<RangePayload> ring;
  ring.push_back(a);                       // itself
  RangePayload negative_zero = a;
  negative_zero.position[1] = -0.0f;       // -0 against +0
  ring.push_back(negative_zero);
  ring.push_back(point(0.0, 0.0, 10.3));   // 0.3 m behind: radius 0.3 at the nearer 10 m
  ring.push_back(point(0.0, 0.0, 9.7));    // 0.3 m in front: radius 0.291, split
  ring.push_back(point(0.02, 0.0, 10.0));  // equal range, 0.2 m aside
  ring.push_back(point(-0.02, 0.0, 10.0));
  ring.push_back(point(0.0, 0.04, 10.0));  // 0.4 m above: split
  require_same_decisions(link, a, ring, rng);
  require_same_decisions(link, negative_zero, ring, rng);
}
