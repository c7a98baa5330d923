// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust replay INPUT --to livox-sdk2://HOST[:PORT]` (or
/// livox-sdk1://): a Livox LiDAR emulated on the network
/// (cli/livox_emulator.hpp), sending any readable input, or a simulated
/// scene, as the device's packets at the device's rate, with faults on
/// demand. `--to ros2:///TOPIC`: the input as a ROS 2 driver publishes it
/// over DDS (a recording's messages as recorded). For tests of `live` and
/// `ros2` and for users without hardware.

#include "cli/livox_emulator.hpp"
#include "cli/options.hpp"
#include "cli/simulate.hpp"

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace streamclust::cli {

/// `--to ros2:///TOPIC`: a ROS 2 driver's publisher over DDS.
struct Ros2ReplayOptions {
  std::string topic;                    ///< the point topic ("/livox/lidar"); empty: a Livox target
  std::string imu_topic = "/livox/imu"; ///< where IMU messages go (recorded ones, or --imu's)
  std::string odom_topic;               ///< --odom-topic: the poses as nav_msgs/msg/Odometry; empty: none
  bool point_cloud2 = false;            ///< --message pointcloud2: the driver's PointCloud2 instead of CustomMsg
  bool best_effort = false;             ///< --qos best-effort (default reliable, keep last 256: livox_ros_driver2's)
  std::size_t subscribers = 1;          ///< wait for this many subscribers before sending (at most --wait)
  std::optional<std::uint32_t> domain;  ///< default: ROS_DOMAIN_ID, else 0
  bool loopback = false;                ///< discovery on 127.0.0.1 by unicast only
  double message_seconds = 0.1;         ///< [s] of points per message (the driver's publish_freq 10 Hz)
};

struct ReplayOptions {
  std::string input;             ///< a point file or recording; empty with --simulate
  io::ReadOptions read;
  bool simulate = false;         ///< a simulated scene instead of INPUT (the options of simulate)
  SimulateOptions simulation;
  EmulatorOptions emulator;
  Ros2ReplayOptions ros2;
  bool quiet = false;
};

ReplayOptions parse_replay_options(const std::vector<std::string>& args);
std::string replay_help();
/// Runs `streamclust replay`; returns the exit code. Throws UsageError (2),
/// io::InputError (4), NetworkError (6).
int run_replay(const ReplayOptions& o, std::ostream& out, std::ostream& err);
/// The `--to ros2://` part (built with Cyclone DDS: cli/replay_ros2.cpp);
/// `simulated` holds the --simulate stream (empty otherwise).
int run_replay_ros2(const ReplayOptions& o, SimulatedStream simulated, std::ostream& out, std::ostream& err);

}  // namespace streamclust::cli
