// SPDX-License-Identifier: MIT
// PosedMotion: a fixed mount (level, pitched, upside down), interpolation
// against PoseTrajectory and Eigen's slerp, the span (no_pose), and motion
// compensation: two observations of one world point from a moving, yawing
// sensor land on the same world point.

#include <doctest/doctest.h>

#include <streamclust/concepts/motion.hpp>
#include <streamclust/motion/pose.hpp>
#include <streamclust/motion/posed_motion.hpp>
#include <streamclust/motion/trajectory.hpp>

#include "support/constants.hpp"
#include "support/invalid_argument.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <vector>

namespace sc = streamclust;
using streamclust::test::invalid_argument_message;

static_assert(sc::is_motion_policy_v<sc::PosedMotion>, "PosedMotion models the motion concept");
static_assert(!sc::PosedMotion::identity, "PosedMotion is not the identity");

namespace {

using streamclust::test::kDeg;

sc::PlacedPoint place(sc::PosedMotion& motion, const Eigen::Vector3f& p, double t) {
  sc::PlacedPoint placed;
  REQUIRE(motion.place(p, t, placed) == sc::RejectReason::accepted);
  return placed;
}

sc::PosedMotion fixed(double roll, double pitch, double yaw,
                      const Eigen::Vector3d& translation = Eigen::Vector3d::Zero()) {
  sc::PosedMotion::Params params;
  params.mount = sc::mount_from_roll_pitch_yaw_deg(roll, pitch, yaw);
  params.mount.translation = translation;
  return sc::PosedMotion(params);
}

/// A vehicle driving at `speed` along its heading while yawing at `yaw_rate`,
/// swaying in roll and pitch, one pose every `period` seconds from `t0`.
std::vector<sc::StampedPose> drive(double t0, double seconds, double period, double speed, double yaw_rate) {
  std::vector<sc::StampedPose> poses;
  Eigen::Vector3d position(5.0, -3.0, 0.2);
  const auto n = static_cast<int>(std::lround(seconds / period));
  for (int i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) * period;
    sc::Pose pose = sc::mount_from_roll_pitch_yaw_deg(3.0 * std::sin(2.0 * t), 2.0 * std::cos(3.0 * t),
                                                      20.0 + yaw_rate * t / kDeg);
    pose.translation = position;
    poses.push_back(sc::StampedPose{t0 + t, pose});
    const double heading = 20.0 * kDeg + yaw_rate * t;
    position += period * speed * Eigen::Vector3d(std::cos(heading), std::sin(heading), 0.01);
  }
  return poses;
}

}  // namespace

TEST_CASE("PosedMotion: the identity mount places a point where it is") {
  sc::PosedMotion motion(sc::PosedMotion::Params{});
  for (const Eigen::Vector3f& p : {Eigen::Vector3f(1.5f, -2.0f, 0.25f), Eigen::Vector3f(-30.0f, 4.0f, 12.0f)}) {
    const sc::PlacedPoint placed = place(motion, p, 123.456);
    CHECK(placed.world == p);
    CHECK(placed.ray == p);
  }
}

TEST_CASE("PosedMotion: a fixed mount rotates as documented (pitch down, upside down)") {
  // Pitched down 30 degrees: what the sensor sees 2 m along its own x axis is lower than the sensor, ahead.
  {
    sc::PosedMotion motion = fixed(0.0, 30.0, 0.0);
    const sc::PlacedPoint placed = place(motion, Eigen::Vector3f(2.0f, 0.0f, 0.0f), 0.0);
    CHECK(placed.world.x() == doctest::Approx(2.0 * std::cos(30.0 * kDeg)).epsilon(1e-6));
    CHECK(placed.world.y() == doctest::Approx(0.0).epsilon(1e-6));
    CHECK(placed.world.z() == doctest::Approx(-1.0).epsilon(1e-6));
  }
  // The same sensor 1 m above the ground (mount translation): that point is on the ground, z = 0.
  {
    sc::PosedMotion motion = fixed(0.0, 30.0, 0.0, Eigen::Vector3d(0.0, 0.0, 1.0));
    const sc::PlacedPoint placed = place(motion, Eigen::Vector3f(2.0f, 0.0f, 0.0f), 0.0);
    CHECK(std::abs(placed.world.z()) < 1e-6f);
    CHECK((placed.world - placed.ray - Eigen::Vector3f(0.0f, 0.0f, 1.0f)).norm() < 1e-6f);
  }
  // Pitch 15: the sensor's x axis points 15 degrees below the horizon.
  {
    sc::PosedMotion motion = fixed(0.0, 15.0, 0.0);
    const sc::PlacedPoint placed = place(motion, Eigen::Vector3f(10.0f, 0.0f, 0.0f), 0.0);
    CHECK(std::atan2(-placed.world.z(), placed.world.x()) == doctest::Approx(15.0 * kDeg).epsilon(1e-6));
  }
  // Upside down (roll 180): the sensor's +z is the world's -z, its +y the world's -y.
  {
    sc::PosedMotion motion = fixed(180.0, 0.0, 0.0);
    const sc::PlacedPoint placed = place(motion, Eigen::Vector3f(1.0f, 2.0f, 3.0f), 0.0);
    CHECK((placed.world - Eigen::Vector3f(1.0f, -2.0f, -3.0f)).norm() < 1e-6f);
    CHECK(placed.ray == placed.world);
  }
}

TEST_CASE("PosedMotion: between and at the poses it places as PoseTrajectory's interpolation (Eigen slerp)") {
  // Segments with small and large turns (the polynomial and the std::sin paths).
  std::vector<sc::StampedPose> poses;
  const double yaws[] = {0.0, 1.0, 5.0, 50.0, 175.0, 190.0, 200.0};
  for (int i = 0; i < 7; ++i) {
    sc::Pose p = sc::mount_from_roll_pitch_yaw_deg(7.0 * i, -3.0 * i, yaws[i]);
    p.translation = Eigen::Vector3d(1.0 * i, -0.5 * i * i, 0.1 * i);
    poses.push_back(sc::StampedPose{100.0 + 0.1 * i, p});
  }
  const auto trajectory = std::make_shared<const sc::PoseTrajectory>(poses);
  sc::PosedMotion::Params params;
  params.trajectory = trajectory;
  params.mount = sc::mount_from_roll_pitch_yaw_deg(2.0, 15.0, -4.0);
  params.mount.translation = Eigen::Vector3d(0.3, 0.0, 0.8);
  sc::PosedMotion motion(params);
  const Eigen::Vector3f p(4.0f, -1.0f, 2.0f);
  double worst = 0.0;
  for (int k = 0; k <= 600; ++k) {
    const double t = 100.0 + 0.001 * k;
    sc::PoseTrajectory::Cursor cursor;
    const std::optional<sc::Pose> at = trajectory->at(t, cursor);
    REQUIRE(at.has_value());
    const sc::Pose sensor = *at * params.mount;
    const sc::PlacedPoint placed = place(motion, p, t);
    const Eigen::Vector3d ray = sensor.rotation * p.cast<double>();
    worst = std::max(worst, (placed.ray.cast<double>() - ray).norm());
    worst = std::max(worst, (placed.world.cast<double>() - (ray + sensor.translation)).norm());
  }
  CHECK(worst < 2e-5);
  // The rotation halfway through the 45-degree segment is Eigen's slerp.
  const Eigen::Quaterniond half = poses[2].pose.rotation.slerp(0.5, poses[3].pose.rotation);
  const Eigen::Vector3d expected = (half * params.mount.rotation) * p.cast<double>();
  CHECK((place(motion, p, 100.25).ray.cast<double>() - expected).norm() < 2e-5);
}

TEST_CASE("PosedMotion: outside the poses' span a point has no pose and is left unplaced") {
  const auto trajectory = std::make_shared<const sc::PoseTrajectory>(drive(50.0, 1.0, 0.01, 5.0, 0.5));
  sc::PosedMotion motion(sc::PosedMotion::Params{sc::Pose{}, trajectory});
  sc::PlacedPoint placed;
  placed.world = Eigen::Vector3f(7.0f, 7.0f, 7.0f);
  const Eigen::Vector3f p(1.0f, 0.0f, 0.0f);
  CHECK(motion.place(p, 49.9999, placed) == sc::RejectReason::no_pose);
  CHECK(motion.place(p, 51.0001, placed) == sc::RejectReason::no_pose);
  CHECK(motion.place(p, std::numeric_limits<double>::quiet_NaN(), placed) == sc::RejectReason::no_pose);
  CHECK(placed.world == Eigen::Vector3f(7.0f, 7.0f, 7.0f));
  CHECK(motion.place(p, 50.0, placed) == sc::RejectReason::accepted);
  CHECK(motion.place(p, 51.0, placed) == sc::RejectReason::accepted);
  // Leaving and coming back (a jump back in time) still places correctly.
  CHECK(motion.place(p, 52.0, placed) == sc::RejectReason::no_pose);
  CHECK(motion.place(p, 50.0, placed) == sc::RejectReason::accepted);
  CHECK((placed.world.cast<double>() - trajectory->poses()[0].pose * p.cast<double>()).norm() < 1e-5);
}

TEST_CASE("PosedMotion: a single pose places the points of its instant only") {
  sc::Pose pose = sc::mount_from_roll_pitch_yaw_deg(0.0, 0.0, 90.0);
  pose.translation = Eigen::Vector3d(1.0, 2.0, 3.0);
  const auto trajectory = std::make_shared<const sc::PoseTrajectory>(std::vector<sc::StampedPose>{{7.0, pose}});
  sc::PosedMotion motion(sc::PosedMotion::Params{sc::Pose{}, trajectory});
  sc::PlacedPoint placed;
  CHECK(motion.place(Eigen::Vector3f(1.0f, 0.0f, 0.0f), 7.0 + 1e-9, placed) == sc::RejectReason::no_pose);
  REQUIRE(motion.place(Eigen::Vector3f(1.0f, 0.0f, 0.0f), 7.0, placed) == sc::RejectReason::accepted);
  CHECK((placed.world - Eigen::Vector3f(1.0f, 3.0f, 3.0f)).norm() < 1e-6f);
  CHECK((placed.ray - Eigen::Vector3f(0.0f, 1.0f, 0.0f)).norm() < 1e-6f);
}

TEST_CASE("PosedMotion: a moving, yawing sensor sees one world point at one world position") {
  // 100 Hz odometry, 10 m/s, 1 rad/s yaw, at epoch-scale times; the sensor pitched on the vehicle.
  const double t0 = 1700000000.0;
  const auto trajectory = std::make_shared<const sc::PoseTrajectory>(drive(t0, 2.0, 0.01, 10.0, 1.0));
  sc::PosedMotion::Params params;
  params.trajectory = trajectory;
  params.mount = sc::mount_from_roll_pitch_yaw_deg(0.0, 20.0, 10.0);
  params.mount.translation = Eigen::Vector3d(0.5, 0.0, 1.2);
  sc::PosedMotion motion(params);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-20.0, 20.0);
  std::uniform_real_distribution<double> time(0.0, 2.0);
  sc::PoseTrajectory::Cursor cursor;
  double worst = 0.0, worst_ray = 0.0;
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d world(coordinate(rng) + 10.0, coordinate(rng), 0.1 * coordinate(rng));
    // Two capture times, in order (the stream's clock), with the point seen from each.
    double ta = t0 + time(rng), tb = t0 + time(rng);
    if (tb < ta) std::swap(ta, tb);
    const sc::Pose sensor_a = *trajectory->at(ta, cursor) * params.mount;
    const sc::Pose sensor_b = *trajectory->at(tb, cursor) * params.mount;
    const Eigen::Vector3f pa = (sensor_a.inverse() * world).cast<float>();
    const Eigen::Vector3f pb = (sensor_b.inverse() * world).cast<float>();
    const sc::PlacedPoint a = place(motion, pa, ta);
    const sc::PlacedPoint b = place(motion, pb, tb);
    worst = std::max({worst, (a.world.cast<double>() - world).norm(), (b.world.cast<double>() - world).norm()});
    // ray == world - the sensor's position at the capture time
    worst_ray = std::max(worst_ray, ((a.world - a.ray).cast<double>() - sensor_a.translation).norm());
    worst_ray = std::max(worst_ray, ((b.world - b.ray).cast<double>() - sensor_b.translation).norm());
  }
  CHECK(worst < 1e-4);
  CHECK(worst_ray < 1e-4);
}

TEST_CASE("PosedMotion: a bad mount is rejected naming the parameter") {
  sc::PosedMotion::Params params;
  params.mount.rotation.coeffs() << 0.0, 0.0, 0.0, 0.0;
  CHECK(invalid_argument_message([&] { sc::PosedMotion m{params}; }).find("mount.rotation norm = 0") !=
        std::string::npos);
  params.mount = sc::Pose{};
  params.mount.translation.x() = std::numeric_limits<double>::quiet_NaN();
  CHECK(invalid_argument_message([&] { sc::PosedMotion m{params}; }).find("mount.translation = nan") !=
        std::string::npos);
}
