// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Points from a recording: one point-cloud topic of a RecordingSource (ROS 1
/// bag, rosbag2 SQLite, MCAP) read as a PointReader, message after message.
///
/// Topic choice works as in the tools users know: the topic named by
/// `ReadOptions::topic`; else the only topic of a point-cloud type
/// (point_messages.hpp); with several, the error lists them. Other topics
/// (IMU, images) are skipped.

#include <streamclust/io/error.hpp>
#include <streamclust/io/point_reader.hpp>
#include <streamclust/io/recording_source.hpp>
#include <streamclust/io/ros/point_messages.hpp>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::io {

/// The index of the topic `source` reads points from (see the file comment).
/// Throws InputError(path, "topics", ...) listing the candidates when the
/// choice is missing or wrong. O(topics).
inline std::size_t choose_point_topic(RecordingSource& source, const std::optional<std::string>& wanted) {
  const std::vector<RecordingTopic>& topics = source.topics();
  std::vector<std::size_t> clouds;
  for (std::size_t i = 0; i < topics.size(); ++i)
    if (ros::point_message_kind(topics[i].type)) clouds.push_back(i);
  const auto describe = [&](const std::vector<std::size_t>& which) {
    std::string s;
    for (const std::size_t i : which) {
      s += (s.empty() ? "" : ", ") + topics[i].name + " (" + (topics[i].type.empty() ? "no schema" : topics[i].type);
      if (topics[i].messages) s += ", " + std::to_string(*topics[i].messages) + (*topics[i].messages == 1 ? " message" : " messages");
      s += ")";
    }
    return s.empty() ? std::string("none") : s;
  };
  std::vector<std::size_t> all(topics.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  if (wanted) {
    for (std::size_t i = 0; i < topics.size(); ++i) {
      if (topics[i].name != *wanted && topics[i].name != "/" + *wanted) continue;
      if (topics[i].type.empty()) {
        throw InputError(source.path(), "topic " + topics[i].name,
                         "the recording has no schema for this topic: its message type and definition are missing");
      }
      if (!ros::point_message_kind(topics[i].type)) {
        throw InputError(source.path(), "topics",
                         "topic " + topics[i].name + " has type " + (topics[i].type.empty() ? "(no schema)" : topics[i].type) +
                             ", which holds no points: expected sensor_msgs/PointCloud2 or a Livox CustomMsg; "
                             "point-cloud topics: " + describe(clouds));
      }
      return i;
    }
    throw InputError(source.path(), "topics", "no topic " + *wanted + "; topics: " + describe(all));
  }
  if (clouds.size() == 1) return clouds.front();
  if (clouds.empty()) {
    std::vector<std::size_t> schemaless;
    for (std::size_t i = 0; i < topics.size(); ++i)
      if (topics[i].type.empty()) schemaless.push_back(i);
    throw InputError(source.path(), "topics",
                     "no point-cloud topic (sensor_msgs/PointCloud2 or a Livox CustomMsg); topics: " + describe(all) +
                         (schemaless.empty() ? std::string()
                                             : "; without a schema (message type and definition missing): " +
                                                   describe(schemaless)));
  }
  throw InputError(source.path(), "topics",
                   std::to_string(clouds.size()) + " point-cloud topics: " + describe(clouds) + "; choose one (--topic NAME)");
}

/// Reads the points of one topic of a recording. Memory: one message's points.
/// Not thread-safe.
///
///     auto reader = streamclust::io::open_reader("run.bag", {});  // picks RecordingReader
///     std::vector<streamclust::io::Record> chunk;
///     while (chunk.clear(), reader->read(chunk, 4096) > 0) { /* ... */ }
class RecordingReader final : public PointReader {
 public:
  /// Chooses the topic, checks that it can be decoded (a definition in a
  /// known encoding), and reads up to its first message so that info()
  /// knows the fields. Throws InputError.
  RecordingReader(std::unique_ptr<RecordingSource> source, Format format, const ReadOptions& options)
      : PointReader(source->path()), source_(std::move(source)) {
    topic_ = choose_point_topic(*source_, options.topic);
    const RecordingTopic& t = source_->topics()[topic_];
    const std::string where = "topic " + t.name;
    ros::Encoding encoding = ros::Encoding::cdr;
    if (t.message_encoding == "ros1") {
      encoding = ros::Encoding::ros1;
    } else if (t.message_encoding != "cdr") {
      throw InputError(path_, where, "message encoding \"" + t.message_encoding + "\": expected cdr (ROS 2) or ros1");
    }
    if (!t.definition || t.definition->empty()) {
      throw InputError(path_, where, "the message definition of " + (t.type.empty() ? std::string("its type") : t.type) +
                                         " is missing from the recording: expected it to decode the messages");
    }
    if (t.definition_encoding != "ros1msg" && t.definition_encoding != "ros2msg") {
      throw InputError(path_, where, "message definition encoding \"" + t.definition_encoding +
                                         "\": expected ros1msg or ros2msg");
    }
    try {
      decoder_.emplace(t.type, *t.definition, encoding, options.point_rate);
    } catch (const std::invalid_argument& e) {
      throw InputError(path_, where, std::string("cannot use the message definition of ") + t.type + ": " + e.what());
    }
    info_.format = format;
    info_.encoding = t.message_encoding;
    info_.has_time = true;
    info_.has_intensity = true;
    info_.time_unit = TimeUnit::ns;
    ReadOptions timing = options;
    timing.time_unit = TimeUnit::ns;  // messages give absolute nanoseconds
    setup_time(timing, TimeUnit::ns);
    fill();  // the first message: fields and time field
    info_.fields = decoder_->fields();
    info_.time_field = decoder_->time_field().empty() ? std::string("header.stamp") : decoder_->time_field();
    info_.has_label = has_label_;
  }

  /// The topic read.
  const RecordingTopic& topic() const { return source_->topics()[topic_]; }
  /// Messages of the topic decoded so far.
  std::uint64_t messages_read() const noexcept { return messages_; }

  std::size_t read(std::vector<Record>& out, std::size_t max_records) override {
    std::size_t n = 0;
    while (n < max_records) {
      if (next_ == pending_.size() && !fill()) break;
      const std::size_t take = std::min(max_records - n, pending_.size() - next_);
      for (std::size_t k = 0; k < take; ++k) {
        const ros::TimedPoint& p = pending_[next_ + k];
        Record r;
        r.x = p.x;
        r.y = p.y;
        r.z = p.z;
        r.intensity = p.intensity;
        r.label = p.label;
        r.t = next_time_unsigned(p.t_ns);
        out.push_back(r);
      }
      next_ += take;
      n += take;
    }
    return n;
  }

 private:
  /// Decodes the next message of the topic into pending_; false at the end.
  bool fill() {
    pending_.clear();
    next_ = 0;
    RecordingMessage m;
    while (source_->next(m)) {
      if (m.topic != topic_) continue;
      ++messages_;
      decoder_->decode(m.data, m.size, m.origin, pending_);
      for (const std::string& f : decoder_->fields()) has_label_ = has_label_ || f == "label";
      if (!pending_.empty()) return true;
    }
    return false;
  }

  std::unique_ptr<RecordingSource> source_;
  std::size_t topic_ = 0;
  std::optional<ros::PointMessageDecoder> decoder_;
  std::vector<ros::TimedPoint> pending_;
  std::size_t next_ = 0;
  std::uint64_t messages_ = 0;
  bool has_label_ = false;
};

}  // namespace streamclust::io
