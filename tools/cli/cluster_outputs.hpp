// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// What `streamclust cluster` reads and writes around the engine: its input,
/// the labels file, `--ply` / `--pcd` / `--png` of the selected cycle,
/// `--png` every N cycles, `--mcap`, `--tracks` (the tracker and its rows),
/// the report file and the summary line.
/// Compiled once (cli/cluster_outputs.cpp) rather than once per engine
/// configuration: the driver's template (cli/cluster_driver.hpp) keeps only
/// what depends on the engine, which halves the compile time of each of its
/// translation units. Not thread-safe.

#include "cli/memory_context.hpp"
#include "cli/options.hpp"
#include "cli/report.hpp"

#include <streamclust/io/point_reader.hpp>
#include <streamclust/io/record.hpp>
#include <streamclust/io/stream_time.hpp>
#include <streamclust/tracking/object_boxes.hpp>
#include <streamclust/tracking/track.hpp>

#include <cstdint>
#include <fstream>
#include <memory>
#include <ostream>
#include <vector>

namespace streamclust {
class KalmanTracker;
}  // namespace streamclust

namespace streamclust::cli {

class McapOutput;

/// One labelled window, kept for the outputs of the selected cycles.
struct LabelledWindow {
  std::uint64_t cycle = 0;
  double time = 0.0;                 ///< [s] the cycle's stream time
  std::vector<std::uint64_t> index;  ///< stream index per row, ascending
  std::vector<std::int64_t> label;   ///< -1: in the window but unlabelled
  std::vector<io::Record> points;    ///< clustered points (for --ply/--pcd)
  std::vector<std::int64_t> point_labels;
};

/// Which cycles go to the labels file and the point clouds.
class CycleSelection {
 public:
  explicit CycleSelection(const ClusterOptions& o);
  bool last_only() const { return !all_ && list_.empty(); }
  bool selected(std::uint64_t cycle) const;

 private:
  bool all_;
  std::vector<std::uint64_t> list_;  ///< ascending
};

/// The input of `o`: its open_input hook, else the file `o.input`. Throws
/// io::InputError.
std::unique_ptr<io::PointReader> open_cluster_input(const ClusterOptions& o);

/// True when standard error is a terminal (the progress line is drawn there).
bool stderr_is_terminal();

/// The outputs of one `cluster` run (see the file comment).
class ClusterOutputs {
 public:
  /// Opens the labels file and the MCAP file. Throws UsageError naming the
  /// option and the path.
  explicit ClusterOutputs(const ClusterOptions& o);
  ~ClusterOutputs();
  ClusterOutputs(const ClusterOutputs&) = delete;
  ClusterOutputs& operator=(const ClusterOutputs&) = delete;

  /// One cycle's labelled window: `--mcap`, `--png` every N cycles, the
  /// labels rows of a selected cycle, and a copy of the window for the
  /// outputs written at the end. `stage` reads Stage::writing while a file
  /// is written and Stage::clustering on return. Throws UsageError.
  void on_window(const LabelledWindow& window, io::TimeOrigin origin, Stage& stage);

  /// True with --tracks.
  bool tracking() const { return tracker_ != nullptr; }
  /// --tracks: the tracker's update with a cycle's objects (time [s]: the
  /// retrieval's); the tracks, valid until the next call.
  const std::vector<tracking::Track>& track(const std::vector<tracking::ObjectObservation>& objects, double time);
  /// --tracks: the tracks after the last track() update.
  const std::vector<tracking::Track>& tracks() const;
  /// --tracks: the rows of the last track() update for cycle `cycle` at
  /// stream time `time` [s]. Throws UsageError when the file fails.
  void write_tracks(std::uint64_t cycle, double time, io::TimeOrigin origin, Stage& stage);

  /// After the last cycle (`stage` becomes Stage::writing): the labels of
  /// the last cycle (without --cycles), the report file, the point clouds
  /// and the picture of the last selected cycle, the MCAP file closed, and
  /// the summary line on `out` unless quiet. Throws UsageError.
  void finish(const Report& report, io::TimeOrigin origin, std::ostream& out, Stage& stage);

 private:
  const ClusterOptions& options_;
  CycleSelection selection_;
  std::ofstream labels_file_;
  std::unique_ptr<McapOutput> mcap_;  ///< every cycle, with --mcap
  std::unique_ptr<KalmanTracker> tracker_;  ///< with --tracks
  std::ofstream tracks_file_;
  std::string tracks_rows_;
  LabelledWindow kept_;               ///< the last selected cycle
  bool have_selected_ = false;
};

}  // namespace streamclust::cli
