// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust evaluate --objects`: are the clusters objects? Simulates one
/// scenario (sensor, scene, mount, height, ego-motion), runs four methods on
/// the same stream and scores every retrieval of a 20 Hz schedule after the
/// first window with eval::object_metrics:
/// - objects: StreamClusterer<ObjectsConfig> from objects_params (structure
///   removal, range-adaptive linkage, poses or mount, sensor height), or
///   with --linkage that preset with another registered linkage in its
///   linkage slot (cli/objects_engine.hpp);
/// - carc: the paper's preset (CArcFastConfig, theta 30 for the Mid-360, 80
///   for the Avia, the sensor's FOV), every point clustered;
/// - euclidean: exact Euclidean single linkage of each window
///   (EuclideanClustering: PCL's definition), one method per radius;
/// - frame: the frame pipeline, per window: RANSAC ground removal checked
///   against gravity and the sensor height, indoors a ceiling removed the
///   same way (cli/structure_planes.hpp), then Euclidean clustering; one
///   method per (inlier tolerance, radius).
/// The peers see the window's points in the sensor frame; gravity comes from
/// the sensor's pose (the vehicle's with poses, the mount without).
/// Results and definitions: docs/evaluation.md, section "Objects".

#include "cli/json.hpp"
#include "cli/objects_engine.hpp"
#include "cli/options.hpp"
#include "cli/simulate.hpp"
#include "cli/structure_planes.hpp"

#include <streamclust/eval/object_average.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/eval/range_coverage.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace streamclust::cli {

/// Everything `streamclust evaluate --objects` needs.
struct EvaluateObjectsOptions {
  SimulateOptions scenario;        ///< sensor, scene, mount, duration (default 3 s), seed, speed, yaw rate, noise
  float height = 0.0f;             ///< [m] sensor above the ground; 0: 1.0, or 2.5 when mounted upside down
  bool poses = true;               ///< the objects engine gets the simulator's vehicle trajectory (else the mount only)
  double window_seconds = 0.5;     ///< T_B [s], every method
  double rate_hz = 20.0;           ///< retrievals per second of stream time
  bool run_objects = true, run_carc = true, run_euclidean = true, run_frame = true;
  /// The objects engine's linkage, a registered name: the preset's
  /// (range-adaptive) by default; every other slot stays the preset's.
  std::string linkage = objects_preset_linkage();
  /// Every linkage's parameters (--theta, --min-distance, a registered
  /// linkage's own): the preset's for its linkage, else the defaults.
  ToolRegistry::Values linkage_params = objects_linkage_values();
  /// [m] the euclidean peer's radii: one method per radius (a sweep).
  std::vector<float> euclidean_distances{0.3f};
  /// [m] the frame pipeline's Euclidean radii, each with every plane distance.
  std::vector<float> frame_distances{0.3f};
  /// [m] frame: points this close to its ground (ceiling) plane are ground (ceiling).
  std::vector<float> plane_distances{0.2f};
  /// frame: remove a ceiling plane too: "on", "off", or "auto" (indoor scenes: the office).
  std::string frame_ceiling = "auto";
  std::size_t ransac_iterations = 100;  ///< frame: accepted RANSAC candidates per plane
  /// frame: a plane's normal within this of gravity [deg]
  float frame_max_tilt_deg = StructurePlaneChecks{}.max_tilt_deg;
  /// frame: the ground plane the sensor height +- this below the sensor [m]
  float frame_height_tolerance = StructurePlaneChecks{}.height_tolerance;
  std::size_t min_points = 10;      ///< eval::MetricOptions::min_points
  bool verify = false;              ///< objects: every retrieval against the batch partition
  bool walls = true;                ///< objects: walls classed as structure (false: --no-walls)
  std::string json_path;
  bool quiet = false;
};

/// The sensor height a run uses [m]: the given one, else 2.5 m for a
/// mount rolled by more than 90 degrees (upside down, under a ceiling or
/// on a mast) and 1.0 m otherwise (the simulator's default).
inline float effective_height(const EvaluateObjectsOptions& o) {
  if (o.height > 0.0f) return o.height;
  const double roll = std::remainder(o.scenario.mount_roll_deg, 360.0);
  return std::abs(roll) > 90.0 ? 2.5f : 1.0f;
}

/// Parses the options of `evaluate --objects` (`args` without "--objects").
/// Throws UsageError naming the option.
EvaluateObjectsOptions parse_evaluate_objects_options(const std::vector<std::string>& args);

/// One method's scores, averaged over the evaluated retrievals.
struct ObjectsMethodResult {
  std::string name;                  ///< objects, carc, euclidean or frame (swept peers: "euclidean@0.3", "frame@0.2/0.3")
  float distance = 0.0f;             ///< [m] euclidean and frame: the Euclidean radius (0: not applicable)
  float plane_distance = 0.0f;       ///< [m] frame: the planes' inlier tolerance (0: not applicable)
  eval::ObjectMetricsAverage average;
  eval::RangeCoverage range_coverage;  ///< object-point coverage per range band, pooled
  std::vector<double> cost_ms;       ///< per evaluated retrieval: the method's work since the previous one [ms]
  double cost_median_ms = 0.0;
  double cost_p99_ms = 0.0;
};

/// Where the objects method's structure removal errs, pooled over the
/// evaluated retrievals: object points (truth instance > 0) and those
/// classed structure (ground, ceiling or wall), by height above the scene's
/// ground; points classed ground, ceiling and wall by their truth class.
struct StructureDiagnostics {
  /// Upper edges of the height bins [m] (a last bin holds the rest).
  static constexpr double kHeightEdges[] = {0.0, 0.25, 0.5, 1.0, 2.0, 4.0};
  static constexpr std::size_t kHeightBins = sizeof(kHeightEdges) / sizeof(kHeightEdges[0]) + 1;
  std::array<std::uint64_t, kHeightBins> object_points{};
  std::array<std::uint64_t, kHeightBins> object_points_lost{};  ///< classed ground, ceiling or wall
  std::array<std::uint64_t, kSurfaceClassCount> classed_ground{};   ///< by truth class
  std::array<std::uint64_t, kSurfaceClassCount> classed_ceiling{};  ///< by truth class
  std::array<std::uint64_t, kSurfaceClassCount> classed_wall{};     ///< by truth class

  static std::size_t bin_of(double height) {
    std::size_t b = 0;
    while (b < kHeightBins - 1 && !(height < kHeightEdges[b])) ++b;
    return b;
  }
};

/// The outcome of one run.
struct ObjectsEvaluation {
  std::size_t records = 0;
  float height = 0.0f;               ///< [m]
  bool scene_has_ceiling = false;    ///< some point's truth class is ceiling
  bool scene_has_wall = false;       ///< some point's truth class is wall
  std::size_t retrievals = 0;        ///< evaluated retrievals
  double window_points = 0.0;        ///< mean points per evaluated window
  std::vector<ObjectsMethodResult> methods;
  StructureDiagnostics structure;    ///< the objects method's
  std::size_t verified = 0;          ///< retrievals checked against the batch (--verify)
  std::vector<std::string> mismatches;  ///< one line per retrieval that differed
};

/// The stream of a Livox scenario (mid360, avia, mid40, mid70) with the
/// sensor `height` above the ground at the start (the simulator keeps it
/// over a terrain), in firing order with its classes and trajectory. Bad
/// parameters and an empty stream are UsageErrors.
SimulatedStream simulate_objects_stream(const SimulateOptions& scenario, float height);

/// The vehicle's trajectory of a simulated stream: its sensor poses with the
/// mount taken off (what odometry would give). O(poses).
inline std::shared_ptr<const PoseTrajectory> vehicle_trajectory(const std::vector<StampedPose>& sensor_poses,
                                                                const Pose& mount) {
  std::vector<StampedPose> vehicle;
  vehicle.reserve(sensor_poses.size());
  const Pose unmount = mount.inverse();
  for (const StampedPose& p : sensor_poses) vehicle.push_back(StampedPose{p.time, p.pose * unmount});
  return std::make_shared<const PoseTrajectory>(std::move(vehicle));
}

/// The checks of an evaluation's scenario no single option makes: a Livox
/// model of the objects preset, ego-motion within bounds, and a duration
/// with one retrieval after the first window. Throws UsageError.
void validate_objects_scenario(const SimulateOptions& scenario, double window_seconds, double rate_hz);

/// Simulates the scenario and runs the methods (tools/cli/evaluate_objects.cpp).
ObjectsEvaluation evaluate_objects(const EvaluateObjectsOptions& o);

/// The run as JSON (docs/cli.md style: one method per entry).
Json objects_evaluation_json(const EvaluateObjectsOptions& o, const ObjectsEvaluation& e);

/// The human-readable table.
void print_objects_evaluation(std::ostream& out, const EvaluateObjectsOptions& o, const ObjectsEvaluation& e);

/// Runs `streamclust evaluate --objects`: 0, or kMismatch (3) when
/// --verify found a difference; throws UsageError (exit 2) and
/// std::runtime_error for an unwritable output (exit 4).
int run_evaluate_objects(const EvaluateObjectsOptions& o, std::ostream& out, std::ostream& err);

/// The help of `evaluate --objects`, the linkages of the tool's registry included.
inline std::string evaluate_objects_help() {
  return std::string(R"(usage: streamclust evaluate --objects [scenario options] [method options] [--verify] [--json FILE]

Simulates one scenario with ground truth and scores, at every retrieval of a
--rate Hz schedule after the first window, four methods on the window's points
(eval::object_metrics; docs/evaluation.md, section Objects):
  objects    the objects preset (StreamClusterer<ObjectsConfig>, objects_params):
             ground / ceiling removal, range-adaptive linkage (--linkage: any other), poses or mount
  carc       the paper's preset (theta 30 Mid-360, 80 Avia; the sensor's FOV), all points clustered
  euclidean  Euclidean single linkage of each window (PCL's definition), per radius
  frame      RANSAC ground plane checked against gravity and the sensor height (normal within
             --frame-max-tilt of up, height +- --frame-height-tolerance; refitted on its inliers,
             else rejected), indoors a ceiling plane above the sensor the same way, then
             Euclidean clustering, per window
The peers (carc, euclidean, frame) see the sensor-frame points; the frame pipeline takes
gravity from the sensor's pose (with --poses off: the mount). Prints ARI on object points,
strict objects correct / over- / under-segmented, object-point coverage (also per range
band: 0-10, 10-30, >= 30 m), ground F1 (walls are their own class: -4), wall precision /
recall when the scene has walls, ceiling F1 when it has a ceiling, and the cycle cost
(median, P99) of each method.

scenario:
  --sensor mid360|avia|mid40|mid70              (default mid360)
  --scene office|forest|street|hills            (default office)
  --mount ROLL,PITCH,YAW                        sensor mount [deg] (pitch > 0 tilts down; roll 180: upside down)
  --height M                                    sensor above the ground (default 1.0; 2.5 upside down)
  --speed M/S | --velocity M/S  --yaw-rate RAD/S   ego-motion (default 0: at rest)
  --poses on|off                                on: the simulator's vehicle trajectory goes to the objects
                                                engine (default); off: the mount only
  --duration S | --seconds S (default 3)  --seed N (default 1)
  --noise M (default 0.02)  --dropout P (default 0)  --max-range M (default 40)
methods:
  --method all|objects|carc|euclidean|frame[,...]  (default all)
  --window-time T_B (default 0.5)  --rate HZ (default 20)
  --distance M (default 0.3)        euclidean and frame linkage radius
  --euclidean-distances M[,M...]    euclidean: one method per radius (a sweep)
  --frame-distances M[,M...]        frame: its Euclidean radii
  --plane-distance M[,M...] (default 0.2)  frame: the planes' inlier tolerance(s); with several
                                    radii or tolerances, one frame method per pair
  --frame-ceiling auto|on|off       frame: remove a ceiling plane (auto: the office)
  --frame-max-tilt DEG (default 10)  --frame-height-tolerance M (default 0.25)  frame: plane checks
  --ransac-iterations N (default 100)  accepted RANSAC candidates per plane
  --min-points N (default 10)       objects smaller than N points are not rated
  --no-walls                        objects: no wall detection (walls clustered like objects)
the objects engine's linkage (every other slot and parameter stays the objects preset's;
--distance also sets the radius of a linkage with a --distance option):
)") + ToolRegistry::help(Slot::linkage, objects_preset_linkage(), objects_linkage_values()) +
         R"(verification:
  --verify                          objects: at every retrieval, the partition must equal the batch
                                    partition of its object points; exit 3 otherwise
outputs:
  --json FILE  --quiet, -q

examples:
  streamclust evaluate --objects --sensor mid360 --scene office
  streamclust evaluate --objects --sensor mid360 --scene office --linkage euclidean --distance 0.3
  streamclust evaluate --objects --sensor avia --scene hills --mount 0,30,0 --speed 1.5 --yaw-rate 0.3
  streamclust evaluate --objects --scene office --mount 180,0,0 --verify --json office_up.json
)";
}

}  // namespace streamclust::cli
