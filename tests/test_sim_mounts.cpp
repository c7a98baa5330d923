// SPDX-License-Identifier: MIT
// Sensor poses in the simulator: mounts (level, pitched, upside down, with a
// lever arm), sensor_pose and trajectory, terrain following, and the check
// that every returned point, mapped by sensor_pose(p.t), lies on the surface
// it hit, with the right surface class.

#include <doctest/doctest.h>

#include <streamclust/motion/pose.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/simulator.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace sc = streamclust;
namespace sim = streamclust::sim;

/// Fires one fixed direction (sensor frame) at a fixed rate.
struct FixedSensor {
  Eigen::Vector3f direction = Eigen::Vector3f::UnitX();
  double rate = 1000.0;
  std::uint64_t index = 0;
  sim::Ray next() {
    sim::Ray r;
    r.direction = direction;
    r.time = static_cast<double>(index++) / rate;
    return r;
  }
  double point_rate() const { return rate; }
};

Eigen::Vector3d world_of(const sc::Pose& pose, const sim::SimPoint& p) {
  return pose * Eigen::Vector3d(static_cast<double>(p.x), static_cast<double>(p.y), static_cast<double>(p.z));
}

/// True when a world point lies (within tol) on the office room's structure of class `c`:
/// the floor z = 0, the ceiling z = 3, or a wall |x| = 10, |y| = 6.
bool on_office_structure(const Eigen::Vector3d& w, sc::SurfaceClass c, double tol) {
  switch (c) {
    case sc::SurfaceClass::ground: return std::abs(w.z()) < tol;
    case sc::SurfaceClass::ceiling: return std::abs(w.z() - 3.0) < tol;
    case sc::SurfaceClass::wall: return std::abs(std::abs(w.x()) - 10.0) < tol || std::abs(std::abs(w.y()) - 6.0) < tol;
    case sc::SurfaceClass::object: return false;
  }
  return false;
}

bool inside(const sim::Aabb& b, const Eigen::Vector3d& w, double tol) {
  for (int k = 0; k < 3; ++k) {
    if (w[k] < static_cast<double>(b.lo[k]) - tol || w[k] > static_cast<double>(b.hi[k]) + tol) return false;
  }
  return true;
}

struct Case {
  const char* name;
  double roll, pitch, yaw;  // mount [deg]
  float speed;              // +x [m/s]
  float yaw_rate;           // [rad/s]
};

const Case kCases[] = {{"level", 0, 0, 0, 0.0f, 0.0f},        {"pitched 15", 0, 15, 0, 0.0f, 0.0f},
                       {"pitched 30", 0, 30, 0, 0.0f, 0.0f},   {"upside down", 180, 0, 0, 0.0f, 0.0f},
                       {"moving, pitched 15", 0, 15, 0, 1.5f, 0.0f},
                       {"yawing, rolled 180", 180, 0, 0, 0.0f, 0.8f},
                       {"moving and yawing, tilted", 10, -20, 30, 1.0f, -0.5f}};

}  // namespace

TEST_CASE("sim mounts: known ranges for a pitched and an upside-down sensor") {
  sim::Scene floor;
  floor.add_structure(sim::ShapeSet().add(sim::Plane::infinite({0, 0, 1}, {0, 0, 0})), sc::SurfaceClass::ground);
  sim::Simulator<FixedSensor>::Params params;
  params.range_noise = 0.0f;
  params.start_position = {0.0f, 0.0f, 1.0f};

  // Pitched 30 deg down, firing forward: the floor 2 m ahead along the ray.
  params.mount = sc::mount_from_roll_pitch_yaw_deg(0.0, 30.0, 0.0);
  sim::Simulator<FixedSensor> pitched(FixedSensor{}, floor, params);
  sim::SimPoint p = pitched.next();
  CHECK(p.x == doctest::Approx(2.0f).epsilon(1e-5));
  CHECK(p.y == doctest::Approx(0.0f));
  CHECK(p.z == doctest::Approx(0.0f));
  CHECK(p.surface == sc::SurfaceClass::ground);
  CHECK(p.instance == 0);

  // Upside down, firing along the sensor's +z: straight down onto the floor;
  // the point is at +z in the sensor frame.
  params.mount = sc::mount_from_roll_pitch_yaw_deg(180.0, 0.0, 0.0);
  sim::Simulator<FixedSensor> flipped(FixedSensor{Eigen::Vector3f::UnitZ()}, floor, params);
  p = flipped.next();
  CHECK(p.z == doctest::Approx(1.0f).epsilon(1e-6));
  CHECK(std::abs(p.x) < 1e-6f);
  CHECK(p.surface == sc::SurfaceClass::ground);
  // Level, the same ray goes to the sky: no return at all.
  params.mount = sc::Pose{};
  sim::Simulator<FixedSensor> level(FixedSensor{Eigen::Vector3f::UnitZ()}, floor, params);
  CHECK_THROWS_AS(level.next(), std::runtime_error);

  // A lever arm: the sensor 0.5 m above the vehicle origin sees the floor 1.5 m below.
  params.mount = sc::mount_from_roll_pitch_yaw_deg(0.0, 90.0, 0.0);  // forward axis straight down
  params.mount.translation = Eigen::Vector3d(0.0, 0.0, 0.5);
  sim::Simulator<FixedSensor> armed(FixedSensor{}, floor, params);
  p = armed.next();
  CHECK(p.x == doctest::Approx(1.5f).epsilon(1e-5));
  CHECK(armed.sensor_position(0.0).z() == doctest::Approx(1.5f));
}

TEST_CASE("sim mounts: points mapped by sensor_pose lie on the surface they hit (office)") {
  for (const Case& c : kCases) {
    const std::string name = c.name;
    CAPTURE(name);
    const sim::Scene scene = sim::office_scene(3);
    sim::Simulator<sim::Mid360Model>::Params params;
    params.range_noise = 0.0f;
    params.start_position = {0.2f, -0.1f, 1.2f};
    params.velocity = {c.speed, 0.0f, 0.0f};
    params.yaw_rate = c.yaw_rate;
    params.mount = sc::mount_from_roll_pitch_yaw_deg(c.roll, c.pitch, c.yaw);
    sim::Simulator<sim::Mid360Model> simulator(sim::Mid360Model{}, scene, params);
    std::map<sc::SurfaceClass, int> seen;
    int wrong = 0;
    for (int i = 0; i < 40000; ++i) {
      const sim::SimPoint p = simulator.next();
      const Eigen::Vector3d w = world_of(simulator.sensor_pose(p.t), p);
      ++seen[p.surface];
      if (p.instance > 0) {
        wrong += p.surface != sc::SurfaceClass::object ||
                 !inside(scene.objects()[static_cast<std::size_t>(p.instance - 1)].bounds, w, 1e-3);
        continue;
      }
      wrong += !on_office_structure(w, p.surface, 2e-3);
    }
    CHECK(wrong == 0);
    CHECK(seen[sc::SurfaceClass::wall] > 500);
    CHECK(seen[sc::SurfaceClass::ground] + seen[sc::SurfaceClass::ceiling] > 500);
    CHECK(seen[sc::SurfaceClass::object] > 500);
  }
}

TEST_CASE("sim mounts: the upside-down Mid-360 looks at the floor, the level one at the ceiling") {
  const auto fraction = [](double roll, sc::SurfaceClass surface) {
    sim::Simulator<sim::Mid360Model>::Params params;
    params.mount = sc::mount_from_roll_pitch_yaw_deg(roll, 0.0, 0.0);
    params.start_position = {0.0f, 0.0f, 1.5f};
    sim::Simulator<sim::Mid360Model> s(sim::Mid360Model{}, sim::office_scene(2), params);
    int n = 0;
    for (int i = 0; i < 20000; ++i) n += s.next().surface == surface;
    return n / 20000.0;
  };
  // The Mid-360 sees -7 .. 52 deg: level, much ceiling and no floor close by; flipped, the reverse.
  const double floor_level = fraction(0.0, sc::SurfaceClass::ground);
  const double floor_flipped = fraction(180.0, sc::SurfaceClass::ground);
  const double ceiling_level = fraction(0.0, sc::SurfaceClass::ceiling);
  const double ceiling_flipped = fraction(180.0, sc::SurfaceClass::ceiling);
  CHECK(floor_flipped > 3.0 * floor_level);
  CHECK(ceiling_level > 3.0 * ceiling_flipped);
}

TEST_CASE("sim mounts: sensor_pose is the vehicle pose times the mount; trajectory samples it") {
  sim::Simulator<FixedSensor>::Params params;
  params.velocity = {1.0f, 0.5f, 0.0f};
  params.yaw_rate = 0.4f;
  params.mount = sc::mount_from_roll_pitch_yaw_deg(5.0, 20.0, -10.0);
  params.mount.translation = Eigen::Vector3d(0.3, 0.0, 0.2);
  params.motion_profile = {{1.0, {0.0f, 1.0f, 0.0f}, -0.2f}};
  sim::Simulator<FixedSensor> s(FixedSensor{}, sim::office_scene(1), params);
  for (double t : {0.0, 0.37, 1.0, 1.8}) {
    CAPTURE(t);
    const sc::Pose pose = s.sensor_pose(t);
    const double yaw = static_cast<double>(s.sensor_yaw(t));
    const Eigen::Quaterniond expected =
        Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())) * params.mount.rotation;
    CHECK(pose.rotation.angularDistance(expected) < 1e-6);
    CHECK((pose.translation - s.sensor_position(t).cast<double>()).norm() < 1e-5);
    // The vehicle's path (1, 0.5) m/s, then (0, 1) m/s from t = 1, plus the lever arm turned by the yaw.
    const Eigen::Vector3d vehicle = t < 1.0 ? Eigen::Vector3d(t, 0.5 * t, 1.0) : Eigen::Vector3d(1.0, 0.5 + (t - 1.0), 1.0);
    const Eigen::Vector3d arm = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * params.mount.translation;
    CHECK((pose.translation - (vehicle + arm)).norm() < 1e-5);
  }
  CHECK(s.sensor_yaw(1.8) == doctest::Approx(0.4 * 1.0 - 0.2 * 0.8).epsilon(1e-6));
  CHECK(s.sensor_position(1.8).y() == doctest::Approx(0.5 + 0.8 + std::sin(0.4 * 1.0 - 0.2 * 0.8) * 0.3).epsilon(1e-4));

  const std::vector<sc::StampedPose> poses = s.trajectory(0.0, 1.0, 200.0);
  REQUIRE(poses.size() == 201);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    CHECK(poses[k].time == doctest::Approx(static_cast<double>(k) / 200.0));
    CHECK(poses[k].pose.translation.isApprox(s.sensor_pose(poses[k].time).translation));
  }
  CHECK(poses.back().time == 1.0);
  const std::vector<sc::StampedPose> odd = s.trajectory(0.1, 0.1125, 200.0);
  REQUIRE(odd.size() == 4);  // 0.1, 0.105, 0.11, then the end 0.1125
  CHECK(odd[2].time == doctest::Approx(0.11));
  CHECK(odd[3].time == 0.1125);
  CHECK(s.trajectory(0.5, 0.5, 200.0).size() == 1);
  CHECK_THROWS_AS(s.trajectory(1.0, 0.5, 200.0), std::invalid_argument);
  CHECK_THROWS_AS(s.trajectory(0.0, 1.0, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(s.trajectory(0.0, std::nan(""), 10.0), std::invalid_argument);
}

TEST_CASE("sim mounts: an invalid mount throws naming it; the identity mount changes nothing") {
  sim::Simulator<FixedSensor>::Params params;
  params.mount.rotation = Eigen::Quaterniond(2.0, 0.0, 0.0, 0.0);
  try {
    sim::Simulator<FixedSensor> s(FixedSensor{}, sim::office_scene(1), params);
    FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("mount rotation") != std::string::npos);
  }
  params.mount = sc::Pose{};
  params.mount.translation.x() = std::nan("");
  CHECK_THROWS_AS(sim::Simulator<FixedSensor>(FixedSensor{}, sim::office_scene(1), params), std::invalid_argument);

  // mount_from_roll_pitch_yaw_deg(0, 0, 0) is the default: the same stream bit for bit.
  sim::Simulator<sim::Mid360Model>::Params a;
  a.velocity = {0.7f, 0.0f, 0.0f};
  a.yaw_rate = 0.3f;
  sim::Simulator<sim::Mid360Model>::Params b = a;
  b.mount = sc::mount_from_roll_pitch_yaw_deg(0.0, 0.0, 0.0);
  sim::Simulator<sim::Mid360Model>::Params c = a;
  c.mount = sc::mount_from_roll_pitch_yaw_deg(0.0, 1.0, 0.0);
  sim::Simulator<sim::Mid360Model> sa(sim::Mid360Model{}, sim::forest_scene(2), a);
  sim::Simulator<sim::Mid360Model> sb(sim::Mid360Model{}, sim::forest_scene(2), b);
  sim::Simulator<sim::Mid360Model> sc1(sim::Mid360Model{}, sim::forest_scene(2), c);
  int differ = 0;
  for (int i = 0; i < 5000; ++i) {
    const sim::SimPoint pa = sa.next();
    const sim::SimPoint pb = sb.next();
    const sim::SimPoint pc = sc1.next();
    REQUIRE(pa.x == pb.x);
    REQUIRE(pa.z == pb.z);
    REQUIRE(pa.t == pb.t);
    REQUIRE(pa.surface == pb.surface);
    differ += pa.z != pc.z;
  }
  CHECK(differ > 1000);
}

TEST_CASE("sim mounts: on the hills the vehicle follows the terrain; points lie on it") {
  const sim::Scene scene = sim::hills_scene(4);
  for (const Case& c : kCases) {
    const std::string name = c.name;
    CAPTURE(name);
    sim::Simulator<sim::Mid360Model>::Params params;
    params.range_noise = 0.0f;
    params.start_position = {0.0f, 0.0f, 1.3f};
    params.velocity = {c.speed * 4.0f, 0.0f, 0.0f};  // crosses terrain quickly
    params.yaw_rate = c.yaw_rate;
    params.mount = sc::mount_from_roll_pitch_yaw_deg(c.roll, c.pitch, c.yaw);
    sim::Simulator<sim::Mid360Model> simulator(sim::Mid360Model{}, scene, params);
    int ground = 0;
    int wrong = 0;
    for (int i = 0; i < 30000; ++i) {
      const sim::SimPoint p = simulator.next();
      const Eigen::Vector3d w = world_of(simulator.sensor_pose(p.t), p);
      if (p.instance > 0) {
        const sim::ObjectInfo& info = scene.objects()[static_cast<std::size_t>(p.instance - 1)];
        wrong += p.surface != sc::SurfaceClass::object || !inside(info.bounds, w, 1e-3);
        continue;
      }
      ++ground;
      const float x = static_cast<float>(w.x());
      const float y = static_cast<float>(w.y());
      // On the surface, or on a kerb face (between the heights on either side).
      float lo = *scene.ground_height(x, y);
      float hi = lo;
      for (const float dx : {-3e-3f, 3e-3f}) {
        for (const float dy : {-3e-3f, 3e-3f}) {
          lo = std::min(lo, *scene.ground_height(x + dx, y + dy));
          hi = std::max(hi, *scene.ground_height(x + dx, y + dy));
        }
      }
      wrong += p.surface != sc::SurfaceClass::ground || w.z() < static_cast<double>(lo) - 3e-3 ||
               w.z() > static_cast<double>(hi) + 3e-3;
    }
    CHECK(wrong == 0);
    CHECK(ground > 5000);
    // The vehicle keeps its start height above the terrain.
    for (double t : {0.0, 0.05, 0.1, 0.15}) {
      const Eigen::Vector3f v = simulator.sensor_position(t);
      CHECK(v.z() == doctest::Approx(*scene.ground_height(v.x(), v.y()) + 1.3f).epsilon(1e-5));
    }
  }
  // Without following, the height stays the start height.
  sim::Simulator<sim::Mid360Model>::Params params;
  params.start_position = {0.0f, 0.0f, 1.3f};
  params.velocity = {6.0f, 0.0f, 0.0f};
  params.follow_terrain = false;
  sim::Simulator<sim::Mid360Model> fixed(sim::Mid360Model{}, scene, params);
  CHECK(fixed.sensor_position(3.0).z() == 1.3f);
  params.follow_terrain = true;
  sim::Simulator<sim::Mid360Model> following(sim::Mid360Model{}, scene, params);
  CHECK(following.sensor_position(3.0).z() == doctest::Approx(*scene.ground_height(18.0f, 0.0f) + 1.3f));
  CHECK(std::abs(following.sensor_position(3.0).z() - 1.3f) > 0.01f);  // the terrain is not flat there
}
