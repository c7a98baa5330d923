// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust info`: format, fields, point count, bounds and time span of
/// any readable input, read in one streaming pass (a recording: its topics
/// with types and message counts, then each point-cloud topic; an LVX file:
/// its LiDARs, then each LiDAR); an input without a time
/// field is described too (its records get times only from --point-rate),
/// and so is one with a header and no points ("points: 0", exit 0; cluster
/// exits 4 on it). Running out of memory: OutOfMemory (memory_context.hpp).

#include "cli/memory_context.hpp"
#include "cli/options.hpp"

#include <streamclust/io/reader.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace streamclust::cli {

/// Prints what `reader` holds: fields, points, time span, bounds (one pass).
inline void describe_points(io::PointReader& reader, const InfoOptions& o, std::ostream& out) {
  const io::InputInfo& info = reader.info();
  std::uint64_t count = 0, finite = 0;
  double t0 = std::numeric_limits<double>::infinity(), t1 = -t0;
  float lo[3] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                 std::numeric_limits<float>::infinity()};
  float hi[3] = {-lo[0], -lo[1], -lo[2]};
  std::vector<io::Record> chunk;
  for (;;) {
    chunk.clear();
    if (reader.read(chunk, 65536) == 0) break;
    for (const io::Record& r : chunk) {
      ++count;
      if (std::isfinite(r.t)) {
        t0 = std::min(t0, r.t);
        t1 = std::max(t1, r.t);
      }
      const float p[3] = {r.x, r.y, r.z};
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
      ++finite;
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    }
  }
  out << "fields:   ";
  for (const auto& f : info.fields) out << " " << f;
  out << "\n";
  out << "points:    " << count << " (" << finite << " with finite coordinates)";
  if (info.declared_points) out << ", header declares " << *info.declared_points;
  out << "\n";
  if (info.has_time) {
    out << "time:      field '" << info.time_field << "'";
  } else if (o.read.point_rate) {
    out << "time:      no time field; t = index / " << *o.read.point_rate << " Hz (--point-rate)";
  } else {
    out << "time:      no time field (cluster needs --point-rate)";
  }
  if ((info.has_time || o.read.point_rate) && count > 0 && t1 >= t0) {
    const io::TimeOrigin origin = reader.time_origin();
    out << ", " << io::format_time(origin, t0) << " s to " << io::format_time(origin, t1) << " s (span " << t1 - t0
        << " s)";
  }
  out << "\n";
  if (finite > 0) {
    out << "bounds:    x [" << lo[0] << ", " << hi[0] << "] y [" << lo[1] << ", " << hi[1] << "] z [" << lo[2] << ", "
        << hi[2] << "] m\n";
  }
}

/// Describes the stream of each of `names` (topics or LiDARs: ReadOptions::topic)
/// under a line "KIND NAME:".
inline void describe_each(const InfoOptions& o, const std::vector<std::string>& names, const char* kind,
                          std::ostream& out) {
  for (const std::string& name : names) {
    io::ReadOptions one = o.read;
    one.topic = name;
    auto reader = io::open_reader(o.input, one);
    out << kind << " " << name << ":\n";
    describe_points(*reader, o, out);
  }
}

/// A recording: its topics (type, messages), then each point-cloud topic
/// (or the one --topic names) described as a point stream.
inline int describe_recording(const InfoOptions& o, io::Format format, std::ostream& out) {
  const auto source = io::detail::open_recording(o.input, format);
  const std::vector<io::RecordingTopic>& topics = source->topics();
  out << "file:      " << o.input << "\n";
  out << "format:    " << io::to_string(format) << "\n";
  out << "topics:    " << topics.size() << "\n";
  std::vector<std::string> clouds;
  for (const io::RecordingTopic& t : topics) {
    out << "  " << t.name << "  " << (t.type.empty() ? "(no schema)" : t.type) << "  "
        << (t.messages ? std::to_string(*t.messages) : std::string("?")) << " messages\n";
    if (io::ros::point_message_kind(t.type)) clouds.push_back(t.name);
  }
  describe_each(o, o.read.topic ? std::vector<std::string>{*o.read.topic} : clouds, "topic", out);
  return kOk;
}

/// An LVX file: its LiDARs (type, serial, packages, points), then each LiDAR
/// (or the one --topic names) described as a point stream.
inline int describe_lvx(const InfoOptions& o, std::ostream& out) {
  const io::LvxSummary summary = io::summarize_lvx(o.input);
  out << "file:      " << o.input << "\n";
  out << "format:    lvx (" << summary.encoding << "), " << summary.frames << " frames\n";
  out << "lidars:    " << summary.devices.size() << "\n";
  for (const io::LvxDeviceSummary& d : summary.devices) {
    out << "  index " << d.device.index << "  " << d.device.type_name << "  serial \""
        << io::detail::printable(d.device.serial) << "\"  " << d.point_packages << " packages, " << d.points
        << " points\n";
  }
  std::vector<std::string> lidars;
  for (const io::LvxDeviceSummary& d : summary.devices) lidars.push_back(std::to_string(d.device.index));
  describe_each(o, o.read.topic ? std::vector<std::string>{*o.read.topic} : lidars, "lidar", out);
  return kOk;
}

inline int run_info_reading(const InfoOptions& o, std::ostream& out) {
  // The readers need a point rate to open an input without a time field;
  // without --point-rate, any rate does: no time is reported then.
  io::ReadOptions read = o.read;
  if (!read.point_rate) read.point_rate = 1.0;
  const io::Format format = read.format ? *read.format : io::detect_format(o.input);
  if (format == io::Format::ros1_bag || format == io::Format::rosbag2_sqlite || format == io::Format::mcap) {
    return describe_recording(o, format, out);  // messages carry times; no rate forced
  }
  if (format == io::Format::lvx) return describe_lvx(o, out);
  auto reader = io::open_reader(o.input, read);
  const io::InputInfo& info = reader->info();
  out << "file:      " << o.input << "\n";
  out << "format:    " << io::to_string(info.format) << (info.encoding.empty() ? "" : " (" + info.encoding + ")") << "\n";
  describe_points(*reader, o, out);
  return kOk;
}

inline int run_info(const InfoOptions& o, std::ostream& out) {
  return with_memory_context("info", o.input, [&](Stage&) { return run_info_reading(o, out); });
}

}  // namespace streamclust::cli
