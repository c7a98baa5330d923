// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The interface every recording container implements (ROS 1 bag, rosbag2
/// SQLite, MCAP): its topics with their types and definitions, and its
/// messages one at a time in file order.

#include <streamclust/io/byte_cursor.hpp>

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace streamclust::io {

/// A topic (a bag connection, an MCAP channel, a rosbag2 topic).
struct RecordingTopic {
  std::string name;        ///< "/livox/lidar"
  std::string type;        ///< "livox_ros_driver2/CustomMsg" or "sensor_msgs/msg/PointCloud2"
  /// How messages are serialized, as the recording names it ("ros1", "cdr",
  /// or another encoding this library does not decode).
  std::string message_encoding;
  /// The message definition text; nothing when the recording has none for it.
  std::optional<std::string> definition;
  /// How the definition is written ("ros1msg", "ros2msg"; MCAP may say "ros2idl", ...).
  std::string definition_encoding;
  /// Messages on the topic, when the container says (index, statistics) or a
  /// scan counted them.
  std::optional<std::uint64_t> messages;
};

/// One message, valid until the next call of RecordingSource::next.
struct RecordingMessage {
  std::size_t topic = 0;          ///< index into RecordingSource::topics()
  std::uint64_t log_time_ns = 0;  ///< when it was recorded [ns]
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
  /// Locates the payload in error messages ("... payload byte N").
  detail::BufferOrigin origin;
};

namespace detail {

/// A decompressed chunk of a bag or MCAP file, read record by record.
struct OpenChunk {
  std::vector<std::uint8_t> bytes;  ///< the chunk's records, decompressed
  std::size_t next = 0;             ///< offset of the next record in `bytes`
  bool open = false;
  /// Errors inside: "byte AT (chunk), decompressed byte K".
  BufferOrigin origin;

  /// Starts reading `bytes` (filled by the caller) of the chunk record at file offset `at`.
  void start(const std::string& file, std::uint64_t at) {
    next = 0;
    open = true;
    origin = BufferOrigin{file, "byte " + std::to_string(at) + " (chunk), decompressed byte ", 0};
  }
  /// A cursor at the next record; after reading one, store its end in `next`.
  ByteCursor cursor() const {
    ByteCursor c(bytes.data(), bytes.size(), origin);
    c.seek(next);
    return c;
  }
  bool done() const noexcept { return next >= bytes.size(); }
};

/// The topics of a container by the id its records use (a bag's connection,
/// an MCAP channel). O(log topics) per lookup; not thread-safe.
class TopicTable {
 public:
  /// Registers `t` under `id`. A container may repeat a definition (a bag's
  /// index section, an MCAP summary): it must then name the same topic and
  /// type, else InputError at `errors`' start. `kind`: "connection", "channel".
  void add(std::uint32_t id, RecordingTopic t, const ByteCursor& errors, const char* kind) {
    const auto known = ids_.find(id);
    if (known != ids_.end()) {
      const RecordingTopic& old = topics_[known->second];
      if (old.name != t.name || old.type != t.type) {
        errors.fail_at(0, std::string(kind) + " " + std::to_string(id) + " redefined as " + t.name + " (" + t.type +
                              "), it was " + old.name + " (" + old.type + ")");
      }
      return;
    }
    ids_[id] = topics_.size();
    topics_.push_back(std::move(t));
  }
  /// The topic index of `id`, or nothing when no record defined it.
  std::optional<std::size_t> index(std::uint32_t id) const {
    const auto it = ids_.find(id);
    if (it == ids_.end()) return std::nullopt;
    return it->second;
  }
  /// Topics in the order their ids were first defined.
  std::vector<RecordingTopic>& topics() noexcept { return topics_; }
  /// (id, topic index) pairs.
  const std::map<std::uint32_t, std::size_t>& ids() const noexcept { return ids_; }

 private:
  std::map<std::uint32_t, std::size_t> ids_;
  std::vector<RecordingTopic> topics_;
};

}  // namespace detail

/// A recording read as topics and messages. Not thread-safe.
class RecordingSource {
 public:
  virtual ~RecordingSource() = default;
  RecordingSource(const RecordingSource&) = delete;
  RecordingSource& operator=(const RecordingSource&) = delete;

  const std::string& path() const noexcept { return path_; }
  /// Every topic of the recording (may scan the file once when it has no index).
  virtual const std::vector<RecordingTopic>& topics() = 0;
  /// The next message in file order; false at the end. Throws InputError.
  virtual bool next(RecordingMessage& message) = 0;

 protected:
  explicit RecordingSource(std::string path) : path_(std::move(path)) {}
  std::string path_;
};

}  // namespace streamclust::io
