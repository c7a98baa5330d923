// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust ros2 --odom TOPIC`: a nav_msgs/msg/Odometry topic as the
/// run's poses, as `--poses` gives them offline. The poses form a
/// trajectory that grows as messages arrive (world from sensor; the
/// odometry's child frame is taken to be the LiDAR's, or the vehicle's with
/// --mount); a point goes to the engine only once a pose at or after its
/// time has come (`covered_until_ns`), so it is placed exactly as `cluster
/// --poses` places it from the recording. A message that does not decode,
/// or whose pose is not later than the last or not a rotation, is counted
/// and skipped.
///
/// Not thread-safe: the engine thread owns it (and so the trajectory it
/// grows, which the engine's motion policy reads on the same thread).

#include "cli/ros2_input_recorder.hpp"

#include <streamclust/io/error.hpp>
#include <streamclust/io/ros/odometry.hpp>
#include <streamclust/io/ros2_messages.hpp>
#include <streamclust/io/time_decoder.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/motion/tum_poses.hpp>
#include <streamclust/ros2/cdr_subscription.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::cli {

struct OdometryCounters {
  std::uint64_t poses = 0;     ///< poses taken into the trajectory
  std::uint64_t rejected = 0;  ///< messages skipped: malformed, not later than the last, not a rotation
  std::string last_error;      ///< why the last one was skipped
};

class OdometryGate {
 public:
  /// The node's type: nav_msgs/msg/Odometry. `recorder` may be null.
  OdometryGate(ros2::CdrSubscription& odometry, const std::string& topic, Ros2InputRecorder* recorder)
      : subscription_(odometry),
        decoder_("nav_msgs/msg/Odometry", io::ros2msg::ros2_definition("nav_msgs/Odometry"), io::ros::Encoding::cdr),
        recorder_(recorder) {
    origin_.file = "ros2:" + topic;
    if (recorder_ != nullptr)
      channel_ = recorder_->add_topic(topic, "nav_msgs/msg/Odometry", io::ros2msg::ros2_definition("nav_msgs/Odometry"));
  }

  /// Takes the messages that arrived; true when there were any.
  bool poll() {
    bool any = false;
    for (int burst = 0; burst < 256; ++burst) {
      ros2::CdrMessage m = subscription_.pop();
      if (!m) break;
      any = true;
      take(m);
    }
    return any;
  }

  /// The time up to which poses are known [ns since 1970]; 0 before the first.
  std::uint64_t covered_until_ns() const noexcept { return last_ns_; }

  /// The trajectory of the poses so far, times from `origin` (the run's);
  /// later poses are appended to it. Call once, after a first pose came
  /// (the points waited for one). Throws std::invalid_argument otherwise.
  std::shared_ptr<const PoseTrajectory> start(io::TimeOrigin origin) {
    if (early_.empty()) throw std::invalid_argument("--odom: no pose yet");
    time_.emplace(io::TimeUnit::ns, origin);
    std::vector<io::TumRecord> records;
    for (const io::ros::OdometryPose& p : early_) records.push_back(record(p));
    trajectory_ = std::make_shared<PoseTrajectory>(to_stamped_poses(records));
    early_.clear();
    return trajectory_;
  }

  const OdometryCounters& counters() const noexcept { return counters_; }
  /// The odometry frame (the last pose's header.frame_id).
  const std::string& frame_id() const noexcept { return frame_id_; }

 private:
  io::TumRecord record(const io::ros::OdometryPose& p) { return io::ros::tum_record(p, *time_); }

  void take(const ros2::CdrMessage& m) {
    origin_.prefix = "message " + std::to_string(++seen_) + ", payload byte ";
    io::ros::OdometryPose p;
    try {
      p = decoder_.decode(m.data(), m.size(), origin_);
      if (p.t_ns <= last_ns_ && (counters_.poses > 0 || !early_.empty()))
        throw std::invalid_argument("stamp " + std::to_string(p.t_ns) + " ns not later than the last pose's " +
                                    std::to_string(last_ns_));
      if (trajectory_) {
        // As `cluster --poses` builds it: to_stamped_poses, then the trajectory's checks.
        trajectory_->append(to_stamped_poses({record(p)}).front());
      } else {
        // Checked now as the trajectory will check it (finite, a rotation).
        PoseTrajectory(to_stamped_poses({io::TumRecord{0.0, p.x, p.y, p.z, p.qx, p.qy, p.qz, p.qw}}));
        early_.push_back(p);
      }
    } catch (const std::exception& e) {  // io::InputError, std::invalid_argument
      ++counters_.rejected;
      counters_.last_error = e.what();
      return;
    }
    last_ns_ = p.t_ns;
    frame_id_ = p.frame_id;
    ++counters_.poses;
    if (recorder_ != nullptr) recorder_->add(channel_, p.t_ns, m.data(), m.size());
  }

  ros2::CdrSubscription& subscription_;
  io::ros::OdometryDecoder decoder_;
  Ros2InputRecorder* recorder_;
  std::uint16_t channel_ = 0;
  io::detail::BufferOrigin origin_;
  std::uint64_t seen_ = 0;
  std::uint64_t last_ns_ = 0;
  std::vector<io::ros::OdometryPose> early_;  // before start()
  std::optional<io::TimeDecoder> time_;
  std::shared_ptr<PoseTrajectory> trajectory_;
  OdometryCounters counters_;
  std::string frame_id_;
};

}  // namespace streamclust::cli
