// SPDX-License-Identifier: MIT
// The input and the outputs of `streamclust cluster` (cli/cluster_outputs.hpp).

#include "cli/cluster_outputs.hpp"

#include "cli/mcap_output.hpp"

#include <streamclust/io/birds_eye.hpp>
#include <streamclust/io/png_writer.hpp>
#include <streamclust/io/reader.hpp>
#include <streamclust/tracking/kalman_tracker.hpp>
#include <streamclust/tracking/tracks_csv.hpp>
#include <streamclust/io/writers.hpp>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <unistd.h>

namespace streamclust::cli {

namespace {

/// `path` with "_NNNNNN" (the cycle, six digits at least) before its extension.
std::string numbered_path(const std::string& path, std::uint64_t cycle) {
  const std::filesystem::path p(path);
  std::string number = std::to_string(cycle);
  if (number.size() < 6) number.insert(0, 6 - number.size(), '0');
  return (p.parent_path() / (p.stem().string() + "_" + number + p.extension().string())).string();
}

/// `--png`: the bird's-eye picture of `window` (io/birds_eye.hpp).
void write_picture(const std::string& path, const LabelledWindow& window) {
  try {
    io::write_png(path, io::render_birds_eye(window.points, window.point_labels));
  } catch (const std::runtime_error&) {
    throw UsageError("--png: cannot write '" + path + "'");
  }
}

}  // namespace

CycleSelection::CycleSelection(const ClusterOptions& o) : all_(o.all_cycles), list_(o.cycle_list) {
  std::sort(list_.begin(), list_.end());
}

bool CycleSelection::selected(std::uint64_t cycle) const {
  return all_ || std::binary_search(list_.begin(), list_.end(), cycle);
}

std::unique_ptr<io::PointReader> open_cluster_input(const ClusterOptions& o) {
  return o.open_input ? o.open_input() : io::open_reader(o.input, o.read);
}

bool stderr_is_terminal() { return ::isatty(2) == 1; }

ClusterOutputs::ClusterOutputs(const ClusterOptions& o) : options_(o), selection_(o) {
  if (!o.labels_path.empty()) {
    labels_file_.open(o.labels_path);
    if (!labels_file_) throw UsageError("--labels: cannot write '" + o.labels_path + "'");
    labels_file_ << "cycle,time,index,label\n";
  }
  if (!o.tracks_path.empty()) {
    tracks_file_.open(o.tracks_path);
    if (!tracks_file_) throw UsageError("--tracks: cannot write '" + o.tracks_path + "'");
    tracks_file_ << tracking::kTracksCsvHeader << '\n';
    tracker_ = std::make_unique<KalmanTracker>();
  }
  if (!o.mcap_path.empty()) {
    try {
      mcap_ = std::make_unique<McapOutput>(o.mcap_path, !o.tracks_path.empty());
    } catch (const std::runtime_error&) {
      throw UsageError("--mcap: cannot write '" + o.mcap_path + "'");
    }
  }
}

ClusterOutputs::~ClusterOutputs() = default;

void ClusterOutputs::on_window(const LabelledWindow& window, io::TimeOrigin origin, Stage& stage) {
  const bool selected = selection_.selected(window.cycle) || selection_.last_only();
  const bool picture = options_.png_every > 0 && window.cycle % options_.png_every == 0;
  const bool labels = selected && labels_file_.is_open() && !selection_.last_only();
  if (mcap_ || picture || labels) {
    stage = Stage::writing;
    if (mcap_) mcap_->write(window.points, window.point_labels, window.time, origin);
    if (picture) write_picture(numbered_path(options_.png_path, window.cycle), window);
    if (labels) write_label_rows(labels_file_, window, origin);
    stage = Stage::clustering;
  }
  if (selected) {
    have_selected_ = true;
    kept_ = window;
  }
}

const std::vector<tracking::Track>& ClusterOutputs::track(const std::vector<tracking::ObjectObservation>& objects,
                                                          double time) {
  return tracker_->update(objects, time);
}

const std::vector<tracking::Track>& ClusterOutputs::tracks() const { return tracker_->tracks(); }

void ClusterOutputs::write_tracks(std::uint64_t cycle, double time, io::TimeOrigin origin, Stage& stage) {
  stage = Stage::writing;
  tracks_rows_.clear();
  tracking::append_track_rows(tracks_rows_, cycle, origin, time, tracker_->tracks());
  tracks_file_ << tracks_rows_;
  if (!tracks_file_) throw UsageError("--tracks: writing '" + options_.tracks_path + "' failed");
  if (mcap_) mcap_->write_tracks(tracker_->tracks(), time, origin);
  stage = Stage::clustering;
}

void ClusterOutputs::finish(const Report& report, io::TimeOrigin origin, std::ostream& out, Stage& stage) {
  const ClusterOptions& o = options_;
  stage = Stage::writing;
  if (labels_file_.is_open() && selection_.last_only()) write_label_rows(labels_file_, kept_, origin);
  if (labels_file_.is_open()) {
    labels_file_.flush();
    if (!labels_file_) throw UsageError("--labels: writing '" + o.labels_path + "' failed");
  }
  if (tracks_file_.is_open()) {
    tracks_file_.flush();
    if (!tracks_file_) throw UsageError("--tracks: writing '" + o.tracks_path + "' failed");
  }
  if (!o.report_path.empty()) write_report_file(o.report_path, report, o.report_extra);
  if (have_selected_ && !o.ply_path.empty()) io::write_ply(o.ply_path, kept_.points, kept_.point_labels, true, origin);
  if (have_selected_ && !o.pcd_path.empty()) {
    io::write_pcd(o.pcd_path, kept_.points, kept_.point_labels, "binary", origin);
  }
  if (have_selected_ && !o.png_path.empty() && o.png_every == 0) write_picture(o.png_path, kept_);
  if (mcap_) {
    try {
      mcap_->close();
    } catch (const std::runtime_error&) {
      throw UsageError("--mcap: writing '" + o.mcap_path + "' failed");
    }
  }
  if (!o.quiet) out << summary_line(report) << "\n";
}

}  // namespace streamclust::cli
