// SPDX-License-Identifier: MIT
// The scan simulator's shapes, scenes and simulator: analytic intersections
// against known values and a random fuzz, ground-truth ids, moving objects,
// ego-motion, noise, dropout, range limits and determinism.

#include <doctest/doctest.h>

#include <streamclust/sim/scene.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/shapes.hpp>
#include <streamclust/sim/simulator.hpp>

#include <Eigen/Core>

#include "support/directions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace sc = streamclust;
namespace sim = streamclust::sim;

using streamclust::test::spherical;

/// A test-only sensor: a fixed list of directions fired in a cycle at a fixed rate.
struct CyclingSensor {
  std::vector<Eigen::Vector3f> directions;
  double rate = 10000.0;
  std::uint64_t index = 0;

  sim::Ray next() {
    sim::Ray r;
    r.direction = directions[index % directions.size()];
    r.time = static_cast<double>(index) / rate;
    ++index;
    return r;
  }
  double point_rate() const { return rate; }
};

/// n_az x n_el directions, elevations in [el_lo, el_hi] [rad].
CyclingSensor raster(int n_az, int n_el, float el_lo, float el_hi, double rate = 100000.0) {
  CyclingSensor s;
  s.rate = rate;
  // Interleave elevations so that any prefix of the cycle covers the field of view.
  for (int a = 0; a < n_az; ++a)
    for (int e = 0; e < n_el; ++e) {
      const float az = 2.0f * sim::detail::kPi * static_cast<float>(a) / static_cast<float>(n_az);
      const float el = n_el == 1 ? el_lo : el_lo + (el_hi - el_lo) * static_cast<float>(e) / static_cast<float>(n_el - 1);
      s.directions.push_back(spherical(az, el));
    }
  return s;
}

CyclingSensor fixed_direction(const Eigen::Vector3f& d, double rate = 1000.0) {
  CyclingSensor s;
  s.rate = rate;
  s.directions = {d.normalized()};
  return s;
}

static_assert(sim::is_sim_sensor_v<CyclingSensor>);
static_assert(!sim::is_sim_sensor_v<int>);

const Eigen::Vector3f kX = Eigen::Vector3f::UnitX();
const Eigen::Vector3f kZ = Eigen::Vector3f::UnitZ();

float value_or(const std::optional<float>& t, float fallback = -1.0f) { return t ? *t : fallback; }

}  // namespace

TEST_CASE("sim shapes: plane known values, bounds, parallel rays") {
  const sim::Plane ground = sim::Plane::infinite({0, 0, 2}, {0, 0, 0});
  CHECK(value_or(sim::intersect(ground, {0, 0, 1}, -kZ)) == doctest::Approx(1.0f));
  CHECK(value_or(sim::intersect(ground, {0, 0, -1}, kZ)) == doctest::Approx(1.0f));  // two-sided
  CHECK_FALSE(sim::intersect(ground, {0, 0, 1}, kZ));                                 // behind
  CHECK_FALSE(sim::intersect(ground, {0, 0, 1}, kX));                                 // parallel
  CHECK_FALSE(sim::intersect(ground, {0, 0, 0}, kX));                                 // in the plane
  const Eigen::Vector3f oblique = Eigen::Vector3f(1, 0, -1).normalized();
  CHECK(value_or(sim::intersect(ground, {0, 0, 1}, oblique)) == doctest::Approx(std::sqrt(2.0f)));

  // A 2 x 1 m rectangle in the plane x = 5 (normal along x).
  const sim::Plane door = sim::Plane::rectangle({5, 0, 1}, {0, 1, 0}, {0, 0, 1}, 1.0f, 0.5f);
  CHECK(value_or(sim::intersect(door, {0, 0, 1}, kX)) == doctest::Approx(5.0f));
  CHECK(value_or(sim::intersect(door, {0, 0.9f, 1.4f}, kX)) == doctest::Approx(5.0f));
  CHECK_FALSE(sim::intersect(door, {0, 1.1f, 1}, kX));
  CHECK_FALSE(sim::intersect(door, {0, 0, 1.6f}, kX));
  CHECK(door.bounds().lo.isApprox(Eigen::Vector3f(5, -1, 0.5f)));
}

TEST_CASE("sim shapes: boxes, aligned and yawed") {
  const sim::Box box = sim::Box::aligned({2, -1, 0}, {3, 1, 1});
  CHECK(value_or(sim::intersect(box, {0, 0, 0.5f}, kX)) == doctest::Approx(2.0f));
  CHECK(value_or(sim::intersect(box, {2.5f, 0, 5}, -kZ)) == doctest::Approx(4.0f));  // top face
  CHECK_FALSE(sim::intersect(box, {0, 0, 0.5f}, -kX));                                // behind
  CHECK_FALSE(sim::intersect(box, {0, 2, 0.5f}, kX));                                 // parallel, outside the y slab
  CHECK(value_or(sim::intersect(box, {0, 1, 0.5f}, kX)) == doctest::Approx(2.0f));    // parallel, on the face plane
  CHECK_FALSE(sim::intersect(box, {2.5f, 0, 0.5f}, kX));  // origin inside: ignored by convention
  CHECK(value_or(sim::intersect(box, {0, 0, 0.5f}, Eigen::Vector3f(2, 0, 0))) == doctest::Approx(1.0f));  // |d| units

  // Half extents (1, 0.25, 0.5) at (5, 0, 0) rotated by 90 degrees: along x it is 0.5 m long.
  const sim::Box turned = sim::Box::rotated({5, 0, 0}, {1.0f, 0.25f, 0.5f}, 0.5f * sim::detail::kPi);
  CHECK(value_or(sim::intersect(turned, {0, 0, 0}, kX)) == doctest::Approx(4.75f));
  CHECK(value_or(sim::intersect(turned, {5, -5, 0}, Eigen::Vector3f::UnitY())) == doctest::Approx(4.0f));
  CHECK(turned.bounds().lo.isApprox(Eigen::Vector3f(4.75f, -1.0f, -0.5f), 1e-5f));
  // 45 degrees: the corner at distance sqrt(2) * 0.5 from the center.
  const sim::Box diamond = sim::Box::rotated({5, 0, 0}, {0.5f, 0.5f, 0.5f}, 0.25f * sim::detail::kPi);
  CHECK(value_or(sim::intersect(diamond, {0, 0, 0}, kX)) == doctest::Approx(5.0f - std::sqrt(0.5f)).epsilon(1e-5));
}

TEST_CASE("sim shapes: capped vertical cylinder") {
  const sim::Cylinder c{5, 0, 1, 0, 2};
  CHECK(value_or(sim::intersect(c, {0, 0, 1}, kX)) == doctest::Approx(4.0f));
  CHECK(value_or(sim::intersect(c, {5, 0, 10}, -kZ)) == doctest::Approx(8.0f));  // top cap
  CHECK(value_or(sim::intersect(c, {5.5f, 0, -3}, kZ)) == doctest::Approx(3.0f));  // bottom cap
  CHECK_FALSE(sim::intersect(c, {0, 0, 3}, kX));                                  // over the top
  CHECK_FALSE(sim::intersect(c, {7, 0, 10}, -kZ));                                // vertical, outside the disc
  CHECK_FALSE(sim::intersect(c, {0, 1.5f, 1}, kX));                               // passes beside
  CHECK_FALSE(sim::intersect(c, {5, 0, 1}, kX));                                  // inside
  // Tangent offset 0.6: the chord's near end at 5 - sqrt(1 - 0.36) = 4.2.
  CHECK(value_or(sim::intersect(c, {0, 0.6f, 1}, kX)) == doctest::Approx(4.2f));
  // A thin trunk far away keeps float precision.
  const sim::Cylinder trunk{40, 0, 0.1f, 0, 10};
  CHECK(value_or(sim::intersect(trunk, {0, 0.05f, 1}, kX)) ==
        doctest::Approx(40.0f - std::sqrt(0.01f - 0.0025f)).epsilon(1e-6));
}

TEST_CASE("sim shapes: spheres and ellipsoids") {
  const sim::Sphere s{{10, 0, 0}, 2};
  CHECK(value_or(sim::intersect(s, {0, 0, 0}, kX)) == doctest::Approx(8.0f));
  CHECK_FALSE(sim::intersect(s, {0, 0, 0}, -kX));
  CHECK_FALSE(sim::intersect(s, {0, 2.1f, 0}, kX));
  CHECK_FALSE(sim::intersect(s, {10, 0, 0}, kX));  // inside
  CHECK(value_or(sim::intersect(s, {0, 1, 0}, kX)) == doctest::Approx(10.0f - std::sqrt(3.0f)));

  const sim::Ellipsoid e{{0, 0, 0}, {1, 2, 3}};
  CHECK(value_or(sim::intersect(e, {0, -10, 0}, Eigen::Vector3f::UnitY())) == doctest::Approx(8.0f));
  CHECK(value_or(sim::intersect(e, {0, 0, 10}, -kZ)) == doctest::Approx(7.0f));
  CHECK(value_or(sim::intersect(e, {-5, 0, 0}, kX)) == doctest::Approx(4.0f));
  CHECK_FALSE(sim::intersect(e, {-5, 0, 3.1f}, kX));
}

TEST_CASE("sim shapes: standing capsule") {
  const sim::Capsule c = sim::Capsule::standing(5, 0, 0, 1.7f, 0.3f);
  CHECK(c.z_low == doctest::Approx(0.3f));
  CHECK(c.z_high == doctest::Approx(1.4f));
  CHECK(value_or(sim::intersect(c, {0, 0, 1}, kX)) == doctest::Approx(4.7f));
  CHECK(value_or(sim::intersect(c, {5, 0, 5}, -kZ)) == doctest::Approx(3.3f));  // top of the head
  CHECK(value_or(sim::intersect(c, {5, 0, -2}, kZ)) == doctest::Approx(2.0f));   // bottom
  // Into the top hemisphere 0.25 m above its center: half chord sqrt(0.09 - 0.0625).
  CHECK(value_or(sim::intersect(c, {0, 0, 1.65f}, kX)) == doctest::Approx(5.0f - std::sqrt(0.0275f)).epsilon(1e-4));
  CHECK_FALSE(sim::intersect(c, {0, 0, 1.75f}, kX));
  CHECK_FALSE(sim::intersect(c, {5, 0, 1}, kX));  // inside
}

TEST_CASE("sim shapes: degenerate inputs give no hit, never NaN") {
  const sim::Sphere s{{10, 0, 0}, 2};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  CHECK_FALSE(sim::intersect(s, {0, 0, 0}, Eigen::Vector3f::Zero()));
  CHECK_FALSE(sim::intersect(s, {nan, 0, 0}, kX));
  CHECK_FALSE(sim::intersect(sim::Box::aligned({1, 1, 1}, {2, 2, 2}), {0, 0, 0}, {nan, 1, 0}));
  CHECK_FALSE(sim::intersect(sim::Plane::infinite(kZ, {0, 0, 0}), {0, 0, 1}, Eigen::Vector3f::Zero()));
}

TEST_CASE("sim shapes: random rays hit the surfaces they report") {
  sim::detail::SplitMix64 rng(42);
  const sim::Box box = sim::Box::rotated({1, 2, 0.5f}, {1.5f, 0.4f, 0.5f}, 0.7f);
  const sim::Cylinder cyl{-1, 1, 0.6f, -0.5f, 1.5f};
  const sim::Sphere sph{{0.5f, -1, 0.2f}, 0.8f};
  const sim::Ellipsoid ell{{-0.5f, -0.5f, 1}, {1.2f, 0.5f, 0.8f}};
  const sim::Capsule cap = sim::Capsule::standing(1, -1, -0.5f, 1.8f, 0.35f);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    // One draw per statement: argument evaluation order is unspecified.
    Eigen::Vector3f o;
    for (int k = 0; k < 3; ++k) o[k] = rng.uniform(-6, 6);
    // Aim near the shapes so that many rays hit; some directions are axis-parallel.
    Eigen::Vector3f target;
    const float target_lo[3] = {-2.0f, -2.0f, -1.0f};
    for (int k = 0; k < 3; ++k) target[k] = rng.uniform(target_lo[k], 2.0f);
    Eigen::Vector3f d = (target - o).normalized();
    if (i % 5 == 0) d[i % 3] = 0.0f;
    if (i % 7 == 0) d = Eigen::Vector3f::Unit(i % 3) * (i % 2 ? 1.0f : -1.0f);
    if (d.squaredNorm() == 0.0f) continue;
    d.normalize();
    if (const auto t = sim::intersect(box, o, d)) {
      ++hits;
      REQUIRE(std::isfinite(*t));
      const Eigen::Vector3f r = o + *t * d - box.center;
      const Eigen::Vector3f local(box.cos_yaw * r.x() + box.sin_yaw * r.y(), -box.sin_yaw * r.x() + box.cos_yaw * r.y(), r.z());
      CHECK(local.cwiseAbs().cwiseQuotient(box.half).maxCoeff() == doctest::Approx(1.0f).epsilon(1e-4));
    }
    if (const auto t = sim::intersect(cyl, o, d)) {
      ++hits;
      const Eigen::Vector3f p = o + *t * d;
      const float radial = std::hypot(p.x() - cyl.x, p.y() - cyl.y);
      const bool on_side = std::abs(radial - cyl.radius) < 1e-4f && p.z() > cyl.z_min - 1e-4f && p.z() < cyl.z_max + 1e-4f;
      const bool on_cap = radial < cyl.radius + 1e-4f &&
                          (std::abs(p.z() - cyl.z_min) < 1e-4f || std::abs(p.z() - cyl.z_max) < 1e-4f);
      CHECK((on_side || on_cap));
    }
    if (const auto t = sim::intersect(sph, o, d)) {
      ++hits;
      CHECK((o + *t * d - sph.center).norm() == doctest::Approx(sph.radius).epsilon(1e-4));
    }
    if (const auto t = sim::intersect(ell, o, d)) {
      ++hits;
      CHECK((o + *t * d - ell.center).cwiseQuotient(ell.radii).norm() == doctest::Approx(1.0f).epsilon(1e-4));
    }
    if (const auto t = sim::intersect(cap, o, d)) {
      ++hits;
      const Eigen::Vector3f p = o + *t * d;
      const float z = std::clamp(p.z(), cap.z_low, cap.z_high);
      CHECK((p - Eigen::Vector3f(cap.x, cap.y, z)).norm() == doctest::Approx(cap.radius).epsilon(1e-4));
    }
  }
  CHECK(hits > 10000);
}

TEST_CASE("sim scene: nearest hit and instance ids") {
  sim::Scene scene;
  scene.add_structure(sim::ShapeSet().add(sim::Plane::infinite(kZ, {0, 0, 0})), sc::SurfaceClass::ground);
  const int near_box = scene.add_object("box", sim::ShapeSet().add(sim::Box::aligned({4, -1, 0}, {5, 1, 2})));
  const int far_box = scene.add_object("box", sim::ShapeSet().add(sim::Box::aligned({8, -1, 0}, {9, 1, 3})));
  const int ball = scene.add_object("ball", sim::ShapeSet().add(sim::Sphere{{0, 6, 1}, 0.5f}));
  CHECK(near_box == 1);
  CHECK(far_box == 2);
  CHECK(ball == 3);
  CHECK(scene.object_count() == 3);
  CHECK_THROWS_AS(scene.add_object("nothing", sim::ShapeSet()), std::invalid_argument);
  CHECK_THROWS_AS(scene.add_object("plane", sim::ShapeSet().add(sim::Plane::infinite(kX, {0, 0, 0}))),
                  std::invalid_argument);

  const Eigen::Vector3f o(0, 0, 1);
  auto hit = scene.cast(o, -kZ, 0.0);
  REQUIRE(hit);
  CHECK(hit->instance == 0);
  CHECK(hit->surface == sc::SurfaceClass::ground);
  CHECK(hit->range == doctest::Approx(1.0f));
  hit = scene.cast(o, kX, 0.0);
  REQUIRE(hit);
  CHECK(hit->instance == near_box);
  CHECK(hit->surface == sc::SurfaceClass::object);
  CHECK(hit->range == doctest::Approx(4.0f));
  hit = scene.cast({0, 0, 2.5f}, kX, 0.0);  // over the near box
  REQUIRE(hit);
  CHECK(hit->instance == far_box);
  CHECK(hit->range == doctest::Approx(8.0f));
  hit = scene.cast(o, Eigen::Vector3f(0, 3, 0), 0.0);  // not normalized: normalized by cast
  REQUIRE(hit);
  CHECK(hit->instance == ball);
  CHECK(hit->range == doctest::Approx(5.5f));
  CHECK_FALSE(scene.cast(o, kZ, 0.0));                           // sky
  CHECK_FALSE(scene.cast(o, Eigen::Vector3f::Zero(), 0.0));      // degenerate
  CHECK(scene.position(ball, 0.0).isApprox(Eigen::Vector3f(0, 6, 1)));
  CHECK_THROWS_AS(scene.position(4, 0.0), std::out_of_range);
  CHECK_THROWS_AS(scene.add_structure(sim::ShapeSet().add(sim::Plane::infinite(kX, {30, 0, 0})), sc::SurfaceClass::object),
                  std::invalid_argument);
}

TEST_CASE("sim scene: trajectories") {
  const sim::Trajectory walk = sim::Trajectory::back_and_forth({0, 0, 0}, {4, 0, 0}, 2.0f);
  CHECK(walk.period() == doctest::Approx(4.0));
  CHECK(walk.position(0.0).isApprox(Eigen::Vector3f(0, 0, 0)));
  CHECK(walk.position(1.0).isApprox(Eigen::Vector3f(2, 0, 0)));
  CHECK(walk.position(2.0).isApprox(Eigen::Vector3f(4, 0, 0)));
  CHECK(walk.position(3.0).isApprox(Eigen::Vector3f(2, 0, 0)));
  CHECK(walk.position(5.0).isApprox(Eigen::Vector3f(2, 0, 0)));  // periodic
  CHECK(walk.pose(0.5).cos_yaw == doctest::Approx(1.0f));
  CHECK(walk.pose(2.5).cos_yaw == doctest::Approx(-1.0f));  // walking back
  const sim::Trajectory shifted = sim::Trajectory::back_and_forth({0, 0, 0}, {4, 0, 0}, 2.0f, 5.0f);
  CHECK(shifted.position(0.0).isApprox(Eigen::Vector3f(3, 0, 0)));

  const sim::Trajectory circle = sim::Trajectory::circle({1, 1, 0}, 2.0f, 1.0f);
  CHECK(circle.position(0.0).isApprox(Eigen::Vector3f(3, 1, 0)));
  CHECK(circle.position(sim::detail::kPi).isApprox(Eigen::Vector3f(1, 3, 0), 1e-5f));  // a quarter turn
  CHECK(circle.pose(0.0).sin_yaw == doctest::Approx(1.0f));                            // heading +y
  CHECK(circle.period() == doctest::Approx(4.0 * sim::detail::kPi));

  const sim::Trajectory still = sim::Trajectory::fixed({1, 2, 3});
  CHECK(still.position(100.0).isApprox(Eigen::Vector3f(1, 2, 3)));
  CHECK(std::isinf(still.period()));

  // Departing at t = 2 s from (0, 0) along (0, 0) -> (10, 0) -> (10, 40):
  // 2 m/s^2 up to 4 m/s (4 m in the first 2 s), then 4 m/s; it stops at the end.
  const sim::Trajectory depart = sim::Trajectory::depart({{0, 0, 0}, {10, 0, 0}, {10, 40, 0}}, 2.0, 4.0f, 2.0f);
  CHECK(depart.position(0.0).isApprox(Eigen::Vector3f(0, 0, 0)));
  CHECK(depart.position(2.0).isApprox(Eigen::Vector3f(0, 0, 0)));
  CHECK(depart.position(3.0).isApprox(Eigen::Vector3f(1, 0, 0)));     // a t^2 / 2 = 1 m
  CHECK(depart.position(4.0).isApprox(Eigen::Vector3f(4, 0, 0)));     // top speed reached
  CHECK(depart.position(5.5).isApprox(Eigen::Vector3f(10, 0, 0)));    // the corner
  CHECK(depart.position(6.0).isApprox(Eigen::Vector3f(10, 2, 0)));    // turned: heading +y
  CHECK(depart.pose(6.0).sin_yaw == doctest::Approx(1.0f));
  CHECK(depart.pose(1.0).cos_yaw == doctest::Approx(1.0f));           // standing, facing its way
  CHECK(depart.position(15.5).isApprox(Eigen::Vector3f(10, 40, 0)));  // arrived
  CHECK(depart.position(100.0).isApprox(Eigen::Vector3f(10, 40, 0)));  // and stays
  CHECK(std::isinf(depart.period()));
  CHECK(depart.swept_bounds().hi.isApprox(Eigen::Vector3f(10, 40, 0)));
  CHECK_THROWS_AS(sim::Trajectory::depart({{0, 0, 0}}, 0.0, 1.0f, 1.0f), std::invalid_argument);
  CHECK_THROWS_AS(sim::Trajectory::depart({{0, 0, 0}, {1, 0, 0}}, 0.0, 0.0f, 1.0f), std::invalid_argument);
}

TEST_CASE("sim scene: moving objects move along their trajectory") {
  sim::Scene scene;
  const int ball = scene.add_moving_object("ball", sim::ShapeSet().add(sim::Sphere{{0, 0, 0}, 0.5f}),
                                           sim::Trajectory::back_and_forth({5, -2, 1}, {5, 2, 1}, 1.0f));
  // A car-like box facing its motion: 4 m long along its heading.
  const int car = scene.add_moving_object("car", sim::ShapeSet().add(sim::Box::aligned({-2, -1, 0}, {2, 1, 1.5f})),
                                          sim::Trajectory::back_and_forth({-20, 10, 0}, {-20, 30, 0}, 10.0f));
  const Eigen::Vector3f o(0, 0, 1);
  const auto toward = [&](const Eigen::Vector3f& p) -> Eigen::Vector3f { return (p - o).normalized(); };

  auto hit = scene.cast(o, toward({5, -2, 1}), 0.0);
  REQUIRE(hit);
  CHECK(hit->instance == ball);
  CHECK(hit->range == doctest::Approx(std::sqrt(29.0f) - 0.5f));
  CHECK_FALSE(scene.cast(o, toward({5, -2, 1}), 1.0));  // it left
  hit = scene.cast(o, toward({5, -1, 1}), 1.0);        // to here
  REQUIRE(hit);
  CHECK(hit->instance == ball);
  CHECK(scene.position(ball, 1.0).isApprox(Eigen::Vector3f(5, -1, 1)));
  CHECK(scene.position(ball, 5.0).isApprox(Eigen::Vector3f(5, 1, 1)));  // on the way back

  // The car heads +y at t = 1 (center (-20, 20)): its length lies along y.
  hit = scene.cast({-20, 0, 0.5f}, Eigen::Vector3f::UnitY(), 1.0);
  REQUIRE(hit);
  CHECK(hit->instance == car);
  CHECK(hit->range == doctest::Approx(18.0f));
  hit = scene.cast({-30, 20, 0.5f}, kX, 1.0);
  REQUIRE(hit);
  CHECK(hit->range == doctest::Approx(9.0f));  // 1 m half width
  // The swept bounds cover the whole path.
  const sim::Aabb& b = scene.objects()[1].bounds;
  CHECK(b.lo.y() <= 8.0f);
  CHECK(b.hi.y() >= 32.0f);
  CHECK(scene.objects()[1].moving);
}

namespace {

struct ExpectedCount {
  const char* label;
  int lo, hi;
};

void check_scene(const sim::Scene& scene, const std::vector<ExpectedCount>& expected, std::size_t min_objects) {
  CHECK(scene.object_count() >= min_objects);
  std::map<std::string, int> counts;
  std::set<int> ids;
  for (const sim::ObjectInfo& o : scene.objects()) {
    CHECK(o.instance > 0);
    ids.insert(o.instance);
    ++counts[o.label];
    CHECK_FALSE(o.bounds.empty());
    if (o.moving) {
      for (double t = 0.0; t < 60.0; t += 0.25) CHECK(scene.position(o.instance, t).head<2>().norm() >= 1.3f);
    }
  }
  // Nothing in the sensor's start column (radius 1 m, z in [0.3, 2.5]): no
  // object within 1 m of the axis, casting out from it and in toward it
  // (two directions, since a shape containing a ray's origin is ignored).
  for (float z = 0.3f; z <= 2.5f; z += 0.2f) {
    for (int a = 0; a < 72; ++a) {
      const Eigen::Vector3f d = spherical(2.0f * sim::detail::kPi * static_cast<float>(a) / 72.0f, 0.0f);
      const Eigen::Vector3f axis(0.0f, 0.0f, z);
      const auto out = scene.cast(axis, d, 0.0);
      if (out && out->instance > 0) CHECK(out->range >= 1.0f);
      const auto in = scene.cast(axis + d, -d, 0.0);
      if (in && in->instance > 0) CHECK(in->range >= 1.0f);
    }
  }
  CHECK(ids.size() == scene.object_count());                            // unique
  CHECK(*ids.rbegin() == static_cast<int>(scene.object_count()));       // 1..N
  std::size_t listed = 0;
  for (const ExpectedCount& e : expected) {
    INFO(e.label);
    CHECK(counts[e.label] >= e.lo);
    CHECK(counts[e.label] <= e.hi);
    listed += static_cast<std::size_t>(counts[e.label]);
  }
  CHECK(listed == scene.object_count());  // no unexpected labels
}

}  // namespace

TEST_CASE("sim scenes: contents, unique ids, clear start, determinism") {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    CAPTURE(seed);
    check_scene(sim::office_scene(seed),
                {{"pillar", 2, 4}, {"desk", 6, 10}, {"cabinet", 3, 5}, {"bookshelf", 2, 4}, {"person", 2, 3}}, 15);
    check_scene(sim::forest_scene(seed),
                {{"tree", 30, 60}, {"bush", 10, 20}, {"vehicle", 2, 2}, {"pedestrian", 2, 4}}, 44);
    check_scene(sim::street_scene(seed),
                {{"parked_car", 35, 44}, {"pole", 10, 20}, {"tree", 6, 30}, {"car", 5, 7}, {"cyclist", 2, 2},
                 {"pedestrian", 4, 6}},
                70);
  }
  // Same seed, same scene (compare casts); another seed, another scene.
  const CyclingSensor probe = raster(90, 9, -0.6f, 0.8f);
  for (int k = 0; k < 3; ++k) {
    const auto make = [k](std::uint64_t s) { return k == 0 ? sim::office_scene(s) : k == 1 ? sim::forest_scene(s) : sim::street_scene(s); };
    const sim::Scene a = make(5);
    const sim::Scene b = make(5);
    const sim::Scene c = make(6);
    int same = 0;
    int differ = 0;
    for (std::size_t i = 0; i < probe.directions.size(); ++i) {
      const double t = 0.01 * static_cast<double>(i);
      const auto ha = a.cast({0, 0, 1}, probe.directions[i], t);
      const auto hb = b.cast({0, 0, 1}, probe.directions[i], t);
      const auto hc = c.cast({0, 0, 1}, probe.directions[i], t);
      same += ha.has_value() == hb.has_value() && (!ha || (ha->range == hb->range && ha->instance == hb->instance));
      differ += ha.has_value() != hc.has_value() || (ha && ha->range != hc->range);
    }
    CHECK(same == static_cast<int>(probe.directions.size()));
    CHECK(differ > 50);
  }
}

TEST_CASE("sim scenes: golden fingerprints (the same scene for a seed on every compiler)") {
  // Scenes are part of a dataset's identity: a seed must always give the same
  // scene. Changing a factory on purpose means updating these values; a
  // change by accident (e.g. two random draws in one argument list, whose
  // order GCC and clang evaluate differently) fails here.
  struct Golden {
    std::size_t objects;
    double range_sum;
    long id_sum;
  };
  const Golden golden[3] = {{20, 18865.331560, 3173}, {60, 29136.755536, 20594}, {82, 33899.592731, 21250}};
  for (int k = 0; k < 3; ++k) {
    CAPTURE(k);
    const sim::Scene scene = k == 0 ? sim::office_scene(1) : k == 1 ? sim::forest_scene(1) : sim::street_scene(1);
    double range_sum = 0.0;
    long id_sum = 0;
    for (int i = 0; i < 3600; ++i) {
      const float az = 2.0f * 3.14159265f * static_cast<float>(i % 60) / 60.0f;
      const float el = -0.5f + static_cast<float>(i / 60) / 59.0f * 1.2f;
      const auto hit = scene.cast({0, 0, 1}, spherical(az, el), 0.01 * i);
      if (!hit) continue;
      range_sum += static_cast<double>(hit->range);
      id_sum += hit->instance;
    }
    CHECK(scene.object_count() == golden[k].objects);
    CHECK(range_sum == doctest::Approx(golden[k].range_sum).epsilon(1e-6));
    CHECK(id_sum == golden[k].id_sum);
  }
}

TEST_CASE("sim scenes: a scan from the start sees structure and many objects, nothing too close") {
  const CyclingSensor probe = raster(360, 16, -0.5f, 0.9f);
  const std::size_t wanted[3] = {10, 25, 20};
  for (int k = 0; k < 3; ++k) {
    CAPTURE(k);
    const sim::Scene scene = k == 0 ? sim::office_scene(3) : k == 1 ? sim::forest_scene(3) : sim::street_scene(3);
    std::set<int> seen;
    float closest = 1e9f;
    for (std::size_t i = 0; i < probe.directions.size(); ++i) {
      const auto hit = scene.cast({0, 0, 1}, probe.directions[i], 0.0005 * static_cast<double>(i));
      if (!hit) continue;
      seen.insert(hit->instance);
      closest = std::min(closest, hit->range);
      REQUIRE(hit->instance <= static_cast<int>(scene.object_count()));
    }
    CHECK(seen.count(0) == 1);
    CHECK(seen.size() >= wanted[k]);
    CHECK(closest >= 0.95f);
  }
}

TEST_CASE("sim scenes: office objects carry their ids") {
  const sim::Scene scene = sim::office_scene(9);
  auto hit = scene.cast({0, 0, 1}, -kZ, 0.0);
  REQUIRE(hit);
  CHECK(hit->instance == 0);  // floor
  CHECK(hit->range == doctest::Approx(1.0f));
  hit = scene.cast({0, 0, 1}, kZ, 0.0);
  REQUIRE(hit);
  CHECK(hit->instance == 0);  // ceiling
  CHECK(hit->range == doctest::Approx(2.0f));
  for (const sim::ObjectInfo& o : scene.objects()) {
    CAPTURE(o.label);
    if (o.label == "desk" || o.label == "cabinet" || o.label == "bookshelf") {
      const Eigen::Vector3f c = o.bounds.center();
      hit = scene.cast({c.x(), c.y(), 2.95f}, -kZ, 0.0);  // from just under the ceiling
      REQUIRE(hit);
      CHECK(hit->instance == o.instance);
      CHECK(hit->range == doctest::Approx(2.95f - o.bounds.hi.z()).epsilon(1e-4));
    } else if (o.label == "pillar") {
      const Eigen::Vector3f c = o.bounds.center();
      const float r = 0.5f * (o.bounds.hi.x() - o.bounds.lo.x());
      hit = scene.cast({c.x() + r + 0.5f, c.y(), 1.5f}, -kX, 0.0);
      REQUIRE(hit);
      CHECK(hit->instance == o.instance);
      CHECK(hit->range == doctest::Approx(0.5f).epsilon(1e-4));
    } else {
      REQUIRE(o.label == "person");
      for (double t : {0.0, 1.7, 4.2}) {
        const Eigen::Vector3f p = scene.position(o.instance, t);
        hit = scene.cast({p.x(), p.y(), 2.95f}, -kZ, t);
        REQUIRE(hit);
        CHECK(hit->instance == o.instance);
        CHECK(hit->range == doctest::Approx(1.25f).epsilon(1e-4));
      }
      CHECK((scene.position(o.instance, 0.5) - scene.position(o.instance, 0.0)).norm() <= 0.6f + 1e-4f);
      CHECK((scene.position(o.instance, 0.5) - scene.position(o.instance, 0.0)).norm() > 0.3f);
    }
  }
}

namespace {

/// The 2D distance from `p` to the xy footprint of `box` [m].
float footprint_distance(const Eigen::Vector2f& p, const sim::Aabb& box) {
  const float dx = std::max({box.lo.x() - p.x(), 0.0f, p.x() - box.hi.x()});
  const float dy = std::max({box.lo.y() - p.y(), 0.0f, p.y() - box.hi.y()});
  return std::hypot(dx, dy);
}

}  // namespace

TEST_CASE("sim scenes: street parked cars in unbroken rows, lamp poles 0.9-1.0 m from them by the kerb") {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    CAPTURE(seed);
    const sim::Scene scene = sim::street_scene(seed);
    std::vector<sim::Aabb> cars[2];  // y < 0, y > 0
    std::vector<const sim::ObjectInfo*> poles;
    for (const sim::ObjectInfo& o : scene.objects()) {
      if (o.label == "parked_car") cars[o.bounds.center().y() > 0.0f ? 1 : 0].push_back(o.bounds);
      if (o.label == "pole") poles.push_back(&o);
    }
    // The departing car: the moving car standing in the y < 0 row at t = 0.
    const sim::ObjectInfo* departing = nullptr;
    for (const sim::ObjectInfo& o : scene.objects()) {
      if (o.label == "car" && scene.position(o.instance, 0.0).y() < -5.0f) departing = &o;
    }
    REQUIRE(departing != nullptr);
    const float departing_x = scene.position(departing->instance, 0.0).x();
    CHECK(departing_x >= 18.0f);
    CHECK(departing_x <= 33.0f);
    for (int r = 0; r < 2; ++r) {
      auto& row = cars[r];
      std::sort(row.begin(), row.end(), [](const sim::Aabb& a, const sim::Aabb& b) { return a.lo.x() < b.lo.x(); });
      REQUIRE(row.size() >= 17);
      CHECK(row.front().lo.x() <= -58.0f);
      CHECK(row.back().hi.x() >= 54.0f);
      int spaces = 0;
      for (std::size_t k = 1; k < row.size(); ++k) {
        const float gap = row[k].lo.x() - row[k - 1].hi.x();
        CHECK(gap >= 0.6f - 1e-3f);
        if (gap <= 1.5f + 1e-3f) continue;
        // Unbroken but for the parking space of the y < 0 row: the departing
        // car (2.1-2.4 m half length) 0.6-1.5 m ahead of the car behind it
        // (+x), 6 m and more behind the car ahead of it.
        ++spaces;
        CHECK(r == 0);
        const float behind = row[k].lo.x() - departing_x;
        const float ahead = departing_x - row[k - 1].hi.x();
        CHECK(behind >= 2.1f + 0.6f - 1e-3f);
        CHECK(behind <= 2.4f + 1.5f + 1e-3f);
        CHECK(ahead >= 2.4f + 6.0f - 1e-3f);
      }
      CHECK(spaces == (r == 0 ? 1 : 0));
    }
    for (const sim::ObjectInfo* pole : poles) {
      // The mast at 1 m: its near and far faces from rays across the
      // sidewalk along y (below the arm and the lamp, above the kerb).
      const float side = pole->bounds.center().y() > 0.0f ? 1.0f : -1.0f;
      const float x = pole->bounds.center().x();
      const auto near_hit = scene.cast({x, side * 6.6f, 1.0f}, {0.0f, side, 0.0f}, 0.0);
      const auto far_hit = scene.cast({x, side * 7.8f, 1.0f}, {0.0f, -side, 0.0f}, 0.0);
      REQUIRE(near_hit);
      REQUIRE(far_hit);
      CHECK(near_hit->instance == pole->instance);
      CHECK(far_hit->instance == pole->instance);
      const float near_y = 6.6f + near_hit->range;
      const float far_y = 7.8f - far_hit->range;
      const float r = 0.5f * (far_y - near_y);
      const Eigen::Vector2f axis(x, side * 0.5f * (near_y + far_y));
      CHECK(r >= 0.079f);
      CHECK(r <= 0.121f);
      CHECK(near_y >= 7.0f);  // on the sidewalk
      CHECK(far_y <= 7.7f);   // by the kerb, clear of the pedestrians' lines (7.9 m and beyond)
      // In a gap of its row, 0.9-1.0 m from the nearest car body.
      const auto& row = cars[side > 0.0f ? 1 : 0];
      float clearance = 1e9f;
      for (const sim::Aabb& car : row) clearance = std::min(clearance, footprint_distance(axis, car) - r);
      CHECK(clearance >= 0.9f - 2e-3f);
      CHECK(clearance <= 1.0f + 2e-3f);
      const bool in_gap = std::any_of(row.begin(), row.end(), [&](const sim::Aabb& a) {
        return a.hi.x() < x && std::any_of(row.begin(), row.end(), [&](const sim::Aabb& b) {
                 return b.lo.x() > x && b.lo.x() - a.hi.x() <= 1.5f + 1e-3f;
               });
      });
      CHECK(in_gap);
    }
    // No moving object comes within 0.3 m of a parked car or a pole: its
    // footprint (half length along x, half width along y, the loops' U-turns
    // lie beyond |x| = 100) against theirs.
    for (const sim::ObjectInfo& o : scene.objects()) {
      if (!o.moving) continue;
      CAPTURE(o.label);
      const Eigen::Vector2f half = o.label == "car" ? Eigen::Vector2f(2.4f, 0.95f)
                                   : o.label == "cyclist" ? Eigen::Vector2f(0.85f, 0.22f)
                                                          : Eigen::Vector2f(0.3f, 0.3f);
      for (double t = 0.0; t < 60.0; t += 0.1) {
        const Eigen::Vector3f p = scene.position(o.instance, t);
        if (std::abs(p.x()) > 95.0f) continue;
        for (const sim::ObjectInfo& other : scene.objects()) {
          if (other.label != "parked_car" && other.label != "pole") continue;
          const sim::Aabb& b = other.bounds;
          const float dx = std::max({b.lo.x() - (p.x() + half.x()), 0.0f, (p.x() - half.x()) - b.hi.x()});
          // Poles: the mast only (the arm and lamp hang above 5.5 m).
          const float lo_y = other.label == "pole" && b.lo.y() > 0.0f ? b.hi.y() - 0.25f : b.lo.y();
          const float hi_y = other.label == "pole" && b.hi.y() < 0.0f ? b.lo.y() + 0.25f : b.hi.y();
          const float dy = std::max({lo_y - (p.y() + half.y()), 0.0f, (p.y() - half.y()) - hi_y});
          if (std::hypot(dx, dy) < 0.3f) {
            FAIL_CHECK(o.label << " at t = " << t << " s within 0.3 m of " << other.label);
          }
        }
      }
    }
  }
}

TEST_CASE("sim scenes: a street car pulls out of its parking space into the lane, clear of the traffic") {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    CAPTURE(seed);
    const sim::Scene scene = sim::street_scene(seed);
    const sim::ObjectInfo* departing = nullptr;
    for (const sim::ObjectInfo& o : scene.objects()) {
      if (o.label == "car" && scene.position(o.instance, 0.0).y() < -5.0f) departing = &o;
    }
    REQUIRE(departing != nullptr);
    const int id = departing->instance;
    const Eigen::Vector3f parked = scene.position(id, 0.0);
    double start = 0.0;
    while (start < 60.0 && (scene.position(id, start + 0.05) - parked).norm() < 1e-4f) start += 0.05;
    CHECK(start >= 1.0 - 1e-6);
    CHECK(start < 30.0);
    // From standing, 2.5 m/s^2 up to 10 m/s: 5 m in the first 2 s, in the
    // lane and at top speed after 4 s, heading -x.
    CHECK((scene.position(id, start + 2.0) - parked).norm() == doctest::Approx(5.0f).epsilon(0.05));
    const Eigen::Vector3f cruising = scene.position(id, start + 5.0);
    CHECK(cruising.y() == doctest::Approx(-2.0f));
    CHECK((scene.position(id, start + 5.5) - cruising).x() == doctest::Approx(-5.0f).epsilon(1e-3));
    for (double t = 0.0; t < start + 20.0; t += 0.1) {
      CHECK((scene.position(id, t + 0.1) - scene.position(id, t)).norm() <= 1.0f + 1e-3f);
    }
    CHECK(scene.position(id, 100.0).isApprox(Eigen::Vector3f(-140.0f, -2.0f, 0.0f)));  // stopped at the end
    // Clear of every car and cyclist: the footprints at their largest
    // (the scene keeps 1 m between the actual ones; headings ignored) 0.3 m
    // apart and more, short of the loops' U-turns (|x| >= 100).
    for (const sim::ObjectInfo& o : scene.objects()) {
      if (!o.moving || o.instance == id || (o.label != "car" && o.label != "cyclist")) continue;
      CAPTURE(o.label);
      const Eigen::Vector2f half = o.label == "car" ? Eigen::Vector2f(4.8f, 1.9f) : Eigen::Vector2f(2.4f + 0.85f, 0.95f + 0.22f);
      for (double t = 0.0; scene.position(id, t).x() > -95.0f; t += 0.05) {
        const Eigen::Vector2f d = (scene.position(o.instance, t) - scene.position(id, t)).head<2>().cwiseAbs();
        const Eigen::Vector2f gap = (d - half).cwiseMax(0.0f);
        if (gap.norm() < 0.3f - 1e-3f) FAIL_CHECK(o.label << " at t = " << t << " s too close to the departing car");
      }
    }
  }
}

TEST_CASE("sim scenes: office bookshelves and some desks against the walls, walkers clear of all furniture") {
  constexpr float kHalfX = 10.0f, kHalfY = 6.0f;
  const auto wall_gap = [&](const sim::Aabb& b) {
    return std::min({b.lo.x() + kHalfX, kHalfX - b.hi.x(), b.lo.y() + kHalfY, kHalfY - b.hi.y()});
  };
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    CAPTURE(seed);
    const sim::Scene scene = sim::office_scene(seed);
    int wall_desks = 0;
    for (const sim::ObjectInfo& o : scene.objects()) {
      CAPTURE(o.label);
      const sim::Aabb& b = o.bounds;
      const Eigen::Vector3f size = b.hi - b.lo;
      if (o.label == "bookshelf") {
        CHECK(wall_gap(b) >= 0.02f - 1e-4f);
        CHECK(wall_gap(b) <= 0.05f + 1e-4f);
        CHECK(size.z() >= 1.6f - 1e-4f);
        CHECK(size.z() <= 2.0f + 1e-4f);
        const float depth = std::min(size.x(), size.y());
        const float width = std::max(size.x(), size.y());
        CHECK(depth >= 0.3f - 1e-4f);
        CHECK(depth <= 0.4f + 1e-4f);
        CHECK(width >= 0.8f - 1e-4f);
        CHECK(width <= 1.6f + 1e-4f);
        // Its long side faces the room: the shallow extent is across the nearest wall.
        const bool y_wall = std::min(b.lo.y() + kHalfY, kHalfY - b.hi.y()) <= 0.05f + 1e-4f;
        CHECK((y_wall ? size.y() : size.x()) == doctest::Approx(depth));
      } else if (o.label == "cabinet") {
        CHECK(wall_gap(b) == doctest::Approx(0.02f).epsilon(1e-3));
      } else if (o.label == "desk") {
        const float gap = wall_gap(b);
        if (gap <= 0.05f + 1e-4f) {
          ++wall_desks;
          CHECK(gap >= 0.02f - 1e-4f);
          // The long side along the wall.
          const bool y_wall = std::min(b.lo.y() + kHalfY, kHalfY - b.hi.y()) <= 0.05f + 1e-4f;
          CHECK((y_wall ? size.x() : size.y()) >= 1.4f - 1e-4f);
        } else {
          CHECK(gap >= 0.3f - 1e-4f);  // the others stand free
        }
      }
    }
    CHECK(wall_desks >= 2);
    CHECK(wall_desks <= 3);
    // The walkers (r 0.3 m) never touch furniture or pillars.
    for (const sim::ObjectInfo& o : scene.objects()) {
      if (!o.moving) continue;
      for (double t = 0.0; t < 40.0; t += 0.1) {
        const Eigen::Vector2f p = scene.position(o.instance, t).head<2>();
        for (const sim::ObjectInfo& other : scene.objects()) {
          if (other.moving) continue;
          if (footprint_distance(p, other.bounds) < 0.3f) FAIL_CHECK("person at t = " << t << " s touches " << other.label);
        }
      }
    }
  }
}

TEST_CASE("sim simulator: ego-motion shrinks the range to a wall at the driving speed") {
  sim::Scene wall;
  wall.add_structure(sim::ShapeSet().add(sim::Plane::infinite(kX, {20, 0, 0})), sc::SurfaceClass::wall);
  sim::Simulator<CyclingSensor>::Params params;
  params.range_noise = 0.0f;
  params.velocity = {2.0f, 0.0f, 0.0f};
  sim::Simulator<CyclingSensor> simulator(fixed_direction(kX, 1000.0), wall, params);
  double st = 0, sr = 0, stt = 0, str = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    CHECK(simulator.time() == doctest::Approx(i / 1000.0));
    const sim::SimPoint p = simulator.next();
    CHECK(p.t == doctest::Approx(i / 1000.0));
    CHECK(p.x == doctest::Approx(20.0 - 2.0 * p.t).epsilon(1e-5));  // sensor frame at capture time
    CHECK(p.y == 0.0f);
    CHECK(p.z == 0.0f);
    CHECK(p.instance == 0);
    st += p.t;
    sr += p.x;
    stt += p.t * p.t;
    str += p.t * p.x;
  }
  const double slope = (n * str - st * sr) / (n * stt - st * st);
  CHECK(slope == doctest::Approx(-2.0).epsilon(1e-4));
  CHECK(simulator.sensor_position(1.0).isApprox(Eigen::Vector3f(2, 0, 1)));
}

TEST_CASE("sim simulator: yaw rotates the rays into the world") {
  sim::Scene wall;
  wall.add_structure(sim::ShapeSet().add(sim::Plane::infinite(kX, {20, 0, 0})), sc::SurfaceClass::wall);
  sim::Simulator<CyclingSensor>::Params params;
  params.range_noise = 0.0f;
  params.yaw_rate = 0.3f;
  sim::Simulator<CyclingSensor> simulator(fixed_direction(kX, 100.0), wall, params);
  for (int i = 0; i < 300; ++i) {
    const sim::SimPoint p = simulator.next();
    CHECK(p.x == doctest::Approx(20.0 / std::cos(0.3 * p.t)).epsilon(1e-5));
    CHECK(p.y == 0.0f);
  }
}

TEST_CASE("sim simulator: points in the sensor frame map back onto the office walls") {
  sim::Simulator<CyclingSensor>::Params params;
  params.range_noise = 0.0f;
  params.velocity = {0.8f, 0.3f, 0.0f};
  params.yaw_rate = 0.5f;
  params.max_range = 100.0f;
  sim::Simulator<CyclingSensor> simulator(raster(72, 8, -0.8f, 0.8f, 20000.0), sim::office_scene(4), params);
  int structure = 0;
  for (int i = 0; i < 20000; ++i) {
    const sim::SimPoint p = simulator.next();
    if (p.instance != 0) continue;
    ++structure;
    const float yaw = simulator.sensor_yaw(p.t);
    const Eigen::Vector3f o = simulator.sensor_position(p.t);
    const Eigen::Vector3f w = o + Eigen::Vector3f(std::cos(yaw) * p.x - std::sin(yaw) * p.y,
                                                  std::sin(yaw) * p.x + std::cos(yaw) * p.y, p.z);
    const float gap = std::min({std::abs(w.z()), std::abs(w.z() - 3.0f), std::abs(std::abs(w.x()) - 10.0f),
                                std::abs(std::abs(w.y()) - 6.0f)});
    CHECK(gap < 1e-3f);
  }
  CHECK(structure > 5000);
}

TEST_CASE("sim simulator: deterministic for a seed") {
  sim::Simulator<CyclingSensor>::Params params;
  params.dropout = 0.2f;
  params.range_noise = 0.05f;
  params.velocity = {0.5f, 0, 0};
  params.seed = 11;
  const CyclingSensor sensor = raster(100, 10, -0.5f, 0.5f);
  sim::Simulator<CyclingSensor> a(sensor, sim::street_scene(2), params);
  sim::Simulator<CyclingSensor> b(sensor, sim::street_scene(2), params);
  params.seed = 12;
  sim::Simulator<CyclingSensor> c(sensor, sim::street_scene(2), params);
  int differ = 0;
  for (int i = 0; i < 5000; ++i) {
    const sim::SimPoint pa = a.next();
    const sim::SimPoint pb = b.next();
    const sim::SimPoint pc = c.next();
    REQUIRE(pa.x == pb.x);
    REQUIRE(pa.y == pb.y);
    REQUIRE(pa.z == pb.z);
    REQUIRE(pa.t == pb.t);
    REQUIRE(pa.instance == pb.instance);
    REQUIRE(pa.intensity == pb.intensity);
    differ += pa.x != pc.x || pa.t != pc.t;
  }
  CHECK(a.stats().fired == b.stats().fired);
  CHECK(differ > 4000);
}

TEST_CASE("sim simulator: dropout rate and range noise") {
  sim::Scene room;  // a closed box: every ray returns
  room.add_structure(sim::ShapeSet()
                         .add(sim::Plane::infinite(kX, {-10, 0, 0}))
                         .add(sim::Plane::infinite(kX, {10, 0, 0}))
                         .add(sim::Plane::infinite(Eigen::Vector3f::UnitY(), {0, -10, 0}))
                         .add(sim::Plane::infinite(Eigen::Vector3f::UnitY(), {0, 10, 0}))
                         .add(sim::Plane::infinite(kZ, {0, 0, -9}))
                         .add(sim::Plane::infinite(kZ, {0, 0, 11})),
                     sc::SurfaceClass::wall);
  SUBCASE("dropout") {
    sim::Simulator<CyclingSensor>::Params params;
    params.dropout = 0.3f;
    sim::Simulator<CyclingSensor> simulator(raster(36, 5, -0.5f, 0.5f), room, params);
    for (int i = 0; i < 20000; ++i) simulator.next();
    const auto& s = simulator.stats();
    CHECK(s.returned == 20000);
    CHECK(s.no_hit == 0);
    CHECK(s.out_of_range == 0);
    CHECK(s.fired == s.returned + s.dropped);
    const double rate = static_cast<double>(s.dropped) / static_cast<double>(s.fired);
    CHECK(rate == doctest::Approx(0.3).epsilon(0.05));  // +-0.015; the standard error is 0.0027
  }
  SUBCASE("noise") {
    sim::Simulator<CyclingSensor>::Params params;
    params.range_noise = 0.05f;
    sim::Simulator<CyclingSensor> simulator(fixed_direction(kX), room, params);
    const int n = 20000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
      const sim::SimPoint p = simulator.next();
      CHECK(p.y == 0.0f);
      sum += p.x;
      sum2 += static_cast<double>(p.x) * p.x;
    }
    const double mean = sum / n;
    const double sd = std::sqrt(sum2 / n - mean * mean);
    CHECK(mean == doctest::Approx(10.0).epsilon(2e-4));  // +-0.002; standard error 0.00035
    CHECK(sd == doctest::Approx(0.05).epsilon(0.05));    // +-5 %; standard error 0.5 %
  }
}

TEST_CASE("sim simulator: min and max range are honoured") {
  sim::Simulator<CyclingSensor>::Params params;
  params.max_range = 5.0f;
  params.min_range = 1.5f;
  sim::Simulator<CyclingSensor> simulator(raster(180, 12, -1.2f, 1.2f), sim::office_scene(1), params);
  for (int i = 0; i < 20000; ++i) {
    const sim::SimPoint p = simulator.next();
    const float r = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    CHECK(r <= 5.0f + 1e-4f);
    CHECK(r >= 1.5f - 1e-4f);
    CHECK(p.intensity >= 0.0f);
    CHECK(p.intensity <= 150.0f);  // diffuse only: the office has no retroreflector
  }
  CHECK(simulator.stats().out_of_range > 1000);
}

TEST_CASE("sim simulator: invalid params and scenes without returns throw") {
  using Sim = sim::Simulator<CyclingSensor>;
  const CyclingSensor sensor = fixed_direction(kX);
  const auto make = [&](auto edit) {
    Sim::Params p;
    edit(p);
    return Sim(sensor, sim::Scene{}, p);
  };
  CHECK_THROWS_AS(make([](Sim::Params& p) { p.range_noise = -0.1f; }), std::invalid_argument);
  CHECK_THROWS_AS(make([](Sim::Params& p) { p.dropout = 1.0f; }), std::invalid_argument);
  CHECK_THROWS_AS(make([](Sim::Params& p) { p.min_range = -1.0f; }), std::invalid_argument);
  CHECK_THROWS_AS(make([](Sim::Params& p) { p.max_range = 0.05f; }), std::invalid_argument);
  CHECK_THROWS_AS(make([](Sim::Params& p) { p.velocity.x() = std::nanf(""); }), std::invalid_argument);
  CHECK_THROWS_WITH_AS(make([](Sim::Params& p) { p.dropout = 1.5f; }), doctest::Contains("dropout"),
                       std::invalid_argument);
  Sim empty = make([](Sim::Params&) {});
  CHECK_THROWS_AS(empty.next(), std::runtime_error);
  CHECK(empty.stats().no_hit == Sim::kMaxConsecutiveMisses);
}

TEST_CASE("sim simulator: a piecewise ego-motion profile integrates pose and turns the rays") {
  sim::Scene wall;
  wall.add_structure(sim::ShapeSet().add(sim::Plane::infinite(kX, {20, 0, 0})), sc::SurfaceClass::wall);
  sim::Simulator<CyclingSensor>::Params params;
  params.range_noise = 0.0f;
  params.velocity = {1.0f, 0.0f, 0.0f};  // before the first segment
  // rest from 1 s, a turning and driving burst over [2, 2.5), rest again.
  params.motion_profile = {{1.0, {0.0f, 0.0f, 0.0f}, 0.0f},
                           {2.0, {2.0f, 0.0f, 0.0f}, 0.4f},
                           {2.5, {0.0f, 0.0f, 0.0f}, 0.0f}};
  sim::Simulator<CyclingSensor> simulator(fixed_direction(kX, 100.0), wall, params);
  // The pose is the integral of the piecewise velocity and yaw rate.
  CHECK(simulator.sensor_position(0.5).isApprox(Eigen::Vector3f(0.5f, 0, 1)));
  CHECK(simulator.sensor_position(1.7).isApprox(Eigen::Vector3f(1.0f, 0, 1)));
  CHECK(simulator.sensor_position(2.25).isApprox(Eigen::Vector3f(1.5f, 0, 1)));
  CHECK(simulator.sensor_position(3.0).isApprox(Eigen::Vector3f(2.0f, 0, 1)));
  CHECK(simulator.sensor_yaw(1.9) == 0.0f);
  CHECK(simulator.sensor_yaw(2.25) == doctest::Approx(0.1));
  CHECK(simulator.sensor_yaw(2.9) == doctest::Approx(0.2));
  // The returns follow the same pose: range to the wall along the turned ray.
  for (int i = 0; i < 300; ++i) {
    const sim::SimPoint p = simulator.next();
    const double x = static_cast<double>(simulator.sensor_position(p.t).x());
    const double yaw = static_cast<double>(simulator.sensor_yaw(p.t));
    CHECK(p.x == doctest::Approx((20.0 - x) / std::cos(yaw)).epsilon(1e-5));
  }
  // An empty profile and a profile repeating the base motion give the same stream.
  sim::Simulator<CyclingSensor>::Params plain;
  plain.yaw_rate = 0.2f;
  plain.velocity = {0.5f, 0.1f, 0.0f};
  sim::Simulator<CyclingSensor>::Params repeated = plain;
  repeated.motion_profile = {{0.0, plain.velocity, plain.yaw_rate}};
  sim::Simulator<CyclingSensor> a(raster(36, 4, -0.3f, 0.3f), sim::office_scene(2), plain);
  sim::Simulator<CyclingSensor> b(raster(36, 4, -0.3f, 0.3f), sim::office_scene(2), repeated);
  for (int i = 0; i < 2000; ++i) {
    const sim::SimPoint pa = a.next();
    const sim::SimPoint pb = b.next();
    CHECK(pa.t == pb.t);
    CHECK(pa.instance == pb.instance);
    CHECK(Eigen::Vector3f(pa.x - pb.x, pa.y - pb.y, pa.z - pb.z).norm() < 1e-3f);
  }
  // Invalid profiles name the field.
  using Sim = sim::Simulator<CyclingSensor>;
  Sim::Params bad;
  bad.motion_profile = {{1.0, {0, 0, 0}, 0.0f}, {0.5, {0, 0, 0}, 0.0f}};
  CHECK_THROWS_WITH_AS(Sim(fixed_direction(kX), wall, bad), doctest::Contains("motion_profile start"),
                       std::invalid_argument);
  bad.motion_profile = {{0.0, {0, 0, 0}, std::nanf("")}};
  CHECK_THROWS_WITH_AS(Sim(fixed_direction(kX), wall, bad), doctest::Contains("motion_profile yaw_rate"),
                       std::invalid_argument);
}
