// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust ros2 --record`: the input messages as received.

#include <streamclust/io/mcap_writer.hpp>

#include <cstdint>
#include <string>

namespace streamclust::cli {

/// The messages of a run as received, in an MCAP file (ROS 2 profile, the
/// types' definitions as ros2msg schemas), which `cluster` reads as it
/// reads any recording. Not thread-safe.
class Ros2InputRecorder {
 public:
  explicit Ros2InputRecorder(const std::string& path) : mcap_(path, io::McapWriter::Options{}) {}

  /// Adds a topic; returns its channel for add().
  std::uint16_t add_topic(const std::string& topic, const std::string& type, const std::string& definition) {
    return mcap_.add_channel(mcap_.add_schema(type, "ros2msg", definition), topic, "cdr");
  }
  void add(std::uint16_t channel, std::uint64_t log_time_ns, const std::uint8_t* payload, std::size_t size) {
    mcap_.write(channel, log_time_ns, payload, size);
  }
  void close() { mcap_.close(); }

 private:
  io::McapWriter mcap_;
};

}  // namespace streamclust::cli
