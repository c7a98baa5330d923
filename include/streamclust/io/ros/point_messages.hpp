// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Points from the point-cloud messages Livox users record, with absolute
/// per-point times in nanoseconds:
///
/// | type | per-point time [ns] |
/// |---|---|
/// | `livox_ros_driver/CustomMsg`, `livox_ros_driver2/CustomMsg`, `livox_interfaces/CustomMsg` | `timebase` + `offset_time` |
/// | `sensor_msgs/PointCloud2` with `timestamp` float64 (Livox driver) | the value (absolute ns; below 1e14 it is read as absolute seconds) |
/// | ... with `timestamp` or `t` uint64 | the value (absolute ns) |
/// | ... with `t` or `offset_time` uint32 (converters, Ouster) | header stamp + value |
/// | ... with `time` float32 / float64 (Velodyne) | header stamp + value [s] |
/// | ... with none of these, and a point rate | header stamp + index / rate |
///
/// Intensity: `intensity`, else `reflectivity`, else `i`. Label: `label`.

#include <streamclust/io/byte_cursor.hpp>
#include <streamclust/io/ros/message_decoder.hpp>
#include <streamclust/io/ros/message_definition.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace streamclust::io::ros {

/// One point of a message, with its absolute time.
struct TimedPoint {
  float x = 0, y = 0, z = 0;  ///< [m]
  float intensity = 0;
  std::int64_t label = -1;
  std::uint64_t t_ns = 0;  ///< absolute time [ns]
};

/// Point-cloud message kinds.
enum class PointMessageKind { livox_custom, point_cloud2 };

/// The kind of a type name ("pkg/Type" or "pkg/msg/Type"), or nothing when it
/// holds no points this module reads.
inline std::optional<PointMessageKind> point_message_kind(std::string_view type) {
  const std::string t = MessageDefinitions::normalize(type);
  if (t == "sensor_msgs/PointCloud2") return PointMessageKind::point_cloud2;
  if (t == "livox_ros_driver/CustomMsg" || t == "livox_ros_driver2/CustomMsg" || t == "livox_interfaces/CustomMsg")
    return PointMessageKind::livox_custom;
  return std::nullopt;
}

/// Turns messages of one topic into points. Construct once per topic with the
/// topic's type, definition text and encoding; decode() per message. Throws
/// InputError (via the BufferOrigin) for a message that does not decode or
/// whose content is inconsistent, and std::invalid_argument from the
/// constructor for a definition that does not parse. O(points) per message;
/// not thread-safe.
class PointMessageDecoder {
 public:
  /// `point_rate` [Hz] times PointCloud2 messages without a time field.
  PointMessageDecoder(std::string_view type, std::string_view definition, Encoding encoding,
                      std::optional<double> point_rate = std::nullopt)
      : definitions_(type, definition), decoder_(definitions_, encoding), point_rate_(point_rate) {
    const auto kind = point_message_kind(type);
    if (!kind) throw std::invalid_argument("type " + std::string(type) + " holds no points");
    kind_ = *kind;
  }

  PointMessageKind kind() const noexcept { return kind_; }

  /// The field names of the last PointCloud2 decoded, or of a CustomMsg point.
  const std::vector<std::string>& fields() const noexcept { return fields_; }
  /// The time field used by the last message ("" when timed by the point rate).
  const std::string& time_field() const noexcept { return time_field_; }
  /// The header's frame id of the last message decoded ("" without one).
  std::string frame_id() const {
    const Leaf* l = message_.find("header.frame_id");
    return l != nullptr ? l->text : std::string();
  }

  /// Appends the points of the message in `payload` to `out` (every point,
  /// NaN ones included, in message order). `origin` locates the message in
  /// errors.
  void decode(const std::uint8_t* payload, std::size_t size, const detail::BufferOrigin& origin,
              std::vector<TimedPoint>& out) {
    decoder_.decode(payload, size, origin, message_);
    detail::ByteCursor at(payload, size, origin);  // for errors only
    if (kind_ == PointMessageKind::livox_custom) {
      custom(at, out);
    } else {
      cloud(at, out);
    }
  }

 private:
  const Leaf& leaf(const detail::ByteCursor& at, std::string_view path) const {
    const Leaf* l = message_.find(path);
    if (l == nullptr) at.fail_at(0, definitions_.main().name + " has no field " + std::string(path));
    return *l;
  }
  std::uint64_t unsigned_leaf(const detail::ByteCursor& at, std::string_view path) const {
    const Leaf& l = leaf(at, path);
    return message_.unsigned64(l.primitive, l.offset);
  }

  /// Header stamp [ns]: ROS 1 `stamp.sec/.nsec`, ROS 2 `stamp.sec/.nanosec`.
  std::uint64_t stamp_ns(const detail::ByteCursor& at) const {
    const Leaf& sec = leaf(at, "header.stamp.sec");
    const Leaf* nsec = message_.find("header.stamp.nanosec");
    if (nsec == nullptr) nsec = &leaf(at, "header.stamp.nsec");
    const std::int64_t s = message_.integer(sec.primitive, sec.offset);
    const std::int64_t n = message_.integer(nsec->primitive, nsec->offset);
    if (s < 0 || n < 0 || n >= 1000000000) {
      at.fail_at(sec.offset, "header stamp " + std::to_string(s) + " s " + std::to_string(n) +
                                 " ns: expected seconds >= 0 and nanoseconds in [0, 1e9)");
    }
    return static_cast<std::uint64_t>(s) * 1000000000u + static_cast<std::uint64_t>(n);
  }

  void custom(const detail::ByteCursor& at, std::vector<TimedPoint>& out) {
    const std::uint64_t timebase = unsigned_leaf(at, "timebase");
    const StructArray* points = message_.find_array("points");
    if (points == nullptr) at.fail_at(0, definitions_.main().name + " has no fixed-size array field points");
    if (const Leaf* n = message_.find("point_num")) {
      const std::uint64_t declared = message_.unsigned64(n->primitive, n->offset);
      if (declared != points->count) {
        at.fail_at(n->offset, "point_num says " + std::to_string(declared) + " points, the points array holds " +
                                  std::to_string(points->count));
      }
    }
    const std::size_t i_time = points->leaf("offset_time"), i_x = points->leaf("x"), i_y = points->leaf("y"),
                      i_z = points->leaf("z"), i_r = points->leaf("reflectivity");
    for (const std::size_t i : {i_time, i_x, i_y, i_z, i_r}) {
      if (i == StructArray::npos) at.fail_at(0, "CustomPoint needs offset_time, x, y, z and reflectivity");
    }
    fields_ = {"offset_time", "x", "y", "z", "reflectivity"};
    time_field_ = "offset_time";
    const auto& lv = points->leaves;
    points->for_each([&](std::size_t base, const ElementLayout& l) {
      TimedPoint p;
      p.x = static_cast<float>(message_.real(lv[i_x].second, base + l.offsets[i_x]));
      p.y = static_cast<float>(message_.real(lv[i_y].second, base + l.offsets[i_y]));
      p.z = static_cast<float>(message_.real(lv[i_z].second, base + l.offsets[i_z]));
      p.intensity = static_cast<float>(message_.real(lv[i_r].second, base + l.offsets[i_r]));
      p.t_ns = timebase + message_.unsigned64(lv[i_time].second, base + l.offsets[i_time]);
      out.push_back(p);
    });
  }

  struct CloudField {
    std::string name;
    std::size_t offset = 0;
    Primitive type = Primitive::uint8;
  };

  static std::optional<Primitive> point_field_type(std::int64_t datatype) {
    switch (datatype) {
      case 1: return Primitive::int8;
      case 2: return Primitive::uint8;
      case 3: return Primitive::int16;
      case 4: return Primitive::uint16;
      case 5: return Primitive::int32;
      case 6: return Primitive::uint32;
      case 7: return Primitive::float32;
      case 8: return Primitive::float64;
      default: return std::nullopt;
    }
  }
  static const char* type_name(Primitive p) {
    switch (p) {
      case Primitive::int8: return "int8";
      case Primitive::uint8: return "uint8";
      case Primitive::int16: return "int16";
      case Primitive::uint16: return "uint16";
      case Primitive::int32: return "int32";
      case Primitive::uint32: return "uint32";
      case Primitive::float32: return "float32";
      case Primitive::float64: return "float64";
      default: return "?";
    }
  }

  enum class TimeRule { none, absolute_ns, offset_ns, offset_s };

  void cloud(const detail::ByteCursor& at, std::vector<TimedPoint>& out) {
    const std::uint64_t height = unsigned_leaf(at, "height"), width = unsigned_leaf(at, "width");
    const std::uint64_t point_step = unsigned_leaf(at, "point_step"), row_step = unsigned_leaf(at, "row_step");
    const bool big_endian = unsigned_leaf(at, "is_bigendian") != 0;
    const Leaf& data = leaf(at, "data");
    // The fields table.
    std::vector<CloudField> fields;
    fields_.clear();
    for (std::size_t k = 0;; ++k) {
      const std::string p = "fields." + std::to_string(k) + ".";
      const Leaf* name = message_.find(p + "name");
      if (name == nullptr) break;
      const std::int64_t datatype = message_.integer(leaf(at, p + "datatype").primitive, leaf(at, p + "datatype").offset);
      const auto type = point_field_type(datatype);
      if (!type) at.fail_at(leaf(at, p + "datatype").offset, "field " + name->text + ": unknown PointField datatype " + std::to_string(datatype) + " (expected 1..8)");
      CloudField f{name->text, static_cast<std::size_t>(unsigned_leaf(at, p + "offset")), *type};
      const std::uint64_t count = unsigned_leaf(at, p + "count");
      if (f.offset + primitive_size(f.type) * std::max<std::uint64_t>(count, 1) > point_step) {
        at.fail_at(leaf(at, p + "offset").offset, "field " + f.name + " (offset " + std::to_string(f.offset) + ", " +
                                                      type_name(f.type) + " x " + std::to_string(count) +
                                                      ") does not fit the point step of " + std::to_string(point_step) + " bytes");
      }
      fields_.push_back(f.name);
      fields.push_back(std::move(f));
    }
    const auto find = [&](std::initializer_list<const char*> names) -> const CloudField* {
      for (const char* n : names)
        for (const CloudField& f : fields)
          if (f.name == n) return &f;
      return nullptr;
    };
    const CloudField* fx = find({"x"});
    const CloudField* fy = find({"y"});
    const CloudField* fz = find({"z"});
    if (fx == nullptr || fy == nullptr || fz == nullptr) at.fail_at(data.offset, "PointCloud2 without x, y and z fields (found: " + field_list(fields) + ")");
    const CloudField* fi = find({"intensity", "reflectivity", "i"});
    const CloudField* fl = find({"label"});
    // The time rule.
    TimeRule rule = TimeRule::none;
    const CloudField* ft = nullptr;
    for (const CloudField& f : fields) {
      const TimeRule r = time_rule(f);
      if (r != TimeRule::none) {
        ft = &f;
        rule = r;
        break;
      }
    }
    if (rule == TimeRule::none) {
      for (const CloudField& f : fields) {
        if (f.name == "t" || f.name == "time" || f.name == "timestamp" || f.name == "offset_time") {
          at.fail_at(data.offset, "time field " + f.name + " of type " + type_name(f.type) +
                                      " is not understood: expected timestamp (float64 absolute ns, or uint64), t or "
                                      "offset_time (uint32 ns after the header stamp, or uint64 absolute ns), time "
                                      "(float32/float64 s after the header stamp); found fields " + field_list(fields));
        }
      }
      if (!point_rate_) {
        at.fail_at(data.offset, "PointCloud2 without a per-point time field (found: " + field_list(fields) +
                                    "); expected timestamp, t, time or offset_time, or give a point rate "
                                    "(--point-rate HZ) to time points as header stamp + index / rate");
      }
    }
    time_field_ = ft != nullptr ? ft->name : std::string();
    // Geometry of the data block, without overflow: width x point_step <=
    // row_step and height x row_step == the data's size, so the points read
    // below are at most the data's bytes (an empty cloud reads no point,
    // however large its other side).
    if (width > 0 && (point_step == 0 || width > row_step / point_step)) {
      at.fail_at(data.offset, "row_step " + std::to_string(row_step) + " is less than width x point_step = " +
                                  std::to_string(width) + " x " + std::to_string(point_step));
    }
    if (height > 0 ? row_step > data.count / height || data.count != row_step * height : data.count != 0) {
      at.fail_at(data.offset, "data holds " + std::to_string(data.count) + " bytes: expected height x row_step = " +
                                  std::to_string(height) + " x " + std::to_string(row_step));
    }
    if (width == 0 || height == 0) return;
    const std::uint64_t stamp = stamp_ns(at);
    const DecodedMessage view = with_order(big_endian);
    const auto value = [&](const CloudField& f, std::size_t base) { return view.real(f.type, base + f.offset); };
    std::uint64_t index = 0;
    for (std::uint64_t r = 0; r < height; ++r) {
      for (std::uint64_t c = 0; c < width; ++c, ++index) {
        const std::size_t base = data.offset + static_cast<std::size_t>(r * row_step + c * point_step);
        TimedPoint p;
        p.x = static_cast<float>(value(*fx, base));
        p.y = static_cast<float>(value(*fy, base));
        p.z = static_cast<float>(value(*fz, base));
        if (fi != nullptr) p.intensity = static_cast<float>(value(*fi, base));
        if (fl != nullptr) p.label = view.integer(fl->type, base + fl->offset);
        p.t_ns = point_time(rule, ft, view, base, stamp, index, at);
        out.push_back(p);
      }
    }
  }

  static std::string field_list(const std::vector<CloudField>& fields) {
    std::string s;
    for (const CloudField& f : fields) s += (s.empty() ? "" : ", ") + f.name + " (" + type_name(f.type) + ")";
    return s.empty() ? "no fields" : s;
  }

  static TimeRule time_rule(const CloudField& f) {
    const bool u32 = f.type == Primitive::uint32, u64 = f.type == Primitive::uint64;
    const bool real = f.type == Primitive::float32 || f.type == Primitive::float64;
    if (f.name == "timestamp" && f.type == Primitive::float64) return TimeRule::absolute_ns;  // magnitude decides ns or s
    if ((f.name == "timestamp" || f.name == "t") && u64) return TimeRule::absolute_ns;
    if ((f.name == "t" || f.name == "offset_time") && u32) return TimeRule::offset_ns;
    if (f.name == "time" && real) return TimeRule::offset_s;
    return TimeRule::none;
  }

  /// A view of the message reading point data in the cloud's byte order.
  DecodedMessage with_order(bool big_endian) const {
    DecodedMessage v;
    v.payload = message_.payload;
    v.size = message_.size;
    v.big_endian = big_endian;
    return v;
  }

  std::uint64_t point_time(TimeRule rule, const CloudField* f, const DecodedMessage& view, std::size_t base,
                           std::uint64_t stamp, std::uint64_t index, const detail::ByteCursor& at) const {
    switch (rule) {
      case TimeRule::none:
        return stamp + static_cast<std::uint64_t>(std::llround(static_cast<double>(index) * 1e9 / *point_rate_));
      case TimeRule::absolute_ns: {
        if (f->type == Primitive::uint64) return view.load<std::uint64_t>(base + f->offset);
        const double v = view.real(f->type, base + f->offset);
        const double ns = v < 1e14 ? v * 1e9 : v;
        return checked_ns(ns, *f, base, at);
      }
      case TimeRule::offset_ns: return stamp + view.unsigned64(f->type, base + f->offset);
      case TimeRule::offset_s: {
        const double s = view.real(f->type, base + f->offset);
        if (!(std::fabs(s) < 1e9)) {
          at.fail_at(base + f->offset, "time field " + f->name + " = " + std::to_string(s) +
                                           " s after the header stamp: expected a finite offset");
        }
        const std::int64_t offset = std::llround(s * 1e9);
        if (offset < 0 && static_cast<std::uint64_t>(-offset) > stamp) {
          at.fail_at(base + f->offset, "time field " + f->name + " puts the point before 1970");
        }
        return offset < 0 ? stamp - static_cast<std::uint64_t>(-offset) : stamp + static_cast<std::uint64_t>(offset);
      }
    }
    return stamp;
  }

  /// Nanoseconds from a double, checked to lie in [1970, 2262].
  static std::uint64_t checked_ns(double ns, const CloudField& f, std::size_t base, const detail::ByteCursor& at) {
    if (!(ns >= 0 && ns < 9.2e18)) {
      at.fail_at(base + f.offset, "time field " + f.name + " gives " + std::to_string(ns) +
                                      " ns: expected a time between 1970 and 2262");
    }
    return static_cast<std::uint64_t>(std::llround(ns));
  }

  MessageDefinitions definitions_;
  MessageDecoder decoder_;
  std::optional<double> point_rate_;
  PointMessageKind kind_ = PointMessageKind::point_cloud2;
  DecodedMessage message_;
  std::vector<std::string> fields_;
  std::string time_field_;
};

}  // namespace streamclust::io::ros
