// SPDX-License-Identifier: MIT
// rebind_params: a preset's parameters carried to a configuration that swaps
// slots. Every field of the source is set away from its default, so a field
// the rebind dropped would show up as a default in the target.

#include <doctest/doctest.h>

#include <streamclust/ground/runtime_ground.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/motion/runtime_motion.hpp>
#include <streamclust/objects_presets.hpp>
#include <streamclust/rebind_params.hpp>
#include <streamclust/resolution/runtime_resolution.hpp>

#include <memory>
#include <type_traits>
#include <vector>

namespace sc = streamclust;

namespace {

struct EuclideanObjects : sc::ObjectsConfig {
  using linkage = sc::EuclideanLinkage;
};

/// The objects preset's slots with the tool's run-time motion, ground and
/// resolution (tools/cli/engine_config.hpp's CliConfig).
struct RuntimeObjects : sc::ObjectsConfig {
  using motion = sc::RuntimeMotion;
  using ground = sc::RuntimeGround;
  using resolution = sc::RuntimeResolution;
};

/// Objects parameters with every field away from its default.
sc::ClustererParams<sc::ObjectsConfig> non_default_params() {
  sc::ObjectsSetup setup;
  setup.mount = sc::mount_from_roll_pitch_yaw_deg(5.0, 20.0, -30.0);
  setup.trajectory = std::make_shared<const sc::PoseTrajectory>(
      std::vector<sc::StampedPose>{{0.0, sc::Pose{}}, {1.0, sc::Pose{}}});
  setup.sensor_height = 1.3f;
  setup.window_seconds = 0.35;
  auto p = sc::objects_mid360_params(setup);
  p.projection.min_range = 0.4f;
  p.spatial_index.capacity = 7;
  p.linkage.min_distance = 0.31f;
  p.resolution.initial_rows = 17;
  p.resolution.target_density = 0.8f;
  p.mask_size = 9;
  p.crowded_cell_chains = false;
  p.connectivity.min_fold_edges = 1000;
  p.ground.ground_tolerance = 0.07f;
  p.ground.detect_ceiling = false;
  p.time_order.max_jump = 12.5;
  p.time_order.jump_confirmations = 9;
  p.first_stream_index = 123456789;
  return p;
}

void check_projection(const sc::SphericalProjection::Params& a, const sc::SphericalProjection::Params& b) {
  CHECK(a.azimuth_min_deg == b.azimuth_min_deg);
  CHECK(a.azimuth_max_deg == b.azimuth_max_deg);
  CHECK(a.elevation_min_deg == b.elevation_min_deg);
  CHECK(a.elevation_max_deg == b.elevation_max_deg);
  CHECK(a.min_range == b.min_range);
}

void check_resolution(const sc::AdaptiveResolution::Params& a, const sc::AdaptiveResolution::Params& b) {
  CHECK(a.initial_rows == b.initial_rows);
  CHECK(a.target_density == b.target_density);
  CHECK(a.max_multiplicity == b.max_multiplicity);
}

void check_motion(const sc::PosedMotion::Params& a, const sc::PosedMotion::Params& b) {
  CHECK(a.mount.rotation.isApprox(b.mount.rotation));
  CHECK(a.trajectory == b.trajectory);
}

void check_ground(const sc::HeightMapGround::Params& a, const sc::HeightMapGround::Params& b) {
  CHECK(a.sensor_height == b.sensor_height);
  CHECK(a.lowest_ray_elevation_deg == b.lowest_ray_elevation_deg);
  CHECK(a.ground_tolerance == b.ground_tolerance);
  CHECK(a.detect_ceiling == b.detect_ceiling);
}

/// The slots and engine parameters both configurations share.
template <class A, class B>
void check_engine_fields(const sc::ClustererParams<A>& a, const sc::ClustererParams<B>& b) {
  check_projection(a.projection, b.projection);
  CHECK(a.spatial_index.capacity == b.spatial_index.capacity);
  CHECK(a.window.duration == b.window.duration);
  CHECK(a.mask_size == b.mask_size);
  CHECK(a.crowded_cell_chains == b.crowded_cell_chains);
  CHECK(a.connectivity.min_fold_edges == b.connectivity.min_fold_edges);
  CHECK(a.time_order.max_jump == b.time_order.max_jump);
  CHECK(a.time_order.jump_confirmations == b.time_order.jump_confirmations);
  CHECK(a.first_stream_index == b.first_stream_index);
}

}  // namespace

TEST_CASE("rebind_params carries every field of a preset; the swapped slot takes the value given") {
  const auto from = non_default_params();
  REQUIRE(from.ground.lowest_ray_elevation_deg > -90.0f);  // set by the preset (sensor height given)
  sc::EuclideanLinkage::Params euclidean;
  euclidean.max_distance = 0.42f;
  const auto to = sc::rebind_params<EuclideanObjects>(from, euclidean);
  static_assert(std::is_same_v<std::decay_t<decltype(to)>, sc::ClustererParams<EuclideanObjects>>);
  check_engine_fields(from, to);
  check_resolution(from.resolution, to.resolution);
  check_motion(from.motion, to.motion);
  check_ground(from.ground, to.ground);
  CHECK(to.linkage.max_distance == 0.42f);

  SUBCASE("a value given for a kept slot replaces it") {
    sc::HeightMapGround::Params ground;
    ground.sensor_height = 2.5f;
    const auto replaced = sc::rebind_params<sc::ObjectsConfig>(from, ground);
    CHECK(replaced.ground.sensor_height == 2.5f);
    CHECK(replaced.ground.lowest_ray_elevation_deg == -90.0f);
    CHECK(replaced.linkage.min_distance == from.linkage.min_distance);
    check_engine_fields(from, replaced);
  }
  SUBCASE("a configuration with the same slots gets an exact copy") {
    const auto same = sc::rebind_params<sc::ObjectsConfig>(from);
    check_engine_fields(from, same);
    CHECK(same.linkage.min_distance == from.linkage.min_distance);
    check_ground(from.ground, same.ground);
  }
}

TEST_CASE("rebind_params to run-time slots: the wrappers hold the preset's motion, ground and resolution") {
  const auto from = non_default_params();
  const auto to = sc::rebind_params<RuntimeObjects>(from, sc::RuntimeMotion::Params{true, from.motion, false},
                                                    sc::RuntimeGround::Params{true, from.ground, false},
                                                    sc::RuntimeResolution::Params{true, {}, from.resolution});
  check_engine_fields(from, to);
  CHECK(to.linkage.min_distance == from.linkage.min_distance);
  CHECK(to.motion.enabled);
  check_motion(from.motion, to.motion.posed);
  CHECK(to.ground.use_height_map);
  check_ground(from.ground, to.ground.height_map);
  CHECK(to.resolution.adaptive);
  check_resolution(from.resolution, to.resolution.adaptive_loop);
}
