// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A recording's odometry as a trajectory: the `nav_msgs/Odometry` messages
/// of one topic of a ROS 1 bag, rosbag2 bag or MCAP file, as the TUM records
/// `--poses` takes (io/tum.hpp), times from the stream's time origin shifted
/// exactly as the points' are (TimeDecoder: integer nanoseconds, one
/// division). The topic: the one named, else the recording's only odometry
/// topic. O(messages); memory: one record per message.
///
///     auto poses = streamclust::io::read_odometry("run.mcap", origin);  // TumRecord per message

#include <streamclust/io/error.hpp>
#include <streamclust/io/reader.hpp>
#include <streamclust/io/recording_source.hpp>
#include <streamclust/io/ros/known_definitions.hpp>
#include <streamclust/io/ros/odometry.hpp>
#include <streamclust/io/ros2_messages.hpp>
#include <streamclust/io/time_decoder.hpp>
#include <streamclust/io/tum.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace streamclust::io {

/// True when `path` names a recording odometry can be read from (.mcap,
/// .db3, .bag, or a rosbag2 folder) rather than a TUM text file.
inline bool is_odometry_recording(const std::string& path) {
  if (std::filesystem::is_directory(path)) return true;
  const std::string ext = detail::lower(std::filesystem::path(path).extension().string());
  return ext == ".mcap" || ext == ".db3" || ext == ".bag";
}

/// The odometry of the recording at `path` (see the file comment). Throws
/// InputError naming the file and the topic or message: no or several
/// odometry topics (listed), a topic of another type, a message that does
/// not decode, or times not strictly increasing.
inline std::vector<TumRecord> read_odometry(const std::string& path, TimeOrigin origin,
                                            const std::optional<std::string>& wanted = std::nullopt) {
  auto source = detail::open_recording(path, detect_format(path));
  const std::vector<RecordingTopic>& topics = source->topics();
  std::vector<std::size_t> odometry;
  std::string all;
  for (std::size_t i = 0; i < topics.size(); ++i) {
    all += (all.empty() ? "" : ", ") + topics[i].name + " (" + (topics[i].type.empty() ? "no schema" : topics[i].type) + ")";
    if (ros::is_odometry_type(topics[i].type)) odometry.push_back(i);
  }
  std::size_t topic = 0;
  if (wanted) {
    bool found = false;
    for (std::size_t i = 0; i < topics.size() && !found; ++i) {
      if (topics[i].name != *wanted && topics[i].name != "/" + *wanted) continue;
      if (!ros::is_odometry_type(topics[i].type))
        throw InputError(path, "topic " + topics[i].name, "type " + topics[i].type + ": expected nav_msgs/Odometry");
      topic = i;
      found = true;
    }
    if (!found) throw InputError(path, "topics", "no topic " + *wanted + "; topics: " + (all.empty() ? "none" : all));
  } else if (odometry.size() != 1) {
    throw InputError(path, "topics",
                     std::string(odometry.empty() ? "no nav_msgs/Odometry topic" : "several nav_msgs/Odometry topics") +
                         "; topics: " + (all.empty() ? "none" : all) +
                         (odometry.empty() ? "" : "; choose one (--poses-topic NAME)"));
  } else {
    topic = odometry.front();
  }
  const RecordingTopic& t = topics[topic];
  const std::string where = "topic " + t.name;
  ros::Encoding encoding = ros::Encoding::cdr;
  if (t.message_encoding == "ros1") {
    encoding = ros::Encoding::ros1;
  } else if (t.message_encoding != "cdr") {
    throw InputError(path, where, "message encoding \"" + t.message_encoding + "\": expected cdr (ROS 2) or ros1");
  }
  // A ROS 2 recording without definitions (older rosbag2): the built-in one.
  const std::string definition = t.definition && !t.definition->empty()
                                     ? *t.definition
                                     : (encoding == ros::Encoding::cdr ? ros2msg::ros2_definition("nav_msgs/Odometry")
                                                                       : std::string());
  if (definition.empty())
    throw InputError(path, where, "the message definition of " + t.type + " is missing from the recording");
  std::optional<ros::OdometryDecoder> decoder;
  try {
    decoder.emplace(t.type, definition, encoding);
  } catch (const std::invalid_argument& e) {
    throw InputError(path, where, std::string("cannot use the message definition of ") + t.type + ": " + e.what());
  }
  TimeDecoder time(TimeUnit::ns, origin);
  std::vector<TumRecord> records;
  RecordingMessage m;
  std::uint64_t previous_ns = 0;
  while (source->next(m)) {
    if (m.topic != topic) continue;
    const ros::OdometryPose p = decoder->decode(m.data, m.size, m.origin);
    if (!records.empty() && p.t_ns <= previous_ns) {
      throw InputError(path, where + ", message " + std::to_string(records.size() + 1),
                       "stamp " + std::to_string(p.t_ns) + " ns: expected a time later than the previous message's " +
                           std::to_string(previous_ns) + " ns");
    }
    previous_ns = p.t_ns;
    records.push_back(ros::tum_record(p, time));
  }
  if (records.empty()) throw InputError(path, where, "no message: expected the sensor's poses");
  return records;
}

}  // namespace streamclust::io
