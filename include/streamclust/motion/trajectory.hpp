// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// PoseTrajectory: a validated, time-ordered sequence of sensor (or vehicle)
/// poses and the pose at any time within its span, interpolated between the
/// two surrounding poses (linear position, slerp rotation; pose.hpp).
///
/// \code
/// std::vector<streamclust::StampedPose> poses = ...;           // e.g. to_stamped_poses(io::read_tum("odom.tum"))
/// const streamclust::PoseTrajectory trajectory(poses);       // throws std::invalid_argument if bad
/// streamclust::PoseTrajectory::Cursor cursor;                 // one per reader (thread)
/// if (const auto pose = trajectory.at(t, cursor)) use(*pose * p_sensor);
/// \endcode
///
/// Thread safety: the const members, `at(t, cursor)` included, only read the
/// poses: any number of threads may share one trajectory, each with its own
/// Cursor. `at(t)` without a cursor moves the trajectory's own cursor and is
/// therefore not safe to call concurrently.

#include <streamclust/motion/pose.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace streamclust {

/// Quaternions shorter than this are rejected as "zero" before normalising.
inline constexpr double kMinQuaternionNorm = 1e-6;

/// A time-ordered trajectory of poses, interpolated within its span.
/// Memory: one StampedPose (64 bytes) per pose.
class PoseTrajectory {
 public:
  /// Where the last lookup ended: the index of the segment [i, i + 1] it
  /// found. Lookups at non-decreasing times through one cursor cost O(1)
  /// amortised. A default cursor is valid for every trajectory.
  struct Cursor {
    std::size_t segment = 0;
  };

  /// Validates and stores `poses`; quaternions are normalised. Throws
  /// std::invalid_argument naming the index and value unless there is at
  /// least one pose, every time, coordinate and quaternion component is
  /// finite, the times are strictly increasing and no quaternion has a norm
  /// below kMinQuaternionNorm. O(n).
  explicit PoseTrajectory(std::vector<StampedPose> poses) : poses_(std::move(poses)) {
    if (poses_.empty()) throw std::invalid_argument("PoseTrajectory: poses is empty; allowed: at least one pose");
    for (std::size_t i = 0; i < poses_.size(); ++i) check(i);
  }

  /// Appends a pose later than the last (a trajectory that grows as
  /// odometry arrives), validated and normalised as the constructor's;
  /// throws std::invalid_argument (and keeps the trajectory) otherwise.
  /// O(1) amortised. Not thread-safe: no reader may use the trajectory
  /// meanwhile (PosedMotion on the same thread may: it looks the segment up
  /// again once a time leaves its cached one).
  void append(const StampedPose& pose) {
    poses_.push_back(pose);
    try {
      check(poses_.size() - 1);
    } catch (...) {
      poses_.pop_back();
      throw;
    }
  }

  /// The pose at time `t` [s]: exactly the stored pose at a knot, else the
  /// interpolation of the two surrounding poses; nullopt when t lies outside
  /// [time_begin(), time_end()] or is NaN. O(1) amortised for non-decreasing
  /// t through one cursor, O(log n) for a jump. Thread-safe (own cursor).
  std::optional<Pose> at(double t, Cursor& cursor) const {
    if (!(t >= time_begin() && t <= time_end())) return std::nullopt;
    if (poses_.size() == 1) return poses_.front().pose;
    const std::size_t i = find_segment(t, cursor.segment);
    cursor.segment = i;
    const StampedPose& a = poses_[i];
    const StampedPose& b = poses_[i + 1];
    if (t == a.time) return a.pose;
    if (t == b.time) return b.pose;
    return interpolate(a.pose, b.pose, (t - a.time) / (b.time - a.time));
  }

  /// `at(t, cursor)` with the trajectory's own cursor. Not thread-safe.
  std::optional<Pose> at(double t) { return at(t, cursor_); }

  /// The segment [i, i + 1] holding `t` (time_begin() <= t <= time_end()):
  /// `hint` if it holds t, else the next one if it does, else by binary
  /// search. A t on a knot between two segments gives the earlier one; a
  /// single pose gives 0. O(1) when t is in `hint` or the next, else O(log n).
  std::size_t find_segment(double t, std::size_t hint) const {
    if (poses_.size() < 2) return 0;
    const std::size_t last = poses_.size() - 2;  // the last segment
    if (hint <= last && poses_[hint].time <= t && t <= poses_[hint + 1].time) return hint;
    if (hint + 1 <= last && poses_[hint + 1].time <= t && t <= poses_[hint + 2].time) return hint + 1;
    // First pose later than or at t, among poses 1 .. n-1: the segment ends there.
    const auto it = std::lower_bound(poses_.begin() + 1, poses_.end(), t,
                                     [](const StampedPose& s, double v) { return s.time < v; });
    const auto end = static_cast<std::size_t>(it - poses_.begin());
    return std::min(end - 1, last);
  }

  double time_begin() const { return poses_.front().time; }  ///< [s], the first pose's time
  double time_end() const { return poses_.back().time; }     ///< [s], the last pose's time
  std::size_t size() const { return poses_.size(); }         ///< number of poses
  /// The stored poses (normalised quaternions), in time order.
  const std::vector<StampedPose>& poses() const { return poses_; }

 private:
  /// Validates and normalises poses_[i] against poses_[i - 1].
  void check(std::size_t i) {
    StampedPose& s = poses_[i];
    const Eigen::Vector4d q = s.pose.rotation.coeffs();
    if (!std::isfinite(s.time)) fail(i, "time", s.time, "finite");
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(s.pose.translation[k])) fail(i, "translation", s.pose.translation[k], "finite");
    }
    for (int k = 0; k < 4; ++k) {
      if (!std::isfinite(q[k])) fail(i, "rotation", q[k], "finite quaternion components");
    }
    if (q.norm() < kMinQuaternionNorm) fail(i, "rotation norm", q.norm(), "a quaternion norm >= 1e-6");
    s.pose.rotation.normalize();
    if (i > 0 && !(s.time > poses_[i - 1].time)) {
      fail(i, "time", s.time, "times strictly increasing (previous " + number(poses_[i - 1].time) + ")");
    }
  }

  static std::string number(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
  }
  [[noreturn]] static void fail(std::size_t i, const char* what, double value, const std::string& allowed) {
    throw std::invalid_argument("PoseTrajectory: poses[" + std::to_string(i) + "]." + what + " = " + number(value) +
                                " is invalid; allowed: " + allowed);
  }

  std::vector<StampedPose> poses_;
  Cursor cursor_;
};

}  // namespace streamclust
