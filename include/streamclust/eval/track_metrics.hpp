// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// TrackMetricsAccumulator: a tracker's reported objects against the truth,
/// frame by frame (retrieval by retrieval), scored with CLEAR MOT (MOTA,
/// MOTP, id switches), IDF1, recall and precision, bird's-eye box IoU, the
/// velocity error of moving objects and the share of static objects
/// reported still.
///
/// Per frame a truth object is *rated* with at least `min_points` points in
/// the window, *ignored* with fewer (but some): a track matched to an
/// ignored object is neither right nor wrong. A track matches a truth
/// object when its centre lies within `match_distance` of the object's
/// footprint (a box seen from one side has its centre off the object's)
/// and their height ranges overlap (when both are given: a patch of
/// ceiling above a person is not the person);
/// correspondences of the previous frame are kept while they hold, the rest
/// are assigned with the least total centre distance (min_cost_assignment).
/// - MOTA = 1 - (misses + false positives + id switches) / rated objects;
///   an id switch: a rated object matched to another track than at its last
///   match.
/// - MOTP: mean centre distance of the rated matches [m]; IoU: their mean
///   footprint_iou.
/// - IDF1 = 2 IDTP / (rated objects + tracks), IDTP from the one-to-one
///   assignment of truth ids to track ids with the most frames in which the
///   pair is within `match_distance` (Ristani et al. 2016).
/// - Velocity RMSE over the rated matches of moving objects [m/s], ground
///   plane, and over those in steady motion (`steady`: the velocity has not
///   changed over the window; a velocity measured over a window lags a turn
///   made within it); still share: rated matches of static objects whose reported
///   speed is below `still_speed`.

#include <streamclust/eval/assignment.hpp>
#include <streamclust/eval/footprint.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

namespace streamclust {
namespace eval {

/// One truth object in one frame.
struct TruthObjectState {
  std::int64_t id = 0;
  Footprint box;
  Eigen::Vector2f velocity = Eigen::Vector2f::Zero();  ///< [m/s]
  bool moving = false;
  std::size_t points = 0;  ///< its points in the frame's window
  float bottom = 0.0f, top = 0.0f;  ///< [m] height range; top <= bottom: not given
  bool steady = true;  ///< the velocity has been the same over the window (no turn, no start or stop)
};

/// One reported track in one frame.
struct TrackReport {
  std::uint64_t id = 0;
  Footprint box;
  Eigen::Vector2f velocity = Eigen::Vector2f::Zero();  ///< [m/s]
  float bottom = 0.0f, top = 0.0f;  ///< [m] height range; top <= bottom: not given
};

/// Settings of the tracking metrics.
struct TrackMetricOptions {
  float match_distance = 1.0f;  ///< [m] a track's centre this close to an object's footprint can match it
  std::size_t min_points = 50;  ///< a truth object with fewer points in the window is ignored, not rated
  float still_speed = 0.2f;     ///< [m/s] a static object reported slower than this counts as still

  void validate() const {
    if (!(match_distance > 0.0f && match_distance <= 100.0f)) {
      throw std::invalid_argument("TrackMetricOptions: match_distance must be in (0, 100] m");
    }
    if (min_points < 1) throw std::invalid_argument("TrackMetricOptions: min_points must be >= 1");
    if (!(still_speed > 0.0f)) throw std::invalid_argument("TrackMetricOptions: still_speed must be > 0");
  }
};

/// The scores over every frame added.
struct TrackMetrics {
  std::size_t frames = 0;
  std::size_t objects = 0;          ///< distinct truth ids rated at least once
  std::size_t truth = 0;            ///< rated objects, summed over frames
  std::size_t tracks = 0;           ///< tracks not matched to an ignored object, summed over frames
  std::size_t matches = 0;          ///< rated objects matched
  std::size_t misses = 0;           ///< rated objects not matched
  std::size_t false_positives = 0;  ///< tracks matched to nothing
  std::size_t id_switches = 0;
  double mota = 0.0;
  double motp = 0.0;      ///< [m]
  double mean_iou = 0.0;
  double idf1 = 0.0;
  double recall = 0.0;
  double precision = 0.0;
  double velocity_rmse = 0.0;        ///< [m/s] moving objects' rated matches
  std::size_t velocity_samples = 0;
  double steady_velocity_rmse = 0.0;  ///< [m/s] those in steady motion
  std::size_t steady_velocity_samples = 0;
  double still_share = 0.0;          ///< static objects' rated matches reported still
  std::size_t static_samples = 0;
};

/// Accumulates frames; result() scores them. Not thread-safe. Memory:
/// O(objects + tracks + matched id pairs).
class TrackMetricsAccumulator {
 public:
  explicit TrackMetricsAccumulator(TrackMetricOptions options = {}) : options_(options) { options_.validate(); }

  /// Scores one frame. O(objects x tracks + n^2 m) for the assignment.
  void add_frame(const std::vector<TruthObjectState>& truth, const std::vector<TrackReport>& tracks) {
    ++frames_;
    const std::size_t n = truth.size(), m = tracks.size();
    std::vector<long> match(n, -1);
    std::vector<char> track_taken(m, 0);
    const auto gated = [&](std::size_t g, std::size_t h) {
      const TruthObjectState& a = truth[g];
      const TrackReport& b = tracks[h];
      const bool heights = a.top > a.bottom && b.top > b.bottom;
      if (heights && (b.bottom > a.top || a.bottom > b.top)) return false;
      return a.box.distance_to(b.box.center) <= options_.match_distance;
    };
    // The previous frame's correspondences that still hold.
    std::unordered_map<std::uint64_t, std::size_t> track_index;
    for (std::size_t h = 0; h < m; ++h) track_index.emplace(tracks[h].id, h);
    for (std::size_t g = 0; g < n; ++g) {
      const auto prev = previous_.find(truth[g].id);
      if (prev == previous_.end()) continue;
      const auto h = track_index.find(prev->second);
      if (h == track_index.end() || track_taken[h->second] || !gated(g, h->second)) continue;
      match[g] = static_cast<long>(h->second);
      track_taken[h->second] = 1;
    }
    // The rest: least total centre distance among gated pairs.
    std::vector<std::size_t> free_truth, free_tracks;
    for (std::size_t g = 0; g < n; ++g)
      if (match[g] < 0) free_truth.push_back(g);
    for (std::size_t h = 0; h < m; ++h)
      if (!track_taken[h]) free_tracks.push_back(h);
    constexpr double kForbidden = 1e30;
    std::vector<double> cost(free_truth.size() * free_tracks.size(), kForbidden);
    for (std::size_t a = 0; a < free_truth.size(); ++a) {
      for (std::size_t b = 0; b < free_tracks.size(); ++b) {
        const std::size_t g = free_truth[a], h = free_tracks[b];
        if (gated(g, h)) cost[a * free_tracks.size() + b] = (truth[g].box.center - tracks[h].box.center).norm();
      }
    }
    const std::vector<long> assigned = min_cost_assignment(cost, free_truth.size(), free_tracks.size(), kForbidden);
    for (std::size_t a = 0; a < free_truth.size(); ++a) {
      if (assigned[a] < 0) continue;
      const std::size_t h = free_tracks[static_cast<std::size_t>(assigned[a])];
      match[free_truth[a]] = static_cast<long>(h);
      track_taken[h] = 1;
    }

    previous_.clear();
    std::size_t on_ignored = 0;
    for (std::size_t g = 0; g < n; ++g) {
      const TruthObjectState& object = truth[g];
      const bool rated = object.points >= options_.min_points;
      if (match[g] >= 0) previous_[object.id] = tracks[static_cast<std::size_t>(match[g])].id;
      if (!rated) {
        on_ignored += match[g] >= 0 ? 1u : 0u;
        continue;
      }
      ++truth_;
      rated_ids_.insert(object.id);
      if (match[g] < 0) {
        ++misses_;
        continue;
      }
      const TrackReport& track = tracks[static_cast<std::size_t>(match[g])];
      ++matches_;
      const auto last = last_match_.find(object.id);
      if (last != last_match_.end() && last->second != track.id) ++id_switches_;
      last_match_[object.id] = track.id;
      centre_distance_ += static_cast<double>((object.box.center - track.box.center).norm());
      iou_ += static_cast<double>(footprint_iou(object.box, track.box));
      if (object.moving) {
        const auto squared = static_cast<double>((track.velocity - object.velocity).squaredNorm());
        velocity_squared_ += squared;
        ++velocity_samples_;
        if (object.steady) {
          steady_velocity_squared_ += squared;
          ++steady_velocity_samples_;
        }
      } else {
        still_ += track.velocity.norm() < options_.still_speed ? 1u : 0u;
        ++static_samples_;
      }
    }
    tracks_ += m - on_ignored;
    false_positives_ += m - on_ignored - (matches_ - matches_before_);
    matches_before_ = matches_;
    // IDF1: every rated pair within the gate this frame.
    for (std::size_t g = 0; g < n; ++g) {
      if (truth[g].points < options_.min_points) continue;
      for (std::size_t h = 0; h < m; ++h)
        if (gated(g, h)) ++pair_frames_[{truth[g].id, tracks[h].id}];
    }
  }

  /// The scores so far. O(ids^2 x min(ids)) for IDF1's assignment.
  TrackMetrics result() const {
    TrackMetrics r;
    r.frames = frames_;
    r.objects = rated_ids_.size();
    r.truth = truth_;
    r.tracks = tracks_;
    r.matches = matches_;
    r.misses = misses_;
    r.false_positives = false_positives_;
    r.id_switches = id_switches_;
    const auto ratio = [](double a, double b) { return b > 0.0 ? a / b : 0.0; };
    r.mota = truth_ > 0 ? 1.0 - static_cast<double>(misses_ + false_positives_ + id_switches_) / static_cast<double>(truth_)
                        : 0.0;
    r.motp = ratio(centre_distance_, static_cast<double>(matches_));
    r.mean_iou = ratio(iou_, static_cast<double>(matches_));
    r.recall = ratio(static_cast<double>(matches_), static_cast<double>(truth_));
    r.precision = ratio(static_cast<double>(matches_), static_cast<double>(tracks_));
    r.velocity_samples = velocity_samples_;
    r.velocity_rmse = std::sqrt(ratio(velocity_squared_, static_cast<double>(velocity_samples_)));
    r.steady_velocity_samples = steady_velocity_samples_;
    r.steady_velocity_rmse =
        std::sqrt(ratio(steady_velocity_squared_, static_cast<double>(steady_velocity_samples_)));
    r.static_samples = static_samples_;
    r.still_share = ratio(static_cast<double>(still_), static_cast<double>(static_samples_));
    r.idf1 = ratio(2.0 * identity_true_positives(), static_cast<double>(truth_ + tracks_));
    return r;
  }

 private:
  /// The most frames any one-to-one assignment of truth ids to track ids
  /// keeps within the gate.
  double identity_true_positives() const {
    if (pair_frames_.empty()) return 0.0;
    std::map<std::int64_t, std::size_t> rows;
    std::map<std::uint64_t, std::size_t> cols;
    std::size_t most = 0;
    for (const auto& [pair, count] : pair_frames_) {
      rows.emplace(pair.first, rows.size());
      cols.emplace(pair.second, cols.size());
      most = std::max(most, count);
    }
    // Maximum weight as least cost: most - count, every pair allowed (a
    // pair never within the gate adds nothing).
    std::vector<double> cost(rows.size() * cols.size(), static_cast<double>(most));
    for (const auto& [pair, count] : pair_frames_) {
      cost[rows.at(pair.first) * cols.size() + cols.at(pair.second)] = static_cast<double>(most - count);
    }
    const std::vector<long> assigned =
        min_cost_assignment(cost, rows.size(), cols.size(), static_cast<double>(most) + 1.0);
    double total = 0.0;
    for (std::size_t r = 0; r < rows.size(); ++r) {
      if (assigned[r] >= 0) total += static_cast<double>(most) - cost[r * cols.size() + static_cast<std::size_t>(assigned[r])];
    }
    return total;
  }

  TrackMetricOptions options_;
  std::size_t frames_ = 0, truth_ = 0, tracks_ = 0, matches_ = 0, matches_before_ = 0, misses_ = 0,
              false_positives_ = 0, id_switches_ = 0, velocity_samples_ = 0, steady_velocity_samples_ = 0,
              static_samples_ = 0, still_ = 0;
  double centre_distance_ = 0.0, iou_ = 0.0, velocity_squared_ = 0.0, steady_velocity_squared_ = 0.0;
  std::set<std::int64_t> rated_ids_;
  std::unordered_map<std::int64_t, std::uint64_t> previous_;    ///< last frame's correspondences
  std::unordered_map<std::int64_t, std::uint64_t> last_match_;  ///< each rated object's last track
  std::map<std::pair<std::int64_t, std::uint64_t>, std::size_t> pair_frames_;
};

}  // namespace eval
}  // namespace streamclust
