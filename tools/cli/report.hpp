// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The `--report` JSON, the `--labels` CSV rows and the one-line summary of
/// `streamclust cluster`.

#include "cli/json.hpp"
#include "cli/latency_histogram.hpp"

#include <streamclust/io/stream_time.hpp>
#include <streamclust/percentiles.hpp>
#include <streamclust/resolution/adaptive.hpp>
#include <streamclust/stream_clusterer.hpp>
#include <streamclust/types.hpp>

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::cli {

/// One retrieval cycle as reported.
struct CycleReport {
  std::uint64_t cycle = 0;
  double time = 0.0;          ///< scheduled stream time of the retrieval [s]
  std::size_t window = 0;     ///< clustered (object) points in the window
  std::size_t structure = 0;  ///< points of the window classed ground or ceiling (--ground)
  std::uint64_t inserted = 0; ///< points accepted since the previous cycle
  std::uint64_t evicted = 0;  ///< points evicted since the previous cycle (continuous mode)
  std::size_t components = 0;
  double retrieve_us = 0.0;   ///< the retrieval (continuous: components and labels; frame: advance and batch) [us]
  double batch_us = 0.0;      ///< frame mode: the batch clustering of the window [us]
  double ground_us = 0.0;     ///< of total_us: the ground model's updates and decisions (--ground) [us]
  double placement_us = 0.0;  ///< of total_us: placing points by poses or mount [us]
  double tracking_us = 0.0;   ///< after total_us: the boxes and the tracker (--tracks) [us]
  /// The cycle's latency [us]: wall time of everything the clusterer did
  /// for it since the previous cycle (the inserts of the records in between,
  /// the eviction, the retrieval), reading the input excluded.
  double total_us = 0.0;
};

/// The cycles of a run: every cycle counted and summed, and the cycles
/// themselves kept for the report: all of them (a recording's run), or,
/// after `keep_last(n)`, the last n (a live run: fixed memory however long
/// it runs; its latency summary then comes from a histogram of 0.1 ms
/// bins). push_back: O(1).
class CycleLog {
 public:
  CycleLog() = default;

  /// Keeps only the last `n` cycles from now on (0: every cycle).
  void keep_last(std::size_t n) {
    limit_ = n;
    if (n > 0 && !histogram_) {
      histogram_ = std::make_unique<LatencyHistogram>();
      for (const CycleReport& c : kept_) histogram_->add(c.total_us / 1000.0);
    }
    trim();
  }
  void push_back(const CycleReport& c) {
    ++count_;
    inserted_ += c.inserted;
    evicted_ += c.evicted;
    if (histogram_) histogram_->add(c.total_us / 1000.0);
    kept_.push_back(c);
    trim();
  }
  /// Every cycle of the run, kept or not.
  std::uint64_t size() const noexcept { return count_; }
  /// The cycles kept, oldest first.
  const std::deque<CycleReport>& kept() const noexcept { return kept_; }
  std::uint64_t omitted() const noexcept { return count_ - kept_.size(); }
  std::uint64_t inserted() const noexcept { return inserted_; }
  std::uint64_t evicted() const noexcept { return evicted_; }
  /// The cycle latencies of every cycle [us]: exact when every cycle is
  /// kept, else median and P99 to the histogram's 0.1 ms (upper bin edges).
  LatencySummary latency_us() const {
    if (!histogram_) {
      std::vector<double> v;
      v.reserve(kept_.size());
      for (const CycleReport& c : kept_) v.push_back(c.total_us);
      return streamclust::summarize(std::move(v));
    }
    LatencySummary s;
    s.count = static_cast<std::size_t>(histogram_->count());
    s.median = histogram_->percentile(50.0) * 1000.0;
    s.p99 = histogram_->percentile(99.0) * 1000.0;
    s.max = histogram_->max() * 1000.0;
    return s;
  }

 private:
  void trim() {
    while (limit_ > 0 && kept_.size() > limit_) kept_.pop_front();
  }

  std::deque<CycleReport> kept_;
  std::size_t limit_ = 0;
  std::uint64_t count_ = 0, inserted_ = 0, evicted_ = 0;
  std::unique_ptr<LatencyHistogram> histogram_;
};

struct Report {
  std::string input, format, mode;
  io::TimeOrigin time_origin;  ///< the input's (stream_time.hpp): cycle times are written as origin + time
  std::string connectivity;  ///< continuous mode: "lazy-bfs" or "forest"; empty in frame mode
  std::uint32_t grid_rows = 0, grid_cols = 0;
  bool grid_wraps = false;
  bool adaptive = false;
  std::vector<AdaptiveStep> trace;
  AdaptiveStop stop = AdaptiveStop::not_run;
  CycleLog cycles;
  std::uint64_t records = 0;
  RejectionCounts rejections{};
  bool ground = false;          ///< structure removal was on
  bool motion = false;          ///< points were placed by poses or a mount
  bool tracking = false;        ///< objects were tracked (--tracks)
  float sensor_height = 0.0f;   ///< [m] the ground model's (0: unknown)
  bool estimated_mount = false, estimated_height = false;
  double estimated_roll_deg = 0.0, estimated_pitch_deg = 0.0;  ///< when estimated_mount
};

/// The rows `cycle,time,index,label` of one labelled window; the time as
/// origin + w.time with nanoseconds (io::format_time).
template <class Rows>
void write_label_rows(std::ostream& out, const Rows& w, io::TimeOrigin origin) {
  const std::string time = io::format_time(origin, w.time);
  for (std::size_t i = 0; i < w.index.size(); ++i) {
    out << w.cycle << ',' << time << ',' << w.index[i] << ',' << w.label[i] << '\n';
  }
}

/// The report as a JSON document (docs/cli.md).
inline Json report_json(const Report& r) {
  Json doc;
  doc["input"] = r.input;
  doc["format"] = r.format;
  doc["mode"] = r.mode;
  if (!r.connectivity.empty()) doc["connectivity"] = r.connectivity;
  Json trace = Json::array();
  for (const AdaptiveStep& s : r.trace) {
    trace.push_back({{"rows", s.grid.rows},
                     {"cols", s.grid.cols},
                     {"density_v", s.density_v},
                     {"density_h", s.density_h},
                     {"gap_v", s.gap_v},
                     {"gap_h", s.gap_h},
                     {"mean_multiplicity", s.mean_multiplicity}});
  }
  doc["grid"] = {{"rows", r.grid_rows},       {"cols", r.grid_cols},         {"wrap_columns", r.grid_wraps},
                 {"adaptive", r.adaptive},    {"stop", to_string(r.stop)},   {"trace", std::move(trace)}};
  Json cycles = Json::array();
  for (const CycleReport& c : r.cycles.kept()) {
    Json latency = {{"insertion", c.total_us - c.retrieve_us},
                    {"retrieval", c.retrieve_us},
                    {"batch", c.batch_us},
                    {"total", c.total_us}};
    if (r.ground) latency["ground"] = c.ground_us;
    if (r.motion) latency["placement"] = c.placement_us;
    if (r.tracking) latency["tracking"] = c.tracking_us;
    Json cycle = {{"cycle", c.cycle},
                  {"time", number_text(io::format_time(r.time_origin, c.time))},
                  {"window_size", c.window},
                  {"inserted", c.inserted},
                  {"evicted", c.evicted},
                  {"components", c.components},
                  {"latency_us", std::move(latency)}};
    if (r.ground) cycle["structure_size"] = c.structure;
    cycles.push_back(std::move(cycle));
  }
  doc["cycles"] = std::move(cycles);
  if (r.cycles.omitted() > 0) doc["cycles_omitted"] = r.cycles.omitted();  // the oldest, not kept
  if (r.ground) {
    Json ground = {{"sensor_height", r.sensor_height}, {"sensor_height_estimated", r.estimated_height}};
    if (r.estimated_mount) ground["estimated_mount"] = {{"roll_deg", r.estimated_roll_deg}, {"pitch_deg", r.estimated_pitch_deg}};
    doc["ground"] = std::move(ground);
  }
  Json rejected = Json::object();
  for (std::size_t k = 1; k < kRejectReasonCount; ++k) {
    rejected[to_string(static_cast<RejectReason>(k))] = r.rejections.by_reason[k];
  }
  const LatencySummary latency = r.cycles.latency_us();
  doc["totals"] = {{"records", r.records},
                   {"inserted", r.cycles.inserted()},
                   {"evicted", r.cycles.evicted()},
                   {"cycles", r.cycles.size()},
                   {"rejected", std::move(rejected)},
                   {"latency_us", {{"median", latency.median}, {"p99", latency.p99}, {"max", latency.max}}}};
  return doc;
}

/// Writes the report; `extra`, when set, adds its members to the document.
inline void write_report_file(const std::string& path, const Report& r,
                              const std::function<void(Json&)>& extra = nullptr) {
  Json doc = report_json(r);
  if (extra) extra(doc);
  write_json_file("--report", path, doc);
}

inline std::string summary_line(const Report& r) {
  const LatencySummary latency = r.cycles.latency_us();
  std::ostringstream s;
  s.precision(3);
  s << std::fixed << "streamclust: " << r.records << " records, " << r.rejections[RejectReason::accepted]
    << " clustered, " << r.rejections.rejected() << " rejected, " << r.cycles.size() << " cycles, grid " << r.grid_rows
    << "x" << r.grid_cols << ", cycle latency median " << latency.median / 1000.0 << " ms, P99 "
    << latency.p99 / 1000.0 << " ms";
  return s.str();
}

}  // namespace streamclust::cli
