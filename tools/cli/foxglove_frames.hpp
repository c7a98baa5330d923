// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Foxglove messages of one retrieval cycle, as CDR payloads (ROS 2
/// `foxglove_msgs`, each with its 4-byte encapsulation header), for every output
/// that shows cycles in Foxglove: `cluster --mcap` (cli/mcap_output.hpp) and
/// the live view's WebSocket server. The topics and types:
///
/// | topic | type | content |
/// |---|---|---|
/// | `/streamclust/points` | `foxglove_msgs/msg/PointCloud` | the window: x y z (float32), label (int32), red green blue alpha (uint8: the label's colour; ground brown, ceiling pale blue, unlabelled grey) |
/// | `/streamclust/clusters` | `foxglove_msgs/msg/SceneUpdate` | one box per component (its axis-aligned extent, the label's colour) with its id above it; each update replaces the last |
/// | `/streamclust/raw` | `foxglove_msgs/msg/PointCloud` | points as received: x y z intensity (float32) |
/// | `/streamclust/tracks` | `foxglove_msgs/msg/SceneUpdate` | one oriented box per confirmed or coasting track (`--tracks`), its id and speed above it, an arrow of its velocity (1 s of travel) while it moves; each update replaces the last |
///
/// Frame id `streamclust`. Not thread-safe; reuses its buffers (no allocation
/// in steady state once they have grown).

#include "cli/cluster_boxes.hpp"
#include "cli/track_display.hpp"

#include <streamclust/io/foxglove_messages.hpp>
#include <streamclust/io/stream_time.hpp>
#include <streamclust/io/writers.hpp>
#include <streamclust/tracking/track.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace streamclust::cli {

/// Builds the CDR payloads of a cycle (see the file comment).
class FoxgloveFrames {
 public:
  static constexpr const char* kPointsTopic = "/streamclust/points";
  static constexpr const char* kClustersTopic = "/streamclust/clusters";
  static constexpr const char* kRawTopic = "/streamclust/raw";
  static constexpr const char* kTracksTopic = "/streamclust/tracks";
  static constexpr const char* kPointCloudType = "foxglove_msgs/PointCloud";  // io::foxglove::ros2_definition key
  static constexpr const char* kSceneUpdateType = "foxglove_msgs/SceneUpdate";
  static constexpr const char* kPointCloudSchema = "foxglove_msgs/msg/PointCloud";  // schema name
  static constexpr const char* kSceneUpdateSchema = "foxglove_msgs/msg/SceneUpdate";

  /// Builds point_cloud() and scene_update() of the labelled window `points`
  /// (`labels` one per point, -1 unlabelled, -2 ground, -3 ceiling), stamped
  /// `log_ns` [ns since 1970]. O(n log clusters).
  void build(const std::vector<io::Record>& points, const std::vector<std::int64_t>& labels, std::uint64_t log_ns) {
    const io::foxglove::Stamp stamp = stamp_of(log_ns);
    data_.assign(points.size() * kStride, 0);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const io::Record& p = points[i];
      const std::int64_t label = i < labels.size() ? labels[i] : -1;
      const auto c = label_display_color(label);
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
    }
    static const std::vector<io::foxglove::PackedField> fields = {
        {"x", 0, io::foxglove::FieldType::float32},    {"y", 4, io::foxglove::FieldType::float32},
        {"z", 8, io::foxglove::FieldType::float32},    {"label", 12, io::foxglove::FieldType::int32},
        {"red", 16, io::foxglove::FieldType::uint8},   {"green", 17, io::foxglove::FieldType::uint8},
        {"blue", 18, io::foxglove::FieldType::uint8},  {"alpha", 19, io::foxglove::FieldType::uint8}};
    io::foxglove::write_point_cloud(cloud_, stamp, kFrame, kStride, fields, data_);

    cluster_boxes(points, labels, extents_);
    boxes_.clear();
    for (const ClusterBox& e : extents_) {
      io::foxglove::Box b;
      b.id = std::to_string(e.label);
      b.center = e.center;
      b.size = e.size;
      const auto c = label_display_color(e.label);
      b.color = io::foxglove::Color{c[0] / 255.0, c[1] / 255.0, c[2] / 255.0, 0.35};
      b.metadata = {{"points", std::to_string(e.points)}};
      boxes_.push_back(std::move(b));
    }
    io::foxglove::write_scene_update(scene_, stamp, kFrame, boxes_);
  }

  /// Builds tracks_update(): the confirmed and coasting `tracks` (tentative
  /// ones are left out), stamped `log_ns`. O(tracks).
  void build_tracks(const std::vector<tracking::Track>& tracks, std::uint64_t log_ns) {
    track_boxes_.clear();
    for (const tracking::Track& t : tracks) {
      if (!shown_track(t)) continue;
      const TrackDisplay d = track_display(t);
      io::foxglove::Box b;
      b.id = "track " + std::to_string(t.id);
      b.center = {t.position.x(), t.position.y(), t.position.z()};
      b.size = {t.length, t.width, t.height};
      b.yaw = t.yaw;
      b.color = io::foxglove::Color{d.rgba[0], d.rgba[1], d.rgba[2], d.rgba[3]};
      b.text = d.text;
      b.arrow_length = d.arrow_length;
      b.arrow_yaw = d.arrow_yaw;
      b.metadata = {{"state", tracking::to_string(t.state)},
                    {"cluster", t.cluster_id == kNoComponent ? std::string("-1") : std::to_string(t.cluster_id)},
                    {"points", std::to_string(t.points)}};
      track_boxes_.push_back(std::move(b));
    }
    io::foxglove::write_scene_update(tracks_, stamp_of(log_ns), kFrame, track_boxes_);
  }
  /// The last build_tracks()'s `foxglove_msgs/msg/SceneUpdate`.
  const std::vector<std::uint8_t>& tracks_update() const { return tracks_.bytes(); }

  /// Builds raw_cloud(): `points` as received (x y z intensity), stamped `log_ns`. O(n).
  void build_raw(const std::vector<io::Record>& points, std::uint64_t log_ns) {
    data_.assign(points.size() * kRawStride, 0);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const float v[4] = {points[i].x, points[i].y, points[i].z, points[i].intensity};
      std::memcpy(data_.data() + i * kRawStride, v, kRawStride);
    }
    static const std::vector<io::foxglove::PackedField> fields = {
        {"x", 0, io::foxglove::FieldType::float32},
        {"y", 4, io::foxglove::FieldType::float32},
        {"z", 8, io::foxglove::FieldType::float32},
        {"intensity", 12, io::foxglove::FieldType::float32}};
    io::foxglove::write_point_cloud(raw_, stamp_of(log_ns), kFrame, kRawStride, fields, data_);
  }

  /// The last build()'s `foxglove_msgs/msg/PointCloud` of the labelled window.
  const std::vector<std::uint8_t>& point_cloud() const { return cloud_.bytes(); }
  /// The last build()'s `foxglove_msgs/msg/SceneUpdate` of the cluster boxes.
  const std::vector<std::uint8_t>& scene_update() const { return scene_.bytes(); }
  /// The last build_raw()'s `foxglove_msgs/msg/PointCloud` of the raw points.
  const std::vector<std::uint8_t>& raw_cloud() const { return raw_.bytes(); }

  /// Absolute nanoseconds of stream time `t` [s] since `origin` (0 before 1970).
  static std::uint64_t nanoseconds(io::TimeOrigin origin, double t) {
    const double ns = static_cast<double>(origin.seconds) * 1e9 + std::nearbyint(t * 1e9);
    if (!(ns > 0)) return 0;
    if (!(ns < 9.2e18)) return std::numeric_limits<std::int64_t>::max();
    const std::int64_t relative = std::llround(t * 1e9);  // exact below 2^53 ns (104 days)
    return static_cast<std::uint64_t>(origin.seconds * 1000000000 + relative);
  }

 private:
  static constexpr std::uint32_t kStride = 20;     // [bytes] x y z label r g b a
  static constexpr std::uint32_t kRawStride = 16;  // [bytes] x y z intensity
  static constexpr const char* kFrame = "streamclust";

  static io::foxglove::Stamp stamp_of(std::uint64_t log_ns) {
    return {static_cast<std::int32_t>(log_ns / 1000000000u), static_cast<std::uint32_t>(log_ns % 1000000000u)};
  }

  io::CdrWriter cloud_, scene_, raw_, tracks_;
  std::vector<std::uint8_t> data_;
  std::vector<io::foxglove::Box> boxes_, track_boxes_;
  std::vector<ClusterBox> extents_;
};

}  // namespace streamclust::cli
