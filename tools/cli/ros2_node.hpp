// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust ros2`: a ROS 2 node without a ROS installation. It
/// subscribes over DDS to a point topic (Livox CustomMsg or
/// sensor_msgs/msg/PointCloud2, the type learnt from the publisher), runs
/// the live pipeline on it (one engine thread behind a bounded queue, the
/// options and outputs of `cluster`), and publishes each retrieval as a
/// labelled PointCloud2, a MarkerArray of boxes and a Detection3DArray
/// (docs/ros2.md). Built when Cyclone DDS is found.

#include "cli/options.hpp"

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace streamclust::cli {

/// How the input subscription chooses its reliability.
enum class InputQos { automatic, reliable, best_effort };

struct Ros2Options {
  std::string input = "/livox/lidar";  ///< the point topic
  std::string input_type;              ///< ROS 2 type; empty: learnt from the first publisher discovered
  InputQos input_qos = InputQos::automatic;
  std::string imu;                     ///< sensor_msgs/msg/Imu topic; empty: none
  std::string odom;                    ///< nav_msgs/msg/Odometry topic: the poses (as --poses); empty: none
  std::string ns = "/streamclust";     ///< the outputs' namespace
  std::int32_t depth = 5;              ///< output history depth (reliable, keep last)
  std::string level_frame;             ///< the outputs' frame when placed by a mount; empty: input frame + "_level"
  std::size_t queue_messages = 64;     ///< DDS-to-engine queue [messages]
  std::optional<std::uint32_t> domain; ///< default: ROS_DOMAIN_ID, else 0
  bool loopback = false;               ///< discovery on 127.0.0.1 by unicast only
  double duration = 0.0;               ///< [s] of wall time; 0: until stopped
  double idle_exit = 0.0;              ///< [s] without messages ends the run (once messages came); 0: never
  double first_message_timeout = 10.0; ///< [s] to wait for a publisher and its first message
  std::string record_path;             ///< --record: the input messages as received
  std::string record_out_path;         ///< --record-out: what the node published
  bool status = true;
  ClusterOptions cluster;
};

Ros2Options parse_ros2_options(const std::vector<std::string>& args);
std::string ros2_help();
/// Runs `streamclust ros2`; returns the exit code. Throws UsageError (2),
/// NetworkError (6: DDS failed, no publisher or no message in time).
int run_ros2(const Ros2Options& o, std::ostream& out, std::ostream& err);

}  // namespace streamclust::cli
