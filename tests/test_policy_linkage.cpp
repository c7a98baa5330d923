// SPDX-License-Identifier: MIT
// Unit tests of the linkage policies. First the contract every linkage of
// the Linkages list (support/policy_lists.hpp) must keep, generated per
// linkage by the test kit's linkage laws: exact symmetry, no state, the
// compact payload and link_many deciding as the Sample operator, known
// values at the default parameters. Then each
// linkage's own properties: thresholds, known beta values, the
// near-coincident-ray remedy, the range-adaptive radius and the combinators.

#include <doctest/doctest.h>

#include <streamclust/testing/doctest.hpp>
#include <streamclust/testing/linkage_laws.hpp>

#include "support/constants.hpp"
#include "support/invalid_argument.hpp"
#include "support/policy_hooks.hpp"
#include "support/policy_lists.hpp"

#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/combinators.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/linkage/range_adaptive.hpp>
#include <streamclust/linkage/runtime_linkage.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using streamclust::AllOf;
using streamclust::AngularLinkage;
using streamclust::AngularOrEuclidean;
using streamclust::AnyOf;
using streamclust::EuclideanLinkage;
using streamclust::RangeAdaptiveLinkage;
using streamclust::RuntimeLinkage;
using streamclust::Sample;

namespace {

using streamclust::test::kDeg;
using streamclust::test::kInf;
using streamclust::test::kNaN;

Sample at(const Eigen::Vector3f& p) { return streamclust::make_sample(p, p.norm(), 0.0f, 0.0); }

/// Sample at `range` [m] along the ray of azimuth / elevation [deg] (computed in double).
Sample ray(double az_deg, double el_deg, double range) {
  const Eigen::Vector3d d(std::cos(el_deg * kDeg) * std::cos(az_deg * kDeg),
                          std::cos(el_deg * kDeg) * std::sin(az_deg * kDeg), std::sin(el_deg * kDeg));
  return at((d * range).cast<float>());
}

/// Reference beta [deg] from the formula with real atan2, given alpha directly.
double beta_formula_deg(double d1, double d2, double alpha_deg) {
  const double a = alpha_deg * kDeg;
  return std::atan2(d2 * std::sin(a), d1 - d2 * std::cos(a)) / kDeg;
}

using streamclust::test::invalid_argument_message;

/// Linkage with a fixed answer that counts its calls (for the combinators).
template <int Id>
struct Fixed {
  struct Params {
    bool value = false;
  };
  explicit Fixed(const Params& p) : value(p.value) {}
  bool operator()(const Sample&, const Sample&) const {
    ++calls;
    return value;
  }
  bool value;
  static inline int calls = 0;
};

void reset_calls() { Fixed<0>::calls = Fixed<1>::calls = Fixed<2>::calls = 0; }

/// Random pairs of Samples of the kinds a mask search meets (the test kit's).
std::vector<std::pair<Sample, Sample>> random_pairs(std::uint32_t seed, int count) {
  return streamclust::testing::random_candidate_pairs(seed, static_cast<std::size_t>(count));
}

/// The linkage's default parameters, then `draws` random ones (RandomParams).
template <class L>
std::vector<typename L::Params> params_to_test(int draws) {
  std::vector<typename L::Params> out(1);
  std::mt19937_64 rng(77);
  for (int i = 0; i < draws; ++i) {
    typename L::Params p{};
    streamclust::test::RandomParams<L>::draw(p, rng);
    out.push_back(p);
  }
  return out;
}

}  // namespace

// ------------------------------------------------ the contract of every linkage

// The test kit's linkage laws (<streamclust/testing/linkage_laws.hpp>):
// symmetry, statelessness, the payload and link_many against the Sample
// operator, Params, on random, simulated Livox and threshold pairs; at the
// defaults and 8 random parameter sets, with the known pairs of the hooks.
TEST_CASE_TEMPLATE_DEFINE("linkage contract: the test kit's linkage laws hold", L, linkage_laws) {
  streamclust::testing::LinkageLawOptions<L> options;
  options.params = params_to_test<L>(8);
  options.must_link.push_back(streamclust::test::KnownPairs<L>::linked());
  options.must_split.push_back(streamclust::test::KnownPairs<L>::split());
  STREAMCLUST_CHECK_LAW(streamclust::testing::check_linkage<L>(options));
}

TEST_CASE_TEMPLATE_APPLY(linkage_laws, streamclust::test::Linkages);

// ------------------------------------------------------ each linkage's own

TEST_CASE("EuclideanLinkage: squared distance <= max_distance^2") {
  const EuclideanLinkage link{{0.5f}};
  const Sample o = at({10.0f, 0.0f, 0.0f});
  CHECK(link(o, at({10.5f, 0.0f, 0.0f})));
  CHECK(link(at({10.5f, 0.0f, 0.0f}), o));
  CHECK_FALSE(link(o, at({10.51f, 0.0f, 0.0f})));
  CHECK(link(o, at({10.3f, 0.0f, 0.39f})));   // 0.4924 m
  CHECK_FALSE(link(o, at({10.3f, 0.0f, 0.41f})));  // 0.5099 m
  CHECK(link(o, o));
  CHECK(EuclideanLinkage{{}}.params().max_distance == 0.5f);
  for (const float bad : {0.0f, -1.0f, kNaN, kInf}) {
    const std::string m = invalid_argument_message([&] { EuclideanLinkage{{bad}}; });
    CHECK(m.find("max_distance") != std::string::npos);
  }
}

TEST_CASE("AngularLinkage: beta_deg matches known values") {
  // equal ranges: the triangle is isosceles, beta = 90 - alpha / 2
  for (const double alpha : {0.1, 1.0, 5.0, 30.0}) {
    const Sample a = ray(0.0, 0.0, 10.0);
    const Sample b = ray(alpha, 0.0, 10.0);
    CHECK(AngularLinkage::beta_deg(a, b) == doctest::Approx(90.0 - alpha / 2.0).epsilon(1e-4));
  }
  // field notes 2.7: wall at 10 m, 2 cm range difference
  CHECK(AngularLinkage::beta_deg(ray(0.0, 0.0, 10.02), ray(0.01, 0.0, 10.0)) == doctest::Approx(5.0).epsilon(0.01));
  CHECK(AngularLinkage::beta_deg(ray(0.0, 0.0, 10.02), ray(0.05, 0.0, 10.0)) == doctest::Approx(23.6).epsilon(0.01));
  CHECK(AngularLinkage::beta_deg(ray(0.0, 0.0, 10.02), ray(0.1, 0.0, 10.0)) == doctest::Approx(41.1).epsilon(0.01));
  // d1 = 10, d2 = 5, alpha = 10 deg, independent of argument order and of the ray plane
  const double expected = beta_formula_deg(10.0, 5.0, 10.0);
  CHECK(expected == doctest::Approx(9.7066).epsilon(1e-3));
  CHECK(AngularLinkage::beta_deg(ray(20.0, 3.0, 10.0), ray(20.0, 13.0, 5.0)) == doctest::Approx(expected).epsilon(1e-4));
  CHECK(AngularLinkage::beta_deg(ray(20.0, 13.0, 5.0), ray(20.0, 3.0, 10.0)) == doctest::Approx(expected).epsilon(1e-4));
  // d1 >= d2 keeps beta below 90 degrees; large alpha with similar ranges comes close
  CHECK(AngularLinkage::beta_deg(ray(0.0, 0.0, 5.0), ray(60.0, 0.0, 5.5)) ==
        doctest::Approx(beta_formula_deg(5.5, 5.0, 60.0)).epsilon(1e-4));
  CHECK(beta_formula_deg(5.5, 5.0, 60.0) == doctest::Approx(55.285).epsilon(1e-4));
}

TEST_CASE("AngularLinkage: the trig-free decision equals beta > theta on both sides of theta") {
  struct Case {
    double d1, d2, alpha_deg;
  };
  const std::vector<Case> cases = {{10.0, 5.0, 10.0}, {10.0, 9.9, 1.0},  {20.0, 19.0, 0.5}, {3.0, 2.0, 30.0},
                                   {50.0, 49.5, 2.0}, {10.0, 10.0, 0.5}, {8.0, 1.0, 45.0}, {5.5, 5.0, 60.0}};
  for (const Case& c : cases) {
    const double beta = beta_formula_deg(c.d1, c.d2, c.alpha_deg);
    CAPTURE(c.d1);
    CAPTURE(c.d2);
    CAPTURE(c.alpha_deg);
    CAPTURE(beta);
    const Sample a = ray(-7.0, 2.0, c.d1);
    const Sample b = ray(-7.0 + c.alpha_deg, 2.0, c.d2);
    for (const double margin : {0.05, 0.5, 3.0}) {
      if (beta - margin > 0.0 && beta - margin < 90.0) {
        const AngularLinkage below{{static_cast<float>(beta - margin), 0.0f}};
        CHECK(below(a, b));
        CHECK(below(b, a));
      }
      if (beta + margin < 90.0) {
        const AngularLinkage above{{static_cast<float>(beta + margin), 0.0f}};
        CHECK_FALSE(above(a, b));
        CHECK_FALSE(above(b, a));
      }
    }
  }
}

TEST_CASE("AngularLinkage: agrees with beta_deg on random pairs and is exactly symmetric") {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> az(-180.0, 180.0);
  std::uniform_real_distribution<double> el(-30.0, 30.0);
  std::uniform_real_distribution<double> range(0.5, 80.0);
  std::uniform_real_distribution<double> small(-2.0, 2.0);
  std::uniform_real_distribution<double> tiny(-0.02, 0.02);
  const AngularLinkage pure{{10.0f, 0.0f}};
  const AngularLinkage floored{{10.0f, 0.2f}};
  const AngularLinkage strict{{30.0f, 1.0f}};
  const AngularOrEuclidean hybrid{{{10.0f, 0.0f}, {0.1f}}};
  int linked = 0;
  int split = 0;
  for (int i = 0; i < 50000; ++i) {
    const double az0 = az(rng);
    const double el0 = el(rng);
    const double r0 = range(rng);
    const Sample a = ray(az0, el0, r0);
    // draw in a fixed order (argument evaluation order is unspecified)
    const double x1 = az(rng);
    const double x2 = el(rng);
    const double x3 = range(rng);
    const double s1 = small(rng);
    const double s2 = small(rng);
    const double s3 = small(rng);
    const double t1 = tiny(rng);
    Sample b;
    switch (i % 4) {
      case 0: b = ray(x1, x2, x3); break;                                     // anything
      case 1: b = ray(az0 + s1, el0 + s2, r0 * (1.0 + 0.1 * s3)); break;      // neighbours
      case 2: b = ray(az0 + 0.01 * s1, el0 + 0.01 * s2, r0 + t1); break;      // revisits
      default: b = ray(az0 + s1, el0, r0); b.range = a.range; break;          // equal ranges
    }
    for (const AngularLinkage* l : {&pure, &floored, &strict}) REQUIRE((*l)(a, b) == (*l)(b, a));
    REQUIRE(hybrid(a, b) == hybrid(b, a));
    // a threshold right at this pair's beta: the decision hinges on the last bits,
    // so any operand-order dependence of the float arithmetic would show here
    const float beta_here = AngularLinkage::beta_deg(a, b);
    if (beta_here > 0.0f && beta_here < 90.0f) {
      const AngularLinkage edge{{beta_here, 0.0f}};
      REQUIRE(edge(a, b) == edge(b, a));
    }
    // the pure criterion agrees with the reference beta away from the threshold
    const float beta = AngularLinkage::beta_deg(a, b);
    if (std::fabs(beta - 10.0f) > 0.01f && i % 4 != 2) {
      REQUIRE(pure(a, b) == (beta > 10.0f));
      (beta > 10.0f ? linked : split)++;
    }
    // the floor only ever adds links
    if (pure(a, b)) REQUIRE(floored(a, b));
  }
  CHECK(linked > 1000);
  CHECK(split > 1000);
}

TEST_CASE("AngularLinkage: near-coincident rays on a wall split without the floor and link with it") {
  // a flat wall (plane x = 10 m) seen along rays 0.01 deg apart, +-2 cm range noise
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> noise(-0.02, 0.02);
  std::vector<Sample> wall;
  for (int k = 0; k < 200; ++k) {
    const double az = -1.0 + 0.01 * k;
    const double r = 10.0 / std::cos(az * kDeg) + noise(rng);
    wall.push_back(ray(az, 0.0, r));
  }
  const AngularLinkage pure{{10.0f, 0.0f}};
  const AngularLinkage floored{{}};  // defaults: theta 10 deg, floor 0.2 deg
  const AngularOrEuclidean hybrid{{{10.0f, 0.0f}, {0.1f}}};
  int pure_breaks = 0;
  for (std::size_t k = 1; k < wall.size(); ++k) pure_breaks += pure(wall[k - 1], wall[k]) ? 0 : 1;
  CHECK(pure_breaks > 50);  // the chain falls apart into many pieces
  // with the floor every pair within 10 rays (0.1 deg) links, as with the hybrid
  for (std::size_t i = 0; i < wall.size(); ++i) {
    for (std::size_t j = i + 1; j < wall.size() && j <= i + 10; ++j) {
      REQUIRE(floored(wall[i], wall[j]));
      REQUIRE(hybrid(wall[i], wall[j]));
    }
  }
  // the floor does not join a real depth discontinuity: same rays, a second wall 1 m behind
  const Sample front = ray(0.0, 0.0, 10.0);
  const Sample back = ray(0.01, 0.0, 11.0);
  CHECK_FALSE(floored(front, back));
  CHECK_FALSE(pure(front, back));
  CHECK_FALSE(hybrid(front, back));
}

TEST_CASE("AngularLinkage: invalid Params throw") {
  using P = AngularLinkage::Params;
  const auto msg = [](const P& p) { return invalid_argument_message([&] { AngularLinkage{p}; }); };
  CHECK(msg(P{}).empty());
  CHECK(msg(P{0.0f, 0.2f}).find("theta_deg") != std::string::npos);
  CHECK(msg(P{90.0f, 0.2f}).find("theta_deg") != std::string::npos);
  CHECK(msg(P{-5.0f, 0.2f}).find("theta_deg") != std::string::npos);
  CHECK(msg(P{kNaN, 0.2f}).find("theta_deg") != std::string::npos);
  CHECK(msg(P{10.0f, -0.1f}).find("min_ray_angle_deg") != std::string::npos);
  CHECK(msg(P{10.0f, 90.0f}).find("min_ray_angle_deg") != std::string::npos);
  CHECK(msg(P{10.0f, kInf}).find("min_ray_angle_deg") != std::string::npos);
  CHECK(msg(P{10.0f, 0.0f}).empty());
}

TEST_CASE("RangeAdaptiveLinkage: the radius is max(min_distance, range_factor * nearer range)") {
  const RangeAdaptiveLinkage link{{0.2f, 0.03f}};
  CHECK(link.radius(2.0f, 30.0f) == 0.2f);                  // near: the floor
  CHECK(link.radius(30.0f, 25.0f) == doctest::Approx(0.75f));  // far: 3 cm per metre of the nearer range
  CHECK(link.radius(25.0f, 30.0f) == link.radius(30.0f, 25.0f));
  CHECK(link.radius(6.0f, 6.0f) == doctest::Approx(0.2f));  // where the two meet: 0.2 / 0.03 = 6.67 m
  CHECK(link.radius(10.0f, 10.0f) == doctest::Approx(0.3f));
  // the boundary along the ray and across it, near (floor) and far (proportional)
  struct Case {
    double range, radius;
  };
  for (const Case c : {Case{3.0, 0.2}, Case{10.0, 0.3}, Case{25.0, 0.75}, Case{40.0, 1.2}}) {
    CAPTURE(c.range);
    // b behind a on the same ray: the nearer range is a's
    CHECK(link(ray(10.0, 5.0, c.range), ray(10.0, 5.0, c.range + 0.99 * c.radius)));
    CHECK_FALSE(link(ray(10.0, 5.0, c.range), ray(10.0, 5.0, c.range + 1.01 * c.radius)));
    // across the ray at equal range: chord 2 r sin(alpha / 2)
    const double alpha_in = 2.0 * std::asin(0.99 * c.radius / (2.0 * c.range)) / kDeg;
    const double alpha_out = 2.0 * std::asin(1.01 * c.radius / (2.0 * c.range)) / kDeg;
    CHECK(link(ray(-20.0, 0.0, c.range), ray(-20.0 + alpha_in, 0.0, c.range)));
    CHECK_FALSE(link(ray(-20.0, 0.0, c.range), ray(-20.0 + alpha_out, 0.0, c.range)));
  }
  // the nearer range decides: 0.5 m apart links at 20 m (radius 0.6), not
  // when one point is at 5 m (radius 0.2), whatever the farther one's range
  CHECK(link(ray(0.0, 0.0, 20.0), ray(0.0, 0.0, 20.5)));
  CHECK_FALSE(link(ray(0.0, 0.0, 5.0), ray(0.0, 0.0, 5.5)));
  // range_factor 0 is a fixed radius: EuclideanLinkage with min_distance
  const RangeAdaptiveLinkage fixed{{0.3f, 0.0f}};
  const EuclideanLinkage euclidean{{0.3f}};
  for (const auto& [a, b] : random_pairs(31, 4000)) REQUIRE(fixed(a, b) == euclidean(a, b));
}

TEST_CASE("RangeAdaptiveLinkage reads position and range, not direction") {
  // a moving sensor: the position (world frame) and the ray (from the
  // sensor's position at capture time) no longer agree
  const RangeAdaptiveLinkage link{{0.2f, 0.03f}};
  Sample a = ray(0.0, 0.0, 20.0);
  Sample b = ray(0.0, 0.0, 20.5);  // 0.5 m apart, radius 0.6 at 20 m
  CHECK(link(a, b));
  a.direction = Eigen::Vector3f(0.0f, 1.0f, 0.0f);  // the ray plays no part
  CHECK(link(a, b));
  a.range = 5.0f;  // a measured at 5 m: radius 0.2
  CHECK_FALSE(link(a, b));
  CHECK_FALSE(link(b, a));
  b.position += Eigen::Vector3f(-0.35f, 0.0f, 0.0f);  // now 0.15 m apart
  CHECK(link(a, b));
}

TEST_CASE("RangeAdaptiveLinkage: exactly symmetric at its radius") {
  // pairs drawn so that the squared distance lands within a few ulps of the
  // squared radius, in every order of magnitude of range
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> log_range(std::log(0.2), std::log(80.0));
  const RangeAdaptiveLinkage link{{0.2f, 0.03f}};
  int linked = 0;
  int split = 0;
  for (int i = 0; i < 20000; ++i) {
    const double r = std::exp(log_range(rng));
    const Sample a = ray(90.0 * unit(rng), 30.0 * unit(rng), r);
    Eigen::Vector3d step(unit(rng), unit(rng), unit(rng));
    step.normalize();
    const double radius = std::max(0.2, 0.03 * r);  // b's range is at least r (below)
    const Eigen::Vector3d pb = a.position.cast<double>() + step * radius * (1.0 + 1e-6 * unit(rng));
    Sample b = at(pb.cast<float>());
    b.range = std::max(b.range, a.range);
    const bool ab = link(a, b);
    REQUIRE(ab == link(b, a));
    (ab ? linked : split)++;
  }
  CHECK(linked > 1000);
  CHECK(split > 1000);
}

TEST_CASE("RangeAdaptiveLinkage: invalid Params throw naming the parameter, the value and the range") {
  using P = RangeAdaptiveLinkage::Params;
  const auto msg = [](const P& p) { return invalid_argument_message([&] { RangeAdaptiveLinkage{p}; }); };
  CHECK(msg(P{}).empty());
  CHECK(RangeAdaptiveLinkage{P{}}.params().min_distance == 0.2f);
  CHECK(RangeAdaptiveLinkage{P{}}.params().range_factor == 0.05f);
  CHECK(msg(P{0.2f, 0.0f}).empty());
  CHECK(msg(P{100.0f, 1.0f}).empty());
  for (const float bad : {0.0f, -0.1f, 100.5f, kNaN, kInf}) {
    CAPTURE(bad);
    const std::string m = msg(P{bad, 0.03f});
    CHECK(m.find("RangeAdaptiveLinkage: parameter min_distance = ") == 0);
    CHECK(m.find("(0, 100] m") != std::string::npos);
  }
  for (const float bad : {-0.01f, 1.5f, kNaN, -kInf}) {
    CAPTURE(bad);
    const std::string m = msg(P{0.2f, bad});
    CHECK(m.find("RangeAdaptiveLinkage: parameter range_factor = ") == 0);
    CHECK(m.find("[0, 1]") != std::string::npos);
  }
  CHECK(msg(P{0.2f, 1.5f}).find("= 1.5 ") != std::string::npos);
}

TEST_CASE("RuntimeLinkage answers as the linkage its kind selects") {
  RuntimeLinkage::Params p;
  p.angular = {30.0f, 0.2f};
  p.euclidean = {0.4f};
  p.range_adaptive = {0.1f, 0.02f};
  const AngularLinkage angular{p.angular};
  const EuclideanLinkage euclidean{p.euclidean};
  const RangeAdaptiveLinkage adaptive{p.range_adaptive};
  p.kind = RuntimeLinkage::Kind::angular;
  const RuntimeLinkage as_angular{p};
  p.kind = RuntimeLinkage::Kind::euclidean;
  const RuntimeLinkage as_euclidean{p};
  p.kind = RuntimeLinkage::Kind::range_adaptive;
  const RuntimeLinkage as_adaptive{p};
  CHECK(as_adaptive.kind() == RuntimeLinkage::Kind::range_adaptive);
  int differ = 0;
  for (const auto& [a, b] : random_pairs(12, 5000)) {
    REQUIRE(as_angular(a, b) == angular(a, b));
    REQUIRE(as_euclidean(a, b) == euclidean(a, b));
    REQUIRE(as_adaptive(a, b) == adaptive(a, b));
    differ += adaptive(a, b) != euclidean(a, b) ? 1 : 0;
  }
  CHECK(differ > 0);  // the kinds are distinguishable on these pairs
  p.range_adaptive.range_factor = -1.0f;  // every child validates, whatever the kind
  p.kind = RuntimeLinkage::Kind::angular;
  CHECK(invalid_argument_message([&] { RuntimeLinkage{p}; }).find("range_factor") != std::string::npos);
}

TEST_CASE("AllOf / AnyOf: truth tables and short-circuit evaluation") {
  using And2 = AllOf<Fixed<0>, Fixed<1>>;
  using Or2 = AnyOf<Fixed<0>, Fixed<1>>;
  const Sample s = at({1.0f, 0.0f, 0.0f});
  for (const bool x : {false, true}) {
    for (const bool y : {false, true}) {
      CAPTURE(x);
      CAPTURE(y);
      reset_calls();
      const And2 both{{{x}, {y}}};
      CHECK(both(s, s) == (x && y));
      CHECK(Fixed<0>::calls == 1);
      CHECK(Fixed<1>::calls == (x ? 1 : 0));  // second child skipped when the first is false
      reset_calls();
      const Or2 either{{{x}, {y}}};
      CHECK(either(s, s) == (x || y));
      CHECK(Fixed<0>::calls == 1);
      CHECK(Fixed<1>::calls == (x ? 0 : 1));  // second child skipped when the first is true
      for (const bool z : {false, true}) {
        const AllOf<Fixed<0>, Fixed<1>, Fixed<2>> all3{{{x}, {y}, {z}}};
        const AnyOf<Fixed<0>, Fixed<1>, Fixed<2>> any3{{{x}, {y}, {z}}};
        CHECK(all3(s, s) == (x && y && z));
        CHECK(any3(s, s) == (x || y || z));
      }
    }
  }
  CHECK(AllOf<>{{}}(s, s));
  CHECK_FALSE(AnyOf<>{{}}(s, s));
  CHECK(AllOf<Fixed<0>>{{{true}}}(s, s));
  CHECK_FALSE(AnyOf<Fixed<0>>{{{false}}}(s, s));
  CHECK(streamclust::is_linkage_policy_v<And2>);
  CHECK(streamclust::is_linkage_policy_v<AnyOf<>>);
}

TEST_CASE("AllOf / AnyOf with real linkages: defaults, params, validation") {
  const AngularOrEuclidean defaults{AngularOrEuclidean::Params{}};
  CHECK(defaults.child<0>().params().theta_deg == 10.0f);
  CHECK(defaults.child<1>().params().max_distance == 0.5f);
  const AngularOrEuclidean custom{{{12.0f, 0.0f}, {0.1f}}};
  CHECK(custom.child<0>().params().theta_deg == 12.0f);
  CHECK(custom.child<1>().params().max_distance == 0.1f);
  // a depth jump of 5 cm at nearly coincident rays: angular splits, Euclidean (0.1 m) joins
  const Sample a = ray(0.0, 0.0, 10.0);
  const Sample b = ray(0.01, 0.0, 10.05);
  CHECK_FALSE(custom.child<0>()(a, b));
  CHECK(custom(a, b));
  // AllOf: angular AND within 1 m
  const AllOf<AngularLinkage, EuclideanLinkage> bounded{{{10.0f, 0.2f}, {1.0f}}};
  const Sample far_a = ray(0.0, 0.0, 60.0);
  const Sample far_b = ray(1.5, 0.0, 60.0);  // beta ~ 89 deg but 1.57 m apart
  CHECK(bounded.child<0>()(far_a, far_b));
  CHECK_FALSE(bounded(far_a, far_b));
  CHECK(bounded(a, ray(0.5, 0.0, 10.0)));
  CHECK_THROWS_AS((AngularOrEuclidean{{{0.0f, 0.2f}, {0.1f}}}), std::invalid_argument);
  CHECK_THROWS_AS((AngularOrEuclidean{{{10.0f, 0.2f}, {-0.1f}}}), std::invalid_argument);
}
