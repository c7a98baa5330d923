// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Poses from `nav_msgs/Odometry` messages (ROS 1 or CDR): the header's
/// stamp and `pose.pose` (position [m], orientation quaternion), the pose of
/// `child_frame_id` in `header.frame_id` (the odometry frame). Covariances
/// and the twist are not read. O(fields) per message; not thread-safe.

#include <streamclust/io/byte_cursor.hpp>
#include <streamclust/io/ros/message_decoder.hpp>
#include <streamclust/io/ros/message_definition.hpp>
#include <streamclust/io/time_decoder.hpp>
#include <streamclust/io/tum.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace streamclust::io::ros {

/// One odometry message's pose.
struct OdometryPose {
  std::uint64_t t_ns = 0;                   ///< header stamp [ns since 1970]
  double x = 0, y = 0, z = 0;               ///< position [m]
  double qx = 0, qy = 0, qz = 0, qw = 1;    ///< orientation (as sent; not normalised)
  std::string frame_id;                     ///< header.frame_id: the odometry frame
};

/// The pose as a TUM record (io/tum.hpp): its time from `time`'s origin,
/// shifted as the points' times are (integer nanoseconds, one division).
inline TumRecord tum_record(const OdometryPose& p, TimeDecoder& time) {
  TumRecord r;
  r.t = time.from_unsigned(p.t_ns);
  r.tx = p.x;
  r.ty = p.y;
  r.tz = p.z;
  r.qx = p.qx;
  r.qy = p.qy;
  r.qz = p.qz;
  r.qw = p.qw;
  return r;
}

/// True for "nav_msgs/Odometry" and "nav_msgs/msg/Odometry".
inline bool is_odometry_type(std::string_view type) {
  return MessageDefinitions::normalize(type) == "nav_msgs/Odometry";
}

class OdometryDecoder {
 public:
  /// Throws std::invalid_argument for a definition that does not parse.
  OdometryDecoder(std::string_view type, std::string_view definition, Encoding encoding)
      : definitions_(type, definition), decoder_(definitions_, encoding) {}

  /// The pose of the message in `payload`; throws InputError (through
  /// `origin`) for a message that does not decode, lacks a field or has a
  /// stamp out of range.
  OdometryPose decode(const std::uint8_t* payload, std::size_t size, const detail::BufferOrigin& origin) {
    decoder_.decode(payload, size, origin, message_);
    const detail::ByteCursor at(payload, size, origin);
    auto real = [&](std::string_view path) {
      const Leaf* l = message_.find(path);
      if (l == nullptr) at.fail_at(0, definitions_.main().name + " has no field " + std::string(path));
      return message_.real(l->primitive, l->offset);
    };
    auto integer = [&](std::string_view path) -> std::optional<std::int64_t> {
      const Leaf* l = message_.find(path);
      if (l == nullptr) return std::nullopt;
      return message_.integer(l->primitive, l->offset);
    };
    const auto sec = integer("header.stamp.sec");
    auto nsec = integer("header.stamp.nanosec");
    if (!nsec) nsec = integer("header.stamp.nsec");
    if (!sec || !nsec) at.fail_at(0, definitions_.main().name + " has no header stamp");
    if (*sec < 0 || *nsec < 0 || *nsec >= 1'000'000'000) {
      at.fail_at(0, "header stamp " + std::to_string(*sec) + " s " + std::to_string(*nsec) +
                        " ns: expected seconds >= 0 and nanoseconds in [0, 1e9)");
    }
    OdometryPose p;
    p.t_ns = static_cast<std::uint64_t>(*sec) * 1'000'000'000u + static_cast<std::uint64_t>(*nsec);
    p.x = real("pose.pose.position.x");
    p.y = real("pose.pose.position.y");
    p.z = real("pose.pose.position.z");
    p.qx = real("pose.pose.orientation.x");
    p.qy = real("pose.pose.orientation.y");
    p.qz = real("pose.pose.orientation.z");
    p.qw = real("pose.pose.orientation.w");
    if (const Leaf* f = message_.find("header.frame_id")) p.frame_id = f->text;
    return p;
  }

 private:
  MessageDefinitions definitions_;
  MessageDecoder decoder_;
  DecodedMessage message_;
};

}  // namespace streamclust::io::ros
