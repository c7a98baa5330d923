// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust evaluate`: simulates a scenario with ground truth, clusters
/// it with C-ARC (the continuous engine on a bucket or capped grid) and/or the
/// frame baseline (Bogoslavskyi & Stachniss' overwrite range image, the batch
/// clusterer in range-image mode on each window), both on the grid the
/// adaptive loop chooses from the first window, and scores every retrieval
/// against the ground truth (streamclust::eval). Definitions and results:
/// docs/evaluation.md.

#include "cli/engine_config.hpp"
#include "cli/json.hpp"
#include "cli/options.hpp"
#include "cli/simulate.hpp"

#include <streamclust/acceptance.hpp>
#include <streamclust/eval/average.hpp>
#include <streamclust/eval/labelled_subset.hpp>
#include <streamclust/eval/recovery.hpp>
#include <streamclust/eval/report.hpp>
#include <streamclust/grid_choice.hpp>
#include <streamclust/retrieval_schedule.hpp>
#include <streamclust/resolution/runtime_resolution.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::cli {

/// How the baseline publishes: re-clustering the current window at every
/// retrieval (sliding: the same windows as C-ARC, isolating the index), or
/// clustering non-overlapping frames of T_B and holding the last result in
/// between (tumbling: what a frame-based driver publishes).
enum class FrameSchedule { sliding, tumbling };

/// Everything `streamclust evaluate` needs.
struct EvaluateOptions {
  SimulateOptions scenario;  ///< sensor, scene, duration, seed, ego-motion, burst, noise, dropout
  ClusterOptions policy;     ///< linkage, theta, distances, mask, window, rate, index, grid, T_M, FOV
  bool run_carc = true;
  bool run_baseline = true;
  FrameSchedule frames = FrameSchedule::sliding;
  std::size_t min_points = 10;  ///< eval::MetricOptions::min_points
  /// Oracle structure removal: drop the ground-truth structure points
  /// (ground, walls, ceiling, facades: instance 0) before clustering, as a
  /// pipeline with a perfect ground/wall segmentation would.
  bool drop_structure = false;
  std::string json_path, series_path;
  bool quiet = false;
};

/// The field of view of each simulated sensor (degrees), used unless
/// --fov-azimuth / --fov-elevation override it: the Livox sensors' from
/// <streamclust/sensors.hpp> (a margin of kFieldOfViewMarginDeg keeps every
/// simulated ray inside). The spinning sensor's FOV is shifted so
/// that its natural grid (--grid 32x1800: one row per beam, one column per
/// firing column) has a firing direction at the centre of every cell: its
/// 32 beams span -25..15 deg (1.29 deg apart), so rows of 41.29 / 32 deg from
/// -25.645 deg; its columns are 0.2 deg apart from azimuth 0, so the azimuth
/// range starts half a column early (-180.1 .. 179.9 deg). On cell edges
/// instead, rounding puts two firing columns in one cell and none in the
/// next, an artefact that costs the overwrite grid ~18 % of its points.
inline void apply_sensor_fov(const std::string& sensor, ClusterOptions& o) {
  struct Fov {
    const char* name;
    float az_min, az_max, el_min, el_max;
  };
  static constexpr Fov kFov[] = {{"mid360", livox_mid360.projection_azimuth_min_deg(), livox_mid360.projection_azimuth_max_deg(), livox_mid360.projection_elevation_min_deg(), livox_mid360.projection_elevation_max_deg()},
                                 {"mid40", livox_mid40.projection_azimuth_min_deg(), livox_mid40.projection_azimuth_max_deg(), livox_mid40.projection_elevation_min_deg(), livox_mid40.projection_elevation_max_deg()},
                                 {"mid70", livox_mid70.projection_azimuth_min_deg(), livox_mid70.projection_azimuth_max_deg(), livox_mid70.projection_elevation_min_deg(), livox_mid70.projection_elevation_max_deg()},
                                 {"avia", livox_avia.projection_azimuth_min_deg(), livox_avia.projection_azimuth_max_deg(), livox_avia.projection_elevation_min_deg(), livox_avia.projection_elevation_max_deg()},
                                 {"spinning32", -180.1f, 179.9f, -25.645f, 15.645f}};
  for (const Fov& f : kFov) {
    if (sensor == f.name) {
      o.azimuth_min = f.az_min;
      o.azimuth_max = f.az_max;
      o.elevation_min = f.el_min;
      o.elevation_max = f.el_max;
    }
  }
}

inline EvaluateOptions parse_evaluate_options(const std::vector<std::string>& args) {
  EvaluateOptions o;
  o.scenario.seconds = 2.0;
  o.policy.mask = 3;  // the paper's comparison: w = 3 for both methods
  // The sensor's FOV applies first, wherever --sensor stands; --fov-* override it.
  for (std::size_t i = 0; i + 1 < args.size(); ++i) {
    if (args[i] == "--sensor") o.scenario.sensor = args[i + 1];
  }
  apply_sensor_fov(o.scenario.sensor, o.policy);
  for (ArgCursor c(args); !c.done(); c.next()) {
    const std::string& a = c.option();
    if (parse_simulation_option(c, o.scenario) || parse_policy_option(c, o.policy)) continue;
    if (a == "--method") {
      const std::string v = c.choice({"carc", "baseline", "both"});
      o.run_carc = v != "baseline";
      o.run_baseline = v != "carc";
    } else if (a == "--frames") {
      o.frames = c.choice({"sliding", "tumbling"}) == "sliding" ? FrameSchedule::sliding : FrameSchedule::tumbling;
    } else if (a == "--structure") {
      o.drop_structure = c.choice({"keep", "drop"}) == "drop";
    } else if (a == "--min-points") {
      o.min_points = static_cast<std::size_t>(parse_count(a, c.value()));
    } else if (a == "--json") {
      o.json_path = c.value();
    } else if (a == "--series") {
      o.series_path = c.value();
    } else if (a == "--quiet" || a == "-q") {
      o.quiet = true;
    } else {
      throw UsageError("unknown option '" + a + "' (see streamclust evaluate --help)");
    }
  }
  validate_simulation_options(o.scenario);
  validate_policy_options(o.policy);
  if (o.scenario.sensor == "synthetic") {
    throw UsageError("--sensor: evaluate needs a simulated sensor (mid360|mid40|mid70|avia|spinning32)");
  }
  if (o.policy.index == "overwrite") {
    throw UsageError("--index: C-ARC runs on bucket|capped; the overwrite grid is the baseline (--method baseline)");
  }
  if (!(o.policy.window_seconds > 0.0)) throw UsageError("--window-time: expected a window T_B > 0 s");
  const double period = 1.0 / o.policy.rate_hz;
  if (o.scenario.seconds < o.policy.window_seconds + period) {
    throw UsageError("--duration: at least one retrieval after the first window is needed: expected >= T_B + 1/rate = " +
                     std::to_string(o.policy.window_seconds + period) + " s, got " +
                     std::to_string(o.scenario.seconds) + " s");
  }
  return o;
}

/// One scored retrieval.
struct CycleQuality {
  double time = 0.0;        ///< scheduled stream time of the retrieval [s]
  std::size_t window = 0;   ///< points in the window (clustered or lost)
  double cost_us = 0.0;     ///< clustering work for this retrieval [us] (C-ARC: inserts, evictions and retrieval since the previous one; baseline: the batch run, 0 for a held frame)
  eval::MeanQuality quality;
  /// The metrics on the points the baseline labelled in this window (both
  /// methods scored on the same subset; empty unless both methods run).
  std::optional<eval::MeanQuality> on_labelled;
};

/// The recovery of the methods' metrics after an ego-motion burst.
struct BurstRecovery {
  eval::Recovery use;    ///< under-segmentation entropy (TRAVEL's sum over clusters)
  eval::Recovery under;  ///< fraction of objects under-segmented
  eval::Recovery ari;    ///< 1 - ARI (an error, higher = worse)
};

struct MethodResult {
  std::string name;  ///< "carc" or "baseline"
  std::vector<CycleQuality> cycles;
  eval::MeanQuality mean;
  std::optional<eval::MeanQuality> mean_on_labelled;  ///< mean of CycleQuality::on_labelled, when every cycle has it
  double cost_median_us = 0.0;
  std::optional<BurstRecovery> recovery;
};

struct GridChoice {
  GridSize grid{};
  bool adaptive = true;
  float mean_multiplicity = 0.0f;  ///< of the chosen grid on the first window (adaptive only)
  std::vector<AdaptiveStep> trace;
};

struct Evaluation {
  std::size_t records = 0;
  GridChoice grid;
  std::vector<MethodResult> methods;
};

/// The grid for both methods: --grid if given, else the adaptive loop's
/// choice on the first window, exactly as a calibrating engine makes it
/// (acceptance.hpp's rule, then grid_choice.hpp's FirstWindow: the accepted
/// points before the first one at or after T_B from the first). Computed
/// here rather than by an engine so that both methods share it and the
/// adaptive loop's trace can be reported.
inline GridChoice choose_grid(const EvaluateOptions& o, const std::vector<io::Record>& records) {
  GridChoice g;
  if (o.policy.grid) {
    g.adaptive = false;
    g.grid = GridSize{o.policy.grid->first, o.policy.grid->second};
    return g;
  }
  using Config = CliConfig<SphericalProjection, BucketGrid, AngularLinkage, TimeWindow>;
  ClusterOptions c = o.policy;
  c.grid.reset();
  const ClustererParams<Config> params = make_params<Config>(c);
  const SphericalProjection projection(params.projection);
  const TimeWindow window(params.window);
  FirstWindow<TimeWindow> first_window(window);
  StreamTimeOrder order;
  for (const io::Record& r : records) {
    const Projected pr = projection.project(Eigen::Vector3f(r.x, r.y, r.z));
    if (order.admit(pr, r.t) != RejectReason::accepted) continue;
    if (first_window.offer(pr, r.t)) break;
  }
  if (!first_window.complete()) {
    throw UsageError("the simulated stream does not fill one window (--window-time, --duration)");
  }
  RuntimeResolution resolution(params.resolution);
  const GridShape grid = ::streamclust::choose_grid(resolution, projection, first_window.points());
  g.grid = GridSize{grid.rows, grid.cols};
  g.trace = resolution.trace();
  for (const AdaptiveStep& s : g.trace) {
    if (s.grid == g.grid) g.mean_multiplicity = s.mean_multiplicity;
  }
  return g;
}

/// Drives the retrieval schedule of `cluster` (RetrievalSchedule: t0 + k /
/// rate) over the records: `insert(record, index)` for each,
/// `retrieve(time)` before the first record at or after each scheduled time.
template <class Insert, class Retrieve>
void run_schedule(const std::vector<io::Record>& records, double rate_hz, Insert&& insert, Retrieve&& retrieve) {
  RetrievalSchedule schedule(rate_hz);
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (const auto due = schedule.on_record(records[i].t)) retrieve(*due);
    insert(records[i], i);
  }
}

/// Scores one window: `truth` from the records' labels, `predicted` as given.
inline eval::MeanQuality score_window(const std::vector<std::int64_t>& truth, const std::vector<std::int64_t>& predicted,
                                      std::size_t min_points) {
  eval::MetricOptions m;
  m.min_points = min_points;
  return eval::to_mean_quality(eval::evaluate(truth, predicted, m));
}

/// The stream indices of the points the baseline labelled, one sorted list
/// per evaluated retrieval (in order): the subset on which both methods get
/// their `on_labelled` scores.
using LabelledSets = std::vector<std::vector<std::size_t>>;

/// Scores one window on the points `reference` labelled (>= 0).
inline eval::MeanQuality score_labelled(const std::vector<std::int64_t>& truth, const std::vector<std::int64_t>& predicted,
                                        const std::vector<std::int64_t>& reference, std::size_t min_points) {
  eval::MetricOptions m;
  m.min_points = min_points;
  return eval::to_mean_quality(eval::evaluate_on_labelled(truth, predicted, reference, m));
}

/// True when a retrieval at `time` sees a full window (the first window is skipped).
inline bool window_is_full(double time, double first_time, double window_seconds) {
  return time - first_time >= window_seconds - 1e-9;
}

/// Runs the whole evaluation of a scenario on its simulated records
/// (tools/cli/evaluate.cpp: the methods' compiled configurations).
Evaluation evaluate_records(const EvaluateOptions& o, const std::vector<io::Record>& records);

/// The metric names of MeanQuality, in kMeanQualityFields order.
inline const char* const* mean_quality_names() {
  static const char* const kNames[] = {"points",   "object_points",   "objects",        "ari",
                                       "ose",      "use",             "ose_mean",       "use_mean",
                                       "precision", "recall",         "sq",             "rq",
                                       "pq",       "coverage",        "object_coverage", "correct",
                                       "over_segmented", "under_segmented", "missed"};
  static_assert(sizeof(kNames) / sizeof(kNames[0]) == sizeof(eval::kMeanQualityFields) / sizeof(eval::kMeanQualityFields[0]),
                "one name per MeanQuality field");
  return kNames;
}

inline Json json_quality(const eval::MeanQuality& q) {
  Json j = Json::object();
  const char* const* names = mean_quality_names();
  std::size_t k = 0;
  for (const auto field : eval::kMeanQualityFields) j[names[k++]] = q.*field;
  return j;
}

inline Json json_recovery(const eval::Recovery& r) {
  return {{"before", r.before},
          {"peak", r.peak},
          {"settled", r.settled},
          {"threshold", r.threshold},
          {"time", r.time ? Json(*r.time) : Json(nullptr)}};
}

/// The evaluation as a JSON document (docs/cli.md); one retrieval per line.
inline Json evaluation_json(const EvaluateOptions& o, const Evaluation& e) {
  const SimulateOptions& s = o.scenario;
  const ClusterOptions& p = o.policy;
  Json doc;
  doc["scenario"] = {{"sensor", s.sensor},
                     {"scene", s.scene},
                     {"seconds", s.seconds},
                     {"seed", s.seed},
                     {"speed", s.speed},
                     {"yaw_rate", s.yaw_rate},
                     {"noise", s.noise},
                     {"dropout", s.dropout},
                     {"max_range", s.max_range},
                     {"burst", s.burst_length > 0.0 ? Json{{"start", s.burst_start},
                                                           {"length", s.burst_length},
                                                           {"speed", s.burst_speed},
                                                           {"yaw_rate", s.burst_yaw_rate}}
                                                     : Json(nullptr)}};
  doc["policy"] = {{"linkage", p.linkage},
                   {"mask", p.mask},
                   {"window_time", p.window_seconds},
                   {"rate", p.rate_hz},
                   {"index", p.index},
                   {"connectivity", p.connectivity},
                   {"multiplicity", p.max_multiplicity},
                   {"frames", o.frames == FrameSchedule::sliding ? "sliding" : "tumbling"},
                   {"min_points", o.min_points},
                   {"structure", o.drop_structure ? "drop" : "keep"}};
  // every registered policy option by its key (theta_deg, distance, cap, ...)
  for (const registry::OptionValue& v : ToolRegistry::values_of(p.params)) {
    doc["policy"][v.key] = v.integral ? Json(static_cast<std::int64_t>(v.value)) : Json(v.value);
  }
  doc["records"] = e.records;
  doc["grid"] = {{"rows", e.grid.grid.rows},
                 {"cols", e.grid.grid.cols},
                 {"adaptive", e.grid.adaptive},
                 {"mean_multiplicity", e.grid.mean_multiplicity},
                 {"iterations", e.grid.trace.size()}};
  Json methods = Json::array();
  for (const MethodResult& m : e.methods) {
    Json method;
    method["name"] = m.name;
    method["cycles_evaluated"] = m.cycles.size();
    method["cycle_cost_median_us"] = m.cost_median_us;
    method["mean"] = json_quality(m.mean);
    method["mean_on_baseline_labelled"] = m.mean_on_labelled ? json_quality(*m.mean_on_labelled) : Json(nullptr);
    method["recovery"] = m.recovery ? Json{{"use", json_recovery(m.recovery->use)},
                                           {"under_segmented", json_recovery(m.recovery->under)},
                                           {"ari_error", json_recovery(m.recovery->ari)}}
                                    : Json(nullptr);
    Json cycles = Json::array();
    for (const CycleQuality& q : m.cycles) {
      cycles.push_back({{"time", q.time},
                        {"window", q.window},
                        {"cost_us", q.cost_us},
                        {"ari_labelled", q.on_labelled ? Json(q.on_labelled->ari) : Json(nullptr)},
                        {"pq_labelled", q.on_labelled ? Json(q.on_labelled->pq) : Json(nullptr)},
                        {"quality", json_quality(q.quality)}});
    }
    method["cycles"] = std::move(cycles);
    methods.push_back(std::move(method));
  }
  doc["methods"] = std::move(methods);
  return doc;
}

/// Per-retrieval metrics as CSV (one row per method and retrieval).
inline void write_series_csv(std::ostream& out, const Evaluation& e) {
  out << "method,time,window";
  const char* const* names = mean_quality_names();
  for (std::size_t k = 0; k < sizeof(eval::kMeanQualityFields) / sizeof(eval::kMeanQualityFields[0]); ++k) {
    out << ',' << names[k];
  }
  out << '\n';
  out.precision(6);
  for (const MethodResult& m : e.methods) {
    for (const CycleQuality& q : m.cycles) {
      out << m.name << ',' << q.time << ',' << q.window;
      for (const auto field : eval::kMeanQualityFields) out << ',' << q.quality.*field;
      out << '\n';
    }
  }
}

inline void write_text_file(const std::string& option, const std::string& path,
                            const std::function<void(std::ostream&)>& write) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error(option + ": cannot write '" + path + "'");
  write(f);
  f.flush();
  if (!f) throw std::runtime_error(option + ": writing '" + path + "' failed");
}

/// The human-readable table.
inline void print_evaluation(std::ostream& out, const EvaluateOptions& o, const Evaluation& e) {
  const SimulateOptions& s = o.scenario;
  const ClusterOptions& p = o.policy;
  char line[160];
  out << "streamclust evaluate: sensor " << s.sensor << ", scene " << s.scene << ", " << s.seconds << " s, seed "
      << s.seed << ", " << e.records << " points" << (o.drop_structure ? " (structure dropped)" : "") << "\n";
  if (e.grid.adaptive) {
    std::snprintf(line, sizeof line, "grid %ux%u (adaptive loop, T_M %.3g: mean multiplicity %.2f after %zu iterations)",
                  e.grid.grid.rows, e.grid.grid.cols, static_cast<double>(p.max_multiplicity),
                  static_cast<double>(e.grid.mean_multiplicity), e.grid.trace.size());
  } else {
    std::snprintf(line, sizeof line, "grid %ux%u (given)", e.grid.grid.rows, e.grid.grid.cols);
  }
  out << line << "\n";
  std::snprintf(line, sizeof line, "linkage %s, mask %d, window %.3g s, retrievals %.3g Hz",
                ToolRegistry::describe(Slot::linkage, p.linkage, p.params).c_str(), p.mask, p.window_seconds, p.rate_hz);
  out << line << "\n";
  if (s.burst_length > 0.0) {
    std::snprintf(line, sizeof line, "ego-motion burst at %.3g s for %.3g s: %.3g m/s, %.3g rad/s", s.burst_start,
                  s.burst_length, static_cast<double>(s.burst_speed), static_cast<double>(s.burst_yaw_rate));
    out << line << "\n";
  }
  out << "\n";
  std::snprintf(line, sizeof line, "%-28s", "mean over retrievals");
  out << line;
  for (const MethodResult& m : e.methods) {
    std::snprintf(line, sizeof line, "%12s", m.name == "baseline" && o.frames == FrameSchedule::tumbling
                                                 ? "baseline(t)"
                                                 : m.name.c_str());
    out << line;
  }
  out << "\n";
  struct Row {
    const char* label;
    double eval::MeanQuality::*field;
  };
  static const Row kRows[] = {{"ARI (object points)", &eval::MeanQuality::ari},
                              {"OSE per object", &eval::MeanQuality::ose_mean},
                              {"USE per cluster", &eval::MeanQuality::use_mean},
                              {"PQ", &eval::MeanQuality::pq},
                              {"precision", &eval::MeanQuality::precision},
                              {"recall", &eval::MeanQuality::recall},
                              {"coverage (all points)", &eval::MeanQuality::coverage},
                              {"coverage (object points)", &eval::MeanQuality::object_coverage},
                              {"objects correct", &eval::MeanQuality::correct},
                              {"objects over-segmented", &eval::MeanQuality::over_segmented},
                              {"objects under-segmented", &eval::MeanQuality::under_segmented},
                              {"objects missed", &eval::MeanQuality::missed},
                              {"objects rated", &eval::MeanQuality::objects},
                              {"points per window", &eval::MeanQuality::points}};
  for (const Row& r : kRows) {
    std::snprintf(line, sizeof line, "%-28s", r.label);
    out << line;
    for (const MethodResult& m : e.methods) {
      std::snprintf(line, sizeof line, "%12.3f", m.mean.*(r.field));
      out << line;
    }
    out << "\n";
  }
  // Both methods on the points the baseline labelled (its losses excluded).
  static const Row kLabelledRows[] = {{"ARI, baseline-labelled pts", &eval::MeanQuality::ari},
                                      {"PQ, baseline-labelled pts", &eval::MeanQuality::pq},
                                      {"under-seg, baseline-labelled", &eval::MeanQuality::under_segmented},
                                      {"baseline-labelled points", &eval::MeanQuality::points}};
  bool labelled = !e.methods.empty();
  for (const MethodResult& m : e.methods) labelled = labelled && m.mean_on_labelled.has_value();
  for (const Row& r : kLabelledRows) {
    if (!labelled) break;
    std::snprintf(line, sizeof line, "%-28s", r.label);
    out << line;
    for (const MethodResult& m : e.methods) {
      std::snprintf(line, sizeof line, "%12.3f", (*m.mean_on_labelled).*(r.field));
      out << line;
    }
    out << "\n";
  }
  std::snprintf(line, sizeof line, "%-28s", "retrievals evaluated");
  out << line;
  for (const MethodResult& m : e.methods) {
    std::snprintf(line, sizeof line, "%12zu", m.cycles.size());
    out << line;
  }
  out << "\n";
  std::snprintf(line, sizeof line, "%-28s", "cycle cost median [ms]");
  out << line;
  for (const MethodResult& m : e.methods) {
    std::snprintf(line, sizeof line, "%12.2f", m.cost_median_us / 1000.0);
    out << line;
  }
  out << "\n";
  bool any = false;
  for (const MethodResult& m : e.methods) any = any || m.recovery.has_value();
  if (!any) return;
  out << "\nrecovery after the burst (first retrieval from which the metric stays within 20 % of\n"
         "the way from its settled level to its peak; settled = mean from burst end + 3 T_B on)\n";
  for (const MethodResult& m : e.methods) {
    if (!m.recovery) continue;
    const auto row = [&](const char* what, const eval::Recovery& r) {
      std::snprintf(line, sizeof line, "  %-9s %-16s before %7.3f  peak %7.3f  settled %7.3f  recovery ", m.name.c_str(),
                    what, r.before, r.peak, r.settled);
      out << line;
      if (r.time) {
        std::snprintf(line, sizeof line, "%.3f s (%.2f T_B)", *r.time, *r.time / p.window_seconds);
        out << line << "\n";
      } else {
        out << "not within the run\n";
      }
    };
    row("USE", m.recovery->use);
    row("under-segmented", m.recovery->under);
    row("1 - ARI", m.recovery->ari);
  }
}

/// Runs `streamclust evaluate`. Returns the exit code; throws UsageError
/// (exit 2) and std::runtime_error for unwritable outputs (exit 4).
inline int run_evaluate(const EvaluateOptions& o, std::ostream& out) {
  std::vector<io::Record> records = simulate_records(o.scenario);
  if (o.drop_structure) {
    records.erase(std::remove_if(records.begin(), records.end(), [](const io::Record& r) { return r.label == 0; }),
                  records.end());
  }
  const Evaluation e = evaluate_records(o, records);
  if (!o.json_path.empty()) {
    write_json_file("--json", o.json_path, evaluation_json(o, e));
  }
  if (!o.series_path.empty()) {
    write_text_file("--series", o.series_path, [&](std::ostream& f) { write_series_csv(f, e); });
  }
  if (!o.quiet) print_evaluation(out, o, e);
  return kOk;
}

}  // namespace streamclust::cli
