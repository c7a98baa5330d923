// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The driver of `streamclust cluster`, a template over the compiled
/// configuration: reads the input in chunks, offers the records to the
/// clusterer (StreamClusterer, or FrameClusterer in frame mode), retrieves
/// on the RetrievalSchedule and hands each labelled window to the outputs
/// (cli/cluster_outputs.hpp, compiled once). Included only by the
/// translation units that instantiate it (tools/cli/cluster_*.cpp).

#include "cli/cluster.hpp"
#include "cli/cluster_outputs.hpp"
#include "cli/engine_config.hpp"
#include "cli/memory_context.hpp"
#include "cli/options.hpp"
#include "cli/report.hpp"
#include "cli/structure_labels.hpp"

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/frame_clusterer.hpp>
#include <streamclust/io/error.hpp>
#include <streamclust/io/point_reader.hpp>
#include <streamclust/partition_compare.hpp>
#include <streamclust/retrieval_schedule.hpp>
#include <streamclust/stream_clusterer.hpp>
#include <streamclust/tracking/object_boxes.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>


namespace streamclust::cli {

/// Accumulates wall time [us] over the clusterer's calls of one cycle.
class CycleClock {
 public:
  template <class F>
  void time(F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    us_ += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  }
  /// The time so far, and a new start at zero.
  double take() {
    const double us = us_;
    us_ = 0.0;
    return us;
  }

 private:
  double us_ = 0.0;
};

/// run_cluster_with's work; `stage` follows it (reading, clustering, writing).
template <class Config, bool Frame>
int run_cluster_stages(const ClusterOptions& o, std::ostream& out, std::ostream& err, Stage& stage) {
  stage = Stage::clustering;
  using Engine = std::conditional_t<Frame, FrameClusterer<Config>, StreamClusterer<Config>>;
  std::unique_ptr<Engine> engine;
  std::unique_ptr<BatchClusterer<Config>> batch;  // --verify
  try {
    const ClustererParams<Config> params = make_params<Config>(o);
    engine = std::make_unique<Engine>(params);
    if (o.verify) batch = std::make_unique<BatchClusterer<Config>>(params, BatchMode::insertion_order);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }

  stage = Stage::reading;
  std::unique_ptr<io::PointReader> reader = open_cluster_input(o);
  ClusterOutputs outputs(o);
  Report report;
  report.cycles.keep_last(o.report_cycles_kept);
  report.input = o.input;
  report.format = io::to_string(reader->info().format);
  report.mode = Frame ? "frame" : "continuous";
  if constexpr (!Frame) {  // named from the engine's type: what ran, not what was asked
    report.connectivity = std::is_same_v<typename Config::connectivity, LazyBfsConnectivity> ? "lazy-bfs" : "forest";
    if (o.setup) {
      report.ground = o.setup->ground.use_height_map;
      report.motion = o.setup->motion.enabled;
      report.sensor_height = o.setup->ground.height_map.sensor_height;
      report.estimated_height = o.setup->estimated_height;
      report.estimated_mount = o.setup->estimated_mount;
      if (o.setup->estimate) {
        report.estimated_roll_deg = o.setup->estimate->roll_deg;
        report.estimated_pitch_deg = o.setup->estimate->pitch_deg;
      }
    }
  }

  RejectionCounts rejected_by_reason{};
  std::deque<std::uint64_t> rejected;  // stream indices of rejected records, ascending
  LabelledWindow window_out;  // the current cycle
  std::uint64_t records = 0;
  std::uint64_t cycle = 0;
  double first_time = 0.0, last_time = 0.0;
  RetrievalSchedule schedule(o.rate_hz);
  // The clusterer's time order, judged ahead of it: records whose time it
  // will reject (non-finite, backwards, a jump) do not move the schedule.
  StreamTimeOrder record_times(engine_time_order_params(o));
  std::uint64_t valid_times = 0;
  std::uint64_t inserted_since = 0;
  CycleClock clock;
  const bool progress = !o.quiet && !o.on_cycle && stderr_is_terminal();  // a watcher prints its own status
  auto last_progress = std::chrono::steady_clock::now();
  const auto declared = reader->info().declared_points;
  std::vector<std::uint64_t> index;
  std::vector<std::int64_t> label;
  std::vector<std::uint64_t> rows_index;  // object and structure rows, ascending
  std::vector<std::int64_t> rows_label;
  // --verify: the accepted records as offered (the batch places and projects
  // them as the engine did), from the window's oldest point on.
  std::deque<std::pair<std::uint64_t, io::Record>> offered_records;
  std::vector<io::Record> verify_input;
  double ground_seen_us = 0.0, placement_seen_us = 0.0;
  // The window's rows (labels, point clouds, the comparison of --verify) are
  // gathered only when an output needs them: copying a window per cycle
  // would evict the clusterer's data from the caches and slow the next cycle.
  const bool rows_wanted = !o.labels_path.empty() || !o.ply_path.empty() || !o.pcd_path.empty() ||
                           !o.mcap_path.empty() || !o.png_path.empty() || o.verify || o.cycle_windows;
  // --tracks: the boxes of the components of 10 points or more (the tracker's observations).
  std::optional<tracking::ObjectBoxes> boxes;
  if (outputs.tracking()) boxes.emplace(tracking::ObjectBoxParams{});
  report.tracking = outputs.tracking();
  const std::vector<io::Record> no_points;
  const std::vector<std::int64_t> no_labels;
  auto tracks_after = [&]() { return outputs.tracking() ? &outputs.tracks() : nullptr; };

  // Retrieves at `cycle_time`, then writes/keeps the outputs of a selected cycle.
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
    index.clear();
    label.clear();
    if constexpr (Frame) {
      const BatchResult* result = nullptr;
      double batch_us = 0.0;
      clock.time([&] {
        engine->advance_to(cycle_time);
        const auto b0 = std::chrono::steady_clock::now();
        result = &engine->retrieve();
        batch_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - b0).count();
      });
      c.batch_us = batch_us;
      c.retrieve_us = batch_us;
      c.components = result->components;
      c.window = engine->size();
      if (rows_wanted) {
        label = result->labels;
        engine->for_each_point([&](const Sample& s, std::uint64_t stream_index) {
          index.push_back(stream_index);
          window_out.points.push_back(
              io::Record{s.position.x(), s.position.y(), s.position.z(), s.intensity, s.time, -1});
        });
      }
    } else {
      const Clustering* result = nullptr;
      clock.time([&] {
        engine->advance_to(cycle_time);
        const auto r0 = std::chrono::steady_clock::now();
        result = &engine->retrieve();
        c.retrieve_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - r0).count();
      });
      if (boxes) {
        const auto k0 = std::chrono::steady_clock::now();
        outputs.track(boxes->update(*engine, *result), result->time);
        c.tracking_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - k0).count();
        outputs.write_tracks(cycle, cycle_time, reader->time_origin(), stage);
      }
      const RetrievalStats& s = engine->last_stats();
      c.evicted = s.evicted;
      c.components = result->components.size();
      c.window = result->points.size();
      c.structure = result->structure.size();
      c.ground_us = engine->ground().elapsed_us() - ground_seen_us;
      ground_seen_us += c.ground_us;
      c.placement_us = engine->motion().elapsed_us() - placement_seen_us;
      placement_seen_us += c.placement_us;
      if (rows_wanted) {
        for (const PointLabel& p : result->points) {
          index.push_back(p.stream_index);
          label.push_back(static_cast<std::int64_t>(p.label));
        }
        engine->for_each_point([&](const Sample& s2, std::uint64_t) {
          window_out.points.push_back(
              io::Record{s2.position.x(), s2.position.y(), s2.position.z(), s2.intensity, s2.time, -1});
        });
        if (batch) {
          // The records of the window's object points, as offered.
          const std::uint64_t oldest_in_window = std::min(
              index.empty() ? records : index.front(),
              result->structure.empty() ? records : result->structure.front().stream_index);
          while (!offered_records.empty() && offered_records.front().first < oldest_in_window) {
            offered_records.pop_front();
          }
          verify_input.clear();
          auto it = offered_records.begin();
          for (const std::uint64_t want : index) {
            while (it != offered_records.end() && it->first < want) ++it;
            if (it != offered_records.end() && it->first == want) verify_input.push_back(it->second);
          }
          batch->set_grid({engine->grid().rows, engine->grid().cols});
          const auto& reference = batch->cluster(verify_input);
          if (const auto m = first_partition_mismatch(label, reference.labels)) {
            const std::size_t i = std::min(m->position, index.empty() ? 0 : index.size() - 1);
            err << "streamclust: verify: cycle " << cycle << " (t = " << io::format_time(reader->time_origin(), cycle_time)
                << " s): point "
                << (index.empty() ? 0 : index[i]) << " has continuous label " << (label.empty() ? -1 : label[i])
                << " but the batch clusterer puts it with a different set of points (batch component "
                << (m->position < reference.labels.size() ? reference.labels[m->position] : -1) << ")\n";
            return kMismatch;
          }
        }
      }
    }
    c.inserted = inserted_since;
    inserted_since = 0;
    c.total_us = clock.take();
    if (!rows_wanted) {
      report.cycles.push_back(c);
      if (o.on_cycle) o.on_cycle(CycleView{c, no_points, no_labels, tracks_after()});
      ++cycle;
      return kOk;
    }
    window_out.point_labels = label;
    // The rows: object points (their component), structure points (-2
    // ground, -3 ceiling) and, below, rejected records (-1), by stream index.
    rows_index.clear();
    rows_label.clear();
    {
      std::size_t k = 0;
      auto take_objects_before = [&](std::uint64_t limit) {
        for (; k < index.size() && index[k] < limit; ++k) {
          rows_index.push_back(index[k]);
          rows_label.push_back(label[k]);
        }
      };
      if constexpr (!Frame) {
        engine->for_each_structure_point([&](const StructureEntry& e) {
          const std::int64_t code = structure_label(e.surface);
          take_objects_before(e.stream_index);
          rows_index.push_back(e.stream_index);
          rows_label.push_back(code);
          window_out.points.push_back(io::Record{e.world.x(), e.world.y(), e.world.z(), 0.0f, e.time, -1});
          window_out.point_labels.push_back(code);
        });
      }
      take_objects_before(std::numeric_limits<std::uint64_t>::max());
    }
    // Rejected records inside the window's span of stream indices: -1.
    const std::uint64_t oldest = rows_index.empty() ? records : rows_index.front();
    while (!rejected.empty() && rejected.front() < oldest) rejected.pop_front();
    std::size_t i = 0, j = 0;
    while (i < rows_index.size() || j < rejected.size()) {
      if (j == rejected.size() || (i < rows_index.size() && rows_index[i] < rejected[j])) {
        window_out.index.push_back(rows_index[i]);
        window_out.label.push_back(rows_label[i]);
        ++i;
      } else {
        window_out.index.push_back(rejected[j]);
        window_out.label.push_back(-1);
        ++j;
      }
    }
    report.cycles.push_back(c);
    if (o.on_cycle) {
      if (o.cycle_windows) {
        o.on_cycle(CycleView{c, window_out.points, window_out.point_labels, tracks_after()});
      } else {
        o.on_cycle(CycleView{c, no_points, no_labels, tracks_after()});
      }
    }
    outputs.on_window(window_out, reader->time_origin(), stage);
    ++cycle;
    return kOk;
  };

  std::vector<io::Record> chunk;
  std::vector<RejectReason> reasons;  // of the records being offered
  // Offers chunk[from, to) as one batch and books each record's outcome
  // under its stream index.
  auto offer_records = [&](std::size_t from, std::size_t to) {
    if (from == to) return;
    reasons.resize(to - from);
    const auto first = chunk.begin() + static_cast<std::ptrdiff_t>(from);
    const auto last = chunk.begin() + static_cast<std::ptrdiff_t>(to);
    clock.time([&] { engine->insert_batch(first, last, reasons.begin()); });
    for (std::size_t i = from; i < to; ++i) {
      const RejectReason reason = reasons[i - from];
      const std::uint64_t stream_index = records++;
      ++rejected_by_reason[reason];
      if (reason == RejectReason::accepted) {
        ++inserted_since;
        last_time = chunk[i].t;
        if (batch) offered_records.emplace_back(stream_index, chunk[i]);
      } else if (rows_wanted) {
        rejected.push_back(stream_index);
      }
    }
  };
  for (;;) {
    chunk.clear();
    stage = Stage::reading;
    if (reader->read(chunk, 65536) == 0) break;
    stage = Stage::clustering;
    std::size_t offered = 0;  // chunk[0, offered) went to the clusterer
    for (std::size_t i = 0; i < chunk.size(); ++i) {
      if (record_times.admit_time(chunk[i].t) != RejectReason::accepted) continue;
      ++valid_times;
      const bool started = schedule.started();
      const std::optional<double> due = schedule.on_record(chunk[i].t);
      if (!started && schedule.started()) first_time = schedule.first_time();
      if (!due) continue;
      // The records before this one first, then the retrieval.
      offer_records(offered, i);
      offered = i;
      // No cycle while the clusterer buffers its first window for the grid.
      clock.time([&] { engine->advance_to(*due); });
      if (engine->calibrating()) continue;
      const int code = run_cycle(*due);
      if (code != kOk) return code;
    }
    offer_records(offered, chunk.size());
    if (progress && std::chrono::steady_clock::now() - last_progress > std::chrono::milliseconds(250)) {
      last_progress = std::chrono::steady_clock::now();
      if (declared && *declared > 0) {
        const double f = std::min(1.0, static_cast<double>(records) / static_cast<double>(*declared));
        const int bar = static_cast<int>(f * 30.0);
        err << "\r[" << std::string(static_cast<std::size_t>(bar), '#')
            << std::string(static_cast<std::size_t>(30 - bar), '.') << "] " << static_cast<int>(f * 100.0) << "%  "
            << records << " points" << std::flush;
      } else {
        err << "\r" << records << " points, t = " << last_time - first_time << " s" << std::flush;
      }
    }
  }
  if (progress) err << "\r" << std::string(60, ' ') << "\r";
  if (records == 0)
    throw io::InputError(o.input, "header", "no points: nothing to cluster (info describes such an input)");
  if (valid_times == 0) {
    throw io::InputError(o.input, "record 0", "no record has a usable time: expected finite times within +-9e9 s of "
                                              "the stream's origin (" + std::to_string(records) + " records read)");
  }
  stage = Stage::clustering;
  // The final cycle covers the points after the last scheduled retrieval
  // (and, for an input shorter than one window, ends the calibration).
  clock.time([&] { engine->complete_calibration(); });
  if (inserted_since > 0 || cycle == 0) {
    const int code = run_cycle(schedule.started() ? std::max(last_time, first_time) : 0.0);
    if (code != kOk) return code;
  }

  report.grid_rows = engine->grid().rows;
  report.grid_cols = engine->grid().cols;
  report.grid_wraps = engine->grid().wrap_columns;
  report.adaptive = engine->resolution().adaptive();
  report.trace = engine->resolution().trace();
  report.stop = engine->resolution().stop_reason();
  report.records = records;
  report.time_origin = reader->time_origin();  // found with the first timed record unless the options fix it
  report.rejections = rejected_by_reason;
  outputs.finish(report, reader->time_origin(), out, stage);
  return kOk;
}

/// Runs `streamclust cluster` on the compiled configuration `Config`,
/// continuously (StreamClusterer) or, with `Frame`, re-clustering each
/// window from scratch (FrameClusterer). Returns the exit code; throws
/// io::InputError (exit 4), UsageError (exit 2) and OutOfMemory (exit 5,
/// naming the stage).
template <class Config, bool Frame>
int run_cluster_with(const ClusterOptions& o, std::ostream& out, std::ostream& err) {
  return with_memory_context("cluster", o.input,
                             [&](Stage& stage) { return run_cluster_stages<Config, Frame>(o, out, err, stage); });
}

/// Dispatches on index, window, mode and connectivity for one projection
/// and linkage.
template <class Projection, class Linkage>
int run_cluster_for(const ClusterOptions& o, std::ostream& out, std::ostream& err) {
  if (o.mode == Mode::frame) {
    return with_engine_config<true, Projection, Linkage>(o, [&](auto config) {
      return run_cluster_with<typename decltype(config)::type, true>(o, out, err);
    });
  }
  return with_engine_config<false, Projection, Linkage>(o, [&](auto config) {
    return run_cluster_with<typename decltype(config)::type, false>(o, out, err);
  });
}

}  // namespace streamclust::cli

/// The translation unit of `streamclust cluster` for one projection and
/// linkage (every index, window, mode and connectivity of the registry).
#define STREAMCLUST_INSTANTIATE_CLUSTER(Projection, Linkage)                                    \
  template int streamclust::cli::run_cluster_for<Projection, Linkage>(                           \
      const streamclust::cli::ClusterOptions&, std::ostream&, std::ostream&)
