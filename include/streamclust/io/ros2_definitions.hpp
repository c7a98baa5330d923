// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// ROS 2 message definition texts as an MCAP `ros2msg` schema (or a rosbag2
/// `message_definitions` row) holds them, assembled from tables of types:
/// the main type's fields, then every type it uses, each after a line of 80
/// `=` and a line `MSG: pkg/Type`, in depth-first order of first use:
///
///     std_msgs/Header header
///     string child_frame_id
///     ...
///     ================================================================================
///     MSG: std_msgs/Header
///     builtin_interfaces/Time stamp
///     string frame_id
///
/// A table maps "pkg/Type" to the type's .msg lines ("TYPE NAME\n" each;
/// constants "TYPE NAME=VALUE" and default values may appear). Message-typed
/// fields are spelled with their package ("geometry_msgs/Pose pose"), which
/// is how this assembler finds the types a type uses. The table of the
/// common types here (builtin_interfaces, std_msgs, geometry_msgs) holds the
/// fields of their ROS 2 Humble/Jazzy .msg files.

#include <algorithm>
#include <cstddef>
#include <functional>
#include <initializer_list>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace streamclust::io {

/// .msg lines of message types by "pkg/Type".
using Ros2TypeTable = std::map<std::string, std::string, std::less<>>;

/// builtin_interfaces Time and Duration; std_msgs Header and ColorRGBA;
/// geometry_msgs Point, Vector3, Quaternion, Pose, Twist, PoseWithCovariance
/// and TwistWithCovariance. Built on first use; thread-safe to read.
inline const Ros2TypeTable& ros2_common_types() {
  static const Ros2TypeTable t = {
      {"builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n"},
      {"builtin_interfaces/Duration", "int32 sec\nuint32 nanosec\n"},
      {"std_msgs/Header", "builtin_interfaces/Time stamp\nstring frame_id\n"},
      {"std_msgs/ColorRGBA", "float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n"},
      {"geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"geometry_msgs/Quaternion", "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n"},
      {"geometry_msgs/Pose", "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n"},
      {"geometry_msgs/Twist", "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n"},
      {"geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose pose\nfloat64[36] covariance\n"},
      {"geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist twist\nfloat64[36] covariance\n"},
  };
  return t;
}

/// "pkg/msg/Type" -> "pkg/Type"; other names unchanged.
inline std::string ros2_short_name(std::string_view type) {
  std::string s(type);
  if (const std::size_t at = s.find("/msg/"); at != std::string::npos) s.erase(at, 4);
  return s;
}

/// "pkg/Type" -> "pkg/msg/Type", the name ROS 2 recordings give a schema
/// (names that already hold "/msg/" or no "/" stay as they are).
inline std::string ros2_schema_name(std::string_view type) {
  std::string s(type);
  const std::size_t slash = s.find('/');
  if (slash != std::string::npos && s.find("/msg/") == std::string::npos) s.insert(slash, "/msg");
  return s;
}

namespace detail {

inline const std::string& ros2_type_text(const std::string& type, std::initializer_list<const Ros2TypeTable*> tables) {
  for (const Ros2TypeTable* t : tables) {
    if (const auto it = t->find(type); it != t->end()) return it->second;
  }
  throw std::invalid_argument("ROS 2 message type \"" + type + "\" is not in the definition tables");
}

/// Appends to `order` the types `type` uses that `seen` lacks, each followed
/// by the types it uses (depth first, in field order).
inline void add_ros2_dependencies(const std::string& type, std::initializer_list<const Ros2TypeTable*> tables,
                                  std::vector<std::string>& order, std::set<std::string>& seen) {
  const std::string& text = ros2_type_text(type, tables);
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    std::string field_type = text.substr(pos, std::min(text.find(' ', pos), end) - pos);
    pos = end + 1;
    if (const std::size_t bracket = field_type.find('['); bracket != std::string::npos) field_type.resize(bracket);
    if (field_type.find('/') == std::string::npos || !seen.insert(field_type).second) continue;
    order.push_back(field_type);
    add_ros2_dependencies(field_type, tables, order, seen);
  }
}

}  // namespace detail

/// The definition text of `type` ("pkg/Type" or "pkg/msg/Type"), looking
/// each type up in `tables` in order (the first table holding it wins).
/// Throws std::invalid_argument naming a type that no table holds.
/// O(text length x log table size).
inline std::string ros2_definition_text(std::string_view type, std::initializer_list<const Ros2TypeTable*> tables) {
  const std::string main = ros2_short_name(type);
  std::vector<std::string> order;
  std::set<std::string> seen{main};
  detail::add_ros2_dependencies(main, tables, order, seen);
  std::string text = detail::ros2_type_text(main, tables);
  for (const std::string& dep : order) {
    text += std::string(80, '=') + "\nMSG: " + dep + "\n" + detail::ros2_type_text(dep, tables);
  }
  return text;
}

}  // namespace streamclust::io
