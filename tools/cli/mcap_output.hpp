// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `cluster --mcap FILE`: every retrieval cycle as Foxglove shows it, in an
/// MCAP file (ROS 2 profile, CDR messages, zstd chunks), logged at the
/// cycle's stream time: the topics `/streamclust/points`
/// (`foxglove_msgs/msg/PointCloud`, the labelled window) and
/// `/streamclust/clusters` (`foxglove_msgs/msg/SceneUpdate`, the boxes with
/// their ids) of cli/foxglove_frames.hpp, which the live view publishes too,
/// and with `--tracks` `/streamclust/tracks` (the tracks as oriented boxes with
/// velocity arrows).
///
/// Frame id `streamclust` (the coordinates the clusterer used: the sensor's,
/// or the world's with --poses). Not thread-safe.

#include "cli/foxglove_frames.hpp"

#include <streamclust/io/foxglove_messages.hpp>
#include <streamclust/io/mcap_writer.hpp>
#include <streamclust/io/stream_time.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace streamclust::cli {

/// Writes the cycles of a run to an MCAP file (see the file comment).
class McapOutput {
 public:
  /// `tracks`: the file has the tracks' channel too (write_tracks).
  explicit McapOutput(const std::string& path, bool tracks = false) : mcap_(path, io::McapWriter::Options{}) {
    const auto cloud = mcap_.add_schema(FoxgloveFrames::kPointCloudSchema, "ros2msg",
                                        io::foxglove::ros2_definition(FoxgloveFrames::kPointCloudType));
    const auto scene = mcap_.add_schema(FoxgloveFrames::kSceneUpdateSchema, "ros2msg",
                                        io::foxglove::ros2_definition(FoxgloveFrames::kSceneUpdateType));
    points_ = mcap_.add_channel(cloud, FoxgloveFrames::kPointsTopic, "cdr");
    clusters_ = mcap_.add_channel(scene, FoxgloveFrames::kClustersTopic, "cdr");
    if (tracks) tracks_ = mcap_.add_channel(scene, FoxgloveFrames::kTracksTopic, "cdr");
  }

  /// The labelled window of one cycle (`labels` one per point, -1
  /// unlabelled, -2 ground, -3 ceiling), at stream time `time` [s] since `origin`.
  void write(const std::vector<io::Record>& points, const std::vector<std::int64_t>& labels, double time,
             io::TimeOrigin origin) {
    const std::uint64_t log_ns = FoxgloveFrames::nanoseconds(origin, time);
    frames_.build(points, labels, log_ns);
    mcap_.write(points_, log_ns, frames_.point_cloud().data(), frames_.point_cloud().size());
    mcap_.write(clusters_, log_ns, frames_.scene_update().data(), frames_.scene_update().size());
  }

  /// The tracks of one cycle at stream time `time` [s] since `origin`
  /// (constructed with `tracks`).
  void write_tracks(const std::vector<tracking::Track>& tracks, double time, io::TimeOrigin origin) {
    const std::uint64_t log_ns = FoxgloveFrames::nanoseconds(origin, time);
    frames_.build_tracks(tracks, log_ns);
    mcap_.write(tracks_, log_ns, frames_.tracks_update().data(), frames_.tracks_update().size());
  }

  /// Writes the summary and closes the file; throws std::runtime_error naming it on failure.
  void close() { mcap_.close(); }

 private:
  io::McapWriter mcap_;
  std::uint16_t points_ = 0, clusters_ = 0, tracks_ = 0;
  FoxgloveFrames frames_;
};

}  // namespace streamclust::cli
