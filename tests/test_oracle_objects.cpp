// SPDX-License-Identifier: MIT
// The oracle with structure removal: after every retrieval the engine's
// object points, clustered from scratch by the batch clusterer, give the
// engine's partition; object and structure points are the window's,
// disjoint. Over the random and adversarial streams and over simulated
// Livox scenes with ground, walls and ceilings, for every connectivity
// strategy, both windows and both standard linkages.

#include <doctest/doctest.h>

#include <streamclust/ground/height_map_ground.hpp>
#include <streamclust/motion/posed_motion.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/simulator.hpp>
#include <streamclust/window/count_window.hpp>

#include "support/oracle_input.hpp"
#include "support/streams.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <random>
#include <string>
#include <vector>

namespace sc = streamclust;
namespace st = streamclust::test;

namespace {

struct GroundBfs : sc::CArcConfig {
  using ground = sc::HeightMapGround;
};
struct GroundForest : sc::CArcFastConfig {
  using ground = sc::HeightMapGround;
};
struct GroundRebuild : sc::CArcRebuildConfig {
  using ground = sc::HeightMapGround;
};
struct GroundCappedForestCount : sc::CArcCappedFastConfig {
  using ground = sc::HeightMapGround;
  using window = sc::CountWindow;
};
struct GroundForestEuclidean : sc::CArcFastConfig {
  using ground = sc::HeightMapGround;
  using linkage = sc::EuclideanLinkage;
};
struct GroundBfsEuclideanCount : sc::CArcConfig {
  using ground = sc::HeightMapGround;
  using linkage = sc::EuclideanLinkage;
  using window = sc::CountWindow;
};
struct PosedGroundForest : GroundForest {
  using motion = sc::PosedMotion;
};
struct PosedGroundBfs : GroundBfs {
  using motion = sc::PosedMotion;
};
struct PosedRebuildCount : sc::CArcRebuildConfig {
  using motion = sc::PosedMotion;
  using window = sc::CountWindow;
};

/// A trajectory over [t0, t1] at 100 Hz: driving at up to 2 m/s, turning
/// at up to 90 degrees/s, rolling and pitching a little, from the origin.
std::shared_ptr<const sc::PoseTrajectory> random_trajectory(std::mt19937_64& rng, double t0, double t1) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d velocity(2.0 * u(rng), 2.0 * u(rng), 0.2 * u(rng));
  const double yaw_rate = 1.57 * u(rng), roll = 0.1 * u(rng), pitch = 0.1 * u(rng);
  std::vector<sc::StampedPose> poses;
  for (double t = t0; t <= t1 + 0.01; t += 0.01) {
    sc::StampedPose sp;
    sp.time = t;
    const double s = t - t0;
    sp.pose = sc::mount_from_roll_pitch_yaw_deg(57.3 * roll * std::sin(3.0 * s), 57.3 * pitch * std::cos(2.0 * s),
                                                57.3 * yaw_rate * s);
    sp.pose.translation = velocity * s;
    poses.push_back(sp);
  }
  return std::make_shared<const sc::PoseTrajectory>(std::move(poses));
}

/// Ground parameters drawn per seed: small and large cells, tight and loose
/// tolerances, single-point layers, the ceiling and the walls on and off.
sc::HeightMapGround::Params random_ground(std::mt19937_64& rng) {
  sc::HeightMapGround::Params g;
  const float cells[] = {0.2f, 0.5f, 1.0f};
  g.cell_size = cells[rng() % 3];
  g.ground_tolerance = 0.05f + 0.05f * static_cast<float>(rng() % 6);
  g.support = 1 + static_cast<std::uint32_t>(rng() % 3);
  g.search_radius = static_cast<float>(rng() % 4);
  g.detect_ceiling = rng() % 2 == 0;
  g.ceiling_clearance = 0.2f * static_cast<float>(rng() % 4);
  g.detect_walls = rng() % 4 != 0;
  g.surface_evidence = rng() % 3 != 0;
  g.surface_min_points = 1 + static_cast<std::uint32_t>(rng() % 5);
  return g;
}

/// Engine parameters of a test config: the C-ARC preset's, a short window
/// (50 ms or 150 points), a small first grid, random ground parameters.
template <class Config>
sc::ClustererParams<Config> params_for(std::mt19937_64& rng, const sc::SphericalProjection::Params& fov,
                                       std::shared_ptr<const sc::PoseTrajectory> trajectory = nullptr) {
  sc::ClustererParams<Config> p;
  p.projection = fov;
  if constexpr (std::is_same_v<typename Config::window, sc::CountWindow>) {
    p.window.capacity = 150;
  } else {
    p.window.duration = 0.05;
  }
  if constexpr (std::is_same_v<typename Config::linkage, sc::AngularLinkage>) {
    p.linkage.theta_deg = 30.0f;
  } else {
    p.linkage.max_distance = 0.3f;
  }
  if constexpr (std::is_same_v<typename sc::config_traits<Config>::motion, sc::PosedMotion>) {
    p.motion.trajectory = std::move(trajectory);
    p.motion.mount = sc::mount_from_roll_pitch_yaw_deg(rng() % 2 ? 180.0 : 0.0, 30.0 * static_cast<double>(rng() % 2), 0.0);
  }
  p.resolution.initial_rows = 8;
  p.resolution.initial_cols = 32;
  if constexpr (!std::is_same_v<typename sc::config_traits<Config>::ground, sc::NoGround>) p.ground = random_ground(rng);
  return p;
}

/// Offers `stream` in random stretches, point by point or in packets,
/// retrieves after each and compares with the batch. Returns the
/// retrievals that held structure.
template <class Config, class P>
int run_stream(const std::vector<P>& stream, const sc::ClustererParams<Config>& params, std::mt19937_64& rng,
               const std::string& what) {
  sc::StreamClusterer<Config> engine(params);
  sc::BatchClusterer<Config> batch(params);
  const bool packets = rng() % 2 == 0;
  int with_structure = 0;
  for (std::size_t offered = 0; offered < stream.size();) {
    const std::size_t stop = std::min(stream.size(), offered + 1 + static_cast<std::size_t>(rng() % (stream.size() / 6 + 40)));
    if (packets) {
      engine.insert_batch(stream.begin() + static_cast<std::ptrdiff_t>(offered), stream.begin() + static_cast<std::ptrdiff_t>(stop));
    } else {
      for (std::size_t i = offered; i < stop; ++i) engine.insert(stream[i]);
    }
    offered = stop;
    const sc::Clustering& result = engine.retrieve();
    with_structure += result.structure.empty() ? 0 : 1;
    const std::string mismatch = st::compare_with_batch_on_input(engine, batch, stream);
    INFO(what << ", after point " << offered - 1 << ", window " << engine.size() << " objects + "
              << engine.structure_size() << " structure, packets " << packets);
    REQUIRE(mismatch == "");
  }
  return with_structure;
}

}  // namespace

TEST_CASE_TEMPLATE("with ground removal and poses the object partition equals the batch partition of the object points",
                   Config, GroundBfs, GroundForest, GroundRebuild, GroundCappedForestCount, GroundForestEuclidean,
                   GroundBfsEuclideanCount, PosedGroundForest, PosedGroundBfs, PosedRebuildCount) {
  constexpr bool posed = std::is_same_v<typename sc::config_traits<Config>::motion, sc::PosedMotion>;
  constexpr bool grounded = !std::is_same_v<typename sc::config_traits<Config>::ground, sc::NoGround>;
  int with_structure = 0;
  SUBCASE("random and adversarial streams") {
    for (std::uint64_t seed = 0; seed < 24; ++seed) {
      std::mt19937_64 rng(seed * 31 + 7);
      const auto kind = static_cast<st::StreamKind>(seed % static_cast<std::uint64_t>(st::StreamKind::count_));
      const auto stream = st::make_stream(kind, 300 + seed % 300, seed);
      // Poses over most of the stream: points outside are rejected (no_pose).
      double t_end = 0.0;
      for (const auto& p : stream) {
        if (std::isfinite(p.t) && p.t < 1e6) t_end = std::max(t_end, p.t);
      }
      std::shared_ptr<const sc::PoseTrajectory> trajectory;
      if constexpr (posed) {
        trajectory =
            random_trajectory(rng, seed % 3 == 0 ? 0.1 * t_end : -0.1, seed % 4 == 0 ? 0.8 * t_end : t_end + 1.0);
      }
      with_structure += run_stream(stream, params_for<Config>(rng, sc::SphericalProjection::Params{}, trajectory), rng,
                                   std::string("seed ") + std::to_string(seed) + ", stream " + st::to_string(kind));
    }
  }
  SUBCASE("simulated Mid-360 scenes with floor, walls, ceiling and terrain") {
    namespace sim = sc::sim;
    const sim::Scene scenes[] = {sim::office_scene(5), sim::forest_scene(6), sim::street_scene(7)};
    for (int k = 0; k < 3; ++k) {
      std::mt19937_64 rng(static_cast<std::uint64_t>(k) + 100);
      sim::Simulator<sim::Mid360Model>::Params sp;
      sp.seed = static_cast<std::uint64_t>(k) + 1;
      sp.velocity = {k == 2 ? 1.5f : 0.0f, 0.0f, 0.0f};
      sp.yaw_rate = k == 2 ? 1.0f : 0.0f;
      sim::Simulator<sim::Mid360Model> simulator(sim::Mid360Model{}, scenes[k], sp);
      std::vector<sim::SimPoint> stream;
      while (simulator.time() < 0.12) stream.push_back(simulator.next());
      // The simulator's own poses (its sensor is level): world from sensor.
      std::vector<sc::StampedPose> poses;
      for (double t = 0.0; t <= 0.13; t += 0.005) {
        sc::StampedPose pose;
        pose.time = t;
        pose.pose = sc::mount_from_roll_pitch_yaw_deg(0.0, 0.0, 57.29577951308232 * simulator.sensor_yaw(t));
        pose.pose.translation = simulator.sensor_position(t).cast<double>();
        poses.push_back(pose);
      }
      auto trajectory = std::make_shared<const sc::PoseTrajectory>(std::move(poses));
      auto params = params_for<Config>(rng, sc::field_of_view_of(sc::livox_mid360), trajectory);
      if constexpr (posed) params.motion.mount = sc::Pose{};  // the trajectory is the sensor's pose
      with_structure += run_stream(stream, params, rng, std::string("scene ") + std::to_string(k));
    }
  }
  if (grounded) CHECK(with_structure > 0);  // the runs exercised structure removal
  (void)posed;
}
