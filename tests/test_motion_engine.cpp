// SPDX-License-Identifier: MIT
// The engine with poses: a sensor turning fast during the window sees a
// static object in one place of the world-oriented grid, so its points link
// into one cluster; the same stream in the sensor frame smears the object
// over the turn. And a tilted mount: the ground model sees the world's +z.

#include <doctest/doctest.h>

#include <streamclust/ground/height_map_ground.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/motion/posed_motion.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/motion/world_field_of_view.hpp>
#include <streamclust/presets.hpp>

#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <vector>

namespace sc = streamclust;

namespace {

struct Turning : sc::CArcFastConfig {
  using linkage = sc::EuclideanLinkage;
  using resolution = sc::FixedResolution;
  using motion = sc::PosedMotion;
};
struct TurningUnposed : Turning {
  using motion = sc::NoMotion;
};

/// A sensor at the origin yawing at `rate` [rad/s] sees a post 1 x 1 x 2 m
/// at 6 m on the world +x axis (sampled on its surface facing the sensor) at
/// the start and at the end of `seconds`, 20 kHz; returns the points in the
/// sensor frame and the poses (world from sensor).
struct TurningStream {
  std::vector<sc::Point> points;
  std::shared_ptr<const sc::PoseTrajectory> poses;
};
TurningStream turning_stream(double rate, double seconds) {
  TurningStream s;
  std::vector<sc::StampedPose> poses;
  for (double t = 0.0; t <= seconds + 0.01; t += 0.01) {
    poses.push_back({t, sc::mount_from_roll_pitch_yaw_deg(0.0, 0.0, rate * t * 57.29577951308232)});
  }
  auto trajectory = std::make_shared<sc::PoseTrajectory>(poses);
  s.poses = trajectory;
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < static_cast<int>(20000 * seconds); ++i) {
    const double t = i / 20000.0;
    // Seen twice: in the window's first and last 50 ms (the sensor looks away
    // in between), so nothing chains the two views through time.
    if (t > 0.05 && t < seconds - 0.05) continue;
    const Eigen::Vector3d world(5.5, -0.5 + u(rng), -1.0 + 2.0f * u(rng));  // the face towards the sensor
    const sc::Pose pose = *trajectory->at(t);
    const Eigen::Vector3f p = (pose.inverse() * world).cast<float>();
    s.points.push_back(sc::Point{p.x(), p.y(), p.z(), 0.0f, t});
  }
  return s;
}

template <class Config>
std::size_t components_of(const TurningStream& s) {
  sc::ClustererParams<Config> p;
  p.resolution.rows = 64;
  p.resolution.cols = 720;  // 0.5 degree cells
  p.window.duration = 0.5;
  p.linkage.max_distance = 0.3f;
  if constexpr (std::is_same_v<typename Config::motion, sc::PosedMotion>) p.motion.trajectory = s.poses;
  sc::StreamClusterer<Config> engine(p);
  for (const sc::Point& q : s.points) REQUIRE(engine.insert(q) == sc::RejectReason::accepted);
  std::size_t n = 0;
  for (const sc::ComponentSummary& c : engine.retrieve().components) n += c.size >= 20 ? 1 : 0;
  return n;
}

}  // namespace

TEST_CASE("a sensor turning 90 deg/s during T_B: with poses a static post is one cluster, in the sensor frame it is not") {
  const TurningStream s = turning_stream(1.5708, 0.5);  // 45 degrees of yaw within the window
  // With poses both views land in the same cells of the world-oriented grid
  // and link; in the sensor frame they are 40 degrees apart: two clusters.
  CHECK(components_of<Turning>(s) == 1);
  CHECK(components_of<TurningUnposed>(s) == 2);
}

TEST_CASE("a mount pitched 30 degrees down: the ground model classes the floor as ground only with the mount") {
  // Floor points seen by a sensor 1 m above the floor, pitched down 30 degrees.
  const sc::Pose mount = sc::mount_from_roll_pitch_yaw_deg(0.0, 30.0, 0.0);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<sc::Point> points;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d world(6.0 + 4.0 * u(rng), 4.0 * u(rng), -1.0);
    const Eigen::Vector3f p = (mount.inverse() * world).cast<float>();
    points.push_back(sc::Point{p.x(), p.y(), p.z(), 0.0f, i / 20000.0});
  }
  struct Posed : sc::CArcFastConfig {
    using ground = sc::HeightMapGround;
    using motion = sc::PosedMotion;
  };
  struct Level : Posed {
    using motion = sc::NoMotion;
  };
  sc::ClustererParams<Posed> posed;
  posed.motion.mount = mount;
  posed.ground.sensor_height = 1.0f;
  posed.window.duration = 2.0;
  sc::ClustererParams<Level> level;
  level.ground = posed.ground;
  level.window.duration = 2.0;
  sc::StreamClusterer<Posed> with_mount(posed);
  sc::StreamClusterer<Level> without(level);
  with_mount.insert_batch(points);
  without.insert_batch(points);
  with_mount.complete_calibration();
  without.complete_calibration();
  const double ground_with = static_cast<double>(with_mount.retrieve().structure.size()) / 20000.0;
  const double ground_without = static_cast<double>(without.retrieve().structure.size()) / 20000.0;
  CHECK(ground_with > 0.95);
  CHECK(ground_without < 0.5);  // in the sensor frame the floor is a 30 degree slope
}
