// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// What `streamclust ros2` publishes each retrieval, stamped with the
/// cycle's stream time in the input's frame, under the output namespace:
///
/// | topic | type | content |
/// |---|---|---|
/// | `NS/points` | `sensor_msgs/msg/PointCloud2` | the window: x y z intensity (float32), label (int32: component >= 0, -1 unlabelled, -2 ground, -3 ceiling), class (uint8: 0 unlabelled, 1 object, 2 ground, 3 ceiling) |
/// | `NS/clusters` | `visualization_msgs/msg/MarkerArray` | a DELETEALL, then per component a cube (its axis-aligned box, the label's colour) and its id above it |
/// | `NS/detections` | `vision_msgs/msg/Detection3DArray` | per component its box, class "object", score 1, id = the label |
/// | `NS/tracks` | `visualization_msgs/msg/MarkerArray` | with `--tracks`: a DELETEALL, then per confirmed or coasting track its oriented box (the id's colour), "ID S.S m/s" above it and, while it moves, an arrow of its velocity (1 s of travel; namespace `streamclust_tracks_velocity`) |
/// | `NS/tracked_objects` | `vision_msgs/msg/Detection3DArray` | with `--tracks`: per confirmed or coasting track its oriented box, class "moving" or "static", score 1 (confirmed) or 0.5 (coasting), id = the track id |
///
/// When the engine places points by a mount (given, estimated from the
/// first window or from the IMU), the window is in a level frame
/// (`--level-frame`), linked to the input's by a static transform on
/// /tf_static. Every message is published reliably with a history of `depth`, and
/// written to the --record-out MCAP with the payload sent and its type's
/// definition. Not thread-safe: the engine thread owns it.

#include "cli/cluster_boxes.hpp"
#include "cli/structure_labels.hpp"
#include "cli/track_display.hpp"

#include <streamclust/io/cdr_writer.hpp>
#include <streamclust/io/mcap_writer.hpp>
#include <streamclust/io/record.hpp>
#include <streamclust/io/ros2_messages.hpp>
#include <streamclust/ros2/cdr_publisher.hpp>
#include <streamclust/ros2/ros2_names.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace streamclust::cli {

class Ros2Outputs {
 public:
  struct Topic {
    const char* name;      ///< relative to the namespace
    const char* type;      ///< ROS 2 type (pkg/msg/Type)
    const char* msg_type;  ///< its definition's key in io::ros2msg (pkg/Type)
  };
  static constexpr Topic kPoints{"points", "sensor_msgs/msg/PointCloud2", "sensor_msgs/PointCloud2"};
  static constexpr Topic kClusters{"clusters", "visualization_msgs/msg/MarkerArray", "visualization_msgs/MarkerArray"};
  static constexpr Topic kDetections{"detections", "vision_msgs/msg/Detection3DArray", "vision_msgs/Detection3DArray"};
  static constexpr Topic kTracks{"tracks", "visualization_msgs/msg/MarkerArray", "visualization_msgs/MarkerArray"};
  static constexpr Topic kTrackedObjects{"tracked_objects", "vision_msgs/msg/Detection3DArray",
                                         "vision_msgs/Detection3DArray"};

  /// Publishers under namespace `ns` (with `tracks`, the track topics too);
  /// `record_out` (empty: none) an MCAP file of what is published. Throws
  /// ros2::DdsError, std::invalid_argument (a bad namespace),
  /// std::runtime_error (the file).
  Ros2Outputs(const ros2::DdsParticipant& participant, const std::string& ns, std::int32_t depth,
              const std::string& record_out, bool tracks = false) {
    std::vector<const Topic*> topics{&kPoints, &kClusters, &kDetections};
    if (tracks) topics.insert(topics.end(), {&kTracks, &kTrackedObjects});
    for (const Topic* t : topics) {
      Output o;
      o.topic = ros2::resolve_topic(t->name, ns);
      o.publisher = std::make_unique<ros2::CdrPublisher>(participant, ros2::dds_topic_name(o.topic),
                                                         ros2::dds_type_name(t->type), ros2::default_qos(depth));
      outputs_.push_back(std::move(o));
    }
    if (!record_out.empty()) {
      mcap_.emplace(record_out, io::McapWriter::Options{});
      for (std::size_t i = 0; i < outputs_.size(); ++i) {
        const auto schema = mcap_->add_schema(topics[i]->type, "ros2msg", io::ros2msg::ros2_definition(topics[i]->msg_type));
        outputs_[i].channel = mcap_->add_channel(schema, outputs_[i].topic, "cdr");
      }
    }
  }

  /// Publishes the labelled window of a cycle at `stamp_ns` [ns since
  /// 1970] in `frame_id`. O(n log components).
  void publish(std::uint64_t stamp_ns, const std::string& frame_id, const std::vector<io::Record>& points,
               const std::vector<std::int64_t>& labels) {
    const io::ros2msg::Header h = header_of(stamp_ns, frame_id);

    // The window.
    data_.assign(points.size() * kStride, 0);
    bool dense = true;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const io::Record& p = points[i];
      const std::int64_t label = i < labels.size() ? labels[i] : -1;
      const auto label32 = static_cast<std::int32_t>(std::clamp<std::int64_t>(
          label, std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max()));
      const float v[4] = {p.x, p.y, p.z, p.intensity};
      std::uint8_t* d = data_.data() + i * kStride;
      std::memcpy(d, v, 16);
      std::memcpy(d + 16, &label32, 4);
      d[20] = label >= 0 ? 1 : label == kGroundLabel ? 2 : label == kCeilingLabel ? 3 : label == kWallLabel ? 4 : 0;
      dense = dense && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    }
    using F = io::ros2msg::PointField;
    static const std::vector<F> fields = {{"x", 0, F::FLOAT32, 1},         {"y", 4, F::FLOAT32, 1},
                                          {"z", 8, F::FLOAT32, 1},         {"intensity", 12, F::FLOAT32, 1},
                                          {"label", 16, F::INT32, 1},      {"class", 20, F::UINT8, 1}};
    io::ros2msg::write_point_cloud2(cdr_, h, static_cast<std::uint32_t>(points.size()), fields, kStride,
                                    data_.data(), data_.size(), dense);
    send(0, stamp_ns);

    // The components' boxes, as markers and as detections.
    cluster_boxes(points, labels, boxes_);
    markers_.clear();
    detections_.clear();
    for (const ClusterBox& b : boxes_) {
      io::ros2msg::BoxMarker m;
      m.id = static_cast<std::int32_t>(b.label % (std::int64_t{1} << 30));
      m.center = b.center;
      m.size = b.size;
      const auto c = label_display_color(b.label);
      m.rgba = {static_cast<float>(c[0]) / 255.0f, static_cast<float>(c[1]) / 255.0f,
                static_cast<float>(c[2]) / 255.0f, 0.35f};
      m.text = std::to_string(b.label);
      markers_.push_back(std::move(m));
      io::ros2msg::Detection d;
      d.id = std::to_string(b.label);
      d.center = b.center;
      d.size = b.size;
      detections_.push_back(std::move(d));
    }
    io::ros2msg::write_marker_array(cdr_, h, "streamclust", markers_);
    send(1, stamp_ns);
    io::ros2msg::write_detection3d_array(cdr_, h, detections_);
    send(2, stamp_ns);
  }

  /// With the track topics: publishes the confirmed and coasting `tracks`
  /// of a cycle at `stamp_ns` [ns since 1970] in `frame_id`. O(tracks).
  void publish_tracks(std::uint64_t stamp_ns, const std::string& frame_id, const std::vector<tracking::Track>& tracks) {
    if (outputs_.size() < 5) return;
    const io::ros2msg::Header h = header_of(stamp_ns, frame_id);
    markers_.clear();
    detections_.clear();
    for (const tracking::Track& t : tracks) {
      if (!shown_track(t)) continue;
      const TrackDisplay d = track_display(t);
      io::ros2msg::BoxMarker m;
      m.id = static_cast<std::int32_t>(t.id % (std::uint64_t{1} << 30));
      m.center = {t.position.x(), t.position.y(), t.position.z()};
      m.size = {t.length, t.width, t.height};
      m.yaw = t.yaw;
      m.rgba = {static_cast<float>(d.rgba[0]), static_cast<float>(d.rgba[1]), static_cast<float>(d.rgba[2]),
                static_cast<float>(d.rgba[3])};
      m.text = d.text;
      m.arrow_length = d.arrow_length;
      m.arrow_yaw = d.arrow_yaw;
      io::ros2msg::Detection o;
      o.id = std::to_string(t.id);
      o.class_id = t.moving ? "moving" : "static";
      o.score = t.state == tracking::TrackState::confirmed ? 1.0 : 0.5;
      o.center = m.center;
      o.size = m.size;
      o.yaw = t.yaw;
      markers_.push_back(std::move(m));
      detections_.push_back(std::move(o));
    }
    io::ros2msg::write_marker_array(cdr_, h, "streamclust_tracks", markers_);
    send(3, stamp_ns);
    io::ros2msg::write_detection3d_array(cdr_, h, detections_);
    send(4, stamp_ns);
  }

  /// Publishes, once, the static transform from `t.parent` (the frame the
  /// outputs are in) to `t.child` (the input's) on /tf_static (reliable,
  /// transient local, keep last 1, as tf2's static broadcaster), so that
  /// viewers place the outputs and the driver's cloud together.
  void publish_static_transform(const io::ros2msg::Transform& t, std::uint64_t stamp_ns,
                                const ros2::DdsParticipant& participant) {
    if (!tf_static_) {
      tf_static_.topic = "/tf_static";
      tf_static_.publisher = std::make_unique<ros2::CdrPublisher>(
          participant, ros2::dds_topic_name("/tf_static"), ros2::dds_type_name("tf2_msgs/msg/TFMessage"),
          ros2::TopicQos{ros2::Reliability::reliable, ros2::Durability::transient_local, 1});
      if (mcap_) {
        const auto schema = mcap_->add_schema("tf2_msgs/msg/TFMessage", "ros2msg",
                                              io::ros2msg::ros2_definition("tf2_msgs/TFMessage"));
        tf_static_.channel = mcap_->add_channel(schema, "/tf_static", "cdr");
      }
    }
    io::ros2msg::write_tf_message(cdr_, header_of(stamp_ns, t.parent), {t});
    tf_static_.publisher->publish(cdr_.bytes());
    if (mcap_) mcap_->write(tf_static_.channel, stamp_ns, cdr_.bytes().data(), cdr_.bytes().size());
  }

  /// Closes the --record-out file (throws std::runtime_error when it cannot be completed).
  void close() {
    if (mcap_) mcap_->close();
  }

  /// The fully qualified output topics, and their publishers' counters.
  std::size_t size() const { return outputs_.size(); }
  const std::string& topic(std::size_t i) const { return outputs_[i].topic; }
  ros2::PublicationCounters counters(std::size_t i) const { return outputs_[i].publisher->counters(); }

 private:
  static constexpr std::uint32_t kStride = 21;  // [bytes] x y z intensity label class

  struct Output {
    std::string topic;
    std::unique_ptr<ros2::CdrPublisher> publisher;
    std::uint16_t channel = 0;
    explicit operator bool() const { return publisher != nullptr; }
  };

  static io::ros2msg::Header header_of(std::uint64_t stamp_ns, const std::string& frame_id) {
    io::ros2msg::Header h;
    h.sec = static_cast<std::int32_t>(stamp_ns / 1'000'000'000u);
    h.nanosec = static_cast<std::uint32_t>(stamp_ns % 1'000'000'000u);
    h.frame_id = frame_id;
    return h;
  }

  void send(std::size_t i, std::uint64_t stamp_ns) {
    outputs_[i].publisher->publish(cdr_.bytes());
    if (mcap_) mcap_->write(outputs_[i].channel, stamp_ns, cdr_.bytes().data(), cdr_.bytes().size());
  }

  std::vector<Output> outputs_;
  Output tf_static_;
  std::optional<io::McapWriter> mcap_;
  io::CdrWriter cdr_;
  std::vector<std::uint8_t> data_;
  std::vector<ClusterBox> boxes_;
  std::vector<io::ros2msg::BoxMarker> markers_;
  std::vector<io::ros2msg::Detection> detections_;
};

}  // namespace streamclust::cli
