// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// PosedMotion: places each point in the world by the sensor's pose at its
/// capture time (motion compensation), or by a fixed mount alone.

#include <streamclust/concepts/motion.hpp>
#include <streamclust/motion/pose.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/types.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace streamclust {

/// The motion policy for a sensor with known poses, or a fixed sensor that
/// is tilted or upside down.
///
/// - Without a trajectory, world from sensor is `mount` at every time: a
///   sensor at rest, e.g. pitched down 30 degrees or mounted upside down
///   (roll 180). With a zero mount translation the world's origin is the
///   sensor; a translation (0, 0, h) puts a ground h below the sensor at z = 0.
/// - With a trajectory, world from sensor at time t is `trajectory(t) *
///   mount`: the trajectory is the pose of the vehicle (odometry) frame, the
///   mount the sensor on it; leave the mount identity when the trajectory
///   is the sensor's own pose. Points outside [time_begin(), time_end()] are
///   rejected as `RejectReason::no_pose`.
///
/// `place` writes `ray = R(t) * p` and `world = ray + position(t)` (float),
/// R(t) and position(t) being world from sensor at t: interpolated between
/// the two poses around t as PoseTrajectory::at does (linear position,
/// slerp rotation), to float precision.
///
/// Cost: per segment between two poses, the policy caches three 3 x 3
/// matrices and three vectors: the slerp is a rotation about the segment's
/// fixed axis by an angle f * theta, `R(f) = R_a (I + sin(f theta) K + (1 -
/// cos(f theta)) K^2) R_mount` (K the axis' cross-product matrix), so a
/// point costs a few polynomial terms (theta <= 0.5 rad; std::sin/cos for a
/// larger turn between two poses) and three matrix products, no
/// trigonometry, no allocation. Moving to the next segment is O(1); a jump
/// in time O(log n). Measured (bench_policies BM_PosedMotion, 200 kHz
/// points on 100 Hz poses, g++ -O3): about 11 ns a point, with or without a
/// trajectory; a slerp per point through PoseTrajectory::at costs 66 ns.
///
/// \code
/// streamclust::PosedMotion::Params params;
/// params.trajectory = std::make_shared<const streamclust::PoseTrajectory>(poses);
/// params.mount = streamclust::mount_from_roll_pitch_yaw_deg(0.0, 15.0, 0.0);  // pitched 15 deg down
/// streamclust::PosedMotion motion(params);
/// streamclust::PlacedPoint placed;
/// if (motion.place(p, t, placed) == streamclust::RejectReason::accepted) use(placed.world, placed.ray);
/// \endcode
///
/// Thread safety: `place` moves the policy's own segment cache (one policy
/// per engine); several policies may share one trajectory across threads.
class PosedMotion {
 public:
  struct Params {
    Pose mount;                                        ///< vehicle (or world) from sensor; default identity
    std::shared_ptr<const PoseTrajectory> trajectory;  ///< world from vehicle over time; null: none
  };

  static constexpr bool identity = false;

  /// Throws std::invalid_argument unless the mount's translation and
  /// quaternion are finite and the quaternion's norm is >= 1e-6 (it is
  /// normalised). The trajectory was validated when it was built.
  explicit PosedMotion(const Params& params) : params_(params) {
    const Eigen::Vector4d q = params_.mount.rotation.coeffs();
    for (int k = 0; k < 4; ++k) {
      if (!std::isfinite(q[k])) fail("mount.rotation", q[k], "finite quaternion components");
    }
    if (q.norm() < kMinQuaternionNorm) fail("mount.rotation norm", q.norm(), ">= 1e-6");
    for (int k = 0; k < 3; ++k) {
      const double v = params_.mount.translation[k];
      if (!std::isfinite(v)) fail("mount.translation", v, "finite");
    }
    params_.mount.rotation.normalize();
    if (params_.trajectory) {
      load_segment(params_.trajectory->find_segment(params_.trajectory->time_begin(), 0));
    } else {
      load_fixed();
    }
  }

  /// Places `p` (sensor frame [m]) captured at `t` [s]: `accepted`, or
  /// `no_pose` when t is outside the trajectory's span (or NaN); `placed` is
  /// then unchanged. O(1) amortised for non-decreasing t, O(log n) for a jump.
  RejectReason place(const Eigen::Vector3f& p, double t, PlacedPoint& placed) {
    if (!(t >= begin_ && t <= end_) && !enter(t)) return RejectReason::no_pose;
    const auto f = static_cast<float>((t - origin_) * inv_duration_);
    const float x = f * theta_;
    float s = 0.0f;  // sin(x)
    float c = 0.0f;  // 1 - cos(x)
    if (small_turn_) {
      const float x2 = x * x;
      s = x * (1.0f - x2 / 6.0f * (1.0f - x2 / 20.0f * (1.0f - x2 / 42.0f)));
      c = 0.5f * x2 * (1.0f - x2 / 12.0f * (1.0f - x2 / 30.0f * (1.0f - x2 / 56.0f)));
    } else {
      s = std::sin(x);
      c = 1.0f - std::cos(x);
    }
    const Eigen::Vector3f ray = m0_ * p + s * (m1_ * p) + c * (m2_ * p);
    placed.ray = ray;
    placed.world = ray + (o0_ + f * shift_ + s * o1_ + c * o2_);
    return RejectReason::accepted;
  }

  const Params& params() const { return params_; }

 private:
  [[noreturn]] static void fail(const char* name, double value, const char* allowed) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", value);
    throw std::invalid_argument(std::string("PosedMotion: parameter ") + name + " = " + buf +
                                " is invalid; allowed: " + allowed);
  }

  /// Moves to the segment holding t; false (cache unchanged) outside the span.
  bool enter(double t) {
    const PoseTrajectory* trajectory = params_.trajectory.get();
    if (trajectory == nullptr || !(t >= trajectory->time_begin() && t <= trajectory->time_end())) return false;
    load_segment(trajectory->find_segment(t, segment_));
    return true;
  }

  /// No trajectory: the mount at every time.
  void load_fixed() {
    begin_ = -std::numeric_limits<double>::infinity();
    end_ = std::numeric_limits<double>::infinity();
    origin_ = 0.0;
    cache(Pose{}, Pose{}, 0.0, Eigen::Vector3d::Zero(), 0.0);
  }

  void load_segment(std::size_t i) {
    const auto& poses = params_.trajectory->poses();
    segment_ = i;
    if (poses.size() == 1) {
      begin_ = end_ = origin_ = poses[0].time;
      cache(poses[0].pose, poses[0].pose, 0.0, Eigen::Vector3d::Zero(), 0.0);
      return;
    }
    const StampedPose& a = poses[i];
    const StampedPose& b = poses[i + 1];
    begin_ = origin_ = a.time;
    end_ = b.time;
    // The slerp from a to b along the shorter arc: a rotation by theta about `axis` (a's frame).
    Eigen::Quaterniond relative = a.pose.rotation.conjugate() * b.pose.rotation;
    if (relative.w() < 0.0) relative.coeffs() = -relative.coeffs();
    const double sin_half = relative.vec().norm();
    const double theta = 2.0 * std::atan2(sin_half, relative.w());
    const Eigen::Vector3d axis = sin_half > 0.0 ? Eigen::Vector3d(relative.vec() / sin_half) : Eigen::Vector3d::Zero();
    cache(a.pose, b.pose, theta, axis, 1.0 / (b.time - a.time));
  }

  /// Fills the per-segment constants from the poses at both ends.
  void cache(const Pose& a, const Pose& b, double theta, const Eigen::Vector3d& axis, double inv_duration) {
    Eigen::Matrix3d k;
    k << 0.0, -axis.z(), axis.y(), axis.z(), 0.0, -axis.x(), -axis.y(), axis.x(), 0.0;
    const Eigen::Matrix3d ra = a.rotation.toRotationMatrix();
    const Eigen::Matrix3d rm = params_.mount.rotation.toRotationMatrix();
    const Eigen::Vector3d& tm = params_.mount.translation;
    m0_ = (ra * rm).cast<float>();
    m1_ = (ra * k * rm).cast<float>();
    m2_ = (ra * k * k * rm).cast<float>();
    o0_ = (ra * tm + a.translation).cast<float>();
    o1_ = (ra * k * tm).cast<float>();
    o2_ = (ra * k * k * tm).cast<float>();
    shift_ = (b.translation - a.translation).cast<float>();
    theta_ = static_cast<float>(theta);
    small_turn_ = theta <= 0.5;
    inv_duration_ = inv_duration;
  }

  Params params_;
  // The current segment [begin_, end_] and its constants.
  double begin_ = 0.0, end_ = 0.0;  ///< [s]; +-infinity without a trajectory
  double origin_ = 0.0;             ///< [s] where f = 0 (begin_, or 0 without a trajectory)
  double inv_duration_ = 0.0;       ///< [1/s]
  std::size_t segment_ = 0;
  Eigen::Matrix3f m0_, m1_, m2_;      ///< R_a R_m, R_a K R_m, R_a K^2 R_m
  Eigen::Vector3f o0_, o1_, o2_;      ///< R_a t_m + t_a, R_a K t_m, R_a K^2 t_m [m]
  Eigen::Vector3f shift_;             ///< t_b - t_a [m]
  float theta_ = 0.0f;                ///< the segment's turn [rad]
  bool small_turn_ = true;            ///< theta_ <= 0.5 rad: polynomial sin / cos
};

STREAMCLUST_CHECK_MOTION_POLICY(PosedMotion);

}  // namespace streamclust
