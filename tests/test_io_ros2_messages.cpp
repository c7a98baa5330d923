// SPDX-License-Identifier: MIT
// The ROS 2 message serializers (io/ros2_messages.hpp): their definition
// texts have the fields of the ROS 2 .msg files, and every message decodes
// back through ros/message_decoder.hpp from that text with nothing left over
// and every field holding what was written, whatever padding the strings
// before it leave. Offsets and sizes worked out by hand pin the layout.

#include <streamclust/io/cdr_writer.hpp>
#include <streamclust/io/foxglove_messages.hpp>
#include <streamclust/io/ros/known_definitions.hpp>
#include <streamclust/io/ros/message_decoder.hpp>
#include <streamclust/io/ros/message_definition.hpp>
#include <streamclust/io/ros2_definitions.hpp>
#include <streamclust/io/ros2_messages.hpp>

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace io = streamclust::io;
namespace ros = streamclust::io::ros;
namespace msg = streamclust::io::ros2msg;

namespace {

/// A serialized message decoded from its definition text (the decoder throws
/// when the bytes do not match the definition or some are left over).
struct Decoded {
  std::vector<std::uint8_t> bytes;
  ros::MessageDefinitions definitions;
  ros::DecodedMessage message;

  Decoded(const std::string& type, const io::CdrWriter& w)
      : bytes(w.bytes()), definitions(type, msg::ros2_definition(type)) {
    const io::detail::BufferOrigin origin{type};
    ros::MessageDecoder decoder(definitions, ros::Encoding::cdr);
    decoder.decode(bytes.data(), bytes.size(), origin, message);
  }

  const ros::Leaf& leaf(const std::string& path) const {
    const ros::Leaf* l = message.find(path);
    INFO(path);
    REQUIRE(l != nullptr);
    return *l;
  }
  bool has(const std::string& path) const { return message.find(path) != nullptr; }
  double real(const std::string& path) const {
    const ros::Leaf& l = leaf(path);
    return message.real(l.primitive, l.offset);
  }
  std::int64_t integer(const std::string& path) const {
    const ros::Leaf& l = leaf(path);
    return message.integer(l.primitive, l.offset);
  }
  std::string text(const std::string& path) const { return leaf(path).text; }
  /// Elements of a float64 array.
  std::vector<double> reals(const std::string& path) const {
    const ros::Leaf& l = leaf(path);
    REQUIRE(l.is_array);
    REQUIRE(l.primitive == ros::Primitive::float64);
    std::vector<double> v;
    for (std::size_t i = 0; i < l.count; ++i) v.push_back(message.real(l.primitive, l.offset + 8 * i));
    return v;
  }
  /// Offset of a leaf from the end of the encapsulation header [bytes].
  std::size_t offset(const std::string& path) const { return leaf(path).offset - 4; }
};

std::vector<std::pair<std::string, std::string>> fields_of(const ros::TypeDefinition& t) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const ros::FieldDefinition& f : t.fields) {
    std::string type = f.type_name;
    if (f.array == ros::FieldDefinition::Array::sequence) type += "[]";
    if (f.array == ros::FieldDefinition::Array::fixed) type += "[" + std::to_string(f.fixed_length) + "]";
    out.emplace_back(type, f.name);
  }
  return out;
}

using Fields = std::vector<std::pair<std::string, std::string>>;

/// Frame ids of 0 to 12 characters: every padding a string can leave.
std::string frame(std::size_t n) { return std::string("abcdefghijklmnop").substr(0, n); }

}  // namespace

TEST_CASE("ros2msg definitions: the fields of the ROS 2 .msg files, each type once") {
  const std::vector<std::string> main_types = {"sensor_msgs/PointCloud2", "visualization_msgs/MarkerArray",
                                               "vision_msgs/Detection3DArray", "sensor_msgs/Imu", "nav_msgs/Odometry"};
  for (const std::string& type : main_types) {
    INFO(type);
    const std::string text = msg::ros2_definition(type);
    CHECK(msg::ros2_definition(io::ros2_schema_name(type)) == text);
    CHECK_NOTHROW(ros::MessageDefinitions(type, text));
    // Every "MSG:" follows a separator line and names a type only once.
    std::size_t at = 0, sections = 0;
    while ((at = text.find("MSG: ", at)) != std::string::npos) {
      REQUIRE(at >= 81);
      CHECK(text.substr(at - 81, 81) == std::string(80, '=') + "\n");
      const std::string name = text.substr(at + 5, text.find('\n', at) - at - 5);
      CHECK(text.find("MSG: " + name + "\n", at + 1) == std::string::npos);
      CHECK(name.find('/') != std::string::npos);
      ++sections;
      ++at;
    }
    CHECK(sections > 1);
  }

  const ros::MessageDefinitions markers("visualization_msgs/MarkerArray",
                                        msg::ros2_definition("visualization_msgs/MarkerArray"));
  CHECK(fields_of(markers.main()) == Fields{{"visualization_msgs/Marker[]", "markers"}});
  CHECK(fields_of(markers.type("visualization_msgs/Marker")) ==
        Fields{{"std_msgs/Header", "header"},
               {"string", "ns"},
               {"int32", "id"},
               {"int32", "type"},
               {"int32", "action"},
               {"geometry_msgs/Pose", "pose"},
               {"geometry_msgs/Vector3", "scale"},
               {"std_msgs/ColorRGBA", "color"},
               {"builtin_interfaces/Duration", "lifetime"},
               {"bool", "frame_locked"},
               {"geometry_msgs/Point[]", "points"},
               {"std_msgs/ColorRGBA[]", "colors"},
               {"string", "texture_resource"},
               {"sensor_msgs/CompressedImage", "texture"},
               {"visualization_msgs/UVCoordinate[]", "uv_coordinates"},
               {"string", "text"},
               {"string", "mesh_resource"},
               {"visualization_msgs/MeshFile", "mesh_file"},
               {"bool", "mesh_use_embedded_materials"}});
  CHECK(fields_of(markers.type("sensor_msgs/CompressedImage")) ==
        Fields{{"std_msgs/Header", "header"}, {"string", "format"}, {"uint8[]", "data"}});
  CHECK(fields_of(markers.type("visualization_msgs/UVCoordinate")) == Fields{{"float32", "u"}, {"float32", "v"}});
  CHECK(fields_of(markers.type("visualization_msgs/MeshFile")) == Fields{{"string", "filename"}, {"uint8[]", "data"}});
  CHECK(fields_of(markers.type("std_msgs/ColorRGBA")) ==
        Fields{{"float32", "r"}, {"float32", "g"}, {"float32", "b"}, {"float32", "a"}});
  CHECK(fields_of(markers.type("builtin_interfaces/Duration")) == Fields{{"int32", "sec"}, {"uint32", "nanosec"}});

  const ros::MessageDefinitions detections("vision_msgs/Detection3DArray",
                                           msg::ros2_definition("vision_msgs/Detection3DArray"));
  CHECK(fields_of(detections.main()) ==
        Fields{{"std_msgs/Header", "header"}, {"vision_msgs/Detection3D[]", "detections"}});
  CHECK(fields_of(detections.type("vision_msgs/Detection3D")) ==
        Fields{{"std_msgs/Header", "header"},
               {"vision_msgs/ObjectHypothesisWithPose[]", "results"},
               {"vision_msgs/BoundingBox3D", "bbox"},
               {"string", "id"}});
  CHECK(fields_of(detections.type("vision_msgs/ObjectHypothesisWithPose")) ==
        Fields{{"vision_msgs/ObjectHypothesis", "hypothesis"}, {"geometry_msgs/PoseWithCovariance", "pose"}});
  CHECK(fields_of(detections.type("vision_msgs/ObjectHypothesis")) ==
        Fields{{"string", "class_id"}, {"float64", "score"}});
  CHECK(fields_of(detections.type("vision_msgs/BoundingBox3D")) ==
        Fields{{"geometry_msgs/Pose", "center"}, {"geometry_msgs/Vector3", "size"}});
  CHECK(fields_of(detections.type("geometry_msgs/PoseWithCovariance")) ==
        Fields{{"geometry_msgs/Pose", "pose"}, {"float64[36]", "covariance"}});

  const ros::MessageDefinitions imu("sensor_msgs/Imu", msg::ros2_definition("sensor_msgs/Imu"));
  CHECK(fields_of(imu.main()) == Fields{{"std_msgs/Header", "header"},
                                        {"geometry_msgs/Quaternion", "orientation"},
                                        {"float64[9]", "orientation_covariance"},
                                        {"geometry_msgs/Vector3", "angular_velocity"},
                                        {"float64[9]", "angular_velocity_covariance"},
                                        {"geometry_msgs/Vector3", "linear_acceleration"},
                                        {"float64[9]", "linear_acceleration_covariance"}});
  CHECK(fields_of(imu.type("geometry_msgs/Quaternion")) ==
        Fields{{"float64", "x"}, {"float64", "y"}, {"float64", "z"}, {"float64", "w"}});

  const ros::MessageDefinitions odom("nav_msgs/Odometry", msg::ros2_definition("nav_msgs/Odometry"));
  CHECK(fields_of(odom.main()) == Fields{{"std_msgs/Header", "header"},
                                         {"string", "child_frame_id"},
                                         {"geometry_msgs/PoseWithCovariance", "pose"},
                                         {"geometry_msgs/TwistWithCovariance", "twist"}});
  CHECK(fields_of(odom.type("geometry_msgs/TwistWithCovariance")) ==
        Fields{{"geometry_msgs/Twist", "twist"}, {"float64[36]", "covariance"}});
  CHECK(fields_of(odom.type("geometry_msgs/Twist")) ==
        Fields{{"geometry_msgs/Vector3", "linear"}, {"geometry_msgs/Vector3", "angular"}});

  // PointCloud2 as the decoder's built-in definition (written separately) has it.
  const ros::MessageDefinitions cloud("sensor_msgs/PointCloud2", msg::ros2_definition("sensor_msgs/PointCloud2"));
  const ros::MessageDefinitions builtin(
      "sensor_msgs/PointCloud2", *ros::known_definition("sensor_msgs/msg/PointCloud2", ros::Encoding::cdr));
  for (const char* type : {"sensor_msgs/PointCloud2", "sensor_msgs/PointField", "std_msgs/Header",
                           "builtin_interfaces/Time"}) {
    INFO(type);
    CHECK(fields_of(cloud.type(type)) == fields_of(builtin.type(type)));
  }
  CHECK(fields_of(cloud.type("sensor_msgs/PointField")) ==
        Fields{{"string", "name"}, {"uint32", "offset"}, {"uint8", "datatype"}, {"uint32", "count"}});

  CHECK_THROWS_AS(msg::ros2_definition("sensor_msgs/Image"), std::invalid_argument);
  CHECK(io::ros2_schema_name("nav_msgs/Odometry") == "nav_msgs/msg/Odometry");
  CHECK(io::ros2_schema_name("nav_msgs/msg/Odometry") == "nav_msgs/msg/Odometry");
  CHECK(io::ros2_short_name("nav_msgs/msg/Odometry") == "nav_msgs/Odometry");
}

TEST_CASE("ros2msg definitions: the shared table leaves the foxglove definitions as they were") {
  const std::string scene = io::foxglove::ros2_definition("foxglove_msgs/SceneUpdate");
  // Depth-first order of first use, common types included once.
  const std::vector<std::string> order = {
      "foxglove_msgs/SceneEntityDeletion", "builtin_interfaces/Time", "foxglove_msgs/SceneEntity",
      "builtin_interfaces/Duration", "foxglove_msgs/KeyValuePair", "foxglove_msgs/ArrowPrimitive",
      "geometry_msgs/Pose", "geometry_msgs/Point", "geometry_msgs/Quaternion", "foxglove_msgs/Color",
      "foxglove_msgs/CubePrimitive", "geometry_msgs/Vector3", "foxglove_msgs/SpherePrimitive",
      "foxglove_msgs/CylinderPrimitive", "foxglove_msgs/LinePrimitive", "foxglove_msgs/TriangleListPrimitive",
      "foxglove_msgs/TextPrimitive", "foxglove_msgs/ModelPrimitive"};
  std::size_t at = 0;
  for (const std::string& type : order) {
    INFO(type);
    const std::size_t next = scene.find("\nMSG: " + type + "\n");
    REQUIRE(next != std::string::npos);
    CHECK(next > at);
    at = next;
  }
  CHECK(scene.rfind("foxglove_msgs/SceneEntityDeletion[] deletions\nfoxglove_msgs/SceneEntity[] entities\n" +
                        std::string(80, '=') + "\nMSG: foxglove_msgs/SceneEntityDeletion\n",
                    0) == 0);
  CHECK(scene.find("\nMSG: geometry_msgs/Quaternion\nfloat64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n") !=
        std::string::npos);
  CHECK_NOTHROW(ros::MessageDefinitions("foxglove_msgs/SceneUpdate", scene));
  CHECK_NOTHROW(ros::MessageDefinitions("foxglove_msgs/PointCloud",
                                        io::foxglove::ros2_definition("foxglove_msgs/PointCloud")));
}

TEST_CASE("ros2msg PointCloud2: every field, for every padding the frame id leaves") {
  const std::vector<msg::PointField> fields = {{"x", 0, msg::PointField::FLOAT32},
                                               {"y", 4, msg::PointField::FLOAT32},
                                               {"z", 8, msg::PointField::FLOAT32},
                                               {"intensity", 12, msg::PointField::UINT8},
                                               {"ring", 14, msg::PointField::UINT16, 1},
                                               {"rgb", 16, msg::PointField::UINT8, 3}};
  constexpr std::uint32_t kStep = 20, kWidth = 5;
  std::vector<std::uint8_t> data(kStep * kWidth);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(i * 7 + 1);
  io::CdrWriter w;
  for (std::size_t n = 0; n <= 12; ++n) {
    INFO("frame id of ", n, " characters");
    msg::write_point_cloud2(w, msg::Header{1700000123, 456789, frame(n)}, kWidth, fields, kStep, data.data(),
                            data.size(), n % 2 == 0);
    const Decoded d("sensor_msgs/PointCloud2", w);
    CHECK(d.integer("header.stamp.sec") == 1700000123);
    CHECK(d.integer("header.stamp.nanosec") == 456789);
    CHECK(d.text("header.frame_id") == frame(n));
    CHECK(d.integer("height") == 1);
    CHECK(d.integer("width") == kWidth);
    for (std::size_t k = 0; k < fields.size(); ++k) {
      const std::string f = "fields." + std::to_string(k) + ".";
      CHECK(d.text(f + "name") == fields[k].name);
      CHECK(d.integer(f + "offset") == fields[k].offset);
      CHECK(d.integer(f + "datatype") == fields[k].datatype);
      CHECK(d.integer(f + "count") == fields[k].count);
    }
    CHECK_FALSE(d.has("fields.6.name"));
    CHECK(d.integer("is_bigendian") == 0);
    CHECK(d.integer("point_step") == kStep);
    CHECK(d.integer("row_step") == kStep * kWidth);
    const ros::Leaf& bytes = d.leaf("data");
    REQUIRE(bytes.count == data.size());
    CHECK(std::memcmp(d.bytes.data() + bytes.offset, data.data(), data.size()) == 0);
    CHECK(d.integer("is_dense") == (n % 2 == 0 ? 1 : 0));
    // The last byte is is_dense, right after the data.
    CHECK(d.bytes.size() == bytes.offset + data.size() + 1);
  }
  // Worked by hand for "lidar" [bytes after the encapsulation header]:
  // stamp 8, frame id 4 + 6 -> 18, pad to 20, height and width -> 28, field
  // count -> 32; a field is its name (4 + characters + NUL), padding to 4,
  // offset 4, datatype 1, padding 3 and count 4: x, y, z 20 each -> 92,
  // "intensity" 4 + 10 + 2 + 12 -> 120, "ring" 4 + 5 + 3 + 12 -> 144, "rgb"
  // 4 + 4 + 12 -> 164; is_bigendian -> 165, pad to 168, point_step and
  // row_step -> 176, data 4 + 100 -> 280, is_dense -> 281.
  msg::write_point_cloud2(w, msg::Header{0, 0, "lidar"}, kWidth, fields, kStep, data.data(), data.size(), true);
  CHECK(w.bytes().size() == 4 + 281);
  CHECK(w.bytes()[0] == 0x00);
  CHECK(w.bytes()[1] == 0x01);
  CHECK(w.bytes()[2] == 0x00);
  CHECK(w.bytes()[3] == 0x00);

  // An empty cloud, and sizes that do not match.
  msg::write_point_cloud2(w, msg::Header{1, 2, "m"}, 0, fields, kStep, nullptr, 0, true);
  CHECK(Decoded("sensor_msgs/PointCloud2", w).leaf("data").count == 0);
  CHECK_THROWS_AS(msg::write_point_cloud2(w, msg::Header{}, kWidth, fields, kStep, data.data(), data.size() - 1, true),
                  std::invalid_argument);
  const std::size_t huge = std::size_t{1} << 33;  // 2^20 points of 2^13 bytes: row_step overflows uint32
  CHECK_THROWS_AS(msg::write_point_cloud2(w, msg::Header{}, 1u << 20, fields, 1u << 13, data.data(), huge, true),
                  std::invalid_argument);
}

TEST_CASE("ros2msg MarkerArray: DELETEALL, then a cube and a label per box") {
  const double pi = std::acos(-1.0);
  const std::vector<msg::BoxMarker> boxes = {
      {3, {1.5, -2.0, 0.75}, {4.0, 2.0, 1.5}, pi / 2, {0.25f, 0.5f, 0.75f, 0.8f}, "car 3"},
      {-7, {-10.0, 5.5, 0.4}, {0.6, 0.7, 1.8}, -0.3, {1.0f, 0.0f, 0.125f, 1.0f}, ""}};
  io::CdrWriter w;
  for (std::size_t n = 0; n <= 9; ++n) {
    INFO("frame id of ", n, " characters, namespace of ", 9 - n);
    const std::string ns = frame(9 - n);
    msg::write_marker_array(w, msg::Header{1700000001, 999999999, frame(n)}, ns, boxes);
    const Decoded d("visualization_msgs/MarkerArray", w);
    REQUIRE(d.has("markers.4.id"));
    CHECK_FALSE(d.has("markers.5.id"));
    for (int m = 0; m < 5; ++m) {
      const std::string p = "markers." + std::to_string(m) + ".";
      CHECK(d.integer(p + "header.stamp.sec") == 1700000001);
      CHECK(d.integer(p + "header.stamp.nanosec") == 999999999);
      CHECK(d.text(p + "header.frame_id") == frame(n));
      CHECK(d.text(p + "ns") == ns);
      CHECK(d.integer(p + "lifetime.sec") == 0);
      CHECK(d.integer(p + "lifetime.nanosec") == 0);
      CHECK(d.integer(p + "frame_locked") == 0);
      REQUIRE(d.message.find_array(p + "points") != nullptr);
      CHECK(d.message.find_array(p + "points")->count == 0);
      CHECK(d.message.find_array(p + "colors")->count == 0);
      CHECK(d.message.find_array(p + "uv_coordinates")->count == 0);
      CHECK(d.text(p + "texture_resource").empty());
      CHECK(d.text(p + "texture.header.frame_id").empty());
      CHECK(d.text(p + "texture.format").empty());
      CHECK(d.leaf(p + "texture.data").count == 0);
      CHECK(d.text(p + "mesh_resource").empty());
      CHECK(d.text(p + "mesh_file.filename").empty());
      CHECK(d.leaf(p + "mesh_file.data").count == 0);
      CHECK(d.integer(p + "mesh_use_embedded_materials") == 0);
      CHECK(d.offset(p + "pose.position.x") % 8 == 0);
    }
    CHECK(d.integer("markers.0.action") == 3);
    CHECK(d.integer("markers.0.id") == 0);
    CHECK(d.text("markers.0.text").empty());
    for (std::size_t b = 0; b < boxes.size(); ++b) {
      const msg::BoxMarker& box = boxes[b];
      const std::string cube = "markers." + std::to_string(1 + 2 * b) + ".";
      const std::string label = "markers." + std::to_string(2 + 2 * b) + ".";
      CHECK(d.integer(cube + "id") == 2 * box.id);
      CHECK(d.integer(cube + "type") == 1);
      CHECK(d.integer(cube + "action") == 0);
      CHECK(d.real(cube + "pose.position.x") == box.center[0]);
      CHECK(d.real(cube + "pose.position.y") == box.center[1]);
      CHECK(d.real(cube + "pose.position.z") == box.center[2]);
      CHECK(d.real(cube + "pose.orientation.x") == 0.0);
      CHECK(d.real(cube + "pose.orientation.y") == 0.0);
      CHECK(d.real(cube + "pose.orientation.z") == doctest::Approx(std::sin(box.yaw / 2)).epsilon(1e-15));
      CHECK(d.real(cube + "pose.orientation.w") == doctest::Approx(std::cos(box.yaw / 2)).epsilon(1e-15));
      CHECK(d.real(cube + "scale.x") == box.size[0]);
      CHECK(d.real(cube + "scale.y") == box.size[1]);
      CHECK(d.real(cube + "scale.z") == box.size[2]);
      CHECK(d.leaf(cube + "color.r").primitive == ros::Primitive::float32);
      CHECK(d.real(cube + "color.r") == static_cast<double>(box.rgba[0]));
      CHECK(d.real(cube + "color.g") == static_cast<double>(box.rgba[1]));
      CHECK(d.real(cube + "color.b") == static_cast<double>(box.rgba[2]));
      CHECK(d.real(cube + "color.a") == static_cast<double>(box.rgba[3]));
      CHECK(d.text(cube + "text").empty());
      CHECK(d.integer(label + "id") == 2 * box.id + 1);
      CHECK(d.integer(label + "type") == 9);
      CHECK(d.integer(label + "action") == 0);
      CHECK(d.real(label + "pose.position.x") == box.center[0]);
      CHECK(d.real(label + "pose.position.z") == doctest::Approx(box.center[2] + box.size[2] / 2 + msg::kLabelGap));
      CHECK(d.real(label + "pose.orientation.w") == 1.0);
      CHECK(d.real(label + "scale.z") == msg::kLabelHeight);
      CHECK(d.real(label + "color.a") == 1.0);
      CHECK(d.text(label + "text") == (box.text.empty() ? std::to_string(box.id) : box.text));
    }
  }
  // No boxes: the DELETEALL marker alone.
  msg::write_marker_array(w, msg::Header{}, "c", {});
  const Decoded empty("visualization_msgs/MarkerArray", w);
  CHECK(empty.integer("markers.0.action") == 3);
  CHECK_FALSE(empty.has("markers.1.id"));
  CHECK_THROWS_AS(msg::write_marker_array(w, msg::Header{}, "c", {msg::BoxMarker{1 << 30, {}, {}, 0, {}, ""}}),
                  std::invalid_argument);
}

TEST_CASE("ros2msg MarkerArray: an arrow per box with one, after the cubes and labels, in its own namespace") {
  msg::BoxMarker still{4, {1.0, 2.0, 0.5}, {0.5, 0.4, 1.7}, 0.2, {0.5f, 0.25f, 1.0f, 0.4f}, "4 0.0 m/s"};
  msg::BoxMarker walking = still;
  walking.id = 9;
  walking.arrow_length = 1.25;
  walking.arrow_yaw = -1.0;
  io::CdrWriter w;
  msg::write_marker_array(w, msg::Header{1, 2, "map"}, "tracks", {walking, still});
  const Decoded d("visualization_msgs/MarkerArray", w);
  REQUIRE(d.has("markers.5.id"));
  CHECK_FALSE(d.has("markers.6.id"));
  const std::string arrow = "markers.5.";
  CHECK(d.text(arrow + "ns") == "tracks_velocity");
  CHECK(d.integer(arrow + "id") == 18);
  CHECK(d.integer(arrow + "type") == 0);
  CHECK(d.integer(arrow + "action") == 0);
  CHECK(d.real(arrow + "pose.position.x") == 1.0);
  CHECK(d.real(arrow + "pose.orientation.z") == doctest::Approx(std::sin(-0.5)).epsilon(1e-15));
  CHECK(d.real(arrow + "pose.orientation.w") == doctest::Approx(std::cos(-0.5)).epsilon(1e-15));
  CHECK(d.real(arrow + "scale.x") == 1.25);
  CHECK(d.real(arrow + "scale.y") == msg::kArrowShaft);
  CHECK(d.real(arrow + "scale.z") == msg::kArrowHead);
  CHECK(d.real(arrow + "color.b") == 1.0);
  CHECK(d.real(arrow + "color.a") == 1.0);
  for (int m = 1; m < 5; ++m) CHECK(d.text("markers." + std::to_string(m) + ".ns") == "tracks");
}

TEST_CASE("ros2msg Detection3DArray: header, one hypothesis, box and id per detection") {
  const std::vector<msg::Detection> detections = {
      {"17", "object", 0.875, {3.0, 4.0, 0.5}, {1.0, 2.0, 1.25}, 0.4},
      {"ground", "ground", 1.0, {0.0, 0.0, -1.7}, {50.0, 50.0, 0.2}, 0.0},
      {"abcdefg", "x", 0.0, {-1.0, -2.0, -3.0}, {0.1, 0.2, 0.3}, -3.0}};
  io::CdrWriter w;
  for (std::size_t n = 0; n <= 8; ++n) {
    INFO("frame id of ", n, " characters");
    msg::write_detection3d_array(w, msg::Header{42, 7, frame(n)}, detections);
    const Decoded d("vision_msgs/Detection3DArray", w);
    CHECK(d.text("header.frame_id") == frame(n));
    CHECK_FALSE(d.has("detections.3.id"));
    for (std::size_t k = 0; k < detections.size(); ++k) {
      const msg::Detection& e = detections[k];
      const std::string p = "detections." + std::to_string(k) + ".";
      CHECK(d.integer(p + "header.stamp.sec") == 42);
      CHECK(d.integer(p + "header.stamp.nanosec") == 7);
      CHECK(d.text(p + "header.frame_id") == frame(n));
      CHECK_FALSE(d.has(p + "results.1.hypothesis.class_id"));
      CHECK(d.text(p + "results.0.hypothesis.class_id") == e.class_id);
      CHECK(d.real(p + "results.0.hypothesis.score") == e.score);
      CHECK(d.offset(p + "results.0.hypothesis.score") % 8 == 0);
      CHECK(d.real(p + "results.0.pose.pose.position.x") == e.center[0]);
      CHECK(d.real(p + "results.0.pose.pose.position.z") == e.center[2]);
      CHECK(d.real(p + "results.0.pose.pose.orientation.z") == doctest::Approx(std::sin(e.yaw / 2)));
      CHECK(d.reals(p + "results.0.pose.covariance") == std::vector<double>(36, 0.0));
      CHECK(d.real(p + "bbox.center.position.x") == e.center[0]);
      CHECK(d.real(p + "bbox.center.position.y") == e.center[1]);
      CHECK(d.real(p + "bbox.center.position.z") == e.center[2]);
      CHECK(d.real(p + "bbox.center.orientation.z") == doctest::Approx(std::sin(e.yaw / 2)));
      CHECK(d.real(p + "bbox.center.orientation.w") == doctest::Approx(std::cos(e.yaw / 2)));
      CHECK(d.real(p + "bbox.size.x") == e.size[0]);
      CHECK(d.real(p + "bbox.size.y") == e.size[1]);
      CHECK(d.real(p + "bbox.size.z") == e.size[2]);
      CHECK(d.text(p + "id") == e.id);
    }
  }
  // By hand for frame "map": header 8 + 4 + 4 -> 16; count 20; detection 0:
  // header -> 36, results count 40, "object" 4 + 7 -> 51, pad to 56: the score.
  msg::write_detection3d_array(w, msg::Header{0, 0, "map"}, detections);
  CHECK(Decoded("vision_msgs/Detection3DArray", w).offset("detections.0.results.0.hypothesis.score") == 56);
  msg::write_detection3d_array(w, msg::Header{0, 0, "map"}, {});
  CHECK(w.bytes().size() == 4 + 20);
}

TEST_CASE("ros2msg Imu: orientation, rates, accelerations and covariances at their aligned offsets") {
  msg::Imu imu;
  imu.orientation = {0.1, -0.2, 0.3, std::sqrt(1 - 0.14)};
  imu.angular_velocity = {0.01, -0.02, 1.5};
  imu.linear_acceleration = {0.2, -0.1, 9.81};
  for (std::size_t i = 0; i < 9; ++i) {
    imu.orientation_covariance[i] = i == 0 ? -1.0 : 0.0;
    imu.angular_velocity_covariance[i] = 1e-4 * static_cast<double>(i + 1);
    imu.linear_acceleration_covariance[i] = -2.5 * static_cast<double>(i);
  }
  // Where the orientation starts [bytes after the encapsulation header], by
  // frame id length: 12 bytes of stamp and length, the characters and NUL,
  // then up to a multiple of 8.
  const std::vector<std::size_t> orientation_at = {16, 16, 16, 16, 24, 24, 24, 24, 24, 24, 24, 24, 32};
  io::CdrWriter w;
  for (std::size_t n = 0; n <= 12; ++n) {
    INFO("frame id of ", n, " characters");
    msg::write_imu(w, msg::Header{-5, 1, frame(n)}, imu);
    const Decoded d("sensor_msgs/Imu", w);
    CHECK(d.integer("header.stamp.sec") == -5);
    CHECK(d.text("header.frame_id") == frame(n));
    CHECK(d.offset("orientation.x") == orientation_at[n]);
    CHECK(d.real("orientation.x") == imu.orientation[0]);
    CHECK(d.real("orientation.y") == imu.orientation[1]);
    CHECK(d.real("orientation.z") == imu.orientation[2]);
    CHECK(d.real("orientation.w") == imu.orientation[3]);
    CHECK(d.reals("orientation_covariance") == std::vector<double>(imu.orientation_covariance.begin(),
                                                                   imu.orientation_covariance.end()));
    CHECK(d.real("angular_velocity.z") == imu.angular_velocity[2]);
    CHECK(d.reals("angular_velocity_covariance") ==
          std::vector<double>(imu.angular_velocity_covariance.begin(), imu.angular_velocity_covariance.end()));
    CHECK(d.real("linear_acceleration.x") == imu.linear_acceleration[0]);
    CHECK(d.real("linear_acceleration.z") == imu.linear_acceleration[2]);
    CHECK(d.reals("linear_acceleration_covariance") == std::vector<double>(imu.linear_acceleration_covariance.begin(),
                                                                           imu.linear_acceleration_covariance.end()));
    // Quaternion 32 + 3 x 72 covariances + 2 x 24 vectors after the orientation.
    CHECK(w.bytes().size() == 4 + orientation_at[n] + 296);
  }
  // Each call starts a new message.
  const std::vector<std::uint8_t> once = w.bytes();
  msg::write_imu(w, msg::Header{-5, 1, frame(12)}, imu);
  CHECK(w.bytes() == once);
}

TEST_CASE("ros2msg Odometry: child frame, pose and twist with covariances") {
  msg::Odometry odom;
  odom.child_frame_id = "base_link";
  odom.position = {12.5, -3.25, 0.125};
  const std::array<double, 4> q = msg::yaw_quaternion(1.0);
  odom.orientation = q;
  odom.linear_velocity = {1.5, 0.0, -0.1};
  odom.angular_velocity = {0.0, 0.02, 0.3};
  for (std::size_t i = 0; i < 36; ++i) {
    odom.pose_covariance[i] = i % 7 == 0 ? 0.01 * static_cast<double>(i + 1) : 0.0;
    odom.twist_covariance[i] = static_cast<double>(i) - 18.0;
  }
  io::CdrWriter w;
  for (std::size_t n = 0; n <= 9; ++n) {
    for (const std::string& child : std::vector<std::string>{"", "b", "base_link", "base_lin"}) {
      INFO("frame id of ", n, " characters, child ", child);
      odom.child_frame_id = child;
      msg::write_odometry(w, msg::Header{1700000000, 500000000, frame(n)}, odom);
      const Decoded d("nav_msgs/Odometry", w);
      CHECK(d.integer("header.stamp.nanosec") == 500000000);
      CHECK(d.text("header.frame_id") == frame(n));
      CHECK(d.text("child_frame_id") == child);
      CHECK(d.offset("pose.pose.position.x") % 8 == 0);
      CHECK(d.real("pose.pose.position.x") == odom.position[0]);
      CHECK(d.real("pose.pose.position.y") == odom.position[1]);
      CHECK(d.real("pose.pose.position.z") == odom.position[2]);
      CHECK(d.real("pose.pose.orientation.z") == q[2]);
      CHECK(d.real("pose.pose.orientation.w") == q[3]);
      CHECK(d.reals("pose.covariance") ==
            std::vector<double>(odom.pose_covariance.begin(), odom.pose_covariance.end()));
      CHECK(d.real("twist.twist.linear.x") == odom.linear_velocity[0]);
      CHECK(d.real("twist.twist.linear.z") == odom.linear_velocity[2]);
      CHECK(d.real("twist.twist.angular.y") == odom.angular_velocity[1]);
      CHECK(d.real("twist.twist.angular.z") == odom.angular_velocity[2]);
      CHECK(d.reals("twist.covariance") ==
            std::vector<double>(odom.twist_covariance.begin(), odom.twist_covariance.end()));
    }
  }
  // By hand: stamp 8, "odom" 4 + 5 -> 17, pad to 20, "base_link" 4 + 10 ->
  // 34, pad to 40, pose 56 -> 96, covariance 288 -> 384, twist 48 -> 432,
  // covariance 288 -> 720; plus the encapsulation header.
  odom.child_frame_id = "base_link";
  msg::write_odometry(w, msg::Header{0, 0, "odom"}, odom);
  CHECK(w.bytes().size() == 4 + 720);
  CHECK(Decoded("nav_msgs/Odometry", w).offset("pose.pose.position.x") == 40);
}

TEST_CASE("ros2msg yaw_quaternion: a unit rotation about +z") {
  const double pi = std::acos(-1.0);
  for (const double yaw : {0.0, 0.5, pi / 2, pi, -2.0}) {
    const std::array<double, 4> q = msg::yaw_quaternion(yaw);
    CHECK(q[0] == 0.0);
    CHECK(q[1] == 0.0);
    CHECK(q[2] * q[2] + q[3] * q[3] == doctest::Approx(1.0));
    // The rotated x axis: (cos yaw, sin yaw).
    CHECK(1 - 2 * q[2] * q[2] == doctest::Approx(std::cos(yaw)));
    CHECK(2 * q[2] * q[3] == doctest::Approx(std::sin(yaw)));
  }
}
