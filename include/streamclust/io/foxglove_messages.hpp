// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Foxglove's scene messages in their ROS 2 form (foxglove_msgs, CDR), for
/// MCAP files the Foxglove 3D panel shows: `foxglove_msgs/msg/PointCloud`
/// (points with packed fields) and `foxglove_msgs/msg/SceneUpdate` (boxes
/// and labels). The definitions list the fields of the foxglove_msgs and
/// common ROS 2 types (https://github.com/foxglove/schemas, ros2/; the
/// common ones from ros2_definitions.hpp); the serializers write exactly
/// those fields (tests decode them back through ros/message_decoder.hpp
/// from the same definitions).

#include <streamclust/io/cdr_writer.hpp>
#include <streamclust/io/ros2_definitions.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::io::foxglove {

namespace detail {

/// Fields of each foxglove_msgs type, as .msg lines ("pkg/Type" -> text);
/// the builtin_interfaces and geometry_msgs types come from ros2_common_types().
inline const Ros2TypeTable& types() {
  static const Ros2TypeTable t = {
      {"foxglove_msgs/Color", "float64 r\nfloat64 g\nfloat64 b\nfloat64 a\n"},
      {"foxglove_msgs/KeyValuePair", "string key\nstring value\n"},
      {"foxglove_msgs/PackedElementField",
       "string name\nuint32 offset\nuint8 UNKNOWN=0\nuint8 UINT8=1\nuint8 INT8=2\nuint8 UINT16=3\nuint8 INT16=4\n"
       "uint8 UINT32=5\nuint8 INT32=6\nuint8 FLOAT32=7\nuint8 FLOAT64=8\nuint8 type\n"},
      {"foxglove_msgs/PointCloud",
       "builtin_interfaces/Time timestamp\nstring frame_id\ngeometry_msgs/Pose pose\nuint32 point_stride\n"
       "foxglove_msgs/PackedElementField[] fields\nuint8[] data\n"},
      {"foxglove_msgs/SceneEntityDeletion",
       "builtin_interfaces/Time timestamp\nuint8 MATCHING_ID=0\nuint8 ALL=1\nuint8 type\nstring id\n"},
      {"foxglove_msgs/ArrowPrimitive",
       "geometry_msgs/Pose pose\nfloat64 shaft_length\nfloat64 shaft_diameter\nfloat64 head_length\n"
       "float64 head_diameter\nfoxglove_msgs/Color color\n"},
      {"foxglove_msgs/CubePrimitive", "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 size\nfoxglove_msgs/Color color\n"},
      {"foxglove_msgs/SpherePrimitive", "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 size\nfoxglove_msgs/Color color\n"},
      {"foxglove_msgs/CylinderPrimitive",
       "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 size\nfloat64 bottom_scale\nfloat64 top_scale\n"
       "foxglove_msgs/Color color\n"},
      {"foxglove_msgs/LinePrimitive",
       "uint8 LINE_STRIP=0\nuint8 LINE_LOOP=1\nuint8 LINE_LIST=2\nuint8 type\ngeometry_msgs/Pose pose\n"
       "float64 thickness\nbool scale_invariant\ngeometry_msgs/Point[] points\nfoxglove_msgs/Color color\n"
       "foxglove_msgs/Color[] colors\nuint32[] indices\n"},
      {"foxglove_msgs/TriangleListPrimitive",
       "geometry_msgs/Pose pose\ngeometry_msgs/Point[] points\nfoxglove_msgs/Color color\n"
       "foxglove_msgs/Color[] colors\nuint32[] indices\n"},
      {"foxglove_msgs/TextPrimitive",
       "geometry_msgs/Pose pose\nbool billboard\nfloat64 font_size\nbool scale_invariant\n"
       "foxglove_msgs/Color color\nstring text\n"},
      {"foxglove_msgs/ModelPrimitive",
       "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 scale\nfoxglove_msgs/Color color\nbool override_color\n"
       "string url\nstring media_type\nuint8[] data\n"},
      {"foxglove_msgs/SceneEntity",
       "builtin_interfaces/Time timestamp\nstring frame_id\nstring id\nbuiltin_interfaces/Duration lifetime\n"
       "bool frame_locked\nfoxglove_msgs/KeyValuePair[] metadata\nfoxglove_msgs/ArrowPrimitive[] arrows\n"
       "foxglove_msgs/CubePrimitive[] cubes\nfoxglove_msgs/SpherePrimitive[] spheres\n"
       "foxglove_msgs/CylinderPrimitive[] cylinders\nfoxglove_msgs/LinePrimitive[] lines\n"
       "foxglove_msgs/TriangleListPrimitive[] triangles\nfoxglove_msgs/TextPrimitive[] texts\n"
       "foxglove_msgs/ModelPrimitive[] models\n"},
      {"foxglove_msgs/SceneUpdate",
       "foxglove_msgs/SceneEntityDeletion[] deletions\nfoxglove_msgs/SceneEntity[] entities\n"},
  };
  return t;
}

}  // namespace detail

/// The ROS 2 definition text of `type` ("foxglove_msgs/PointCloud") as an
/// MCAP `ros2msg` schema holds it: its fields, then each type it uses after a
/// line of `=` and `MSG: pkg/Type`.
/// Throws std::invalid_argument for a type it does not know.
inline std::string ros2_definition(const std::string& type) {
  return ros2_definition_text(type, {&detail::types(), &ros2_common_types()});
}

/// A time as ROS 2 `builtin_interfaces/Time`: whole seconds and nanoseconds.
struct Stamp {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
};

/// An RGBA colour, each in [0, 1].
struct Color {
  double r = 1, g = 1, b = 1, a = 1;
};

inline void put_stamp(CdrWriter& w, Stamp t) {
  w.i32(t.sec);
  w.u32(t.nanosec);
}
inline void put_vector(CdrWriter& w, double x, double y, double z) {
  w.f64(x);
  w.f64(y);
  w.f64(z);
}
/// A pose at (x, y, z) without rotation.
inline void put_pose(CdrWriter& w, double x, double y, double z, double yaw = 0.0) {
  put_vector(w, x, y, z);
  w.f64(0);  // the quaternion of a turn by `yaw` [rad] about z
  w.f64(0);
  w.f64(std::sin(0.5 * yaw));
  w.f64(std::cos(0.5 * yaw));
}
inline void put_color(CdrWriter& w, Color c) {
  w.f64(c.r);
  w.f64(c.g);
  w.f64(c.b);
  w.f64(c.a);
}

/// PackedElementField types.
enum class FieldType : std::uint8_t { uint8 = 1, int8 = 2, uint16 = 3, int16 = 4, uint32 = 5, int32 = 6, float32 = 7,
                                      float64 = 8 };

/// One field of a point cloud's packed points.
struct PackedField {
  std::string name;
  std::uint32_t offset = 0;
  FieldType type = FieldType::float32;
};

/// Writes a `foxglove_msgs/PointCloud` with an identity pose: `data` holds
/// the points, `stride` bytes each, laid out as `fields` say.
inline void write_point_cloud(CdrWriter& w, Stamp t, const std::string& frame_id, std::uint32_t stride,
                              const std::vector<PackedField>& fields, const std::vector<std::uint8_t>& data) {
  w.clear();
  put_stamp(w, t);
  w.string(frame_id);
  put_pose(w, 0, 0, 0);
  w.u32(stride);
  w.count(fields.size());
  for (const PackedField& f : fields) {
    w.string(f.name);
    w.u32(f.offset);
    w.u8(static_cast<std::uint8_t>(f.type));
  }
  w.bytes(data.data(), data.size());
}

/// One box of a scene update: an entity with one cube turned by `yaw` about
/// z, above it `text` (its id when empty), and an arrow from its centre when
/// `arrow_length` > 0.
struct Box {
  std::string id;
  std::array<double, 3> center{}, size{};  ///< [m]; size along the box's own axes
  Color color;
  std::vector<std::pair<std::string, std::string>> metadata;
  double yaw = 0.0;           ///< [rad] the cube's turn about z
  std::string text;           ///< shown above the box; empty: the id
  double arrow_length = 0.0;  ///< [m] 0: no arrow
  double arrow_yaw = 0.0;     ///< [rad] the arrow's heading in the ground plane
};

/// Writes a `foxglove_msgs/SceneUpdate` that deletes every earlier entity
/// and adds `boxes` (each lives until the next update deletes it).
inline void write_scene_update(CdrWriter& w, Stamp t, const std::string& frame_id, const std::vector<Box>& boxes) {
  w.clear();
  w.count(1);  // deletions: all earlier entities
  put_stamp(w, t);
  w.u8(1);  // ALL
  w.string("");
  w.count(boxes.size());
  for (const Box& b : boxes) {
    put_stamp(w, t);
    w.string(frame_id);
    w.string(b.id);
    put_stamp(w, Stamp{});  // lifetime 0: until deleted
    w.boolean(false);       // frame_locked
    w.count(b.metadata.size());
    for (const auto& [key, value] : b.metadata) {
      w.string(key);
      w.string(value);
    }
    w.count(b.arrow_length > 0.0 ? 1 : 0);  // arrows
    if (b.arrow_length > 0.0) {
      const double head = std::min(0.3, 0.5 * b.arrow_length);
      put_pose(w, b.center[0], b.center[1], b.center[2], b.arrow_yaw);
      w.f64(b.arrow_length - head);  // shaft length [m]
      w.f64(0.06);                   // shaft diameter [m]
      w.f64(head);                   // head length [m]
      w.f64(0.18);                   // head diameter [m]
      put_color(w, Color{1, 1, 1, 0.9});
    }
    w.count(1);  // cubes
    put_pose(w, b.center[0], b.center[1], b.center[2], b.yaw);
    put_vector(w, b.size[0], b.size[1], b.size[2]);
    put_color(w, b.color);
    w.count(0);  // spheres
    w.count(0);  // cylinders
    w.count(0);  // lines
    w.count(0);  // triangles
    w.count(1);  // texts: the id above the box
    put_pose(w, b.center[0], b.center[1], b.center[2] + b.size[2] / 2 + 0.2);
    w.boolean(true);  // billboard
    w.f64(14.0);      // font size [px, scale invariant]
    w.boolean(true);
    put_color(w, Color{1, 1, 1, 1});
    w.string(b.text.empty() ? b.id : b.text);
    w.count(0);  // models
  }
}

}  // namespace streamclust::io::foxglove
