// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Runs a decoded scenario on one compiled configuration of the tool and
/// checks, at every retrieval:
///  1. the continuous partition equals the batch partition of the same
///     window (tests/support/oracle_input.hpp: the batch clusterer, in
///     insertion order as for `cluster --verify`, places, projects and
///     clusters the window's object points from scratch; object and
///     structure points are the window's, disjoint);
///  2. the result lists the window's points in window order;
///  3. without ground removal and poses, a FrameClusterer fed the same calls
///     (the baseline's engine, here in insertion order) has the same window,
///     calibration, grid and partition, and every point the same verdict;
///     one in range-image mode (the baseline as the tool runs it) labels
///     every window point;
///  4. every verdict agrees with a StreamTimeOrder judging times alone (what
///     the tool does ahead of the engine to schedule its retrievals).
/// A mismatch aborts with a description. O(points x window) per input.

#include "engine/scenario.hpp"
#include "support/expect.hpp"

#include "cli/engine_config.hpp"
#include "cli/options.hpp"
#include "cli/run_setup.hpp"

#include "support/oracle_input.hpp"
#include "support/partition.hpp"

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/frame_clusterer.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace streamclust::fuzz {

/// The sensor-frame points the tool estimates the ground from without
/// --sensor-height: the finite points of the first window, as
/// cli::first_window_points reads them from a file. O(window).
inline std::vector<Eigen::Vector3f> first_window(const cli::ClusterOptions& o, const std::vector<io::Record>& stream) {
  std::vector<Eigen::Vector3f> points;
  std::optional<double> t0;
  for (const io::Record& r : stream) {
    if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z) || !std::isfinite(r.t)) continue;
    if (!t0) t0 = r.t;
    if (o.window_is_count ? points.size() >= o.window_count : r.t - *t0 >= o.window_seconds) break;
    points.emplace_back(r.x, r.y, r.z);
  }
  return points;
}

/// The options make_run_setup reads, as bytes: equal keys give equal setups
/// when no ground estimate is made (no first window involved).
inline std::string setup_key(const cli::ClusterOptions& o) {
  std::string key;
  const auto add = [&key](const auto& v) { key.append(reinterpret_cast<const char*>(&v), sizeof v); };
  add(o.mount_deg.has_value());
  if (o.mount_deg) add(*o.mount_deg);
  add(o.sensor_height.has_value());
  if (o.sensor_height) add(*o.sensor_height);
  add(o.ground);
  add(o.ceiling);
  add(o.projection);
  for (const float v : {o.ground_tolerance, o.ground_cell, o.max_slope_deg, o.azimuth_min, o.azimuth_max,
                        o.elevation_min, o.elevation_max, o.min_range})
    add(v);
  return key + o.poses_path;
}

/// cli::make_run_setup for the scenario's options and first window. A
/// setup that needs no ground estimate depends on the options alone and is
/// cached: its world field of view costs ~20 ms of sanitized code (a ray
/// grid through the mount), which would otherwise be most of an input's time.
inline std::shared_ptr<const cli::RunSetup> run_setup(const cli::ClusterOptions& o,
                                                      const std::vector<io::Record>& stream) {
  const bool estimates = o.ground && (!cli::has_motion_options(o) || !o.sensor_height);
  std::ostringstream notes;
  if (estimates) {
    const std::vector<Eigen::Vector3f> window = first_window(o, stream);
    return std::make_shared<const cli::RunSetup>(cli::make_run_setup(o, false, notes, &window));
  }
  static std::map<std::string, std::shared_ptr<const cli::RunSetup>> cache;
  const std::string key = setup_key(o);
  auto it = cache.find(key);
  if (it == cache.end()) {
    if (cache.size() >= 1024) cache.clear();
    it = cache.emplace(key, std::make_shared<const cli::RunSetup>(cli::make_run_setup(o, false, notes))).first;
  }
  return it->second;
}

/// `o` with the policy slots of `Config` (what the tool's dispatch reads).
template <class Config>
void set_policy_slots(cli::ClusterOptions& o) {
  using P = typename Config::projection;
  using I = typename Config::spatial_index;
  using L = typename Config::linkage;
  using C = typename Config::connectivity;
  o.projection = registry::PolicyDescriptor<P>::name;
  o.index = registry::PolicyDescriptor<I>::name;
  o.linkage = registry::PolicyDescriptor<L>::name;
  o.window_is_count = std::is_same_v<typename Config::window, CountWindow>;
  o.connectivity = registry::PolicyDescriptor<C>::name;
}

/// The scenario's run on `Config`, with its checks (see the file comment).
template <class Config>
class ScenarioRun {
 public:
  using Engine = StreamClusterer<Config>;
  using Frame = FrameClusterer<Config>;

  /// Builds the engines; false when the options are a usage error (the
  /// tool would exit 2 before reading a point).
  bool setup(const Scenario& s) {
    cli::ClusterOptions o = s.options;
    set_policy_slots<Config>(o);
    try {
      o.setup = run_setup(o, s.stream);
      params_ = cli::make_params<Config>(o);
      if constexpr (std::is_same_v<typename Config::connectivity, SpanningForestConnectivity>) {
        params_.connectivity.min_fold_edges = s.forest.min_fold_edges;
        params_.connectivity.fold_edges_per_point = s.forest.fold_edges_per_point;
        params_.connectivity.prune_witnesses = s.forest.prune_witnesses;
      }
      engine_ = std::make_unique<Engine>(params_);
      batch_ = std::make_unique<BatchClusterer<Config>>(params_, BatchMode::insertion_order);
      if (!params_.ground.use_height_map && !params_.motion.enabled) {
        frame_ = std::make_unique<Frame>(params_, BatchMode::insertion_order);
        baseline_ = std::make_unique<Frame>(params_, BatchMode::range_image);
      }
    } catch (const std::invalid_argument&) {
      return false;  // the tool's UsageError
    }
    times_ = StreamTimeOrder(params_.time_order);
    return true;
  }

  /// Runs the script, then the tool's final cycle (end of calibration and
  /// a last retrieval).
  void run(const Scenario& s) {
    for (const Operation& op : s.script) {
      switch (op.kind) {
        case Operation::insert: insert_one(s.stream[op.first]); break;
        case Operation::insert_batch: insert_batch(s.stream, op.first, op.count); break;
        case Operation::retrieve: retrieve_and_compare(s.stream); break;
        case Operation::advance_and_retrieve:
          advance_to(op.time);
          retrieve_and_compare(s.stream);
          break;
        case Operation::complete_calibration: complete_calibration(); break;
      }
    }
    complete_calibration();
    retrieve_and_compare(s.stream);
  }

 private:
  /// Check 4: a point's verdict against the times-only order.
  void check_time_verdict(double time, RejectReason engine_verdict) {
    const RejectReason order = times_.admit_time(time);
    if (engine_verdict == RejectReason::accepted) {
      require(order == RejectReason::accepted, "a point the engine accepts has an acceptable time");
    } else if (engine_verdict == RejectReason::time_backwards || engine_verdict == RejectReason::time_jump) {
      require(order == engine_verdict, "the engine's time verdict is the times-only order's");
    } else if (order != RejectReason::accepted) {
      require(engine_verdict != RejectReason::accepted, "a point with an unacceptable time is rejected");
    }
  }

  void insert_one(const io::Record& r) {
    const RejectReason verdict = engine_->insert(r);
    check_time_verdict(r.t, verdict);
    if (frame_) {
      require(frame_->insert(r) == verdict, "the frame clusterer gives a point the engine's verdict");
      baseline_->insert(r);
    }
  }

  void insert_batch(const std::vector<io::Record>& stream, std::size_t first, std::size_t count) {
    const auto from = stream.begin() + static_cast<std::ptrdiff_t>(first);
    const auto to = from + static_cast<std::ptrdiff_t>(count);
    reasons_.clear();
    engine_->insert_batch(from, to, std::back_inserter(reasons_));
    require(reasons_.size() == count, "insert_batch reports one verdict per point");
    for (std::size_t k = 0; k < count; ++k) check_time_verdict(stream[first + k].t, reasons_[k]);
    if (frame_) {
      frame_reasons_.clear();
      frame_->insert_batch(from, to, std::back_inserter(frame_reasons_));
      require(frame_reasons_ == reasons_, "the frame clusterer gives each point the engine's verdict");
      baseline_->insert_batch(from, to);
    }
  }

  void advance_to(double time) {
    engine_->advance_to(time);
    if (frame_) {
      frame_->advance_to(time);
      baseline_->advance_to(time);
    }
    if (times_.may_advance_to(time)) times_.advance(time);
  }

  void complete_calibration() {
    engine_->complete_calibration();
    if (frame_) {
      frame_->complete_calibration();
      baseline_->complete_calibration();
    }
  }

  void retrieve_and_compare(const std::vector<io::Record>& stream) {
    const Clustering& result = engine_->retrieve();
    // Check 1.
    const std::string mismatch = test::compare_with_batch_on_input(*engine_, *batch_, stream);
    if (!mismatch.empty()) fail("continuous and batch partitions differ: " + mismatch + describe());
    // Check 2.
    if (!engine_->calibrating()) {
      std::size_t k = 0;
      bool ordered = result.points.size() == engine_->size();
      engine_->for_each_point([&](const Sample&, std::uint64_t index) {
        ordered = ordered && k < result.points.size() && result.points[k].stream_index == index;
        ++k;
      });
      require(ordered, "the result lists the window's points in window order");
    }
    if (frame_) compare_frame(result);
  }

  /// Check 3.
  void compare_frame(const Clustering& result) {
    const BatchResult& peer = frame_->retrieve();
    require(frame_->calibrating() == engine_->calibrating(), "the frame clusterer calibrates on the same window");
    require(frame_->size() == engine_->size(), "the frame clusterer's window has the engine's size");
    if (engine_->calibrating()) return;
    require(frame_->grid().rows == engine_->grid().rows && frame_->grid().cols == engine_->grid().cols,
            "the frame clusterer chooses the engine's grid");
    window_.clear();
    engine_->for_each_point([&](const Sample&, std::uint64_t index) { window_.push_back(index); });
    std::size_t k = 0;
    bool same = true;
    frame_->for_each_point([&](const Sample&, std::uint64_t index) {
      same = same && k < window_.size() && window_[k] == index;
      ++k;
    });
    require(same, "the frame clusterer's window holds the engine's points");
    labels_.clear();
    for (const PointLabel& p : result.points) labels_.push_back(p.label);
    const std::string mismatch = test::partition_mismatch(labels_, peer.labels);
    if (!mismatch.empty()) fail("continuous and frame partitions differ: " + mismatch + describe());
    const BatchResult& range_image = baseline_->retrieve();
    require(!baseline_->calibrating() && range_image.labels.size() == baseline_->size(),
            "the range-image baseline labels every window point");
  }

  std::string describe() const {
    std::ostringstream os;
    os << " (window " << engine_->size() << " objects + " << engine_->structure_size() << " structure, grid "
       << engine_->grid().rows << "x" << engine_->grid().cols << ", mask " << params_.mask_size << ", offered "
       << engine_->offered() << ")";
    return os.str();
  }

  ClustererParams<Config> params_;
  std::unique_ptr<Engine> engine_;
  std::unique_ptr<BatchClusterer<Config>> batch_;
  std::unique_ptr<Frame> frame_, baseline_;
  StreamTimeOrder times_;
  std::vector<RejectReason> reasons_, frame_reasons_;
  std::vector<std::uint64_t> window_;
  std::vector<ComponentId> labels_;
};

/// Runs `s` on `Config` (nothing when its options are a usage error).
template <class Config>
void run_scenario(const Scenario& s) {
  ScenarioRun<Config> run;
  if (run.setup(s)) run.run(s);
}

}  // namespace streamclust::fuzz
