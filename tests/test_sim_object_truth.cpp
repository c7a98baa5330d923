// SPDX-License-Identifier: MIT
// The simulator's object ground truth for trackers: footprints of shape
// sets, moving objects' boxes and velocities over time, and every simulated
// object point inside its object's truth box at its capture time.

#include <doctest/doctest.h>

#include <streamclust/sim/scene.hpp>
#include <streamclust/sim/scene_building.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/simulator.hpp>

#include <Eigen/Core>

#include "support/constants.hpp"

#include <cmath>
#include <cstddef>
#include <map>
#include <string>

namespace {

namespace sim = streamclust::sim;
using streamclust::test::kPi;

/// Distance between two axis directions (modulo pi) [rad].
float axis_gap(float a, float b) { return std::abs(std::remainder(a - b, kPi)); }

/// Is `p` inside `box` grown by `margin` [m]?
bool inside(const sim::ObjectBox& box, const Eigen::Vector3f& p, float margin) {
  const float c = std::cos(box.yaw), s = std::sin(box.yaw);
  const Eigen::Vector3f d = p - box.center;
  const float along = c * d.x() + s * d.y();
  const float across = -s * d.x() + c * d.y();
  return std::abs(along) <= 0.5f * box.length + margin && std::abs(across) <= 0.5f * box.width + margin &&
         std::abs(d.z()) <= 0.5f * box.height + margin;
}

}  // namespace

TEST_CASE("sim object truth: the smallest footprint of boxes, cars and round shapes") {
  const sim::ObjectBox box = sim::smallest_footprint(
      sim::ShapeSet().add(sim::Box::rotated({3, -2, 0.5f}, {1.0f, 0.4f, 0.5f}, 0.6f)));
  CHECK(box.length == doctest::Approx(2.0f));
  CHECK(box.width == doctest::Approx(0.8f));
  CHECK(box.height == doctest::Approx(1.0f));
  CHECK(axis_gap(box.yaw, 0.6f) < 1e-4f);
  CHECK(box.center.isApprox(Eigen::Vector3f(3, -2, 0.5f), 1e-5f));

  // A box whose long side is its y axis: the length turns to it (yaw + pi/2).
  const sim::ObjectBox turned = sim::smallest_footprint(
      sim::ShapeSet().add(sim::Box::rotated({0, 0, 1}, {0.3f, 1.5f, 1.0f}, 0.2f)));
  CHECK(turned.length == doctest::Approx(3.0f));
  CHECK(turned.width == doctest::Approx(0.6f));
  CHECK(axis_gap(turned.yaw, 0.2f + 0.5f * kPi) < 1e-4f);
  CHECK(turned.yaw > -0.5f * kPi);
  CHECK(turned.yaw <= 0.5f * kPi);

  // A car of several parts, yawed: its body's length and width.
  const sim::ObjectBox car = sim::smallest_footprint(sim::detail::car_shapes({10, 4, 0}, 2.5f, 4.5f, 1.8f, 1.5f));
  CHECK(car.length == doctest::Approx(4.5f).epsilon(0.02));
  CHECK(car.width == doctest::Approx(1.8f).epsilon(0.02));
  CHECK(car.height == doctest::Approx(1.5f).epsilon(0.05));
  CHECK(axis_gap(car.yaw, 2.5f) < 1e-3f);
  CHECK((car.center.head<2>() - Eigen::Vector2f(10, 4)).norm() < 0.05f);

  // A tree: trunk and crown; the crown's width.
  const sim::ObjectBox tree = sim::smallest_footprint(
      sim::ShapeSet().add(sim::Cylinder{1, 1, 0.2f, 0.0f, 4.0f}).add(sim::Ellipsoid{{1, 1, 4}, {1.0f, 0.8f, 1.2f}}));
  CHECK(tree.length == doctest::Approx(2.0f));
  CHECK(tree.width == doctest::Approx(1.6f));
  CHECK(tree.height == doctest::Approx(5.2f));
  CHECK(tree.center.z() == doctest::Approx(2.6f));

  CHECK(sim::smallest_footprint(sim::ShapeSet()).length == 0.0f);
}

TEST_CASE("sim object truth: a moving car's box follows its heading, its velocity its speed") {
  sim::Scene scene;
  const int still = scene.add_object("crate", sim::ShapeSet().add(sim::Box::aligned({4, 4, 0}, {5, 6, 1})));
  const int car = scene.add_moving_object("car", sim::ShapeSet().add(sim::Box::aligned({-2, -1, 0}, {2, 1, 1.5f})),
                                          sim::Trajectory::back_and_forth({-20, 10, 0}, {-20, 30, 0}, 10.0f));
  const int ball = scene.add_moving_object("ball", sim::ShapeSet().add(sim::Sphere{{0, 0, 1}, 0.5f}),
                                           sim::Trajectory::circle({0, 0, 0}, 5.0f, 2.0f), false);

  const sim::ObjectState crate = scene.object_state(still, 3.0);
  CHECK_FALSE(crate.moving);
  CHECK(crate.velocity.norm() == 0.0f);
  CHECK(crate.box.center.isApprox(Eigen::Vector3f(4.5f, 5.0f, 0.5f)));
  CHECK(crate.box.length == doctest::Approx(2.0f));
  CHECK(axis_gap(crate.box.yaw, 0.5f * kPi) < 1e-5f);

  // Heading +y at t = 1 (centre (-20, 20)), -y at t = 3 (centre (-20, 20) again).
  const sim::ObjectState out = scene.object_state(car, 1.0);
  CHECK(out.moving);
  CHECK(out.box.center.isApprox(Eigen::Vector3f(-20, 20, 0.75f), 1e-4f));
  CHECK(out.velocity.isApprox(Eigen::Vector3f(0, 10, 0), 1e-3f));
  CHECK(std::abs(std::remainder(out.box.yaw - 0.5f * kPi, 2.0f * kPi)) < 1e-4f);
  CHECK(out.box.length == doctest::Approx(4.0f));
  CHECK(out.box.width == doctest::Approx(2.0f));
  const sim::ObjectState back = scene.object_state(car, 3.0);
  CHECK(back.velocity.isApprox(Eigen::Vector3f(0, -10, 0), 1e-3f));
  CHECK(std::abs(std::remainder(back.box.yaw + 0.5f * kPi, 2.0f * kPi)) < 1e-4f);

  // Circling at 2 m/s without turning: the velocity is tangent, the yaw stays.
  for (const double t : {0.0, 1.3, 7.7}) {
    const sim::ObjectState b = scene.object_state(ball, t);
    const Eigen::Vector3f radial = b.box.center - Eigen::Vector3f(0, 0, 1);
    CHECK(radial.norm() == doctest::Approx(5.0f).epsilon(1e-4));
    CHECK(b.velocity.norm() == doctest::Approx(2.0f).epsilon(1e-3));
    CHECK(std::abs(b.velocity.dot(radial)) < 1e-2f);
    CHECK(b.box.yaw == doctest::Approx(0.0f));
  }
  CHECK_THROWS_AS(scene.object_state(0, 0.0), std::out_of_range);
  CHECK_THROWS_AS(scene.object_state(4, 0.0), std::out_of_range);
}

TEST_CASE("sim object truth: every simulated object point lies in its object's truth box at its time") {
  for (const std::string name : {"office", "street", "forest", "hills"}) {
    CAPTURE(name);
    sim::Simulator<sim::Mid360Model>::Params params;
    params.range_noise = 0.0f;
    params.velocity = Eigen::Vector3f(1.2f, 0.0f, 0.0f);
    params.yaw_rate = 0.2f;
    const sim::Scene scene = sim::make_scene(name, 3);
    sim::Simulator<sim::Mid360Model> simulator(sim::Mid360Model(sim::Mid360Model::Params{}), sim::make_scene(name, 3),
                                               params);
    std::size_t object_points = 0, outside = 0;
    std::map<int, std::size_t> moving_points;
    while (simulator.time() < 0.3) {
      const sim::SimPoint p = simulator.next();
      if (p.instance <= 0) continue;
      ++object_points;
      const float yaw = simulator.sensor_yaw(p.t);
      const Eigen::Vector3f o = simulator.sensor_position(p.t);
      const Eigen::Vector3f w = o + Eigen::Vector3f(std::cos(yaw) * p.x - std::sin(yaw) * p.y,
                                                    std::sin(yaw) * p.x + std::cos(yaw) * p.y, p.z);
      const sim::ObjectState truth = scene.object_state(p.instance, p.t);
      if (truth.moving) ++moving_points[p.instance];
      if (!inside(truth.box, w, 0.01f)) ++outside;
    }
    CHECK(object_points > 1000);
    CHECK(outside == 0);
    CHECK_FALSE(moving_points.empty());
  }
}
