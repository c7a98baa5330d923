// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `live --record FILE.mcap`: the raw input of a live run as a ROS 2
/// recording that `cluster` replays point for point. Every return the
/// clusterer was offered, in the order it was offered, goes into
/// `livox_ros_driver2/msg/CustomMsg` messages on `/livox/lidar` (one per
/// 100 ms of stream time, as the Livox driver publishes them: `timebase`
/// the first point's time [ns], `offset_time` each point's time after it
/// [ns], so times survive exactly); IMU samples go to `/livox/imu` as
/// `sensor_msgs/msg/Imu` (angular velocity [rad/s]; linear acceleration in
/// m/s^2 as REP 145 asks, the LiDAR's g times 9.80665; no orientation:
/// orientation_covariance[0] = -1). Frame id `livox_frame`; MCAP with the
/// ROS 2 profile, CDR messages, schemas as ros2msg text.
///
/// Memory: one message's points (about 20,000 at 200 kHz) and the MCAP
/// writer's chunk (1 MiB) and message index. Not thread-safe.

#include "cli/custom_msg.hpp"

#include <streamclust/io/cdr_writer.hpp>
#include <streamclust/io/mcap_writer.hpp>
#include <streamclust/io/ros/known_definitions.hpp>
#include <streamclust/live/livox_returns.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::cli {

class LiveRecorder {
 public:
  /// Batches span at most this much stream time [ns].
  static constexpr std::uint64_t kMessageSpanNs = 100'000'000;

  explicit LiveRecorder(const std::string& path) : mcap_(path, io::McapWriter::Options{}) {
    const auto custom = io::ros::known_definition("livox_ros_driver2/msg/CustomMsg", io::ros::Encoding::cdr);
    const auto points_schema = mcap_.add_schema("livox_ros_driver2/msg/CustomMsg", "ros2msg", *custom);
    const auto imu_schema = mcap_.add_schema("sensor_msgs/msg/Imu", "ros2msg", imu_definition());
    points_ = mcap_.add_channel(points_schema, "/livox/lidar", "cdr");
    imu_ = mcap_.add_channel(imu_schema, "/livox/imu", "cdr");
  }

  /// Appends returns whose `time_ns` is the stream time [ns], in order.
  void add_returns(const std::vector<live::LivoxReturn>& returns, std::size_t from = 0) {
    for (std::size_t i = from; i < returns.size(); ++i) {
      const live::LivoxReturn& r = returns[i];
      if (!pending_.empty() && r.time_ns - pending_.front().time_ns >= kMessageSpanNs) flush_points();
      pending_.push_back(r);
    }
  }

  /// Writes one IMU sample (time_ns on the stream clock).
  void add_imu(const live::LivoxImuSample& s) {
    constexpr double g = 9.80665;  // [m/s^2]
    cdr_.clear();
    put_header(s.time_ns);
    for (double q : {0.0, 0.0, 0.0, 1.0}) cdr_.f64(q);  // orientation (unknown)
    put_covariance(-1.0);
    for (const float w : s.gyro) cdr_.f64(w);
    put_covariance(0.0);
    for (const float a : s.acceleration) cdr_.f64(a * g);
    put_covariance(0.0);
    mcap_.write(imu_, s.time_ns, cdr_.bytes().data(), cdr_.bytes().size());
  }

  /// Writes what is pending and closes the file (throws std::runtime_error
  /// when the file cannot be completed).
  void close() {
    flush_points();
    mcap_.close();
  }

  /// sensor_msgs/msg/Imu's definition (ros2msg).
  static std::string imu_definition() {
    const std::string rule = "================================================================================\n";
    return "std_msgs/Header header\n"
           "geometry_msgs/Quaternion orientation\n"
           "float64[9] orientation_covariance\n"
           "geometry_msgs/Vector3 angular_velocity\n"
           "float64[9] angular_velocity_covariance\n"
           "geometry_msgs/Vector3 linear_acceleration\n"
           "float64[9] linear_acceleration_covariance\n" +
           std::string(io::ros::builtin::ros2_header_definitions) + rule +
           "MSG: geometry_msgs/Quaternion\nfloat64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n" + rule +
           "MSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n";
  }

 private:
  void put_header(std::uint64_t time_ns) {
    cdr_.i32(static_cast<std::int32_t>(time_ns / 1'000'000'000u));
    cdr_.u32(static_cast<std::uint32_t>(time_ns % 1'000'000'000u));
    cdr_.string("livox_frame");
  }

  void put_covariance(double first) {
    cdr_.f64(first);
    for (int i = 1; i < 9; ++i) cdr_.f64(0.0);
  }

  void flush_points() {
    if (pending_.empty()) return;
    write_custom_msg(cdr_, "livox_frame", pending_, 0, pending_.size());
    mcap_.write(points_, pending_.front().time_ns, cdr_.bytes().data(), cdr_.bytes().size());
    pending_.clear();
  }

  io::McapWriter mcap_;
  std::uint16_t points_ = 0, imu_ = 0;
  io::CdrWriter cdr_;
  std::vector<live::LivoxReturn> pending_;
};

}  // namespace streamclust::cli
