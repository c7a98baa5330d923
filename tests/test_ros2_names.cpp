// SPDX-License-Identifier: MIT
// The ROS 2 to DDS name mapping (ros2/design, "Topic and Service name
// mapping to DDS"; rmw_cyclonedds and rmw_fastrtps apply it): topics get
// the "rt" prefix on their fully qualified name, message types become
// pkg::msg::dds_::Type_; relative names resolve under the namespace.

#include <doctest/doctest.h>

#include <streamclust/ros2/ros2_names.hpp>

#include <stdexcept>
#include <string>

namespace r2 = streamclust::ros2;

TEST_CASE("ros2 names: topics map to rt/<fully qualified name>") {
  CHECK(r2::dds_topic_name("/livox/lidar") == "rt/livox/lidar");
  CHECK(r2::dds_topic_name("livox/lidar") == "rt/livox/lidar");            // relative, root namespace
  CHECK(r2::dds_topic_name("points", "/robot") == "rt/robot/points");      // relative, under the namespace
  CHECK(r2::dds_topic_name("points", "robot/front") == "rt/robot/front/points");
  CHECK(r2::dds_topic_name("/points", "/robot") == "rt/points");           // absolute names ignore it
  CHECK(r2::resolve_topic("clusters", "/streamclust") == "/streamclust/clusters");
  CHECK(r2::ros_topic_name("rt/livox/lidar") == std::optional<std::string>("/livox/lidar"));
  CHECK_FALSE(r2::ros_topic_name("ros_discovery_info"));  // DDS-only topic, no prefix
  CHECK_FALSE(r2::ros_topic_name("rq/fooRequest"));        // a service's, not a topic's
}

TEST_CASE("ros2 names: invalid names are refused, naming the problem") {
  const struct {
    const char* name;
    const char* ns;
    const char* why;
  } bad[] = {
      {"/a//b", "/", "empty token"},     {"/a/", "/", "must not end with '/'"},
      {"/9a", "/", "must not start with a digit"}, {"/a-b", "/", "character '-'"},
      {"~/private", "/", "private names need a node"}, {"", "/", "expected a topic name"},
      {"x", "/a b", "character ' '"},
  };
  for (const auto& b : bad) {
    CAPTURE(b.name);
    try {
      r2::resolve_topic(b.name, b.ns);
      FAIL("accepted");
    } catch (const std::invalid_argument& e) {
      CHECK(std::string(e.what()).find(b.why) != std::string::npos);
    }
  }
  CHECK_THROWS_AS(r2::resolve_topic("/" + std::string(260, 'a')), std::invalid_argument);  // > 256 with "rt"
  CHECK_NOTHROW(r2::resolve_topic("/" + std::string(253, 'a')));                           // 256 with "rt"
}

TEST_CASE("ros2 names: message types map to pkg::msg::dds_::Type_ and back") {
  CHECK(r2::dds_type_name("sensor_msgs/msg/PointCloud2") == "sensor_msgs::msg::dds_::PointCloud2_");
  CHECK(r2::dds_type_name("sensor_msgs/PointCloud2") == "sensor_msgs::msg::dds_::PointCloud2_");
  CHECK(r2::dds_type_name("livox_ros_driver2/msg/CustomMsg") == "livox_ros_driver2::msg::dds_::CustomMsg_");
  CHECK_THROWS_AS(r2::dds_type_name("PointCloud2"), std::invalid_argument);
  CHECK_THROWS_AS(r2::dds_type_name("sensor_msgs/srv/PointCloud2"), std::invalid_argument);
  CHECK(r2::ros_type_name("sensor_msgs::msg::dds_::PointCloud2_") ==
        std::optional<std::string>("sensor_msgs/msg/PointCloud2"));
  CHECK(r2::ros_type_name("vision_msgs::msg::dds_::Detection3DArray_") ==
        std::optional<std::string>("vision_msgs/msg/Detection3DArray"));
  CHECK_FALSE(r2::ros_type_name("sensor_msgs::msg::PointCloud2"));   // an IDL name without the dds_ module
  CHECK_FALSE(r2::ros_type_name("std_msgs::msg::dds_::String"));     // no trailing underscore
  CHECK_FALSE(r2::ros_type_name("a::msg::dds_::b::c_"));
}
