// SPDX-License-Identifier: MIT
// `streamclust evaluate`: the two methods on their compiled configurations
// (C-ARC: the continuous engine on a bucket or capped grid; the baseline:
// the frame clusterer on the overwrite grid), each retrieval scored against
// the ground truth.

#include "cli/evaluate.hpp"

#include <streamclust/frame_clusterer.hpp>
#include <streamclust/percentiles.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <chrono>
#include <optional>
#include <utility>
#include <vector>

namespace streamclust::cli {
namespace {

/// C-ARC on `grid`; with `baseline_labelled` (one entry per evaluated
/// retrieval, from run_baseline_method) each retrieval is also scored on the
/// points the baseline labelled.
template <class Config>
MethodResult run_carc_method(const EvaluateOptions& o, const std::vector<io::Record>& records, GridSize grid,
                             const LabelledSets* baseline_labelled) {
  ClusterOptions c = o.policy;
  c.grid = std::make_pair(grid.rows, grid.cols);
  if (!c.setup) c.setup = sensor_fit_setup(c, records);  // a linkage fitted to the sensor: to the first window
  StreamClusterer<Config> engine(make_params<Config>(c));
  MethodResult m;
  m.name = "carc";
  std::vector<std::int64_t> truth, predicted, reference;
  std::vector<char> labelled_by_baseline(baseline_labelled ? records.size() : 0, 0);
  const double first = records.empty() ? 0.0 : records.front().t;
  // The engine's work since the previous cycle [us] (wall time of its calls).
  double cost_us = 0.0;
  const auto timed = [&cost_us](auto&& call) {
    const auto t0 = std::chrono::steady_clock::now();
    call();
    cost_us += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  };
  run_schedule(
      records, o.policy.rate_hz, [&](const io::Record& r, std::size_t) { timed([&] { engine.insert(r, r.t); }); },
      [&](double time) {
        const Clustering* retrieved = nullptr;
        timed([&] {
          engine.advance_to(time);
          retrieved = &engine.retrieve();
        });
        const Clustering& result = *retrieved;
        const double cycle_cost_us = cost_us;
        cost_us = 0.0;
        if (!window_is_full(time, first, o.policy.window_seconds)) return;
        truth.clear();
        predicted.clear();
        for (const PointLabel& pl : result.points) {
          truth.push_back(records[pl.stream_index].label);
          predicted.push_back(static_cast<std::int64_t>(pl.label));
        }
        CycleQuality q;
        q.time = time;
        q.window = result.points.size();
        q.cost_us = cycle_cost_us;
        q.quality = score_window(truth, predicted, o.min_points);
        if (baseline_labelled && m.cycles.size() < baseline_labelled->size()) {
          const std::vector<std::size_t>& kept = (*baseline_labelled)[m.cycles.size()];
          for (const std::size_t i : kept) labelled_by_baseline[i] = 1;
          reference.clear();
          for (const PointLabel& pl : result.points) reference.push_back(labelled_by_baseline[pl.stream_index] ? 0 : -1);
          for (const std::size_t i : kept) labelled_by_baseline[i] = 0;
          q.on_labelled = score_labelled(truth, predicted, reference, o.min_points);
        }
        m.cycles.push_back(q);
      });
  return m;
}

/// The overwrite frame baseline on `grid`; with `labelled` it is scored on
/// its own labelled points too, and the stream indices of those points are
/// appended for each evaluated retrieval (for run_carc_method).
template <class Linkage>
MethodResult run_baseline_method(const EvaluateOptions& o, const std::vector<io::Record>& records, GridSize grid,
                                 LabelledSets* labelled) {
  using Config = CliConfig<SphericalProjection, OverwriteGrid, Linkage, TimeWindow>;
  ClusterOptions c = o.policy;
  c.grid = std::make_pair(grid.rows, grid.cols);
  if (!c.setup) c.setup = sensor_fit_setup(c, records);
  FrameClusterer<Config> frame(make_params<Config>(c), BatchMode::range_image);
  MethodResult m;
  m.name = "baseline";
  std::vector<std::int64_t> truth;
  std::vector<std::size_t> indices;
  const double first = records.empty() ? 0.0 : records.front().t;
  std::optional<double> last_frame;
  run_schedule(
      records, o.policy.rate_hz, [&](const io::Record& r, std::size_t) { frame.insert(r, r.t); },
      [&](double time) {
        frame.advance_to(time);
        if (!window_is_full(time, first, o.policy.window_seconds)) return;
        CycleQuality q;
        q.time = time;
        if (o.frames == FrameSchedule::tumbling && last_frame && time - *last_frame < o.policy.window_seconds - 1e-9) {
          // A frame-based driver still shows the last frame it published.
          q.window = m.cycles.back().window;
          q.quality = m.cycles.back().quality;
          q.on_labelled = m.cycles.back().on_labelled;
          if (labelled) labelled->push_back(labelled->back());
          m.cycles.push_back(q);
          return;
        }
        last_frame = time;
        truth.clear();
        indices.clear();
        frame.for_each_point([&](const Sample&, std::uint64_t stream_index) {
          truth.push_back(records[stream_index].label);
          indices.push_back(static_cast<std::size_t>(stream_index));
        });
        const auto t0 = std::chrono::steady_clock::now();
        const BatchResult& r = frame.retrieve();
        q.cost_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
        q.window = indices.size();
        q.quality = score_window(truth, r.labels, o.min_points);
        if (labelled) {
          q.on_labelled = score_labelled(truth, r.labels, r.labels, o.min_points);
          std::vector<std::size_t> kept;
          for (std::size_t k = 0; k < indices.size(); ++k) {
            if (r.labels[k] >= 0) kept.push_back(indices[k]);
          }
          labelled->push_back(std::move(kept));
        }
        m.cycles.push_back(q);
      });
  return m;
}

/// Mean, median cost and (with a burst) the recovery of one method's cycles.
void summarize_method(const EvaluateOptions& o, MethodResult& m) {
  eval::QualityAverage average, on_labelled;
  std::vector<double> costs;
  for (const CycleQuality& q : m.cycles) {
    average.add(q.quality);
    if (q.on_labelled) on_labelled.add(*q.on_labelled);
    if (q.cost_us > 0.0) costs.push_back(q.cost_us);
  }
  m.mean = average.mean();
  if (!m.cycles.empty() && on_labelled.frames() == m.cycles.size()) m.mean_on_labelled = on_labelled.mean();
  m.cost_median_us = percentile(costs, 50.0);
  const SimulateOptions& s = o.scenario;
  if (s.burst_length <= 0.0 || m.cycles.empty()) return;
  const double event_start = s.burst_start;
  const double event_end = s.burst_start + s.burst_length;
  const double settle_from = event_end + 3.0 * o.policy.window_seconds;
  std::vector<double> times, use, under, ari_error;
  std::size_t settled = 0;
  for (const CycleQuality& q : m.cycles) {
    times.push_back(q.time);
    use.push_back(q.quality.use);
    under.push_back(q.quality.under_segmented);
    ari_error.push_back(1.0 - q.quality.ari);
    settled += q.time >= settle_from ? 1u : 0u;
  }
  if (settled < 3) return;  // too short to know the settled level
  m.recovery = BurstRecovery{eval::recovery_after(times, use, event_start, event_end, settle_from),
                             eval::recovery_after(times, under, event_start, event_end, settle_from),
                             eval::recovery_after(times, ari_error, event_start, event_end, settle_from)};
}

}  // namespace

/// Runs the whole evaluation of a scenario on its simulated records.
Evaluation evaluate_records(const EvaluateOptions& o, const std::vector<io::Record>& records) {
  Evaluation e;
  e.records = records.size();
  try {
    e.grid = choose_grid(o, records);
    // With both methods, the baseline runs first and records the points it
    // labels, so that C-ARC is also scored on that subset.
    LabelledSets labelled;
    const bool both = o.run_carc && o.run_baseline;
    std::optional<MethodResult> baseline;
    // Calls f(TypeTag<Linkage>{}) with the linkage the options name (any registered one).
    const auto with_linkage = [&](auto&& f) { return ToolRegistry::with_policy<Slot::linkage>(o.policy.linkage, f); };
    if (o.run_baseline) {
      LabelledSets* sets = both ? &labelled : nullptr;
      baseline = with_linkage([&](auto linkage) {
        return run_baseline_method<typename decltype(linkage)::type>(o, records, e.grid.grid, sets);
      });
    }
    if (o.run_carc) {
      const LabelledSets* sets = both ? &labelled : nullptr;
      ClusterOptions policy = o.policy;
      policy.window_is_count = false;
      const auto run = [&](auto config) { return run_carc_method<typename decltype(config)::type>(o, records, e.grid.grid, sets); };
      e.methods.push_back(with_linkage([&](auto linkage) {
        return with_engine_config<false, SphericalProjection, typename decltype(linkage)::type>(policy, run);
      }));
    }
    if (baseline) e.methods.push_back(std::move(*baseline));
  } catch (const std::invalid_argument& ex) {
    throw UsageError(ex.what());
  }
  for (MethodResult& m : e.methods) summarize_method(o, m);
  return e;
}


}  // namespace streamclust::cli
