// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// ScheduledRun: the CLI driver's retrieval schedule (tools/cli/cluster_driver.hpp)
/// over points given in chunks: retrievals at t0 + k / rate of stream time,
/// none while the engine buffers its first window for the grid, and one
/// more after the last point. Cycle k is the CLI's cycle k on the same
/// stream, however the stream is cut into chunks: at each due time the
/// engine holds exactly the points before the one that made it due.
/// `cluster_stream` feeds one chunk; a live source feeds each chunk as it
/// arrives.
///
/// With `tracks`, each cycle also fits the objects' boxes and updates a
/// KalmanTracker (continuous mode only), as `cluster --tracks`.
///
/// Not thread-safe (one caller at a time; the GIL need not be held).

#include "window_rows.hpp"

#include "cli/engine_config.hpp"
#include "cli/options.hpp"

#include <streamclust/retrieval_schedule.hpp>
#include <streamclust/acceptance.hpp>
#include <streamclust/tracking/kalman_tracker.hpp>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

namespace streamclust::python {

class ScheduledRun {
 public:
  /// `o` resolved (resolve_setup); retrievals at `o.rate_hz`. Throws
  /// std::invalid_argument for `tracks` with the frame mode.
  explicit ScheduledRun(const cli::ClusterOptions& o, bool tracks = false)
      : session_(make_erased_clusterer(o)), schedule_(o.rate_hz), record_times_(cli::engine_time_order_params(o)) {
    if (!tracks) return;
    if (!session_.engine().continuous()) {
      throw std::invalid_argument(
          "tracks: tracking follows the continuous engine's components; not with mode=\"frame\"");
    }
    tracker_.emplace();
  }

  /// Offers `points` (the stream's next ones, in order) and runs the cycles
  /// they make due: `on_cycle(cycle, time, rows, result, tracks)` for each
  /// (`tracks`: the tracker's tracks, null without tracking).
  /// O(points) plus the cycles' work.
  template <class OnCycle>
  void feed(const PointBuffers& points, OnCycle&& on_cycle) {
    std::size_t offered = 0;  // points [0, offered) of this chunk went to the engine
    for (std::size_t i = 0; i < points.size; ++i) {
      if (record_times_.admit_time(points.t[i]) != RejectReason::accepted) continue;  // as the CLI: only valid times move the schedule
      ++valid_times_;
      const bool started = schedule_.started();
      const std::optional<double> due = schedule_.on_record(points.t[i]);
      if (!started && schedule_.started()) first_time_ = schedule_.first_time();
      if (!due) continue;
      inserted_since_ += session_.insert(points.slice(offered, i), nullptr);
      offered = i;
      session_.advance_to(*due);
      if (session_.calibrating()) continue;  // no cycle while the engine buffers its first window for the grid
      run_cycle(*due, on_cycle);
    }
    inserted_since_ += session_.insert(points.slice(offered, points.size), nullptr);
  }

  /// The stream ended: ends the calibration and runs the last cycle (when
  /// points came since the previous one, or there was none).
  template <class OnCycle>
  void finish(OnCycle&& on_cycle) {
    session_.complete_calibration();
    if (inserted_since_ > 0 || cycle_ == 0) {
      run_cycle(schedule_.started() ? std::max(session_.last_accepted_time(), first_time_) : 0.0, on_cycle);
    }
  }

  /// Points with a usable time so far (0: the schedule never started).
  std::uint64_t valid_times() const { return valid_times_; }
  /// Cycles run so far.
  std::uint64_t cycles() const { return cycle_; }
  /// Points offered to the engine so far (the next point's stream index);
  /// during `on_cycle`, the points before the one that made it due.
  std::uint64_t offered() const { return session_.engine().offered(); }

 private:
  template <class OnCycle>
  void run_cycle(double cycle_time, OnCycle& on_cycle) {
    session_.advance_to(cycle_time);  // as the CLI's run_cycle (a no-op after the scheduled advance)
    const Clustering& result = session_.retrieve(rows_);
    const std::vector<tracking::Track>* tracks = nullptr;
    if (tracker_) tracks = &tracker_->update(*session_.engine().objects(result), result.time);
    on_cycle(cycle_, cycle_time, rows_, result, tracks);
    inserted_since_ = 0;
    ++cycle_;
  }

  StreamSession session_;
  WindowRows rows_;
  RetrievalSchedule schedule_;
  StreamTimeOrder record_times_;
  std::optional<KalmanTracker> tracker_;  ///< with tracks
  std::uint64_t valid_times_ = 0, cycle_ = 0, inserted_since_ = 0;
  double first_time_ = 0.0;
};

}  // namespace streamclust::python
