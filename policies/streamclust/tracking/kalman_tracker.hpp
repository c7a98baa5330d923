// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// KalmanTracker: a constant-velocity Kalman filter per object in the
/// ground plane, fed by each retrieval's boxes and in-window velocities,
/// associated by the components' stable ids first and by position second.

#include <streamclust/concepts/tracker.hpp>
#include <streamclust/tracking/kalman_tracker_params.hpp>
#include <streamclust/tracking/object_boxes.hpp>
#include <streamclust/tracking/track.hpp>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace streamclust {

/// Tracks objects over retrievals.
///
/// Per track a constant-velocity Kalman filter on (x, y, vx, vy) in the
/// world frame: white acceleration of `acceleration_noise` (m/s^2)
/// between retrievals; each observation measures the box centre (standard
/// deviation by box quality: a partial view moves the centre; a centre
/// outside the 99 % ellipse of the prediction counts with its noise raised by
/// the excess, so a component that changes shape moves the track without
/// making speed) and, when the
/// window showed it (window_velocity), the velocity with its standard error,
/// its variance multiplied by the window's span over the time since the
/// track's last update (successive windows share most of their points: their
/// errors are not independent), its variance raised by the excess when it
/// falls outside the 99 % ellipse of the filter's velocity. A new track
/// starts at the velocity its window shows when that is clear (at least
/// twice `moving_speed` and five standard errors; uncertainty three standard
/// errors, at least 0.5 m/s: a car at 10 m/s moves 0.5 m a retrieval and
/// its pieces are renumbered), else at rest with `initial_speed_noise`;
/// window velocities count from its second sighting.
/// Height, extent and heading are smoothed outside the filter.
///
/// Association, per retrieval: the tracks are predicted to its time. An
/// observation whose box (grown by `group_margin`) holds the predictions of
/// two or more confirmed tracks, with an area at most twice theirs plus
/// 1 m^2, is a group (objects that touch share a component): those tracks
/// are seen in it (its id, their points) and keep their predictions. An observation whose component id is a track's last one goes to that track
/// when within its gate (`gate_distance` plus 3 standard deviations of the
/// predicted position); the rest are paired by distance within the gates,
/// nearest first, when their heights overlap or lie less than `gate_height`
/// apart (merges and splits renumber components; an object seen again
/// after an occlusion has a new id). An observation left over with at least
/// `birth_points` points, shaped like an object (at most `birth_max_length`
/// long and `birth_max_area` large, at least `birth_flatness` times as high as long, not a flat
/// vertical patch narrower than `birth_min_width`), not floating more than `birth_clearance` above
/// the ground under it (where unknown: above the lowest observation within
/// `birth_neighbourhood`), not reaching within `birth_ceiling_gap` of the
/// ceiling over it unless shaped like a pillar (at least 1.5 m high and
/// higher than long), and not centred in the box of a
/// confirmed track seen in this update (grown by `group_margin`: a part of
/// that object), starts a tentative track; `confirm_hits` hits confirm
/// it. A track not seen coasts on its prediction: a tentative one is
/// dropped after `tentative_coast_seconds`, a confirmed one after
/// `coast_seconds`, a confirmed static one after `out_of_sight_seconds`
/// unless an observation stands between it and the sensor (the
/// observations' `viewpoint`; without one, the rule is off): a standing
/// object not seen while nothing hides it has left the field of view or
/// is gone, while one hidden behind a passer-by is there again after it.
///
/// A static track takes a zero-velocity pseudo-measurement of standard
/// deviation `moving_speed` at each update (a box centre that wanders as
/// sides come into view builds no speed), and keeps its place in a group.
/// When its windows show clear motion at `restart_speed` or faster, its
/// object's ends agreeing, in `restart_updates` successive updates, it
/// starts moving at the window velocity as a birth does (a cyclist whose
/// component a standing object's track took over). A static track whose
/// smoothed box reaches within `birth_ceiling_gap` of the ceiling over it,
/// not shaped like a pillar, in `ceiling_hide_updates` successive updates is
/// set aside (kept, not reported): a lamp or a patch of ceiling whose first
/// observations ended lower, or an object merged with a wall for that long.
/// It is reported again, under its id, from the first observation it takes
/// that could start a track (an object come apart from the wall), at that
/// observation's place and box; a lamp's never can.
///
/// Moving or static: a track moves when its speed is at least
/// `moving_speed` and three standard deviations and its smoothed window
/// velocity (the points' own motion; one within three standard errors of
/// zero, or, while static, whose object's ends differ in velocity by more
/// than its speed, counts as zero) at least half `moving_speed` (no
/// window velocity yet: static); it is
/// static again below half `moving_speed`, or a quarter for the window
/// velocity. A static track reports zero velocity (a parked car's
/// centre wanders as the view of it changes; that is not motion). A moving
/// track's yaw is its direction of travel; a static one's the box's.
///
/// update(): O(tracks x observations) for the gating, O(tracks + observations)
/// otherwise; no allocation once the vectors have grown. Thread safety: none.
///
/// \code
///   streamclust::tracking::ObjectBoxes boxes;
///   streamclust::KalmanTracker tracker;
///   const auto& result = engine.retrieve();
///   for (const auto& t : tracker.update(boxes.update(engine, result), result.time)) {
///     if (t.state != streamclust::tracking::TrackState::tentative) publish(t.id, t.position, t.velocity);
///   }
/// \endcode
class KalmanTracker {
 public:
  using Params = KalmanTrackerParams;
  static constexpr bool enabled = true;

  KalmanTracker() : KalmanTracker(Params{}) {}
  /// Throws std::invalid_argument naming a parameter out of range.
  explicit KalmanTracker(const Params& params) : params_(params) { params_.validate(); }

  /// The tracks after the retrieval at `time` [s] whose objects are
  /// `objects` (ObjectBoxes::update). Throws std::invalid_argument when
  /// `time` is before the previous call's.
  const std::vector<tracking::Track>& update(const std::vector<tracking::ObjectObservation>& objects, double time) {
    if (has_time_ && time < time_) {
      throw std::invalid_argument("KalmanTracker::update: time " + std::to_string(time) + " s is before the last (" +
                                  std::to_string(time_) + " s)");
    }
    const double dt = has_time_ ? time - time_ : 0.0;
    time_ = time;
    has_time_ = true;
    for (Filter& f : filters_) {
      predict(f, dt);
      f.seen = false;
    }
    associate(objects);
    for (std::size_t i = 0; i < filters_.size(); ++i) {
      if (track_of_[i] == kNone) continue;
      const tracking::ObjectObservation& o = objects[track_of_[i]];
      if (grouped_[i]) {
        seen_in_group(filters_[i], o);
      } else {
        Filter& f = filters_[i];
        correct(f, o, dt);
        if (f.set_aside && could_start_track(o, objects) && clear_of_ceiling(o)) {
          reappear(f, o);
        } else {
          f.ceiling_updates = grown_to_ceiling(f, o) ? f.ceiling_updates + 1 : 0;
          const std::uint32_t hide = params_.ceiling_hide_updates;
          f.set_aside = f.set_aside || (hide > 0 && f.ceiling_updates >= hide);
        }
      }
    }
    // Births, then misses and deletions.
    for (std::size_t o = 0; o < objects.size(); ++o) {
      if (taken_[o] || !could_start_track(objects[o], objects) || part_of_track(objects[o])) continue;
      filters_.push_back(born(objects[o]));
    }
    const Eigen::Vector3f* viewpoint = objects.empty() || !objects.front().viewpoint ? nullptr : &*objects.front().viewpoint;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < filters_.size(); ++i) {
      Filter& f = filters_[i];
      if (!f.seen) {
        f.track.cluster_id = kNoComponent;
        f.track.points = 0;
        const bool confirmed = f.track.hits >= params_.confirm_hits;
        double limit = confirmed ? params_.coast_seconds : params_.tentative_coast_seconds;
        if (confirmed && !f.track.moving && viewpoint && !hidden(f, *viewpoint, objects)) {
          limit = std::min(limit, params_.out_of_sight_seconds);
        }
        if (time - f.track.last_seen > limit) continue;
      }
      if (kept != i) filters_[kept] = std::move(f);
      ++kept;
    }
    filters_.resize(kept);
    tracks_.clear();
    for (Filter& f : filters_) {
      publish(f);
      if (!f.set_aside) tracks_.push_back(f.track);
    }
    return tracks_;
  }

  const std::vector<tracking::Track>& tracks() const { return tracks_; }
  const Params& params() const { return params_; }

 private:
  using Vector4 = Eigen::Matrix<double, 4, 1>;
  using Matrix4 = Eigen::Matrix<double, 4, 4>;
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  static constexpr double kChi2Gate = 9.21;  // chi-square, 2 degrees of freedom, 99 %
  static constexpr float kPi = 3.14159265358979323846f;
  static constexpr float kPillarHeight = 1.5f;  // [m] at_ceiling: the least height of a pillar

  struct Filter {
    tracking::Track track;
    Vector4 x = Vector4::Zero();  // x, y, vx, vy
    Matrix4 p = Matrix4::Identity();
    float box_yaw = 0.0f;  // the box's heading (a line, period pi), smoothed
    Eigen::Vector2f window_velocity = Eigen::Vector2f::Zero();  // the observations' in-window velocities, smoothed
    bool has_window_velocity = false;
    bool seen = false;     // an observation went to it in this update
    std::uint32_t motion_updates = 0;   // successive updates whose windows showed motion at restart_speed
    std::uint32_t ceiling_updates = 0;  // successive updates with its box reaching the ceiling
    bool set_aside = false;  // grown to the ceiling: kept, not reported (ceiling_hide_updates)
  };

  void predict(Filter& f, double dt) const {
    if (dt <= 0.0) return;
    Matrix4 a = Matrix4::Identity();
    a(0, 2) = dt;
    a(1, 3) = dt;
    const double q = static_cast<double>(params_.acceleration_noise) * params_.acceleration_noise;
    Matrix4 noise = Matrix4::Zero();
    for (int k = 0; k < 2; ++k) {
      noise(k, k) = q * dt * dt * dt / 3.0;
      noise(k, k + 2) = noise(k + 2, k) = q * dt * dt / 2.0;
      noise(k + 2, k + 2) = q * dt;
    }
    f.x = a * f.x;
    f.p = a * f.p * a.transpose() + noise;
  }

  /// True when `o` could start a track: enough points, shaped like an
  /// object, standing on the ground and below the ceiling. O(objects) when
  /// the ground under it is unknown, else O(1).
  bool could_start_track(const tracking::ObjectObservation& o,
                         const std::vector<tracking::ObjectObservation>& objects) const {
    return o.box.points >= params_.birth_points && !structure_shaped(o) && !floating(o, objects) && !at_ceiling(o);
  }

  /// True when `o` is longer than birth_max_length, larger than
  /// birth_max_area, lower than
  /// birth_flatness times its length, or narrower than birth_min_width and
  /// over 2.5 times as long (a post seen from one side is about as long as
  /// it is wide): what the ground and wall models left of walls, buildings,
  /// terrain or a ceiling, not an object to track.
  bool structure_shaped(const tracking::ObjectObservation& o) const {
    const float length = std::max(o.box.length, o.box.width);
    const float width = std::min(o.box.length, o.box.width);
    return length > params_.birth_max_length || length * width > params_.birth_max_area ||
           o.box.height < params_.birth_flatness * length ||
           (width < params_.birth_min_width && length > 2.5f * params_.birth_min_width);
  }

  /// True when `o`'s lowest point is more than birth_clearance above the
  /// ground under it (ObjectObservation::ground_z), or, where that ground is
  /// unknown, above the lowest point of the observations centred within
  /// birth_neighbourhood of it: a tree's crown (over its trunk), a patch of
  /// ceiling, an overhang. The objects tracked stand on the ground.
  /// O(objects) when the ground is unknown, else O(1).
  bool floating(const tracking::ObjectObservation& o, const std::vector<tracking::ObjectObservation>& objects) const {
    if (o.box.on_ground) return false;
    const float bottom = o.box.center.z() - 0.5f * o.box.height;
    if (o.ground_z) return bottom - *o.ground_z > params_.birth_clearance;
    float lowest = bottom;
    const float reach = params_.birth_neighbourhood;
    for (const tracking::ObjectObservation& other : objects) {
      const Eigen::Vector2f d = other.box.center.head<2>() - o.box.center.head<2>();
      if (d.squaredNorm() <= reach * reach) lowest = std::min(lowest, other.box.center.z() - 0.5f * other.box.height);
    }
    return bottom - lowest > params_.birth_clearance;
  }

  /// True when the top of `o` is within birth_ceiling_gap of the ceiling
  /// over it (ObjectObservation::ceiling_z) and `o` is not shaped like a
  /// pillar (at least kPillarHeight high and higher than long): a lamp, a
  /// piece of ceiling the ground policy did not class as one, a wall up to
  /// the ceiling. A pillar, or a person under a low ceiling, passes. O(1).
  bool at_ceiling(const tracking::ObjectObservation& o) const {
    if (!o.ceiling_z) return false;
    return reaches_ceiling(o.box.center.z() + 0.5f * o.box.height, o.box.height, std::max(o.box.length, o.box.width),
                           *o.ceiling_z);
  }

  /// True when the top of `o` is lower than birth_ceiling_gap below the
  /// ceiling over it, or no ceiling is known there (a pillar is not). O(1).
  bool clear_of_ceiling(const tracking::ObjectObservation& o) const {
    return !o.ceiling_z || !within_ceiling_gap(o.box.center.z() + 0.5f * o.box.height, *o.ceiling_z);
  }

  /// at_ceiling for a static track's smoothed box, under the ceiling its
  /// observation `o` sees: a lamp or a patch of ceiling whose first
  /// observations ended lower, or a box that grew into the wall its object
  /// merged with. O(1).
  bool grown_to_ceiling(const Filter& f, const tracking::ObjectObservation& o) const {
    if (f.track.moving || !o.ceiling_z) return false;
    const tracking::Track& t = f.track;
    return reaches_ceiling(t.position.z() + 0.5f * t.height, t.height, std::max(t.length, t.width), *o.ceiling_z);
  }

  /// True when a box with its top at `top`, `height` high and `length` along
  /// its larger side [m] reaches within birth_ceiling_gap of `ceiling` and is
  /// not shaped like a pillar (at least kPillarHeight high and higher than long).
  bool reaches_ceiling(float top, float height, float length, float ceiling) const {
    return within_ceiling_gap(top, ceiling) && (height < kPillarHeight || height < length);
  }

  /// True when a box's top at `top` [m] is within birth_ceiling_gap of `ceiling`, or above it.
  bool within_ceiling_gap(float top, float ceiling) const { return top >= ceiling - params_.birth_ceiling_gap; }

  /// True when the centre of `o` lies in the box of a confirmed track seen
  /// in this update, grown by group_margin: a part of a tracked object that
  /// its component lost (a side beyond a shadow, a limb, a trunk below its
  /// crown), no object of its own.
  bool part_of_track(const tracking::ObjectObservation& o) const {
    for (const Filter& f : filters_) {
      if (!f.seen || f.set_aside || f.track.hits < params_.confirm_hits) continue;
      if (in_grown_box(o.box.center.x(), o.box.center.y(), f.x(0), f.x(1), f.box_yaw, f.track.length, f.track.width)) {
        return true;
      }
    }
    return false;
  }

  /// True when an observation of this update stands between `from` (the
  /// sensor) and the filter's predicted centre in the ground plane: its centre
  /// within half its larger side of the line of sight, between the two, and
  /// farther than that from the track's centre (not the track's own place).
  /// O(observations).
  bool hidden(const Filter& f, const Eigen::Vector3f& from, const std::vector<tracking::ObjectObservation>& objects) const {
    const Eigen::Vector2d a = from.head<2>().cast<double>();
    const Eigen::Vector2d sight = f.x.template head<2>() - a;
    const double length2 = sight.squaredNorm();
    if (length2 <= 0.0) return false;
    for (const tracking::ObjectObservation& o : objects) {
      const Eigen::Vector2d c = o.box.center.head<2>().cast<double>();
      const double along = (c - a).dot(sight) / length2;
      const double reach = 0.5 * static_cast<double>(std::max(o.box.length, o.box.width));
      if (along > 0.0 && along < 1.0 && (a + along * sight - c).norm() <= reach &&
          (c - f.x.template head<2>()).norm() > reach) {
        return true;
      }
    }
    return false;
  }

  /// True when the points of `o` clearly moved within the window: a window
  /// velocity of at least twice moving_speed and five standard errors.
  bool shows_motion(const tracking::ObjectObservation& o) const {
    if (!o.velocity.valid) return false;
    const float speed = o.velocity.velocity.norm();
    return speed >= 2.0f * params_.moving_speed && speed >= 5.0f * o.velocity.error;
  }

  /// What a window velocity adds to the smoothed one that decides moving or
  /// static: itself, or zero when it is within three standard errors of
  /// zero or, for a track not moving, its object's two ends differ in
  /// velocity by more than its speed (a standing object whose visible part
  /// shrinks moves one end, and its centroid with it; a mover going out of
  /// view moves the other, and stays a mover).
  static Eigen::Vector2f motion_sample(const tracking::WindowVelocity& v, bool moving) {
    const float speed = v.velocity.norm();
    const bool ends_agree = moving || v.end_difference <= speed;
    return speed >= 3.0f * v.error && ends_agree ? v.velocity : Eigen::Vector2f::Zero();
  }

  float position_sigma(const tracking::ObjectObservation& o) const {
    return o.box.quality == tracking::BoxQuality::two_sides ? params_.position_noise : params_.partial_position_noise;
  }

  /// Gate radius of a filter [m].
  double gate(const Filter& f) const {
    return static_cast<double>(params_.gate_distance) + 3.0 * std::sqrt(std::max(0.0, f.p(0, 0) + f.p(1, 1)));
  }
  double distance(const Filter& f, const tracking::ObjectObservation& o) const {
    return std::hypot(static_cast<double>(o.box.center.x()) - f.x(0), static_cast<double>(o.box.center.y()) - f.x(1));
  }

  /// True when the heights of `o`'s box and the filter's box (its smoothed
  /// centre height and height) overlap or lie less than gate_height apart:
  /// a patch of ceiling over a walker, or a lamp over a desk, is none of it.
  bool level_with(const Filter& f, const tracking::ObjectObservation& o) const {
    const float track_bottom = f.track.position.z() - 0.5f * f.track.height;
    const float track_top = f.track.position.z() + 0.5f * f.track.height;
    const float bottom = o.box.center.z() - 0.5f * o.box.height;
    const float top = o.box.center.z() + 0.5f * o.box.height;
    return bottom <= track_top + params_.gate_height && top >= track_bottom - params_.gate_height;
  }

  /// True when the box of `o`, grown by group_margin, holds the filter's
  /// predicted centre.
  bool holds(const tracking::ObjectObservation& o, const Filter& f) const {
    return in_grown_box(f.x(0), f.x(1), o.box.center.x(), o.box.center.y(), o.box.yaw, o.box.length, o.box.width);
  }

  /// True when the point (px, py) lies in the box centred at (cx, cy) with
  /// heading `yaw` [rad], `length` along it and `width` across [m], grown
  /// by group_margin on every side.
  bool in_grown_box(double px, double py, double cx, double cy, float yaw, float length, float width) const {
    const double c = std::cos(static_cast<double>(yaw)), s = std::sin(static_cast<double>(yaw));
    const double dx = px - cx, dy = py - cy;
    const double margin = static_cast<double>(params_.group_margin);
    return std::abs(c * dx + s * dy) <= 0.5 * static_cast<double>(length) + margin &&
           std::abs(c * dy - s * dx) <= 0.5 * static_cast<double>(width) + margin;
  }

  /// Fills track_of_ (per filter: the observation, or kNone), grouped_ and taken_.
  void associate(const std::vector<tracking::ObjectObservation>& objects) {
    track_of_.assign(filters_.size(), kNone);
    grouped_.assign(filters_.size(), false);
    taken_.assign(objects.size(), false);
    // By id: observations and filters both in component id order.
    id_order_.clear();
    for (std::size_t i = 0; i < filters_.size(); ++i) {
      if (filters_[i].track.cluster_id != kNoComponent) id_order_.emplace_back(filters_[i].track.cluster_id, i);
    }
    std::sort(id_order_.begin(), id_order_.end());
    for (std::size_t o = 0; o < objects.size(); ++o) {
      const auto it = std::lower_bound(id_order_.begin(), id_order_.end(), std::make_pair(objects[o].id, std::size_t{0}));
      if (it == id_order_.end() || it->first != objects[o].id) continue;
      const std::size_t i = it->second;
      if (distance(filters_[i], objects[o]) > gate(filters_[i])) continue;
      track_of_[i] = o;
      taken_[o] = true;
    }
    // Groups: a box holding the prediction of its own track (if any) and of
    // confirmed tracks without an observation, none of which has another
    // observation nearer than this one's centre within its gate.
    for (std::size_t o = 0; o < objects.size(); ++o) {
      members_.clear();
      for (std::size_t i = 0; i < filters_.size(); ++i) {
        if (track_of_[i] == o) members_.push_back(i);
      }
      const std::size_t own = members_.size();
      for (std::size_t i = 0; i < filters_.size(); ++i) {
        const Filter& f = filters_[i];
        if (track_of_[i] != kNone || f.set_aside || f.track.hits < params_.confirm_hits || !holds(objects[o], f)) {
          continue;
        }
        const double here = distance(f, objects[o]);
        bool nearer_elsewhere = false;
        for (std::size_t q = 0; q < objects.size() && !nearer_elsewhere; ++q) {
          const double d = distance(f, objects[q]);
          nearer_elsewhere = q != o && !taken_[q] && d < here && d <= gate(f);
        }
        if (!nearer_elsewhere) members_.push_back(i);
      }
      if (members_.size() < 2 || members_.size() == own) continue;
      // A group's box is about its members' size: a component spanning a room
      // holds many predictions and is no group of them.
      double members_area = 0.0;
      for (std::size_t i : members_) {
        members_area += static_cast<double>(filters_[i].track.length) * static_cast<double>(filters_[i].track.width);
      }
      const double area = static_cast<double>(objects[o].box.length) * static_cast<double>(objects[o].box.width);
      if (area > 2.0 * members_area + 1.0) continue;
      for (std::size_t i : members_) {
        track_of_[i] = o;
        grouped_[i] = true;
      }
      taken_[o] = true;
    }
    // By position, nearest pairs first.
    pairs_.clear();
    for (std::size_t i = 0; i < filters_.size(); ++i) {
      if (track_of_[i] != kNone) continue;
      for (std::size_t o = 0; o < objects.size(); ++o) {
        if (taken_[o]) continue;
        const double d = distance(filters_[i], objects[o]);
        if (d <= gate(filters_[i]) && level_with(filters_[i], objects[o])) pairs_.push_back(Pair{d, i, o});
      }
    }
    std::sort(pairs_.begin(), pairs_.end(), [](const Pair& a, const Pair& b) {
      return a.d != b.d ? a.d < b.d : (a.filter != b.filter ? a.filter < b.filter : a.object < b.object);
    });
    for (const Pair& pr : pairs_) {
      if (track_of_[pr.filter] != kNone || taken_[pr.object]) continue;
      track_of_[pr.filter] = pr.object;
      taken_[pr.object] = true;
    }
  }

  /// A track seen in a group: its component and points, its prediction kept.
  void seen_in_group(Filter& f, const tracking::ObjectObservation& o) const {
    if (!f.track.moving) f.x.template tail<2>().setZero();  // a static member stays where it was
    f.track.cluster_id = o.id;
    f.track.points = o.box.points;
    ++f.track.hits;
    f.track.last_seen = time_;
    f.seen = true;
  }

  /// The Kalman update with observation `o`, `dt` [s] after the last
  /// retrieval, then the smoothed box.
  void correct(Filter& f, const tracking::ObjectObservation& o, double dt) {
    const double sp = position_sigma(o);
    const double span = o.time - o.time_begin;
    const double overlap = dt > 0.0 ? std::max(1.0, span / std::max(dt, o.time - f.track.last_seen)) : 1.0;
    // A centre beyond the 99 % ellipse (the component changed: a merge, a
    // split, a new side in view) counts as if on it, so a jump of the box
    // moves the track without making speed.
    update_pair<0>(f, o.box.center.template head<2>().cast<double>(), sp * sp, true);
    // A static track whose windows show clear motion at restart_speed, its
    // object's ends agreeing, restart_updates times in a row starts moving
    // at that velocity, as a birth does: a cyclist that the track of
    // something standing took over, which the static prior below would hold.
    const float window_speed = o.velocity.velocity.norm();
    const bool shows = !f.track.moving && shows_motion(o) && window_speed >= params_.restart_speed &&
                       o.velocity.end_difference <= window_speed;
    f.motion_updates = shows ? f.motion_updates + 1 : 0;
    const bool restarts = shows && f.motion_updates >= params_.restart_updates;
    if (restarts) start_moving(f, o);
    // Static: a zero-velocity pseudo-measurement of `moving_speed`, so a box
    // centre that wanders (a side coming into view) does not build speed.
    if (!f.track.moving && !restarts) {
      update_pair<2>(f, Eigen::Vector2d::Zero(), static_cast<double>(params_.moving_speed) * params_.moving_speed, false);
    }
    // The window velocity, its variance times the overlap of successive
    // windows, robust like the centre (a component whose parts change within
    // the window shows a fast, tight, wrong velocity; a filter misled by a
    // jumping centre is pulled back by the points' own motion).
    if (o.velocity.valid) {
      const double rv = static_cast<double>(o.velocity.error) * o.velocity.error * overlap;
      update_pair<2>(f, o.velocity.velocity.cast<double>(), rv, true);
      const Eigen::Vector2f sample = motion_sample(o.velocity, f.track.moving);
      const float a = params_.extent_smoothing;
      f.window_velocity = f.has_window_velocity ? Eigen::Vector2f(f.window_velocity + a * (sample - f.window_velocity))
                                                : sample;
      f.has_window_velocity = true;
    }
    smooth_box(f, o, false);
    f.seen = true;
    f.track.cluster_id = o.id;
    f.track.points = o.box.points;
    ++f.track.hits;
    f.track.last_seen = time_;
    f.track.box_quality = o.box.quality;
  }

  /// The Kalman update with state components At and At + 1 (0: the centre,
  /// 2: the velocity) measured as `z`, each with variance `r`. With `robust`,
  /// a measurement beyond the 99 % ellipse of the prediction (chi-square, 2
  /// degrees of freedom: 9.21) has its variance raised by the excess: it
  /// counts as if on the ellipse. Fixed sizes: no allocation.
  template <int At>
  static void update_pair(Filter& f, const Eigen::Vector2d& z, double r, bool robust) {
    Eigen::Matrix2d s = f.p.template block<2, 2>(At, At);
    s.diagonal().array() += r;
    const Eigen::Vector2d innovation = z - f.x.template segment<2>(At);
    if (robust) {
      const double d2 = innovation.dot(s.inverse() * innovation);
      if (d2 > kChi2Gate) s.diagonal().array() += r * (d2 / kChi2Gate - 1.0);
    }
    // H selects the pair: the gain is P's two columns at At over S.
    const Eigen::Matrix<double, 4, 2> k = f.p.template middleCols<2>(At) * s.inverse();
    f.x += k * innovation;
    f.p -= k * f.p.template middleRows<2>(At);
    f.p = (0.5 * (f.p + f.p.transpose())).eval();
  }

  /// A tentative track for observation `o`.
  Filter born(const tracking::ObjectObservation& o) {
    Filter f;
    f.track.id = next_id_++;
    f.track.first_seen = time_;
    f.track.last_seen = time_;
    f.track.cluster_id = o.id;
    f.track.points = o.box.points;
    f.track.hits = 1;
    f.track.box_quality = o.box.quality;
    const double sp = position_sigma(o);
    const double sv = params_.initial_speed_noise;
    f.x << o.box.center.x(), o.box.center.y(), 0.0, 0.0;
    f.p = Vector4(sp * sp, sp * sp, sv * sv, sv * sv).asDiagonal();
    if (shows_motion(o)) start_moving(f, o);
    if (o.velocity.valid) f.window_velocity = motion_sample(o.velocity, shows_motion(o));
    f.has_window_velocity = o.velocity.valid;
    smooth_box(f, o, true);
    f.seen = true;
    return f;
  }

  /// The filter's velocity set to `o`'s window velocity, uncertain by three
  /// standard errors (at least 0.5 m/s) and independent of its position.
  static void start_moving(Filter& f, const tracking::ObjectObservation& o) {
    const double se = std::max(3.0 * static_cast<double>(o.velocity.error), 0.5);
    f.x.template tail<2>() = o.velocity.velocity.cast<double>();
    f.p.template bottomRows<2>().setZero();
    f.p.template rightCols<2>().setZero();
    f.p(2, 2) = f.p(3, 3) = se * se;
  }

  /// A track set aside, reported again at observation `o`'s place and box:
  /// the object come apart from what it grew into.
  void reappear(Filter& f, const tracking::ObjectObservation& o) const {
    const double sp = position_sigma(o);
    f.x.template head<2>() = o.box.center.template head<2>().cast<double>();
    f.p.template topRows<2>().setZero();
    f.p.template leftCols<2>().setZero();
    f.p(0, 0) = f.p(1, 1) = sp * sp;
    smooth_box(f, o, true);
    f.set_aside = false;
    f.ceiling_updates = 0;
  }

  /// Extent, height, centre height and heading, smoothed; on a two-sided
  /// box the new extent counts, on a partial one only where it is larger.
  void smooth_box(Filter& f, const tracking::ObjectObservation& o, bool first) const {
    const float a = first ? 1.0f : params_.extent_smoothing;
    tracking::Track& t = f.track;
    const tracking::OrientedBox& b = o.box;
    const bool whole = b.quality == tracking::BoxQuality::two_sides;
    const auto blend = [&](float current, float seen) {
      if (first) return seen;
      return whole ? current + a * (seen - current) : std::max(current, current + a * (seen - current));
    };
    t.length = blend(t.length, b.length);
    t.width = blend(t.width, b.width);
    t.height = first ? b.height : t.height + a * (b.height - t.height);
    t.position.z() = first ? b.center.z() : t.position.z() + a * (b.center.z() - t.position.z());
    // Headings are lines: move towards the representative nearest the current one.
    float seen = b.yaw;
    if (!first) {
      while (seen - f.box_yaw > 0.5f * kPi) seen -= kPi;
      while (seen - f.box_yaw < -0.5f * kPi) seen += kPi;
    }
    f.box_yaw = first ? seen : f.box_yaw + a * (seen - f.box_yaw);
  }

  /// The filter's state into its Track.
  void publish(Filter& f) const {
    tracking::Track& t = f.track;
    const bool seen = f.seen;
    const bool confirmed = t.hits >= params_.confirm_hits;
    t.state = !confirmed ? tracking::TrackState::tentative
                         : (seen ? tracking::TrackState::confirmed : tracking::TrackState::coasting);
    t.position.x() = static_cast<float>(f.x(0));
    t.position.y() = static_cast<float>(f.x(1));
    const double speed = std::hypot(f.x(2), f.x(3));
    const double sigma = std::sqrt(0.5 * std::max(0.0, f.p(2, 2) + f.p(3, 3)));
    t.speed_error = static_cast<float>(sigma);
    // The points' own motion within the windows must agree: a static object
    // whose component changes (occluded, merged, a side coming into view)
    // moves its box centre, not its points.
    const double moving = static_cast<double>(params_.moving_speed);
    const double window_speed = static_cast<double>(f.window_velocity.norm());
    if (t.moving) {
      t.moving = speed >= 0.5 * moving && f.has_window_velocity && window_speed >= 0.25 * moving;
    } else {
      t.moving = speed >= moving && speed >= 3.0 * sigma && f.has_window_velocity && window_speed >= 0.5 * moving;
    }
    if (t.moving) {
      t.velocity = Eigen::Vector3f(static_cast<float>(f.x(2)), static_cast<float>(f.x(3)), 0.0f);
      t.yaw = static_cast<float>(std::atan2(f.x(3), f.x(2)));
    } else {
      t.velocity = Eigen::Vector3f::Zero();
      float yaw = std::fmod(f.box_yaw, kPi);  // a line's heading into [-pi/2, pi/2)
      if (yaw >= 0.5f * kPi) yaw -= kPi;
      if (yaw < -0.5f * kPi) yaw += kPi;
      t.yaw = yaw;
    }
  }

  struct Pair {
    double d;
    std::size_t filter, object;
  };

  Params params_;
  std::vector<Filter> filters_;
  std::vector<tracking::Track> tracks_;
  std::vector<std::size_t> track_of_;
  std::vector<bool> grouped_, taken_;
  std::vector<std::size_t> members_;
  std::vector<std::pair<ComponentId, std::size_t>> id_order_;
  std::vector<Pair> pairs_;
  std::uint64_t next_id_ = 1;
  double time_ = 0.0;
  bool has_time_ = false;
};

static_assert(is_tracker_policy_v<KalmanTracker>, "KalmanTracker must model the Tracker policy");

}  // namespace streamclust
