// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Built-in ROS 2 message definitions of the point types this library
/// decodes, for recordings that do not store definitions (rosbag2 SQLite
/// bags written before rosbag2 stored them, Humble and older). Written from
/// the types' .msg files: sensor_msgs/PointCloud2 and PointField,
/// std_msgs/Header, builtin_interfaces/Time, and the Livox drivers'
/// CustomMsg and CustomPoint (livox_ros_driver2, livox_interfaces).

#include <streamclust/io/ros/message_decoder.hpp>
#include <streamclust/io/ros/message_definition.hpp>

#include <optional>
#include <string_view>

namespace streamclust::io::ros {

namespace builtin {

inline constexpr std::string_view ros2_header_definitions =
    "================================================================================\n"
    "MSG: std_msgs/Header\n"
    "builtin_interfaces/Time stamp\n"
    "string frame_id\n"
    "================================================================================\n"
    "MSG: builtin_interfaces/Time\n"
    "int32 sec\n"
    "uint32 nanosec\n";

inline constexpr std::string_view ros2_point_cloud2 =
    "std_msgs/Header header\n"
    "uint32 height\n"
    "uint32 width\n"
    "PointField[] fields\n"
    "bool is_bigendian\n"
    "uint32 point_step\n"
    "uint32 row_step\n"
    "uint8[] data\n"
    "bool is_dense\n"
    "================================================================================\n"
    "MSG: sensor_msgs/PointField\n"
    "string name\n"
    "uint32 offset\n"
    "uint8 datatype\n"
    "uint32 count\n";

inline constexpr std::string_view ros2_livox_custom_msg =
    "std_msgs/Header header\n"
    "uint64 timebase\n"
    "uint32 point_num\n"
    "uint8 lidar_id\n"
    "uint8[3] rsvd\n"
    "CustomPoint[] points\n";

inline constexpr std::string_view livox_custom_point =
    "uint32 offset_time\n"
    "float32 x\n"
    "float32 y\n"
    "float32 z\n"
    "uint8 reflectivity\n"
    "uint8 tag\n"
    "uint8 line\n";

}  // namespace builtin

/// The built-in definition text of `type` in the encoding's dialect, or
/// nothing when the type is not one of the point types. Only ROS 2 (CDR)
/// definitions are built in: ROS 1 bags always store theirs.
inline std::optional<std::string> known_definition(std::string_view type, Encoding encoding) {
  if (encoding != Encoding::cdr) return std::nullopt;
  const std::string t = MessageDefinitions::normalize(type);
  const std::string separator = "================================================================================\n";
  if (t == "sensor_msgs/PointCloud2") {
    return std::string(builtin::ros2_point_cloud2) + std::string(builtin::ros2_header_definitions);
  }
  if (t == "livox_ros_driver2/CustomMsg" || t == "livox_interfaces/CustomMsg") {
    const std::string package = t.substr(0, t.find('/'));
    return std::string(builtin::ros2_livox_custom_msg) + separator + "MSG: " + package + "/CustomPoint\n" +
           std::string(builtin::livox_custom_point) + std::string(builtin::ros2_header_definitions);
  }
  return std::nullopt;
}

}  // namespace streamclust::io::ros
