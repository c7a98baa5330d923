// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `cluster --mcap FILE`: every retrieval cycle as Foxglove shows it, in an
/// MCAP file (ROS 2 profile, CDR messages, zstd chunks), logged at the
/// cycle's stream time:
///
/// | topic | type | content |
/// |---|---|---|
/// | `/streamclust/points` | `foxglove_msgs/msg/PointCloud` | the window: x y z (float32), label (int32), red green blue alpha (uint8: the label's colour; ground brown, ceiling pale blue, unlabelled grey) |
/// | `/streamclust/clusters` | `foxglove_msgs/msg/SceneUpdate` | one box per component (its axis-aligned extent, the label's colour) with its id above it; each update replaces the last |
///
/// Frame id `streamclust` (the coordinates the clusterer used: the sensor's,
/// or the world's with --poses). Not thread-safe.

#include "cli/structure_labels.hpp"

#include <streamclust/io/foxglove_messages.hpp>
#include <streamclust/io/mcap_writer.hpp>
#include <streamclust/io/stream_time.hpp>
#include <streamclust/io/writers.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace streamclust::cli {

/// Writes the cycles of a run to an MCAP file (see the file comment).
class McapOutput {
 public:
  explicit McapOutput(const std::string& path) : mcap_(path, io::McapWriter::Options{}) {
    const auto cloud = mcap_.add_schema("foxglove_msgs/msg/PointCloud", "ros2msg",
                                        io::foxglove::ros2_definition("foxglove_msgs/PointCloud"));
    const auto scene = mcap_.add_schema("foxglove_msgs/msg/SceneUpdate", "ros2msg",
                                        io::foxglove::ros2_definition("foxglove_msgs/SceneUpdate"));
    points_ = mcap_.add_channel(cloud, "/streamclust/points", "cdr");
    clusters_ = mcap_.add_channel(scene, "/streamclust/clusters", "cdr");
  }

  /// The labelled window of one cycle (`labels` one per point, -1
  /// unlabelled, -2 ground, -3 ceiling), at stream time `time` [s] since `origin`.
  void write(const std::vector<io::Record>& points, const std::vector<std::int64_t>& labels, double time,
             io::TimeOrigin origin) {
    const std::uint64_t log_ns = nanoseconds(origin, time);
    const io::foxglove::Stamp stamp{static_cast<std::int32_t>(log_ns / 1000000000u),
                                    static_cast<std::uint32_t>(log_ns % 1000000000u)};
    data_.assign(points.size() * kStride, 0);
    std::map<std::int64_t, Extent> extents;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const io::Record& p = points[i];
      const std::int64_t label = i < labels.size() ? labels[i] : -1;
      const auto c = color_of(label);
      const std::int32_t label32 =
          static_cast<std::int32_t>(std::clamp<std::int64_t>(label, std::numeric_limits<std::int32_t>::min(),
                                                             std::numeric_limits<std::int32_t>::max()));
      std::uint8_t* d = data_.data() + i * kStride;
      std::memcpy(d, &p.x, 4);
      std::memcpy(d + 4, &p.y, 4);
      std::memcpy(d + 8, &p.z, 4);
      std::memcpy(d + 12, &label32, 4);
      d[16] = c[0];
      d[17] = c[1];
      d[18] = c[2];
      d[19] = 255;
      if (label >= 0 && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) extents[label].add(p);
    }
    static const std::vector<io::foxglove::PackedField> fields = {
        {"x", 0, io::foxglove::FieldType::float32},    {"y", 4, io::foxglove::FieldType::float32},
        {"z", 8, io::foxglove::FieldType::float32},    {"label", 12, io::foxglove::FieldType::int32},
        {"red", 16, io::foxglove::FieldType::uint8},   {"green", 17, io::foxglove::FieldType::uint8},
        {"blue", 18, io::foxglove::FieldType::uint8},  {"alpha", 19, io::foxglove::FieldType::uint8}};
    io::foxglove::write_point_cloud(cdr_, stamp, kFrame, kStride, fields, data_);
    mcap_.write(points_, log_ns, cdr_.bytes().data(), cdr_.bytes().size());

    boxes_.clear();
    for (const auto& [label, e] : extents) {
      io::foxglove::Box b;
      b.id = std::to_string(label);
      for (int k = 0; k < 3; ++k) {
        b.center[k] = 0.5 * (static_cast<double>(e.lo[k]) + static_cast<double>(e.hi[k]));
        b.size[k] = std::max(0.05, static_cast<double>(e.hi[k]) - static_cast<double>(e.lo[k]));  // [m]
      }
      const auto c = color_of(label);
      b.color = io::foxglove::Color{c[0] / 255.0, c[1] / 255.0, c[2] / 255.0, 0.35};
      b.metadata = {{"points", std::to_string(e.n)}};
      boxes_.push_back(std::move(b));
    }
    io::foxglove::write_scene_update(cdr_, stamp, kFrame, boxes_);
    mcap_.write(clusters_, log_ns, cdr_.bytes().data(), cdr_.bytes().size());
  }

  /// Writes the summary and closes the file; throws std::runtime_error naming it on failure.
  void close() { mcap_.close(); }

 private:
  static constexpr std::uint32_t kStride = 20;  // [bytes] x y z label r g b a
  static constexpr const char* kFrame = "streamclust";

  struct Extent {
    std::array<float, 3> lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::max()};
    std::array<float, 3> hi{-std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                            -std::numeric_limits<float>::max()};
    std::size_t n = 0;
    void add(const io::Record& p) {
      const float v[3] = {p.x, p.y, p.z};
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], v[k]);
        hi[k] = std::max(hi[k], v[k]);
      }
      ++n;
    }
  };

  /// Colour of a label: the writers' label colour; ground and ceiling apart.
  static std::array<std::uint8_t, 3> color_of(std::int64_t label) {
    if (label == kGroundLabel) return {140, 105, 70};
    if (label == kCeilingLabel) return {170, 190, 215};
    return io::label_color(label);
  }

  /// Absolute nanoseconds of stream time `t` [s] since `origin` (0 before 1970).
  static std::uint64_t nanoseconds(io::TimeOrigin origin, double t) {
    const double ns = static_cast<double>(origin.seconds) * 1e9 + std::nearbyint(t * 1e9);
    if (!(ns > 0)) return 0;
    if (!(ns < 9.2e18)) return std::numeric_limits<std::int64_t>::max();
    const std::int64_t relative = std::llround(t * 1e9);  // exact below 2^53 ns (104 days)
    return static_cast<std::uint64_t>(origin.seconds * 1000000000 + relative);
  }

  io::McapWriter mcap_;
  std::uint16_t points_ = 0, clusters_ = 0;
  io::CdrWriter cdr_;
  std::vector<std::uint8_t> data_;
  std::vector<io::foxglove::Box> boxes_;
};

}  // namespace streamclust::cli
