// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The standard ROS 2 messages a clustering node publishes, serialized as
/// ROS 2 sends and records them: CDR (XCDR1, little-endian) behind the
/// 4-byte encapsulation header `00 01 00 00` (cdr_writer.hpp).
///
/// | message                          | serializer                |
/// |----------------------------------|---------------------------|
/// | `sensor_msgs/PointCloud2`        | write_point_cloud2()      |
/// | `visualization_msgs/MarkerArray` | write_marker_array()      |
/// | `vision_msgs/Detection3DArray`   | write_detection3d_array() |
/// | `sensor_msgs/Imu`                | write_imu()               |
/// | `nav_msgs/Odometry`              | write_odometry()          |
/// | `tf2_msgs/TFMessage`             | write_tf_message()        |
///
/// ros2_definition() gives each one's definition text (an MCAP `ros2msg`
/// schema), with the fields of the ROS 2 Humble/Jazzy .msg files
/// (common_interfaces; vision_msgs 4.x); the serializers write exactly those
/// fields (tests decode them back through ros/message_decoder.hpp, and
/// tests/scripts/check_ros2_roundtrip.mjs re-encodes them with the reference
/// serializer).
///
///     streamclust::io::CdrWriter w;
///     using namespace streamclust::io::ros2msg;
///     write_marker_array(w, Header{sec, nanosec, "lidar"}, "clusters", boxes);
///     mcap.write(channel, log_time_ns, w.bytes().data(), w.bytes().size());
///
/// Units: positions and sizes in metres, angles in radians, times in seconds
/// and nanoseconds, velocities in m/s and rad/s, accelerations in m/s^2.
/// Every serializer starts a new message (CdrWriter::clear()) and costs
/// O(bytes written). The functions share no mutable state; a CdrWriter is
/// not thread-safe (one per thread).

#include <streamclust/io/cdr_writer.hpp>
#include <streamclust/io/ros2_definitions.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::io::ros2msg {

namespace detail {

/// The message types beyond ros2_common_types(), as .msg lines.
inline const Ros2TypeTable& types() {
  static const Ros2TypeTable t = {
      {"sensor_msgs/PointField",
       "uint8 INT8=1\nuint8 UINT8=2\nuint8 INT16=3\nuint8 UINT16=4\nuint8 INT32=5\nuint8 UINT32=6\n"
       "uint8 FLOAT32=7\nuint8 FLOAT64=8\nstring name\nuint32 offset\nuint8 datatype\nuint32 count\n"},
      {"sensor_msgs/PointCloud2",
       "std_msgs/Header header\nuint32 height\nuint32 width\nsensor_msgs/PointField[] fields\nbool is_bigendian\n"
       "uint32 point_step\nuint32 row_step\nuint8[] data\nbool is_dense\n"},
      {"sensor_msgs/CompressedImage", "std_msgs/Header header\nstring format\nuint8[] data\n"},
      {"sensor_msgs/Imu",
       "std_msgs/Header header\ngeometry_msgs/Quaternion orientation\nfloat64[9] orientation_covariance\n"
       "geometry_msgs/Vector3 angular_velocity\nfloat64[9] angular_velocity_covariance\n"
       "geometry_msgs/Vector3 linear_acceleration\nfloat64[9] linear_acceleration_covariance\n"},
      {"nav_msgs/Odometry",
       "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
       "geometry_msgs/TwistWithCovariance twist\n"},
      {"visualization_msgs/UVCoordinate", "float32 u\nfloat32 v\n"},
      {"visualization_msgs/MeshFile", "string filename\nuint8[] data\n"},
      {"visualization_msgs/Marker",
       "int32 ARROW=0\nint32 CUBE=1\nint32 SPHERE=2\nint32 CYLINDER=3\nint32 LINE_STRIP=4\nint32 LINE_LIST=5\n"
       "int32 CUBE_LIST=6\nint32 SPHERE_LIST=7\nint32 POINTS=8\nint32 TEXT_VIEW_FACING=9\nint32 MESH_RESOURCE=10\n"
       "int32 TRIANGLE_LIST=11\nint32 ADD=0\nint32 MODIFY=0\nint32 DELETE=2\nint32 DELETEALL=3\n"
       "std_msgs/Header header\nstring ns\nint32 id\nint32 type\nint32 action\ngeometry_msgs/Pose pose\n"
       "geometry_msgs/Vector3 scale\nstd_msgs/ColorRGBA color\nbuiltin_interfaces/Duration lifetime\n"
       "bool frame_locked\ngeometry_msgs/Point[] points\nstd_msgs/ColorRGBA[] colors\nstring texture_resource\n"
       "sensor_msgs/CompressedImage texture\nvisualization_msgs/UVCoordinate[] uv_coordinates\nstring text\n"
       "string mesh_resource\nvisualization_msgs/MeshFile mesh_file\nbool mesh_use_embedded_materials\n"},
      {"visualization_msgs/MarkerArray", "visualization_msgs/Marker[] markers\n"},
      {"vision_msgs/ObjectHypothesis", "string class_id\nfloat64 score\n"},
      {"vision_msgs/ObjectHypothesisWithPose",
       "vision_msgs/ObjectHypothesis hypothesis\ngeometry_msgs/PoseWithCovariance pose\n"},
      {"vision_msgs/BoundingBox3D", "geometry_msgs/Pose center\ngeometry_msgs/Vector3 size\n"},
      {"vision_msgs/Detection3D",
       "std_msgs/Header header\nvision_msgs/ObjectHypothesisWithPose[] results\nvision_msgs/BoundingBox3D bbox\n"
       "string id\n"},
      {"vision_msgs/Detection3DArray", "std_msgs/Header header\nvision_msgs/Detection3D[] detections\n"},
      {"geometry_msgs/Transform", "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n"},
      {"geometry_msgs/TransformStamped",
       "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n"},
      {"tf2_msgs/TFMessage", "geometry_msgs/TransformStamped[] transforms\n"},
  };
  return t;
}

}  // namespace detail

/// The definition text of `type` ("sensor_msgs/PointCloud2" or
/// "sensor_msgs/msg/PointCloud2") as an MCAP `ros2msg` schema holds it: its
/// fields, then each type it uses after a line of 80 `=` and `MSG: pkg/Type`.
/// Knows the six published types and every type they use; throws
/// std::invalid_argument for another.
inline std::string ros2_definition(const std::string& type) {
  return ros2_definition_text(type, {&detail::types(), &ros2_common_types()});
}

/// `std_msgs/Header`: the stamp (whole seconds and nanoseconds since the
/// epoch) and the coordinate frame.
struct Header {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;  ///< [0, 1e9)
  std::string frame_id;
};

/// One field of a PointCloud2's points (`sensor_msgs/PointField`).
struct PointField {
  /// `datatype` values, as sensor_msgs/PointField names them.
  static constexpr std::uint8_t INT8 = 1, UINT8 = 2, INT16 = 3, UINT16 = 4, INT32 = 5, UINT32 = 6, FLOAT32 = 7,
                                FLOAT64 = 8;
  std::string name;
  std::uint32_t offset = 0;  ///< from the start of a point [bytes]
  std::uint8_t datatype = FLOAT32;
  std::uint32_t count = 1;  ///< elements in the field
};

/// The unit quaternion (x, y, z, w) of a rotation by `yaw` [rad] about +z.
inline std::array<double, 4> yaw_quaternion(double yaw) noexcept {
  return {0.0, 0.0, std::sin(yaw / 2), std::cos(yaw / 2)};
}

namespace detail {

inline void put_header(CdrWriter& w, const Header& h) {
  w.i32(h.sec);
  w.u32(h.nanosec);
  w.string(h.frame_id);
}
inline void put_xyz(CdrWriter& w, const std::array<double, 3>& v) {
  w.f64(v[0]);
  w.f64(v[1]);
  w.f64(v[2]);
}
inline void put_pose(CdrWriter& w, const std::array<double, 3>& position, const std::array<double, 4>& orientation) {
  put_xyz(w, position);
  for (const double q : orientation) w.f64(q);
}
template <std::size_t N>
void put_fixed(CdrWriter& w, const std::array<double, N>& values) {
  for (const double v : values) w.f64(v);
}
inline void put_rgba(CdrWriter& w, const std::array<float, 4>& rgba) {
  for (const float c : rgba) w.f32(c);
}

}  // namespace detail

/// Writes a `sensor_msgs/PointCloud2` of one row (height 1) of `width`
/// points, `point_step` bytes each, laid out as `fields` say: `data` holds
/// the `bytes` = width x point_step bytes of the points, little-endian
/// (is_bigendian false; row_step = width x point_step). `is_dense`: no point
/// is invalid (NaN). Throws std::invalid_argument when `bytes` is not
/// width x point_step or that does not fit 32 bits.
inline void write_point_cloud2(CdrWriter& w, const Header& h, std::uint32_t width,
                               const std::vector<PointField>& fields, std::uint32_t point_step,
                               const std::uint8_t* data, std::size_t bytes, bool is_dense) {
  const std::uint64_t row = std::uint64_t{width} * point_step;
  if (row != bytes || row > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("write_point_cloud2: bytes = " + std::to_string(bytes) + ", expected width (" +
                                std::to_string(width) + ") x point_step (" + std::to_string(point_step) +
                                ") = " + std::to_string(row) + " (at most 2^32 - 1)");
  }
  w.clear();
  detail::put_header(w, h);
  w.u32(1);  // height
  w.u32(width);
  w.count(fields.size());
  for (const PointField& f : fields) {
    w.string(f.name);
    w.u32(f.offset);
    w.u8(f.datatype);
    w.u32(f.count);
  }
  w.boolean(false);  // is_bigendian
  w.u32(point_step);
  w.u32(static_cast<std::uint32_t>(row));  // row_step
  w.bytes(data, bytes);
  w.boolean(is_dense);
}

/// visualization_msgs/Marker `type` and `action` values used here.
inline constexpr std::int32_t kMarkerArrow = 0, kMarkerCube = 1, kMarkerTextViewFacing = 9;
inline constexpr std::int32_t kMarkerAdd = 0, kMarkerDeleteAll = 3;

/// A box of a MarkerArray: a cube and, above it, a label.
struct BoxMarker {
  /// Marker ids: the cube's is 2 id, the label's 2 id + 1 (so ids of
  /// different boxes never collide); |id| < 2^30.
  std::int32_t id = 0;
  std::array<double, 3> center{};  ///< [m]
  std::array<double, 3> size{};    ///< edge lengths along the box's x, y, z [m]
  double yaw = 0;                  ///< rotation about +z [rad]
  std::array<float, 4> rgba{1, 1, 1, 1};  ///< colour of the cube, each in [0, 1]
  std::string text;                       ///< the label; empty: the id
  double arrow_length = 0;                ///< [m] > 0: an arrow from the centre (e.g. 1 s of travel)
  double arrow_yaw = 0;                   ///< [rad] its heading about +z
};

/// Arrow shaft and head diameters [m].
inline constexpr double kArrowShaft = 0.1, kArrowHead = 0.2;

/// Label text height [m] and its gap above the box's top face [m].
inline constexpr double kLabelHeight = 0.5, kLabelGap = 0.2;

namespace detail {

/// One Marker: `rgba` colour, lifetime 0 (until replaced or deleted), not
/// frame-locked, no points, colours, texture, UV coordinates or mesh.
inline void put_marker(CdrWriter& w, const Header& h, const std::string& ns, std::int32_t id, std::int32_t type,
                       std::int32_t action, const std::array<double, 3>& position,
                       const std::array<double, 4>& orientation, const std::array<double, 3>& scale,
                       const std::array<float, 4>& rgba, const std::string& text) {
  put_header(w, h);
  w.string(ns);
  w.i32(id);
  w.i32(type);
  w.i32(action);
  put_pose(w, position, orientation);
  put_xyz(w, scale);
  put_rgba(w, rgba);
  w.i32(0);                 // lifetime.sec: 0, until replaced or deleted
  w.u32(0);                 // lifetime.nanosec
  w.boolean(false);         // frame_locked
  w.count(0);               // points
  w.count(0);               // colors
  w.string("");             // texture_resource
  put_header(w, Header{});  // texture.header
  w.string("");             // texture.format
  w.count(0);               // texture.data
  w.count(0);               // uv_coordinates
  w.string(text);
  w.string("");             // mesh_resource
  w.string("");             // mesh_file.filename
  w.count(0);               // mesh_file.data
  w.boolean(false);         // mesh_use_embedded_materials
}

}  // namespace detail

/// Writes a `visualization_msgs/MarkerArray` that replaces every earlier
/// marker by `boxes`: first a DELETEALL marker (id 0, type ARROW), then for
/// each box a CUBE (id 2 box.id, pose from centre and yaw, scale = size,
/// colour rgba) and a white TEXT_VIEW_FACING label (id 2 box.id + 1,
/// kLabelHeight high, kLabelGap above the top face), all ADD in namespace
/// `ns` with lifetime 0; then for each box with an arrow_length an ARROW
/// (id 2 box.id in namespace `ns` + "_velocity", from the centre along
/// arrow_yaw, scale arrow_length x kArrowShaft x kArrowHead, the cube's
/// colour, opaque). Throws std::invalid_argument when a box id is
/// outside (-2^30, 2^30).
inline void write_marker_array(CdrWriter& w, const Header& h, const std::string& ns,
                               const std::vector<BoxMarker>& boxes) {
  constexpr std::int32_t kIdLimit = 1 << 30;
  for (const BoxMarker& b : boxes) {
    if (b.id <= -kIdLimit || b.id >= kIdLimit) {
      throw std::invalid_argument("write_marker_array: box id " + std::to_string(b.id) +
                                  " outside (-2^30, 2^30): its marker ids 2 id and 2 id + 1 must fit int32");
    }
  }
  const auto arrows = static_cast<std::size_t>(
      std::count_if(boxes.begin(), boxes.end(), [](const BoxMarker& b) { return b.arrow_length > 0; }));
  w.clear();
  w.count(1 + 2 * boxes.size() + arrows);
  detail::put_marker(w, h, ns, 0, kMarkerArrow, kMarkerDeleteAll, {0, 0, 0}, {0, 0, 0, 1}, {0, 0, 0}, {0, 0, 0, 0},
                     "");
  for (const BoxMarker& b : boxes) {
    detail::put_marker(w, h, ns, 2 * b.id, kMarkerCube, kMarkerAdd, b.center, yaw_quaternion(b.yaw), b.size, b.rgba,
                       "");
    const std::array<double, 3> above{b.center[0], b.center[1], b.center[2] + b.size[2] / 2 + kLabelGap};
    detail::put_marker(w, h, ns, 2 * b.id + 1, kMarkerTextViewFacing, kMarkerAdd, above, {0, 0, 0, 1},
                       {kLabelHeight, kLabelHeight, kLabelHeight}, {1, 1, 1, 1},
                       b.text.empty() ? std::to_string(b.id) : b.text);
  }
  if (arrows == 0) return;
  const std::string arrow_ns = ns + "_velocity";
  for (const BoxMarker& b : boxes) {
    if (!(b.arrow_length > 0)) continue;
    detail::put_marker(w, h, arrow_ns, 2 * b.id, kMarkerArrow, kMarkerAdd, b.center, yaw_quaternion(b.arrow_yaw),
                       {b.arrow_length, kArrowShaft, kArrowHead}, {b.rgba[0], b.rgba[1], b.rgba[2], 1.0f}, "");
  }
}

/// One object of a Detection3DArray.
struct Detection {
  std::string id;                  ///< Detection3D.id (a track or cluster id)
  std::string class_id = "object";  ///< the one hypothesis' class ("object", "ground", ...)
  double score = 1;                ///< its confidence in [0, 1]
  std::array<double, 3> center{};  ///< [m]
  std::array<double, 3> size{};    ///< edge lengths along the box's x, y, z [m]
  double yaw = 0;                  ///< rotation about +z [rad]
};

/// Writes a `vision_msgs/Detection3DArray` (vision_msgs 4.x): one Detection3D
/// per detection with header `h`, one result (class_id and score, its pose the
/// box's centre pose with zero covariance), the bounding box (centre pose from
/// centre and yaw, size) and the id.
inline void write_detection3d_array(CdrWriter& w, const Header& h, const std::vector<Detection>& detections) {
  w.clear();
  detail::put_header(w, h);
  w.count(detections.size());
  for (const Detection& d : detections) {
    const std::array<double, 4> q = yaw_quaternion(d.yaw);
    detail::put_header(w, h);
    w.count(1);  // results
    w.string(d.class_id);
    w.f64(d.score);
    detail::put_pose(w, d.center, q);
    detail::put_fixed(w, std::array<double, 36>{});  // pose covariance
    detail::put_pose(w, d.center, q);                 // bbox.center
    detail::put_xyz(w, d.size);
    w.string(d.id);
  }
}

/// The content of a `sensor_msgs/Imu` after its header. Covariances are row
/// major about x, y, z; all zero: unknown; element 0 = -1: that quantity is
/// not estimated.
struct Imu {
  std::array<double, 4> orientation{0, 0, 0, 1};  ///< unit quaternion x, y, z, w
  std::array<double, 9> orientation_covariance{};   ///< [rad^2]
  std::array<double, 3> angular_velocity{};         ///< [rad/s]
  std::array<double, 9> angular_velocity_covariance{};  ///< [(rad/s)^2]
  std::array<double, 3> linear_acceleration{};          ///< [m/s^2]
  std::array<double, 9> linear_acceleration_covariance{};  ///< [(m/s^2)^2]
};

/// Writes a `sensor_msgs/Imu`.
inline void write_imu(CdrWriter& w, const Header& h, const Imu& imu) {
  w.clear();
  detail::put_header(w, h);
  for (const double q : imu.orientation) w.f64(q);
  detail::put_fixed(w, imu.orientation_covariance);
  detail::put_xyz(w, imu.angular_velocity);
  detail::put_fixed(w, imu.angular_velocity_covariance);
  detail::put_xyz(w, imu.linear_acceleration);
  detail::put_fixed(w, imu.linear_acceleration_covariance);
}

/// The content of a `nav_msgs/Odometry` after its header: the pose of
/// `child_frame_id` in the header's frame and its velocity in
/// `child_frame_id`. Covariances are row major 6 x 6 over (x, y, z, rotation
/// about x, y, z).
struct Odometry {
  std::string child_frame_id;
  std::array<double, 3> position{};               ///< [m]
  std::array<double, 4> orientation{0, 0, 0, 1};  ///< unit quaternion x, y, z, w
  std::array<double, 36> pose_covariance{};       ///< [m^2, m rad, rad^2]
  std::array<double, 3> linear_velocity{};        ///< [m/s]
  std::array<double, 3> angular_velocity{};       ///< [rad/s]
  std::array<double, 36> twist_covariance{};      ///< [(m/s)^2, m/s rad/s, (rad/s)^2]
};

/// Writes a `nav_msgs/Odometry`.
inline void write_odometry(CdrWriter& w, const Header& h, const Odometry& odom) {
  w.clear();
  detail::put_header(w, h);
  w.string(odom.child_frame_id);
  detail::put_pose(w, odom.position, odom.orientation);
  detail::put_fixed(w, odom.pose_covariance);
  detail::put_xyz(w, odom.linear_velocity);
  detail::put_xyz(w, odom.angular_velocity);
  detail::put_fixed(w, odom.twist_covariance);
}

/// One transform of a TFMessage: frame `child` placed in the header's
/// frame (the pose of child in parent).
struct Transform {
  std::string parent, child;
  std::array<double, 3> translation{};            ///< [m]
  std::array<double, 4> rotation{0, 0, 0, 1};     ///< unit quaternion x, y, z, w
};

/// Writes a `tf2_msgs/TFMessage` of `transforms`, each stamped `stamp`
/// (header.frame_id its parent).
inline void write_tf_message(CdrWriter& w, const Header& stamp, const std::vector<Transform>& transforms) {
  w.clear();
  w.count(transforms.size());
  for (const Transform& t : transforms) {
    detail::put_header(w, Header{stamp.sec, stamp.nanosec, t.parent});
    w.string(t.child);
    detail::put_xyz(w, t.translation);
    for (const double q : t.rotation) w.f64(q);
  }
}

}  // namespace streamclust::io::ros2msg
