// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The scan simulator: a sensor model's rays, carried by a moving sensor,
/// ray-cast into a Scene, returned as points with ground truth (instance id
/// and surface class) in the sensor frame at capture time.
///
/// Poses: the vehicle moves (start_position, velocity, motion profile, yaw
/// about world +z; its height follows the scene's terrain if it has one);
/// the sensor sits on it with the rotation `mount` (tilted, upside down):
/// `sensor_pose(t) = vehicle(t) * mount`, world from sensor.
///
/// The sensor concept (see ray.hpp):
///
/// | expression          | type                   | meaning                                        |
/// |---------------------|------------------------|------------------------------------------------|
/// | `s.next()`          | convertible to `Ray`   | the next firing: unit direction in the sensor frame (x forward, z up), stream time [s], non-decreasing |
/// | `cs.point_rate()`   | convertible to `double`| nominal firings per second [Hz]                |
///
/// \code
/// namespace sim = streamclust::sim;
/// sim::Simulator<MySensor>::Params params;
/// params.velocity = {1.0f, 0.0f, 0.0f};  // drive along world +x at 1 m/s
/// params.dropout = 0.05f;
/// params.mount = streamclust::mount_from_roll_pitch_yaw_deg(0.0, 15.0, 0.0);  // pitched 15 deg down
/// sim::Simulator<MySensor> simulator(MySensor{}, sim::office_scene(7), params);
/// while (simulator.time() < 1.0) {
///   const sim::SimPoint p = simulator.next();  // sensor frame at p.t, p.instance / p.surface = ground truth
///   const Eigen::Vector3d world = simulator.sensor_pose(p.t) * Eigen::Vector3d(p.x, p.y, p.z);
///   engine.insert(p);
/// }
/// \endcode
///
/// Thread safety: none (one simulator per thread; the Scene may be shared
/// by copies since casting is const).

#include <streamclust/motion/pose.hpp>
#include <streamclust/detail/parameter_check.hpp>
#include <streamclust/sim/intensity.hpp>
#include <streamclust/sim/ray.hpp>
#include <streamclust/sim/scene.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace streamclust::sim {

namespace detail {

template <class S, class = void>
struct is_sim_sensor : std::false_type {};

template <class S>
struct is_sim_sensor<S, std::void_t<decltype(std::declval<S&>().next()), decltype(std::declval<const S&>().point_rate())>>
    : std::bool_constant<std::is_convertible_v<decltype(std::declval<S&>().next()), Ray> &&
                         std::is_convertible_v<decltype(std::declval<const S&>().point_rate()), double>> {};

inline void require_param(bool ok, const char* name, double value, const char* allowed) {
  streamclust::detail::require_parameter(ok, "Simulator::Params", name, value, allowed);
}

}  // namespace detail

/// One piece of a piecewise-constant ego-motion profile: from stream time
/// `start` [s] on, the sensor moves with `velocity` (world frame [m/s]) and
/// turns with `yaw_rate` (about world +z [rad/s]) until the next segment
/// starts. Example, rest / 0.3 s of fast turning / rest:
/// `{{1.0, {1.5f, 0, 0}, 3.0f}, {1.3, {0, 0, 0}, 0.0f}}`.
struct MotionSegment {
  double start = 0.0;                           ///< [s], >= 0; segments sorted by start
  Eigen::Vector3f velocity{0.0f, 0.0f, 0.0f};  ///< [m/s], world frame
  float yaw_rate = 0.0f;                        ///< [rad/s]
};

/// True when `S` models the sensor concept (see the file comment).
template <class S>
inline constexpr bool is_sim_sensor_v = detail::is_sim_sensor<S>::value;

/// Fires a sensor's rays into a scene; see the file comment for an example.
///
/// Per firing, in order:
/// 1. `ray = sensor.next()`; the direction is normalized.
/// 2. Vehicle pose at `ray.time`: position `start_position + velocity * t`
///    (world frame, constant velocity), yaw `yaw_rate * t` about world +z
///    (no roll, no pitch). With a `motion_profile`, velocity and yaw rate
///    are piecewise constant instead and the pose is their integral. When
///    the scene has a terrain (Scene::ground_height) and `follow_terrain`,
///    the vehicle's z is the terrain height under it plus its start height
///    above the terrain (`start_position.z - ground_height(start x, y)`);
///    the vehicle stays level. The sensor pose is `vehicle * mount`. The ray
///    is rotated into the world and cast into the scene at `ray.time`
///    (moving objects are where they are then).
/// 3. Measured range = true range + N(0, range_noise) along the ray.
/// 4. No return when nothing is hit, when the measured range is outside
///    [min_range, max_range], or (with probability `dropout`, drawn only for
///    rays that would have returned) at random. Like a Livox driver, which
///    drops no-return firings, the simulator then moves on to the next ray.
/// 5. The point is `direction * measured range` in the SENSOR frame at
///    capture time, stamped `ray.time`, with the hit's instance id, its
///    surface class (`object`, or the structure's: ground, wall, ceiling) and an
///    intensity: the reflectivity a Livox reports (intensity.hpp) for the
///    hit's reflectance (its material, drawn per object and surface, times
///    the texture: materials.hpp), the incidence angle between the ray and
///    the surface normal and the true range, with measurement noise from a
///    stream of its own.
///
/// Deterministic: the same sensor, scene, and params (seed included) give a
/// bit-identical stream (the generator is SplitMix64 with its own
/// distributions, independent of the standard library). Positions, times
/// and ground truth do not depend on `intensity` (the intensity noise has
/// its own random stream).
template <class Sensor>
class Simulator {
  static_assert(is_sim_sensor_v<Sensor>,
                "STREAMCLUST_SIM_SENSOR_INVALID: a sensor needs `Ray next()` (direction in the sensor frame, time in "
                "seconds) and `double point_rate() const` [Hz]");

 public:
  struct Params {
    float range_noise = 0.02f;  ///< standard deviation of the range noise along the ray [m], >= 0
    float dropout = 0.0f;       ///< probability that a would-be return is lost, in [0, 1)
    float max_range = 40.0f;    ///< measured ranges above: no return [m], > min_range
    float min_range = 0.1f;     ///< measured ranges below: no return [m], >= 0
    Eigen::Vector3f start_position{0.0f, 0.0f, 1.0f};  ///< sensor origin in the world at t = 0 [m]
    Eigen::Vector3f velocity{0.0f, 0.0f, 0.0f};        ///< ego-motion, world frame [m/s]
    float yaw_rate = 0.0f;                             ///< ego-rotation about world +z [rad/s]
    std::uint64_t seed = 1;                            ///< noise and dropout stream
    /// Optional time-varying ego-motion: before the first segment's start the
    /// sensor moves with `velocity` and `yaw_rate`, from each segment's start
    /// on with the segment's. Starts finite, >= 0, non-decreasing.
    std::vector<MotionSegment> motion_profile;
    /// The sensor on the vehicle (vehicle from sensor): a rotation, e.g.
    /// `mount_from_roll_pitch_yaw_deg(180, 0, 0)` upside down, and an
    /// optional lever arm [m]. Unit quaternion, finite translation.
    Pose mount;
    /// With a scene that has a terrain: the vehicle's height follows it.
    bool follow_terrain = true;
    /// The reported reflectivity's range fall-off and noise (intensity.hpp).
    IntensityModel intensity;
  };

  /// What happened to the firings so far.
  struct Stats {
    std::uint64_t fired = 0;         ///< rays taken from the sensor and cast
    std::uint64_t returned = 0;      ///< points returned by next()
    std::uint64_t no_hit = 0;        ///< nothing hit
    std::uint64_t out_of_range = 0;  ///< measured range outside [min_range, max_range]
    std::uint64_t dropped = 0;       ///< lost to random dropout
  };

  /// Consecutive firings without a return after which next() gives up.
  static constexpr std::uint64_t kMaxConsecutiveMisses = 1000000;

  /// Throws std::invalid_argument for invalid params (message names the
  /// parameter, its value and the allowed range). Takes the first ray from
  /// the sensor (so that time() can report it).
  Simulator(Sensor sensor, Scene scene, const Params& params)
      : sensor_(std::move(sensor)),
        scene_(std::move(scene)),
        params_(params),
        rng_(detail::make_rng(params.seed, 0x5115)),
        intensity_rng_(detail::make_rng(params.seed, 0x1A7E)) {
    validate(params_);
    build_knots();
    const Eigen::Quaterniond& q = params_.mount.rotation;
    mount_rotates_ = !(q.x() == 0.0 && q.y() == 0.0 && q.z() == 0.0);
    mount_offset_ = !params_.mount.translation.isZero(0.0);
    mount_rotation_ = q.toRotationMatrix().cast<float>();
    mount_translation_ = params_.mount.translation.template cast<float>();
    if (params_.follow_terrain) {
      const std::optional<float> h = scene_.ground_height(params_.start_position.x(), params_.start_position.y());
      if (h) terrain_clearance_ = params_.start_position.z() - *h;
    }
    pending_ = sensor_.next();
  }

  /// The next point, skipping firings without a return. Throws
  /// std::runtime_error after kMaxConsecutiveMisses firings in a row
  /// without a return (a scene that returns nothing). O(1) amortized
  /// per firing (one Scene::cast).
  SimPoint next() {
    for (std::uint64_t misses = 0; misses < kMaxConsecutiveMisses; ++misses) {
      const Ray ray = pending_;
      pending_ = sensor_.next();
      ++stats_.fired;
      std::optional<SimPoint> p = fire(ray);
      if (p) {
        ++stats_.returned;
        return *p;
      }
    }
    std::string msg("Simulator::next: no return in ");
    msg.append(std::to_string(kMaxConsecutiveMisses));
    msg.append(" consecutive firings (empty scene, or everything out of range?)");
    throw std::runtime_error(msg);
  }

  /// Stream time of the next firing [s] (it may produce no return).
  double time() const { return pending_.time; }

  /// Sensor position in the world at time t [m] (the vehicle's, plus the
  /// mount's lever arm turned by the yaw). O(segments of the motion profile).
  Eigen::Vector3f sensor_position(double t) const {
    const Eigen::Vector3f v = vehicle_position(t);
    if (!mount_offset_) return v;
    const double yaw = yaw_at(t);
    const float c = static_cast<float>(std::cos(yaw));
    const float s = static_cast<float>(std::sin(yaw));
    const Eigen::Vector3f& m = mount_translation_;
    return v + Eigen::Vector3f(c * m.x() - s * m.y(), s * m.x() + c * m.y(), m.z());
  }
  /// Vehicle yaw about world +z at time t [rad] (the sensor's heading when
  /// the mount does not rotate). O(segments of the motion profile).
  float sensor_yaw(double t) const { return static_cast<float>(yaw_at(t)); }

  /// World from sensor at time t: `vehicle(t) * mount`. Maps a point of
  /// time t to the world: `sensor_pose(p.t) * Eigen::Vector3d(p.x, p.y, p.z)`
  /// (to float rounding of the ray casting, about 1e-6 relative). O(segments).
  Pose sensor_pose(double t) const {
    const Pose vehicle{Eigen::Quaterniond(Eigen::AngleAxisd(yaw_at(t), Eigen::Vector3d::UnitZ())),
                       vehicle_position(t).template cast<double>()};
    return vehicle * params_.mount;
  }

  /// Sensor poses at `t0 + k / rate_hz` for every k with a time below `t1`,
  /// then at `t1` (both ends included; a single pose when t0 == t1). Throws
  /// std::invalid_argument unless t0, t1 are finite with t0 <= t1 and rate_hz is finite > 0.
  /// O((t1 - t0) rate_hz) poses.
  std::vector<StampedPose> trajectory(double t0, double t1, double rate_hz) const {
    detail::require_param(std::isfinite(t0), "trajectory t0", t0, "a finite time [s]");
    detail::require_param(std::isfinite(t1) && t1 >= t0, "trajectory t1", t1, "a finite time >= t0 [s]");
    detail::require_param(std::isfinite(rate_hz) && rate_hz > 0.0, "trajectory rate_hz", rate_hz,
                          "a finite rate > 0 [Hz]");
    std::vector<StampedPose> poses;
    const double span = (t1 - t0) * rate_hz;
    poses.reserve(static_cast<std::size_t>(std::min(span, 1e8)) + 2);
    for (std::uint64_t k = 0;; ++k) {
      const double t = t0 + static_cast<double>(k) / rate_hz;
      if (!(t < t1 - 1e-9)) break;
      poses.push_back(StampedPose{t, sensor_pose(t)});
    }
    poses.push_back(StampedPose{t1, sensor_pose(t1)});
    return poses;
  }

  const Stats& stats() const { return stats_; }
  const Params& params() const { return params_; }
  const Scene& scene() const { return scene_; }
  const Sensor& sensor() const { return sensor_; }

 private:
  static void validate(const Params& p) {
    detail::require_param(std::isfinite(p.range_noise) && p.range_noise >= 0.0f, "range_noise", p.range_noise,
                          "a finite value >= 0 [m]");
    detail::require_param(p.dropout >= 0.0f && p.dropout < 1.0f, "dropout", p.dropout, "a probability in [0, 1)");
    detail::require_param(std::isfinite(p.min_range) && p.min_range >= 0.0f, "min_range", p.min_range,
                          "a finite value >= 0 [m]");
    detail::require_param(std::isfinite(p.max_range) && p.max_range > p.min_range, "max_range", p.max_range,
                          "a finite value > min_range [m]");
    detail::require_param(p.start_position.allFinite(), "start_position (a coordinate)",
                          static_cast<double>(p.start_position.sum()), "finite coordinates [m]");
    detail::require_param(p.velocity.allFinite(), "velocity (a component)", static_cast<double>(p.velocity.sum()),
                          "finite components [m/s]");
    detail::require_param(std::isfinite(p.yaw_rate), "yaw_rate", p.yaw_rate, "a finite value [rad/s]");
    detail::require_param(p.mount.rotation.coeffs().allFinite() && std::abs(p.mount.rotation.norm() - 1.0) < 1e-6,
                          "mount rotation (quaternion norm)", p.mount.rotation.norm(),
                          "a unit quaternion (mount_from_roll_pitch_yaw_deg)");
    detail::require_param(p.mount.translation.allFinite(), "mount translation (a component)",
                          p.mount.translation.sum(), "finite components [m]");
    p.intensity.validate();
    double previous = 0.0;
    for (const MotionSegment& m : p.motion_profile) {
      detail::require_param(std::isfinite(m.start) && m.start >= previous, "motion_profile start", m.start,
                            "a finite time >= 0 and >= the previous segment's start [s]");
      detail::require_param(m.velocity.allFinite(), "motion_profile velocity (a component)",
                            static_cast<double>(m.velocity.sum()), "finite components [m/s]");
      detail::require_param(std::isfinite(m.yaw_rate), "motion_profile yaw_rate", m.yaw_rate, "a finite value [rad/s]");
      previous = m.start;
    }
  }

  /// The pose at the start of every motion segment, integrated once.
  struct Knot {
    double start;
    Eigen::Vector3f position;
    double yaw;
    Eigen::Vector3f velocity;
    double yaw_rate;
  };

  void build_knots() {
    Eigen::Vector3f position = params_.start_position;
    Eigen::Vector3f velocity = params_.velocity;
    double yaw = 0.0, yaw_rate = static_cast<double>(params_.yaw_rate), from = 0.0;
    for (const MotionSegment& m : params_.motion_profile) {
      position += static_cast<float>(m.start - from) * velocity;
      yaw += (m.start - from) * yaw_rate;
      from = m.start;
      velocity = m.velocity;
      yaw_rate = static_cast<double>(m.yaw_rate);
      knots_.push_back(Knot{m.start, position, yaw, velocity, yaw_rate});
    }
  }

  /// The last knot starting at or before t; null before the first one
  /// (then the constant-motion formulas apply, bit for bit as without a profile).
  const Knot* knot_at(double t) const {
    const Knot* found = nullptr;
    for (const Knot& k : knots_) {
      if (k.start > t) break;
      found = &k;
    }
    return found;
  }

  /// The vehicle's position: the ego-motion integral, its height on the
  /// terrain when it follows one.
  Eigen::Vector3f vehicle_position(double t) const {
    const Knot* k = knot_at(t);
    Eigen::Vector3f p = k ? Eigen::Vector3f(k->position + static_cast<float>(t - k->start) * k->velocity)
                          : Eigen::Vector3f(params_.start_position + static_cast<float>(t) * params_.velocity);
    if (terrain_clearance_) {
      const std::optional<float> h = scene_.ground_height(p.x(), p.y());
      if (h) p.z() = *h + *terrain_clearance_;
    }
    return p;
  }

  double yaw_at(double t) const {
    const Knot* k = knot_at(t);
    if (!k) return static_cast<double>(params_.yaw_rate) * t;
    return k->yaw + (t - k->start) * k->yaw_rate;
  }

  std::optional<SimPoint> fire(const Ray& ray) {
    const float n2 = ray.direction.squaredNorm();
    if (!(n2 > 0.0f) || !std::isfinite(n2)) {
      ++stats_.no_hit;
      return std::nullopt;
    }
    const Eigen::Vector3f d = ray.direction / std::sqrt(n2);
    const double t = ray.time;
    const double yaw = yaw_at(t);
    const float c = static_cast<float>(std::cos(yaw));
    const float s = static_cast<float>(std::sin(yaw));
    const Eigen::Vector3f v = mount_rotates_ ? Eigen::Vector3f(mount_rotation_ * d) : d;  // vehicle frame
    const Eigen::Vector3f world(c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z());
    const std::optional<Hit> hit = scene_.cast(sensor_position(t), world, t);
    if (!hit) {
      ++stats_.no_hit;
      return std::nullopt;
    }
    float range = hit->range;
    if (params_.range_noise > 0.0f) range += params_.range_noise * static_cast<float>(rng_.normal());
    if (!(range >= params_.min_range) || !(range <= params_.max_range)) {
      ++stats_.out_of_range;
      return std::nullopt;
    }
    if (params_.dropout > 0.0f && rng_.uniform() < static_cast<double>(params_.dropout)) {
      ++stats_.dropped;
      return std::nullopt;
    }
    const Eigen::Vector3f p = range * d;
    const float intensity = reported_reflectivity(params_.intensity, hit->reflectance,
                                                  material_properties(hit->material).retroreflective,
                                                  hit->normal.dot(world), hit->range, intensity_rng_.normal());
    return SimPoint{p.x(), p.y(), p.z(), intensity, t, hit->instance, hit->surface};
  }

  Sensor sensor_;
  Scene scene_;
  Params params_;
  detail::SplitMix64 rng_;            // range noise and dropout
  detail::SplitMix64 intensity_rng_;  // intensity noise: its own stream, so geometry never depends on it
  Ray pending_;
  Stats stats_;
  std::vector<Knot> knots_;
  bool mount_rotates_ = false;  // false: the identity rotation, skipped (no extra rounding)
  bool mount_offset_ = false;
  Eigen::Matrix3f mount_rotation_ = Eigen::Matrix3f::Identity();
  Eigen::Vector3f mount_translation_ = Eigen::Vector3f::Zero();
  std::optional<float> terrain_clearance_;  // set: the vehicle follows the scene's terrain
};

}  // namespace streamclust::sim
