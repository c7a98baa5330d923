// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust cluster`: streams a recorded input through the continuous
/// engine (or the batch clusterer in frame mode), retrieves at a fixed rate of
/// stream time and writes labels, a JSON report and point clouds.

#include "cli/options.hpp"
#include "cli/report.hpp"

#include <streamclust/io/reader.hpp>
#include <streamclust/io/writers.hpp>
#include <streamclust/linkage/runtime_linkage.hpp>
#include <streamclust/resolution/runtime_resolution.hpp>
#include <streamclust/streamclust.hpp>
#include <streamclust/window/runtime_window.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <unistd.h>

namespace streamclust::cli {

/// The tool's configuration: projection, index and connectivity are
/// compiled in (they shape the data structures); linkage, window and
/// resolution are chosen at run time. Phases are timed for the report.
template <class Projection, class Index, class Connectivity = LazyBfsConnectivity>
struct ToolConfig {
  using projection = Projection;
  using spatial_index = Index;
  using connectivity = Connectivity;
  using linkage = RuntimeLinkage;
  using window = RuntimeWindow;
  using resolution = RuntimeResolution;
  static constexpr bool timed = true;
};

template <class Config>
ClustererParams<Config> make_params(const ClusterOptions& o) {
  ClustererParams<Config> p;
  p.projection.azimuth_min_deg = o.azimuth_min;
  p.projection.azimuth_max_deg = o.azimuth_max;
  p.projection.min_range = o.min_range;
  if constexpr (std::is_same_v<typename Config::projection, SphericalProjection>) {
    p.projection.elevation_min_deg = o.elevation_min;
    p.projection.elevation_max_deg = o.elevation_max;
  } else {
    p.projection.z_min = o.z_min;
    p.projection.z_max = o.z_max;
  }
  if constexpr (std::is_same_v<typename Config::spatial_index, CappedGrid>) p.spatial_index.capacity = o.cap;
  p.linkage.kind = o.linkage == LinkageKind::angular ? RuntimeLinkage::Kind::angular : RuntimeLinkage::Kind::euclidean;
  p.linkage.angular.theta_deg = o.theta_deg;
  p.linkage.angular.min_ray_angle_deg = o.min_ray_angle_deg;
  p.linkage.euclidean.max_distance = o.distance;
  p.window.kind = o.window_is_count ? RuntimeWindow::Kind::count : RuntimeWindow::Kind::time;
  p.window.time.duration = o.window_seconds;
  p.window.count.capacity = o.window_count;
  p.resolution.adaptive = !o.grid.has_value();
  if (o.grid) p.resolution.fixed = {o.grid->first, o.grid->second};
  p.resolution.adaptive_loop.max_multiplicity = o.max_multiplicity;
  p.mask_size = o.mask;
  return p;
}

/// Which cycles go to the labels file and the point clouds.
class CycleSelection {
 public:
  explicit CycleSelection(const ClusterOptions& o) : all_(o.all_cycles), list_(o.cycle_list) {
    std::sort(list_.begin(), list_.end());
  }
  bool last_only() const { return !all_ && list_.empty(); }
  bool selected(std::uint64_t cycle) const {
    return all_ || std::binary_search(list_.begin(), list_.end(), cycle);
  }

 private:
  bool all_;
  std::vector<std::uint64_t> list_;
};

/// One labelled window, kept for the outputs of the selected cycles.
struct LabelledWindow {
  std::uint64_t cycle = 0;
  double time = 0.0;
  std::vector<std::uint64_t> index;  ///< stream index per row, ascending
  std::vector<std::int64_t> label;   ///< -1: in the window but unlabelled
  std::vector<io::Record> points;    ///< clustered points (for --ply/--pcd)
  std::vector<std::int64_t> point_labels;
};

/// The window's accepted points for frame mode (the engine keeps its own).
template <class Config>
class FrameWindow {
 public:
  explicit FrameWindow(const ClustererParams<Config>& p) : projection_(p.projection), window_(p.window) {}

  /// Same acceptance rules as StreamClusterer::insert.
  RejectReason offer(const io::Record& r, std::uint64_t index) {
    if (!std::isfinite(r.t)) return RejectReason::non_finite;
    const Eigen::Vector3f pos(r.x, r.y, r.z);
    const Projected pr = projection_.project(pos);
    if (!pr.accepted()) return pr.reason;
    if (has_time_ && r.t < last_time_) return RejectReason::time_backwards;
    has_time_ = true;
    last_time_ = r.t;
    advance_to(r.t, 1);
    points_.push_back({make_sample(pos, pr.range, r.intensity, r.t), index});
    return RejectReason::accepted;
  }
  void advance_to(double t, std::size_t incoming = 0) {
    while (!points_.empty() && window_.expired(points_.front().sample.time, t, points_.size() + incoming)) {
      points_.pop_front();
    }
  }
  bool complete() const {
    return !points_.empty() && window_.complete(points_.front().sample.time, last_time_, points_.size());
  }
  struct Entry {
    Sample sample;
    std::uint64_t index;
  };
  const std::deque<Entry>& points() const { return points_; }

 private:
  typename Config::projection projection_;
  typename Config::window window_;
  std::deque<Entry> points_;
  bool has_time_ = false;
  double last_time_ = 0.0;
};

inline bool stderr_is_terminal() { return ::isatty(2) == 1; }

/// Position of the first point at which two labelings stop being the same
/// partition (no bijection between their labels), or nothing when they agree.
/// O(n log n). Both must have the same length.
inline std::optional<std::size_t> first_partition_mismatch(const std::vector<std::int64_t>& a,
                                                           const std::vector<std::int64_t>& b) {
  std::map<std::int64_t, std::int64_t> forward, backward;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    const auto f = forward.emplace(a[i], b[i]).first;
    const auto r = backward.emplace(b[i], a[i]).first;
    if (f->second != b[i] || r->second != a[i]) return i;
  }
  if (a.size() != b.size()) return std::min(a.size(), b.size());
  return std::nullopt;
}

/// A policy type as a value, for generic lambdas.
template <class T>
struct TypeTag {
  using type = T;
};

/// Calls `f(TypeTag<Connectivity>{})` with the connectivity policy that
/// `kind` names and returns what it returns.
template <class F>
decltype(auto) with_connectivity(ConnectivityKind kind, F&& f) {
  if (kind == ConnectivityKind::spanning_forest) return f(TypeTag<SpanningForestConnectivity>{});
  return f(TypeTag<LazyBfsConnectivity>{});
}

/// Runs `streamclust cluster`. Returns the exit code; throws io::InputError
/// (exit 4) and UsageError (exit 2).
template <class Projection, class Index, class Connectivity>
int run_cluster_with(const ClusterOptions& o, std::ostream& out, std::ostream& err) {
  using Config = ToolConfig<Projection, Index, Connectivity>;
  const ClustererParams<Config> params = [&] {
    try {
      return make_params<Config>(o);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }();
  std::unique_ptr<StreamClusterer<Config>> engine;
  std::unique_ptr<FrameWindow<Config>> frame;
  std::unique_ptr<BatchClusterer<Config>> batch;
  RuntimeResolution frame_resolution(params.resolution);
  try {
    if (o.mode == Mode::continuous) {
      engine = std::make_unique<StreamClusterer<Config>>(params);
      if (o.verify) batch = std::make_unique<BatchClusterer<Config>>(params, BatchMode::insertion_order);
    } else {
      frame = std::make_unique<FrameWindow<Config>>(params);
      batch = std::make_unique<BatchClusterer<Config>>(params, BatchMode::range_image);
    }
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  std::optional<GridSize> frame_grid;
  if (o.mode == Mode::frame && !frame_resolution.needs_calibration()) frame_grid = frame_resolution.grid();

  auto reader = io::open_reader(o.input, o.read);
  const CycleSelection selection(o);
  std::ofstream labels_file;
  if (!o.labels_path.empty()) {
    labels_file.open(o.labels_path);
    if (!labels_file) throw UsageError("--labels: cannot write '" + o.labels_path + "'");
    labels_file << "cycle,time,index,label\n";
    labels_file.precision(9);
  }
  Report report;
  report.input = o.input;
  report.format = io::to_string(reader->info().format);
  report.mode = o.mode == Mode::continuous ? "continuous" : "frame";
  if (engine) {  // named from the engine's type: what ran, not what was asked
    report.connectivity = std::is_same_v<Connectivity, SpanningForestConnectivity> ? "forest" : "lazy-bfs";
  }

  RejectionCounts rejected_by_reason{};
  std::deque<std::uint64_t> rejected;  // stream indices of rejected records, ascending
  LabelledWindow window_out;  // the current cycle
  LabelledWindow kept;        // the last selected cycle, for --ply/--pcd (and --labels with --cycles last)
  bool have_selected = false;
  std::uint64_t records = 0;
  std::uint64_t cycle = 0;
  double first_time = 0.0, last_time = 0.0, next_retrieval = 0.0;
  double next_k = 1.0;  // next_retrieval = first_time + next_k * period
  bool started = false;
  const double period = 1.0 / o.rate_hz;
  std::uint64_t inserted_since = 0;
  const bool progress = !o.quiet && stderr_is_terminal();
  auto last_progress = std::chrono::steady_clock::now();
  const auto declared = reader->info().declared_points;

  // Labels one window and writes/keeps the outputs of a selected cycle.
  auto run_cycle = [&](double cycle_time) -> int {
    CycleReport c;
    c.cycle = cycle;
    c.time = cycle_time;
    window_out.cycle = cycle;
    window_out.time = cycle_time;
    window_out.index.clear();
    window_out.label.clear();
    window_out.points.clear();
    window_out.point_labels.clear();
    std::vector<std::uint64_t> index;
    std::vector<std::int64_t> label;
    const auto t0 = std::chrono::steady_clock::now();
    if (engine) {
      engine->advance_to(cycle_time);
      const Clustering& result = engine->retrieve();
      const RetrievalStats& s = engine->last_stats();
      c.phase = s.phase_us;
      c.inserted = s.inserted;
      c.evicted = s.evicted;
      c.components = result.components.size();
      c.window = result.points.size();
      for (const PointLabel& p : result.points) {
        index.push_back(p.stream_index);
        label.push_back(static_cast<std::int64_t>(p.label));
      }
      if (batch) {
        std::vector<Sample> samples;
        samples.reserve(engine->size());
        engine->for_each_point([&](const Sample& s2, std::uint64_t) { samples.push_back(s2); });
        batch->set_grid({engine->grid().rows, engine->grid().cols});
        const auto& reference = batch->cluster(samples);
        if (const auto i = first_partition_mismatch(label, reference.labels)) {
          err << "streamclust: verify: cycle " << cycle << " (t = " << cycle_time << " s): point " << index[*i]
              << " has continuous label " << label[*i] << " but the batch clusterer puts it with a different set"
              << " of points (batch component " << reference.labels[*i] << ")\n";
          return kMismatch;
        }
      }
    } else {
      frame->advance_to(cycle_time);
      std::vector<Sample> samples;
      for (const auto& e : frame->points()) {
        samples.push_back(e.sample);
        index.push_back(e.index);
      }
      if (!frame_grid && !samples.empty()) {
        std::vector<Projected> coords;
        const typename Config::projection proj(params.projection);
        for (const Sample& s2 : samples) coords.push_back(proj.project(s2.position));
        frame_grid = frame_resolution.calibrate(coords, proj.fov_aspect());
      }
      if (frame_grid) batch->set_grid(*frame_grid);
      const auto b0 = std::chrono::steady_clock::now();
      const auto& r = batch->cluster(samples);
      c.batch_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - b0).count();
      label = r.labels;
      c.components = r.components;
      c.window = samples.size();
      c.inserted = inserted_since;
      if (!samples.empty()) {
        report.grid_rows = r.grid.rows;
        report.grid_cols = r.grid.cols;
        report.grid_wraps = r.grid.wrap_columns;
      }
      for (std::size_t i = 0; i < samples.size(); ++i) {
        const auto& s2 = samples[i];
        window_out.points.push_back(io::Record{s2.position.x(), s2.position.y(), s2.position.z(), s2.intensity,
                                               s2.time, -1});
        window_out.point_labels.push_back(label[i]);
      }
    }
    c.total_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    inserted_since = 0;
    if (engine) {
      engine->for_each_point([&](const Sample& s2, std::uint64_t) {
        window_out.points.push_back(
            io::Record{s2.position.x(), s2.position.y(), s2.position.z(), s2.intensity, s2.time, -1});
      });
      window_out.point_labels = label;
    }
    // Rejected records inside the window's span of stream indices: -1.
    const std::uint64_t oldest = index.empty() ? records : index.front();
    while (!rejected.empty() && rejected.front() < oldest) rejected.pop_front();
    std::size_t i = 0, j = 0;
    while (i < index.size() || j < rejected.size()) {
      if (j == rejected.size() || (i < index.size() && index[i] < rejected[j])) {
        window_out.index.push_back(index[i]);
        window_out.label.push_back(label[i]);
        ++i;
      } else {
        window_out.index.push_back(rejected[j]);
        window_out.label.push_back(-1);
        ++j;
      }
    }
    report.cycles.push_back(c);
    if (selection.selected(cycle) || selection.last_only()) {
      have_selected = true;
      if (labels_file.is_open() && !selection.last_only()) write_label_rows(labels_file, window_out);
      kept = window_out;
    }
    ++cycle;
    return kOk;
  };

  std::vector<io::Record> chunk;
  std::vector<RejectReason> reasons;  // of the records being offered
  // Offers chunk[from, to) (the engine takes them as one batch) and books
  // each record's outcome under its stream index.
  auto offer_records = [&](std::size_t from, std::size_t to) {
    if (from == to) return;
    reasons.clear();
    const auto first = chunk.begin() + static_cast<std::ptrdiff_t>(from);
    const auto last = chunk.begin() + static_cast<std::ptrdiff_t>(to);
    if (engine) {
      engine->insert_batch(first, last, std::back_inserter(reasons));
    } else {
      for (auto r = first; r != last; ++r) reasons.push_back(frame->offer(*r, records + reasons.size()));
    }
    for (std::size_t i = from; i < to; ++i) {
      const RejectReason reason = reasons[i - from];
      const std::uint64_t index = records++;
      ++rejected_by_reason[reason];
      if (reason == RejectReason::accepted) {
        ++inserted_since;
        last_time = chunk[i].t;
      } else {
        rejected.push_back(index);
      }
    }
  };
  for (;;) {
    chunk.clear();
    if (reader->read(chunk, 65536) == 0) break;
    std::size_t offered = 0;  // chunk[0, offered) went to the clusterer
    for (std::size_t i = 0; i < chunk.size(); ++i) {
      const io::Record& r = chunk[i];
      if (!started && std::isfinite(r.t)) {
        started = true;
        first_time = r.t;
        next_retrieval = first_time + period;
      }
      if (started && std::isfinite(r.t) && r.t >= next_retrieval) {
        // The records before this one first, then the retrieval.
        offer_records(offered, i);
        offered = i;
        // No cycle while the engine buffers its first window for the grid.
        if (engine) engine->advance_to(next_retrieval);
        const bool calibrating = engine && engine->calibrating();
        const int code = calibrating ? kOk : run_cycle(next_retrieval);
        if (code != kOk) return code;
        // Skip the empty cycles of a pause, but always move on: floor() may
        // round (r.t - first_time) / period a hair below next_k although
        // r.t >= next_retrieval, which would schedule this retrieval again.
        next_k = std::max(next_k + 1.0, std::floor((r.t - first_time) / period) + 1.0);
        next_retrieval = first_time + next_k * period;
      }
    }
    offer_records(offered, chunk.size());
    if (progress && std::chrono::steady_clock::now() - last_progress > std::chrono::milliseconds(250)) {
      last_progress = std::chrono::steady_clock::now();
      if (declared && *declared > 0) {
        const double f = std::min(1.0, static_cast<double>(records) / static_cast<double>(*declared));
        const int bar = static_cast<int>(f * 30.0);
        err << "\r[" << std::string(static_cast<std::size_t>(bar), '#') << std::string(static_cast<std::size_t>(30 - bar), '.')
            << "] " << static_cast<int>(f * 100.0) << "%  " << records << " points" << std::flush;
      } else {
        err << "\r" << records << " points, t = " << last_time - first_time << " s" << std::flush;
      }
    }
  }
  if (progress) err << "\r" << std::string(60, ' ') << "\r";
  if (records == 0) throw io::InputError(o.input, "header", "no points: the input is empty");
  // The final cycle covers the points after the last scheduled retrieval
  // (and, for an input shorter than one window, ends the calibration).
  if (engine) engine->complete_calibration();
  if (inserted_since > 0 || cycle == 0) {
    const int code = run_cycle(started ? std::max(last_time, first_time) : 0.0);
    if (code != kOk) return code;
  }

  if (engine) {
    report.grid_rows = engine->grid().rows;
    report.grid_cols = engine->grid().cols;
    report.grid_wraps = engine->grid().wrap_columns;
    report.adaptive = engine->resolution().adaptive();
    report.trace = engine->resolution().trace();
    report.stop = engine->resolution().stop_reason();
  } else {
    report.adaptive = frame_resolution.adaptive();
    report.trace = frame_resolution.trace();
    report.stop = frame_resolution.stop_reason();
  }
  report.records = records;
  report.rejections = rejected_by_reason;
  if (labels_file.is_open() && selection.last_only()) write_label_rows(labels_file, kept);
  if (labels_file.is_open()) {
    labels_file.flush();
    if (!labels_file) throw UsageError("--labels: writing '" + o.labels_path + "' failed");
  }
  if (!o.report_path.empty()) write_report_file(o.report_path, report);
  if (have_selected && !o.ply_path.empty()) io::write_ply(o.ply_path, kept.points, kept.point_labels, true);
  if (have_selected && !o.pcd_path.empty()) io::write_pcd(o.pcd_path, kept.points, kept.point_labels, "binary");
  if (!o.quiet) out << summary_line(report) << "\n";
  return kOk;
}

/// Dispatches on projection, index and connectivity, the compiled-in
/// policies (frame mode runs no engine: its connectivity is the default).
inline int run_cluster(const ClusterOptions& o, std::ostream& out, std::ostream& err) {
  return with_connectivity(o.connectivity, [&](auto connectivity) {
    using C = typename decltype(connectivity)::type;
    if (o.projection == ProjectionKind::spherical) {
      switch (o.index) {
        case IndexKind::bucket: return run_cluster_with<SphericalProjection, BucketGrid, C>(o, out, err);
        case IndexKind::capped: return run_cluster_with<SphericalProjection, CappedGrid, C>(o, out, err);
        case IndexKind::overwrite: return run_cluster_with<SphericalProjection, OverwriteGrid, C>(o, out, err);
      }
    }
    switch (o.index) {
      case IndexKind::bucket: return run_cluster_with<CylindricalProjection, BucketGrid, C>(o, out, err);
      case IndexKind::capped: return run_cluster_with<CylindricalProjection, CappedGrid, C>(o, out, err);
      case IndexKind::overwrite: return run_cluster_with<CylindricalProjection, OverwriteGrid, C>(o, out, err);
    }
    return static_cast<int>(kUsage);
  });
}

}  // namespace streamclust::cli
