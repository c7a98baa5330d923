// SPDX-License-Identifier: MIT
// PoseTrajectory: validation, interpolation at and between knots, the span,
// and the cursor (forward walks, jumps back, one cursor per reader).

#include <doctest/doctest.h>

#include <streamclust/motion/pose.hpp>
#include <streamclust/motion/trajectory.hpp>

#include "support/invalid_argument.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <random>
#include <vector>

namespace sc = streamclust;
using streamclust::test::invalid_argument_message;

namespace {

sc::StampedPose stamped(double t, double x, double y, double z, double yaw_deg, double pitch_deg = 0.0) {
  sc::Pose p = sc::mount_from_roll_pitch_yaw_deg(0.0, pitch_deg, yaw_deg);
  p.translation = Eigen::Vector3d(x, y, z);
  return sc::StampedPose{t, p};
}

double angle_between(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) { return a.angularDistance(b); }

}  // namespace

TEST_CASE("PoseTrajectory: exact at the knots, linear position and Eigen's slerp between them") {
  const std::vector<sc::StampedPose> poses = {stamped(10.0, 0, 0, 0, 0), stamped(10.5, 2, -1, 0.5, 40, 10),
                                              stamped(11.0, 3, 1, 0.5, 100, -5)};
  const sc::PoseTrajectory trajectory(poses);
  CHECK(trajectory.size() == 3);
  CHECK(trajectory.time_begin() == 10.0);
  CHECK(trajectory.time_end() == 11.0);
  sc::PoseTrajectory::Cursor cursor;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const std::optional<sc::Pose> p = trajectory.at(poses[i].time, cursor);
    REQUIRE(p.has_value());
    CHECK(p->translation == poses[i].pose.translation);
    CHECK(p->rotation.coeffs() == poses[i].pose.rotation.coeffs());
  }
  for (const double f : {0.1, 0.25, 0.5, 0.9}) {
    const double t = 10.5 + 0.5 * f;
    const std::optional<sc::Pose> p = trajectory.at(t, cursor);
    REQUIRE(p.has_value());
    const Eigen::Vector3d& a = poses[1].pose.translation;
    const Eigen::Vector3d expected = a + f * (poses[2].pose.translation - a);
    CHECK((p->translation - expected).norm() < 1e-12);
    const Eigen::Quaterniond slerp = poses[1].pose.rotation.slerp(f, poses[2].pose.rotation);
    CHECK(angle_between(p->rotation, slerp) < 1e-9);
    // The slerp turns at a constant rate: the angle from the start grows with f.
    const double total = angle_between(poses[1].pose.rotation, poses[2].pose.rotation);
    CHECK(angle_between(poses[1].pose.rotation, p->rotation) == doctest::Approx(f * total).epsilon(1e-9));
  }
}

TEST_CASE("PoseTrajectory: times outside the span or NaN have no pose; one pose spans one instant") {
  sc::PoseTrajectory trajectory({stamped(1.0, 0, 0, 0, 0), stamped(2.0, 1, 0, 0, 90)});
  CHECK_FALSE(trajectory.at(0.999999).has_value());
  CHECK_FALSE(trajectory.at(2.000001).has_value());
  CHECK_FALSE(trajectory.at(std::numeric_limits<double>::quiet_NaN()).has_value());
  CHECK(trajectory.at(1.0).has_value());
  CHECK(trajectory.at(2.0).has_value());

  sc::PoseTrajectory single({stamped(5.0, 1, 2, 3, 30)});
  REQUIRE(single.at(5.0).has_value());
  CHECK(single.at(5.0)->translation == Eigen::Vector3d(1, 2, 3));
  CHECK_FALSE(single.at(5.0 + 1e-9).has_value());
  CHECK_FALSE(single.at(5.0 - 1e-9).has_value());
}

TEST_CASE("PoseTrajectory: a cursor gives what a fresh binary search gives, forwards and after jumps") {
  std::vector<sc::StampedPose> poses;
  for (int i = 0; i < 200; ++i) {
    poses.push_back(stamped(0.01 * i, 0.3 * i, std::sin(0.1 * i), 0.0, 2.0 * i, std::cos(0.2 * i)));
  }
  const sc::PoseTrajectory trajectory(poses);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> any(-0.1, 2.1);
  sc::PoseTrajectory::Cursor walking;
  std::size_t found = 0;
  for (int k = 0; k < 3000; ++k) {
    // mostly forward steps, sometimes a jump anywhere (also outside the span)
    const double t = k % 50 == 49 ? any(rng) : 0.00066 * (k % 3000);
    sc::PoseTrajectory::Cursor fresh;
    const auto a = trajectory.at(t, walking);
    const auto b = trajectory.at(t, fresh);
    REQUIRE(a.has_value() == b.has_value());
    if (!a) continue;
    ++found;
    CHECK(a->translation == b->translation);
    CHECK(a->rotation.coeffs() == b->rotation.coeffs());
    const std::size_t s = trajectory.find_segment(t, 0);
    CHECK(poses[s].time <= t);
    CHECK(t <= poses[s + 1].time);
  }
  CHECK(found > 2500);
}

TEST_CASE("PoseTrajectory: bad poses are rejected naming the index and the value; quaternions are normalised") {
  CHECK(invalid_argument_message([] { sc::PoseTrajectory t{std::vector<sc::StampedPose>{}}; }).find("empty") !=
        std::string::npos);
  std::vector<sc::StampedPose> poses = {stamped(0.0, 0, 0, 0, 0), stamped(1.0, 0, 0, 0, 0), stamped(1.0, 0, 0, 0, 0)};
  std::string m = invalid_argument_message([&] { sc::PoseTrajectory t{poses}; });
  CHECK(m.find("poses[2].time = 1") != std::string::npos);
  CHECK(m.find("strictly increasing") != std::string::npos);

  poses[2].time = 2.0;
  poses[1].pose.translation.y() = std::numeric_limits<double>::infinity();
  m = invalid_argument_message([&] { sc::PoseTrajectory t{poses}; });
  CHECK(m.find("poses[1].translation = inf") != std::string::npos);

  poses[1].pose.translation.y() = 0.0;
  poses[0].pose.rotation.coeffs() << 0.0, 0.0, 0.0, 1e-9;
  m = invalid_argument_message([&] { sc::PoseTrajectory t{poses}; });
  CHECK(m.find("poses[0].rotation norm") != std::string::npos);

  poses[0].time = std::numeric_limits<double>::quiet_NaN();
  m = invalid_argument_message([&] { sc::PoseTrajectory t{poses}; });
  CHECK(m.find("poses[0].time = nan") != std::string::npos);

  poses[0].time = 0.0;
  poses[0].pose.rotation.coeffs() << 0.0, 0.0, 0.0, 3.0;  // identity, scaled
  const sc::PoseTrajectory ok(poses);
  CHECK(ok.poses()[0].pose.rotation.norm() == doctest::Approx(1.0));
}

TEST_CASE("PoseTrajectory::append: a growing trajectory equals one built at once; a bad pose leaves it unchanged") {
  std::vector<sc::StampedPose> poses;
  for (int i = 0; i < 20; ++i) poses.push_back(stamped(0.01 * i, 0.015 * i, 0.002 * i * i, 0.0, 3.0 * i, 0.5 * i));
  poses[7].pose.rotation.coeffs() *= 2.5;  // not normalised: both normalise it alike
  const sc::PoseTrajectory whole(poses);
  sc::PoseTrajectory grown(std::vector<sc::StampedPose>{poses.front()});
  sc::PoseTrajectory::Cursor cursor;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    grown.append(poses[i]);
    CHECK(grown.time_end() == poses[i].time);
    // A reader between appends (the motion policy on the same thread) sees the new span.
    const auto p = grown.at(poses[i].time - 0.004, cursor);
    REQUIRE(p.has_value());
  }
  REQUIRE(grown.size() == whole.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    CHECK(grown.poses()[i].time == whole.poses()[i].time);
    CHECK(grown.poses()[i].pose.rotation.coeffs() == whole.poses()[i].pose.rotation.coeffs());  // bit for bit
    CHECK(grown.poses()[i].pose.translation == whole.poses()[i].pose.translation);
  }
  // Not later than the last, or not a rotation: refused, the trajectory as it was.
  const std::string m = invalid_argument_message([&] { grown.append(stamped(0.19, 0, 0, 0, 0)); });
  CHECK(m.find("poses[20].time = 0.19") != std::string::npos);
  sc::StampedPose zero = stamped(0.5, 0, 0, 0, 0);
  zero.pose.rotation.coeffs() << 0.0, 0.0, 0.0, 0.0;
  CHECK(invalid_argument_message([&] { grown.append(zero); }).find("rotation norm") != std::string::npos);
  CHECK(grown.size() == poses.size());
  CHECK(grown.time_end() == poses.back().time);
}
