// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The objects presets: a continuous clusterer whose clusters are objects.
/// Structure removal (HeightMapGround: ground and ceiling out of the
/// clustering), the range-adaptive linkage (holds on the Avia's dense
/// centre and on sparse far objects), the capped grid and the spanning
/// forest (the fastest exact connectivity), the sensor's poses or mount
/// (PosedMotion) and its field of view in world orientation. Same exactness as every preset: the object
/// partition equals the batch partition of the window's object points.
///
/// | function                 | sensor FOV              | T_B   |
/// |--------------------------|-------------------------|-------|
/// | objects_mid360_params    | 360 x -7..52 (Mid-360)  | 0.5 s |
/// | objects_avia_params      | 70.4 x 77.2 (Avia)      | 0.5 s |
/// | objects_params           | any SensorFacts, or any projection bounds (full sphere: any sensor) | 0.5 s |
///
/// \code
/// streamclust::ObjectsSetup setup;
/// setup.mount = streamclust::mount_from_roll_pitch_yaw_deg(0.0, 15.0, 0.0);  // pitched 15 degrees down
/// setup.sensor_height = 1.2f;                                                // [m] above the ground
/// streamclust::StreamClusterer<streamclust::ObjectsConfig> engine(streamclust::objects_mid360_params(setup));
/// \endcode

#include <streamclust/connectivity/spanning_forest.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/ground/height_map_ground.hpp>
#include <streamclust/linkage/range_adaptive.hpp>
#include <streamclust/motion/pose.hpp>
#include <streamclust/motion/posed_motion.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/motion/world_field_of_view.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/sensors.hpp>

#include <Eigen/Geometry>

#include <memory>
#include <vector>

namespace streamclust {

/// C-ARC's projection, window and adaptive resolution with the objects
/// policies and the capped grid (at most K = 4 points a cell in the index:
/// on the simulated Mid-360 and Avia offices the same quality as the bucket
/// grid at about half the cycle cost, and no steady allocation).
struct ObjectsConfig : CArcCappedFastConfig {
  using linkage = RangeAdaptiveLinkage;
  using ground = HeightMapGround;
  using motion = PosedMotion;
};

/// The objects presets' mask width w and adaptive target T_M.
inline constexpr int kObjectsMaskSize = 5;
inline constexpr float kObjectsMaxMultiplicity = 4.0f;
/// The objects presets' range-adaptive linkage: max(0.4 m, 0.03 x range).
inline constexpr float kObjectsMinLinkDistance = 0.4f;    ///< [m]
inline constexpr float kObjectsLinkRangeFactor = 0.03f;   ///< [m per m of range]

/// How the sensor is carried, for the objects presets.
struct ObjectsSetup {
  Pose mount;  ///< the sensor on the vehicle (roll 180: upside down); identity: level
  std::shared_ptr<const PoseTrajectory> trajectory;  ///< odometry poses of the vehicle; null: at rest
  /// [m] the sensor above the ground under it; 0: unknown (the ground model
  /// then has no cone and no field-of-view cut-off: give it, or estimate it
  /// with estimate_ground from the first window, motion/gravity_estimate.hpp).
  float sensor_height = 0.0f;
  double window_seconds = 0.5;  ///< T_B [s]
};

/// The rotations (world from sensor) a sensor takes: `mount`, turned by
/// every pose of `trajectory` (when not null). O(poses).
inline std::vector<Eigen::Quaterniond> sensor_rotations(const Pose& mount, const PoseTrajectory* trajectory) {
  std::vector<Eigen::Quaterniond> rotations;
  if (!trajectory) {
    rotations.push_back(mount.rotation);
    return rotations;
  }
  for (const StampedPose& p : trajectory->poses()) rotations.push_back(p.pose.rotation * mount.rotation);
  return rotations;
}

/// The elevation [deg] of the lowest ray of a sensor whose rays span
/// `sensor_fov` (sensor frame), in world orientation under `rotations`.
inline float lowest_ray_elevation_deg(const SphericalProjection::Params& sensor_fov,
                                      const std::vector<Eigen::Quaterniond>& rotations) {
  return world_field_of_view(sensor_fov, rotations, 0.0f).elevation_min_deg;
}

/// Objects parameters for a sensor whose rays the projection bounds
/// `sensor_fov` hold (sensor frame: field_of_view_of(sensor), the sensor's
/// field of view widened by kFieldOfViewMarginDeg; SphericalProjection's
/// default, the full sphere, for any sensor) carried as `setup`: the
/// projection bounds hold those rays in world orientation
/// (world_field_of_view), the ground model knows the sensor's height and the
/// lowest ray in world orientation, that of ray_field_of_view(sensor_fov)
/// (a level Mid-360: -7 deg, the spec sheet's; docs/design-decisions.md).
/// The command-line tool places the sensor with this function too. Throws
/// std::invalid_argument from the policies.
inline ClustererParams<ObjectsConfig> objects_params(const SphericalProjection::Params& sensor_fov,
                                                     const ObjectsSetup& setup = {}) {
  ClustererParams<ObjectsConfig> p = to_clusterer_params<ObjectsConfig>(CArcParams{});
  const std::vector<Eigen::Quaterniond> rotations = sensor_rotations(setup.mount, setup.trajectory.get());
  p.projection = world_field_of_view(sensor_fov, rotations);
  p.window.duration = setup.window_seconds;
  // A coarser grid than C-ARC's (T_M 2): the linkage's radius (0.4 m and
  // more) spans more cells of a T_B = 0.5 s grid than a 5 x 5 mask reaches
  // (docs/design-decisions.md).
  p.mask_size = kObjectsMaskSize;
  p.resolution.max_multiplicity = kObjectsMaxMultiplicity;
  // A 0.4 m floor (objects' own gaps: a desk hiding legs) and 0.03 m per m
  // of range (1.7 deg): best of the range-adaptive grid over the evaluation
  // matrix (docs/design-decisions.md).
  p.linkage.min_distance = kObjectsMinLinkDistance;
  p.linkage.range_factor = kObjectsLinkRangeFactor;
  p.motion.mount = setup.mount;
  p.motion.trajectory = setup.trajectory;
  p.ground.sensor_height = setup.sensor_height;
  if (setup.sensor_height > 0.0f) {
    p.ground.lowest_ray_elevation_deg = lowest_ray_elevation_deg(ray_field_of_view(sensor_fov), rotations);
  }
  return p;
}

/// objects_params for a sensor of the table in sensors.hpp.
inline ClustererParams<ObjectsConfig> objects_params(const SensorFacts& sensor, const ObjectsSetup& setup = {}) {
  return objects_params(field_of_view_of(sensor), setup);
}

/// objects_params for the Livox Mid-360.
inline ClustererParams<ObjectsConfig> objects_mid360_params(const ObjectsSetup& setup = {}) {
  return objects_params(livox_mid360, setup);
}

/// objects_params for the Livox Avia.
inline ClustererParams<ObjectsConfig> objects_avia_params(const ObjectsSetup& setup = {}) {
  return objects_params(livox_avia, setup);
}

}  // namespace streamclust
