// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// What `streamclust cluster`'s options resolve to before a run: the poses
/// and mount (given, or the mount estimated from the first window), the
/// ground model's parameters (the sensor height given or estimated), the
/// projection bounds in world orientation and, for a linkage fitted to the
/// sensor (sensor_fit.hpp), the first window and the placement it is fitted to.

#include "cli/options.hpp"
#include "cli/poses.hpp"

#include <streamclust/ground/runtime_ground.hpp>
#include <streamclust/io/reader.hpp>
#include <streamclust/motion/gravity_estimate.hpp>
#include <streamclust/motion/ground_height.hpp>
#include <streamclust/motion/runtime_motion.hpp>
#include <streamclust/objects_presets.hpp>
#include <streamclust/sensor_fit.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstdio>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace streamclust::cli {

struct RunSetup {
  RuntimeMotion::Params motion;  ///< enabled with --poses, --mount or an estimated mount
  RuntimeGround::Params ground;  ///< use_height_map with --ground
  /// Spherical projection bounds in world orientation (motion enabled):
  /// the options' bounds are the sensor's.
  std::optional<SphericalProjection::Params> world_fov;
  std::optional<GroundEstimate> estimate;  ///< the first window's ground, when one was estimated
  /// The height from the lowest dense layer (orientation known, no plane found).
  std::optional<GroundHeightEstimate> height_estimate;
  bool estimated_mount = false;            ///< the mount is the estimate's
  bool estimated_height = false;           ///< the sensor height is the estimate's
  /// What the linkage is fitted to (make_params calls its fit_to_sensor):
  /// the first window and the mount and poses of `motion`; null when the
  /// linkage has no fit.
  std::shared_ptr<const SensorFit> sensor_fit;
};

/// True when the linkage `o.linkage` names is fitted to the sensor before a
/// run (`fit_to_sensor`, sensor_fit.hpp). Throws UsageError for an unknown name.
inline bool linkage_fits_sensor(const ClusterOptions& o) {
  return ToolRegistry::with_policy<Slot::linkage>(
      o.linkage, [](auto tag) { return has_sensor_fit_v<typename decltype(tag)::type>; });
}

/// Sensor-frame positions of the first window of `o.input`: the records of
/// the first T_B seconds (or the first --window-count records), at most
/// `max_points` finite ones; their times [s] in `times` when given. O(window).
inline std::vector<Eigen::Vector3f> first_window_points(const ClusterOptions& o, std::vector<double>* times = nullptr,
                                                        std::size_t max_points = 400000) {
  std::unique_ptr<io::PointReader> reader = o.open_input ? o.open_input() : io::open_reader(o.input, o.read);
  std::vector<Eigen::Vector3f> points;
  std::vector<io::Record> chunk;
  std::optional<double> t0;
  std::size_t seen = 0;
  while (points.size() < max_points) {
    chunk.clear();
    if (reader->read(chunk, 65536) == 0) break;
    for (const io::Record& r : chunk) {
      if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z) || !std::isfinite(r.t)) continue;
      if (!t0) t0 = r.t;
      if (o.window_is_count ? seen >= o.window_count : r.t - *t0 >= o.window_seconds) return points;
      ++seen;
      points.emplace_back(r.x, r.y, r.z);
      if (times) times->push_back(r.t);
      if (points.size() >= max_points) return points;
    }
  }
  return points;
}

/// A run setup for a stream held in memory, sensor frame, no motion and no
/// ground model: only the sensor fit of the linkage `o.linkage` names (null
/// when it has none), from the records of the first T_B seconds. O(window).
inline std::shared_ptr<const RunSetup> sensor_fit_setup(const ClusterOptions& o, const std::vector<io::Record>& records) {
  if (!linkage_fits_sensor(o)) return nullptr;
  SensorFit fit;
  const double t0 = records.empty() ? 0.0 : records.front().t;
  for (const io::Record& r : records) {
    if (r.t - t0 >= o.window_seconds) break;
    fit.first_window.emplace_back(r.x, r.y, r.z);
  }
  RunSetup s;
  s.sensor_fit = std::make_shared<const SensorFit>(std::move(fit));
  return std::make_shared<const RunSetup>(std::move(s));
}

/// The first window's points in world orientation, each minus the sensor's
/// position (estimate_ground_height's rays): turned by the mount and, with a
/// trajectory, by the vehicle's attitude at the point's time (points outside
/// the poses' span, or without times, are left out). O(window).
inline std::vector<Eigen::Vector3f> world_rays(const std::vector<Eigen::Vector3f>& points,
                                               const std::vector<double>* times, const PosedMotion::Params& motion) {
  std::vector<Eigen::Vector3f> rays;
  const Eigen::Matrix3f mount = motion.mount.rotation.cast<float>().toRotationMatrix();
  if (!motion.trajectory) {
    rays.reserve(points.size());
    for (const Eigen::Vector3f& p : points) rays.push_back(mount * p);
    return rays;
  }
  if (!times || times->size() != points.size()) return rays;
  PoseTrajectory::Cursor cursor;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::optional<Pose> pose = motion.trajectory->at((*times)[i], cursor);
    if (pose) rays.push_back(pose->rotation.cast<float>() * (mount * points[i]));
  }
  return rays;
}

/// Up (against gravity) in the sensor frame at the first window's start:
/// the mount's, turned by the vehicle's attitude at the first point's time
/// when there are poses (the mount's alone when that time has no pose).
inline Eigen::Vector3d window_up(const std::vector<double>* times, const PosedMotion::Params& motion) {
  Eigen::Quaterniond world_from_sensor = motion.mount.rotation;
  if (motion.trajectory && times && !times->empty()) {
    PoseTrajectory::Cursor cursor;
    if (const std::optional<Pose> pose = motion.trajectory->at(times->front(), cursor)) {
      world_from_sensor = pose->rotation * motion.mount.rotation;
    }
  }
  return world_from_sensor.conjugate() * Eigen::Vector3d::UnitZ();
}

/// True when the ground estimate's up (from its mount) lies within 15 deg of
/// `up`, the known orientation's (a vehicle's roll and pitch over a window
/// stay well inside it).
inline bool agrees_with_orientation(const GroundEstimate& estimate, const Eigen::Vector3d& up) {
  const Eigen::Vector3d estimated_up = estimate.mount.rotation.conjugate() * Eigen::Vector3d::UnitZ();
  return estimated_up.normalized().dot(up.normalized()) >= std::cos(15.0 * 3.14159265358979323846 / 180.0);
}

/// An angle [deg] for a "%.1f" field: a hair below zero prints 0.0, not -0.0.
inline double printable_deg(double deg) { return std::abs(deg) < 0.05 ? 0.0 : deg; }

/// Resolves `o` for a run: loads --poses (io::InputError on a malformed
/// file), builds the mount; with --ground, estimates from the first window
/// what is not given (the mount when neither --mount nor --poses is, the
/// sensor height without --sensor-height; see estimate_ground) and notes it
/// on `err` unless quiet; an ambiguous estimate (floor and ceiling not told
/// apart) is noted and not used; with the floor out of view (a ceiling
/// alone) the mount is used and the height stays unknown, as without a
/// ground plane. `timed` times the ground and placement stages (the
/// report). A linkage fitted to the sensor gets the first window and the
/// resolved mount and poses (`sensor_fit`). `first_window`, when given,
/// replaces the first window read from `o.input` (a caller that holds the
/// stream in memory), `first_window_times` its points' times. With the
/// orientation known (--mount or --poses) and no ground plane found, or two
/// that nothing but gravity tells apart, the height is the lowest dense
/// horizontal layer under the sensor (estimate_ground_height), noted, or
/// noted as unknown. Throws UsageError for a value a policy rejects.
inline RunSetup make_run_setup(const ClusterOptions& o, bool timed, std::ostream& err,
                               const std::vector<Eigen::Vector3f>* first_window = nullptr,
                               const std::vector<double>* first_window_times = nullptr) {
  RunSetup s;
  s.motion.enabled = has_motion_options(o);
  s.motion.posed = load_motion_params(o);
  s.motion.timed = timed;
  s.ground.use_height_map = o.ground;
  s.ground.timed = timed;
  HeightMapGround::Params& g = s.ground.height_map;
  g.ground_tolerance = o.ground_tolerance;
  g.cell_size = o.ground_cell;
  g.max_slope_deg = o.max_slope_deg;
  g.detect_ceiling = o.ceiling;
  g.detect_walls = o.walls;
  if (o.sensor_height) g.sensor_height = *o.sensor_height;
  std::optional<std::vector<Eigen::Vector3f>> read_window;  // the first window, read once when needed
  std::vector<double> read_times;
  const auto window = [&]() -> const std::vector<Eigen::Vector3f>& {
    if (first_window) return *first_window;
    if (!read_window) read_window = first_window_points(o, &read_times);
    return *read_window;
  };
  const auto window_times = [&]() -> const std::vector<double>* {  // the first window's point times
    window();
    return first_window ? first_window_times : &read_times;
  };
  const bool orientation_known = s.motion.enabled;  // --mount or --poses
  if (o.ground && (!s.motion.enabled || !o.sensor_height)) {
    s.estimate = estimate_ground(window());
    bool plane_found = s.estimate && s.estimate->status != GroundStatus::ambiguous;
    if (plane_found && orientation_known &&
        !agrees_with_orientation(*s.estimate, window_up(window_times(), s.motion.posed))) {
      plane_found = false;  // a plane the known orientation puts elsewhere than below (a ceiling taken for a floor)
    }
    if (orientation_known && !plane_found) {
      // Gravity is known: only the height is, the lowest dense layer under the sensor.
      const std::vector<Eigen::Vector3f> rays =
          world_rays(window(), window_times(), s.motion.posed);
      s.height_estimate = estimate_ground_height(rays);
      if (s.height_estimate) {
        g.sensor_height = static_cast<float>(s.height_estimate->height);
        s.estimated_height = true;
      }
      if (!o.quiet) {
        char line[320];
        const char* from = s.motion.posed.trajectory ? "the poses" : "the mount";
        if (s.height_estimate) {
          std::snprintf(line, sizeof line, "streamclust: ground below the sensor in the first window: %.2f m "
                        "(no ground plane in the sensor frame; orientation from %s, the lowest dense layer)\n",
                        s.height_estimate->height, from);
        } else {
          std::snprintf(line, sizeof line, "streamclust: no ground in the first window, neither a plane nor a "
                        "dense layer below the sensor within %.0f m (orientation from %s): its height unknown "
                        "(give --sensor-height)\n", GroundHeightParams{}.max_distance, from);
        }
        err << line;
      }
    } else if (s.estimate && s.estimate->status == GroundStatus::ambiguous) {
      if (!o.quiet) {
        char planes[96];
        if (s.estimate->opposite_distance > 0.0) {
          std::snprintf(planes, sizeof planes, "a plane %.2f m and one %.2f m from the sensor", s.estimate->height,
                        s.estimate->opposite_distance);
        } else {
          std::snprintf(planes, sizeof planes, "one plane, %.2f m from the sensor", s.estimate->height);
        }
        char line[320];
        std::snprintf(line, sizeof line, "streamclust: the ground of the first window is ambiguous: %s, and nothing "
                      "in view tells floor from ceiling; a level sensor is assumed, its height unknown "
                      "(give --mount and --sensor-height)\n", planes);
        err << line;
      }
    } else if (s.estimate) {  // found, or the floor out of view: the mount, and the height when the floor is seen
      const bool floor_seen = s.estimate->status == GroundStatus::found;
      if (!s.motion.enabled) {
        s.motion.enabled = true;
        s.motion.posed.mount = s.estimate->mount;
        s.estimated_mount = true;
      }
      if (floor_seen && !o.sensor_height) {
        g.sensor_height = static_cast<float>(s.estimate->height);
        s.estimated_height = true;
      }
      if (!o.quiet) {
        char line[320];
        if (floor_seen) {
          std::snprintf(line, sizeof line, "streamclust: ground of the first window: roll %.1f deg, pitch %.1f deg, "
                        "sensor %.2f m above it%s\n", printable_deg(s.estimate->roll_deg),
                        printable_deg(s.estimate->pitch_deg), s.estimate->height,
                        s.estimated_mount ? "" : " (the mount given is used)");
        } else {
          char mount[96] = "the mount given is used";
          if (s.estimated_mount) {
            std::snprintf(mount, sizeof mount, "level from the ceiling (roll %.1f deg, pitch %.1f deg)",
                          printable_deg(s.estimate->roll_deg), printable_deg(s.estimate->pitch_deg));
          }
          std::snprintf(line, sizeof line, "streamclust: the first window shows a ceiling %.2f m above the sensor "
                        "and no floor: %s, %s\n", s.estimate->opposite_distance, mount,
                        o.sensor_height ? "the height given is used" : "height unknown (give --sensor-height)");
        }
        err << line;
      }
    } else if (!o.quiet) {
      err << "streamclust: no ground plane in the first window: a level sensor is assumed, its height unknown "
             "(give --mount and --sensor-height)\n";
    }
  }
  if (o.projection == "spherical") {
    SphericalProjection::Params sensor_fov;  // the projection's bounds in the sensor frame
    sensor_fov.azimuth_min_deg = o.azimuth_min;
    sensor_fov.azimuth_max_deg = o.azimuth_max;
    sensor_fov.elevation_min_deg = o.elevation_min;
    sensor_fov.elevation_max_deg = o.elevation_max;
    sensor_fov.min_range = o.min_range;
    if (s.motion.enabled) {
      // The library's objects presets place the sensor: the bounds in world
      // orientation and the lowest ray objects_params gives the library's engine.
      ObjectsSetup placement;
      placement.mount = s.motion.posed.mount;
      placement.trajectory = s.motion.posed.trajectory;
      placement.sensor_height = g.sensor_height;
      const ClustererParams<ObjectsConfig> placed = objects_params(sensor_fov, placement);
      s.world_fov = placed.projection;
      g.lowest_ray_elevation_deg = placed.ground.lowest_ray_elevation_deg;
    } else if (g.sensor_height > 0.0f) {
      g.lowest_ray_elevation_deg = ray_field_of_view(sensor_fov).elevation_min_deg;  // a level sensor's
    }
  }
  if (linkage_fits_sensor(o)) {
    SensorFit fit;
    fit.first_window = window();
    if (s.motion.enabled) {
      fit.mount = s.motion.posed.mount;
      fit.trajectory = s.motion.posed.trajectory;
    }
    s.sensor_fit = std::make_shared<const SensorFit>(std::move(fit));
  }
  return s;
}

}  // namespace streamclust::cli
