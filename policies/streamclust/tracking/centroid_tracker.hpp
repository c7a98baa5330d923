// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// CentroidTracker: the frame-based baseline of LiDAR tracking packages
/// (multiple-object-tracking-lidar and the like): a constant-velocity
/// Kalman filter per track on the observed centres, associated by global
/// nearest neighbour within a gate, no use of component ids or of the
/// points' capture times. The peer of `streamclust evaluate --tracks`
/// (fed the centroids of per-window Euclidean clusters), and a Tracker
/// policy of its own for ablations.

#include <streamclust/concepts/tracker.hpp>
#include <streamclust/detail/parameter_check.hpp>
#include <streamclust/tracking/object_boxes.hpp>
#include <streamclust/tracking/track.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace streamclust {

/// Centroid tracking: per track x, y and their velocities (two independent
/// constant-velocity filters), z and the box extent from the last
/// observation, yaw 0 (an axis-aligned box). The reported velocity is the
/// filter's (a centroid tracker has no static rule). Update:
/// O(tracks x observations x log) for the greedy nearest-neighbour pairs.
/// Not thread-safe.
class CentroidTracker {
 public:
  struct Params {
    float gate_distance = 2.0f;          ///< [m] an observation this close to a prediction can continue it, (0, 100]
    std::size_t birth_points = 10;       ///< points an observation needs to start a track, [1, 1000000]
    std::uint32_t confirm_hits = 3;      ///< retrievals seen before confirmed, [1, 1000]
    double coast_seconds = 1.0;          ///< [s] a confirmed track unseen this long is dropped, [0, 100]
    double tentative_coast_seconds = 0.2;  ///< [s] the same for a tentative track, [0, 100]
    float acceleration_noise = 1.0f;     ///< [m/s^2] white acceleration of the motion model, (0, 100]
    float position_noise = 0.2f;         ///< [m] of an observed centre, (0, 10]
    float initial_speed_noise = 3.0f;    ///< [m/s] of a new track's velocity, (0, 100]
    float moving_speed = 0.5f;           ///< [m/s] a track faster than this is flagged moving, (0, 100]

    /// Throws std::invalid_argument naming the first setting out of range.
    void validate() const {
      check(gate_distance > 0.0f && gate_distance <= 100.0f, "gate_distance", gate_distance, "(0, 100] m");
      check(birth_points >= 1 && birth_points <= 1000000, "birth_points", static_cast<double>(birth_points),
            "[1, 1000000]");
      check(confirm_hits >= 1 && confirm_hits <= 1000, "confirm_hits", confirm_hits, "[1, 1000]");
      check(coast_seconds >= 0.0 && coast_seconds <= 100.0, "coast_seconds", coast_seconds, "[0, 100] s");
      check(tentative_coast_seconds >= 0.0 && tentative_coast_seconds <= 100.0, "tentative_coast_seconds",
            tentative_coast_seconds, "[0, 100] s");
      check(acceleration_noise > 0.0f && acceleration_noise <= 100.0f, "acceleration_noise", acceleration_noise,
            "(0, 100] m/s^2");
      check(position_noise > 0.0f && position_noise <= 10.0f, "position_noise", position_noise, "(0, 10] m");
      check(initial_speed_noise > 0.0f && initial_speed_noise <= 100.0f, "initial_speed_noise", initial_speed_noise,
            "(0, 100] m/s");
      check(moving_speed > 0.0f && moving_speed <= 100.0f, "moving_speed", moving_speed, "(0, 100] m/s");
    }

   private:
    static void check(bool ok, const char* name, double value, const char* allowed) {
      detail::require_parameter(ok, "CentroidTracker", name, value, allowed);
    }
  };
  static constexpr bool enabled = true;

  CentroidTracker() : CentroidTracker(Params{}) {}
  /// Throws std::invalid_argument naming a parameter out of range.
  explicit CentroidTracker(const Params& params) : params_(params) { params_.validate(); }

  /// The tracks after the retrieval at `time` [s] with `objects` (their box
  /// centres as the measured positions). Throws std::invalid_argument when
  /// `time` is before the last call's.
  const std::vector<tracking::Track>& update(const std::vector<tracking::ObjectObservation>& objects, double time) {
    if (has_time_ && time < time_) {
      throw std::invalid_argument("CentroidTracker::update: time " + std::to_string(time) + " s is before the last (" +
                                  std::to_string(time_) + " s)");
    }
    const double dt = has_time_ ? time - time_ : 0.0;
    has_time_ = true;
    time_ = time;
    for (Filter& f : filters_) f.predict(dt, params_.acceleration_noise);

    // Greedy global nearest neighbour: the closest pairs first.
    pairs_.clear();
    const float gate2 = params_.gate_distance * params_.gate_distance;
    for (std::size_t t = 0; t < filters_.size(); ++t) {
      for (std::size_t o = 0; o < objects.size(); ++o) {
        const Eigen::Vector2f d = objects[o].box.center.head<2>() - filters_[t].position();
        const float d2 = d.squaredNorm();
        if (d2 <= gate2) pairs_.emplace_back(d2, t, o);
      }
    }
    std::sort(pairs_.begin(), pairs_.end());
    std::vector<char> filter_seen(filters_.size(), 0), object_used(objects.size(), 0);
    for (const auto& [d2, t, o] : pairs_) {
      if (filter_seen[t] || object_used[o]) continue;
      filter_seen[t] = 1;
      object_used[o] = 1;
      filters_[t].observe(objects[o], time, params_.position_noise);
    }
    // Drop the tracks unseen too long, start the new ones.
    std::size_t kept = 0;
    for (std::size_t t = 0; t < filters_.size(); ++t) {
      Filter& f = filters_[t];
      const double unseen = time - f.track.last_seen;
      const bool confirmed = f.track.hits >= params_.confirm_hits;
      if (!filter_seen[t] && unseen > (confirmed ? params_.coast_seconds : params_.tentative_coast_seconds)) continue;
      if (!filter_seen[t]) f.track.points = 0;
      filters_[kept++] = f;
    }
    filters_.resize(kept);
    for (std::size_t o = 0; o < objects.size(); ++o) {
      if (object_used[o] || objects[o].box.points < params_.birth_points) continue;
      filters_.push_back(Filter::start(objects[o], time, next_id_++, params_));
    }
    tracks_.clear();
    for (Filter& f : filters_) {
      tracking::Track& t = f.track;
      const bool seen = t.last_seen == time;
      t.state = t.hits < params_.confirm_hits ? tracking::TrackState::tentative
                : seen                         ? tracking::TrackState::confirmed
                                               : tracking::TrackState::coasting;
      if (!seen) t.cluster_id = kNoComponent;
      t.position.head<2>() = f.position();
      t.velocity = Eigen::Vector3f(f.x[1], f.y[1], 0.0f);
      t.speed_error = std::sqrt(0.5f * (f.px[3] + f.py[3]));
      t.moving = t.velocity.norm() >= params_.moving_speed;
      tracks_.push_back(t);
    }
    return tracks_;
  }

  const std::vector<tracking::Track>& tracks() const { return tracks_; }

 private:
  /// One track's two constant-velocity filters: state (position,
  /// velocity) and covariance (pp, pv, vp, vv) per axis.
  struct Filter {
    tracking::Track track;
    float x[2] = {0, 0}, y[2] = {0, 0};
    float px[4] = {0, 0, 0, 0}, py[4] = {0, 0, 0, 0};

    Eigen::Vector2f position() const { return {x[0], y[0]}; }

    static Filter start(const tracking::ObjectObservation& o, double time, std::uint64_t id, const Params& p) {
      Filter f;
      f.track.id = id;
      f.track.first_seen = time;
      const float pos = p.position_noise * p.position_noise, vel = p.initial_speed_noise * p.initial_speed_noise;
      for (float* c : {f.px, f.py}) {
        c[0] = pos;
        c[3] = vel;
      }
      f.x[0] = o.box.center.x();
      f.y[0] = o.box.center.y();
      f.take_box(o, time);
      return f;
    }
    void predict(double dt, float acceleration) {
      const auto step = [&](float* s, float* c) {
        const auto t = static_cast<float>(dt);
        const float q = acceleration * acceleration;
        s[0] += t * s[1];
        // P = F P F^T + Q, F = [1 t; 0 1], Q = q [t^3/3 t^2/2; t^2/2 t].
        const float p00 = c[0] + t * (c[1] + c[2]) + t * t * c[3] + q * t * t * t / 3.0f;
        const float p01 = c[1] + t * c[3] + q * t * t / 2.0f;
        const float p11 = c[3] + q * t;
        c[0] = p00;
        c[1] = c[2] = p01;
        c[3] = p11;
      };
      step(x, px);
      step(y, py);
    }
    void observe(const tracking::ObjectObservation& o, double time, float noise) {
      const auto correct = [&](float* s, float* c, float measured) {
        const float innovation = measured - s[0];
        const float variance = c[0] + noise * noise;
        const float k0 = c[0] / variance, k1 = c[2] / variance;
        s[0] += k0 * innovation;
        s[1] += k1 * innovation;
        const float p00 = (1.0f - k0) * c[0], p01 = (1.0f - k0) * c[1], p11 = c[3] - k1 * c[1];
        c[0] = p00;
        c[1] = c[2] = p01;
        c[3] = p11;
      };
      correct(x, px, o.box.center.x());
      correct(y, py, o.box.center.y());
      take_box(o, time);
    }
    void take_box(const tracking::ObjectObservation& o, double time) {
      track.cluster_id = o.id;
      track.position.z() = o.box.center.z();
      track.length = o.box.length;
      track.width = o.box.width;
      track.height = o.box.height;
      track.yaw = o.box.yaw;
      track.points = o.box.points;
      track.box_quality = o.box.quality;
      track.last_seen = time;
      ++track.hits;
    }
  };

  Params params_;
  std::vector<Filter> filters_;
  std::vector<tracking::Track> tracks_;
  std::vector<std::tuple<float, std::size_t, std::size_t>> pairs_;  ///< (squared distance, filter, object)
  std::uint64_t next_id_ = 1;
  double time_ = 0.0;
  bool has_time_ = false;
};

static_assert(is_tracker_policy_v<CentroidTracker>, "CentroidTracker must model the Tracker policy");

}  // namespace streamclust
