// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// How ROS 2 names map onto DDS names (ros2/design "Topic and Service name
/// mapping to DDS"; rmw_cyclonedds and rmw_fastrtps do the same):
///
/// | ROS 2 | DDS |
/// |---|---|
/// | topic `/livox/lidar` | topic `rt/livox/lidar` |
/// | type `sensor_msgs/msg/PointCloud2` | type `sensor_msgs::msg::dds_::PointCloud2_` |
///
/// A relative topic name is resolved against a namespace (`lidar` in
/// `/robot` is `/robot/lidar`); `~` (private names) has no node to expand
/// to here and is refused. Pure functions, no DDS.

#include <cctype>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace streamclust::ros2 {

namespace detail {

inline bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }

/// Checks a fully qualified name ("/a/b"): tokens of letters, digits and
/// '_' that do not start with a digit, no empty token, no trailing '/'.
inline void check_qualified(const std::string& name, std::string_view what) {
  auto fail = [&](const std::string& why) {
    throw std::invalid_argument(std::string(what) + " '" + name + "': " + why);
  };
  if (name.empty() || name[0] != '/') fail("expected a name starting with '/'");
  if (name.size() > 1 && name.back() == '/') fail("a name must not end with '/'");
  std::size_t token_start = 1;
  for (std::size_t i = 1; i <= name.size(); ++i) {
    if (i == name.size() || name[i] == '/') {
      if (i == token_start && name.size() > 1) fail("empty token ('//')");
      if (i > token_start && std::isdigit(static_cast<unsigned char>(name[token_start])) != 0)
        fail("a token must not start with a digit");
      token_start = i + 1;
    } else if (!name_char(name[i])) {
      fail(std::string("character '") + name[i] + "' (expected letters, digits, '_' and '/')");
    }
  }
}

}  // namespace detail

/// The DDS topic name limit, prefix included (ros2/design).
inline constexpr std::size_t kMaxDdsTopicName = 256;

/// The namespace `ns` checked and written as ROS 2 does ("" and "/" are
/// the root; "robot" is "/robot"). Throws std::invalid_argument naming the
/// problem.
inline std::string normalize_namespace(const std::string& ns) {
  if (ns.empty() || ns == "/") return "/";
  std::string n = ns[0] == '/' ? ns : "/" + ns;
  detail::check_qualified(n, "namespace");
  return n;
}

/// The fully qualified name of topic `name` in namespace `ns`: absolute
/// names stay, relative ones go under the namespace. Throws
/// std::invalid_argument for an invalid name or a private one ("~/...").
inline std::string resolve_topic(const std::string& name, const std::string& ns = "/") {
  if (!name.empty() && name[0] == '~') throw std::invalid_argument("topic '" + name + "': private names need a node");
  std::string full;
  if (!name.empty() && name[0] == '/') {
    full = name;
  } else {
    const std::string n = normalize_namespace(ns);
    full = (n == "/" ? std::string("/") : n + "/") + name;
  }
  detail::check_qualified(full, "topic");
  if (full == "/") throw std::invalid_argument("topic '" + name + "': expected a topic name");
  if (full.size() + 2 > kMaxDdsTopicName)
    throw std::invalid_argument("topic '" + full + "': longer than DDS allows (" + std::to_string(kMaxDdsTopicName) +
                                " characters with the 'rt' prefix)");
  return full;
}

/// The DDS topic of a ROS 2 topic: "rt" + the fully qualified name.
inline std::string dds_topic_name(const std::string& name, const std::string& ns = "/") {
  return "rt" + resolve_topic(name, ns);
}

/// The ROS 2 topic of a DDS topic name ("rt/livox/lidar" -> "/livox/lidar"),
/// or nothing when it is not a ROS 2 topic.
inline std::optional<std::string> ros_topic_name(std::string_view dds) {
  if (dds.size() < 4 || dds.substr(0, 3) != "rt/") return std::nullopt;
  return std::string(dds.substr(2));
}

/// The DDS type of a ROS 2 message type: "sensor_msgs/msg/PointCloud2" or
/// "sensor_msgs/PointCloud2" -> "sensor_msgs::msg::dds_::PointCloud2_".
/// Throws std::invalid_argument for another shape.
inline std::string dds_type_name(std::string_view ros_type) {
  const std::size_t first = ros_type.find('/');
  const std::size_t last = ros_type.rfind('/');
  if (first == std::string_view::npos || first == 0 || last + 1 >= ros_type.size())
    throw std::invalid_argument("type '" + std::string(ros_type) + "': expected pkg/msg/Type");
  const std::string_view middle = ros_type.substr(first + 1, last > first ? last - first - 1 : 0);
  if (last != first && middle != "msg")
    throw std::invalid_argument("type '" + std::string(ros_type) + "': expected pkg/msg/Type");
  return std::string(ros_type.substr(0, first)) + "::msg::dds_::" + std::string(ros_type.substr(last + 1)) + "_";
}

/// The ROS 2 message type of a DDS type name
/// ("sensor_msgs::msg::dds_::PointCloud2_" -> "sensor_msgs/msg/PointCloud2"),
/// or nothing when it does not follow the mapping.
inline std::optional<std::string> ros_type_name(std::string_view dds) {
  const std::string_view mid = "::msg::dds_::";
  const std::size_t at = dds.find(mid);
  if (at == std::string_view::npos || at == 0 || dds.size() < at + mid.size() + 2 || dds.back() != '_')
    return std::nullopt;
  const std::string_view type = dds.substr(at + mid.size(), dds.size() - at - mid.size() - 1);
  if (type.find(':') != std::string_view::npos) return std::nullopt;
  return std::string(dds.substr(0, at)) + "/msg/" + std::string(type);
}

}  // namespace streamclust::ros2
