// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// ObjectBoxes: after a retrieval, each component of enough points as an
/// observed object: its oriented box at the retrieval's time and the
/// velocity its points show within the window. What a tracker consumes.
/// The pieces of one fast mover (components seen one after another along a
/// path within the window) are one object.

#include <streamclust/clustering.hpp>
#include <streamclust/concepts/ground.hpp>
#include <streamclust/tracking/oriented_box.hpp>
#include <streamclust/tracking/window_velocity.hpp>
#include <streamclust/types.hpp>

#include <streamclust/detail/parameter_check.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {
namespace tracking {

/// One component seen as an object in one retrieval.
struct ObjectObservation {
  ComponentId id = kNoComponent;  ///< the component's stable id (of linked pieces: the largest piece's)
  OrientedBox box;                ///< at `time`; the motion within the window undone when it was measured
  WindowVelocity velocity;        ///< from the points' capture times (window_velocity)
  bool compensated = false;       ///< the points were moved to `time` along `velocity` before the box fit
  double time = 0.0;              ///< [s] the retrieval's time (its newest point)
  double time_begin = 0.0;        ///< [s] the component's oldest point
  std::size_t pieces = 1;         ///< components linked into this object (one fast mover seen in pieces)
  /// [m] the ground near the object, when the ground policy knows it: under
  /// the footprint and ground_margin around (the box's bottom stands on that),
  /// else up to 4 m further (a far object beyond sparse ground).
  std::optional<float> ground_z;
  /// [m] the ceiling over the object, when the ground policy knows it
  /// (has_ceiling_height_v): over the footprint and ground_margin around.
  std::optional<float> ceiling_z;
  /// [m] where the sensor was (world frame) when the newest point of the
  /// retrieval's boxed components was captured: the same for every
  /// observation of an update; unset when not known.
  std::optional<Eigen::Vector3f> viewpoint;
};

/// Settings of ObjectBoxes.
struct ObjectBoxParams {
  std::size_t min_points = 10;  ///< components with fewer points get no box, [1, 100000]
  BoxFitParams fit;            ///< the box fit's (oriented_box.hpp)
  WindowVelocityParams velocity;  ///< the in-window velocity's (window_velocity.hpp)
  /// [m/s] a window velocity at least this fast and 3 standard errors from
  /// zero moves the points to the retrieval's time before the box fit (a
  /// walker's 0.5 s window is 0.75 m long otherwise), [0, 100]
  float compensate_speed = 0.3f;
  float ground_margin = 0.5f;  ///< [m] the ground is looked up this far around the footprint, [0, 10]
  /// The ground and ceiling a component's box was last looked up with are
  /// used again, for at most `lookup_reuse_seconds` after that lookup, while
  /// its footprint's centre and half side each stay within
  /// `lookup_reuse_shift` of the looked up ones: a standing object is looked
  /// up about once every 0.5 s, not at every retrieval. 0 s: at every one.
  double lookup_reuse_seconds = 0.5;  ///< [s] [0, 10]
  float lookup_reuse_shift = 0.25f;   ///< [m] [0, 10]
  /// Linking the pieces of a fast mover (a car passing at 10 m/s breaks
  /// into components that each cover 0.1-0.2 s of its path): two components
  /// without a window velocity of their own, seen one after the other (time
  /// ranges overlapping at most `piece_overlap`, apart at most `piece_gap`),
  /// whose centroids at their mean times move at `piece_min_speed` to
  /// `piece_max_speed`; each at least `piece_min_height` tall (flat patches
  /// are ceilings and roofs) and reaching down to within
  /// `piece_max_clearance` of the ground near it (a mover stands on the
  /// ground; a piece hanging higher is the top of a structure the turning
  /// view passes over); their heights overlapping by half the shorter one's,
  /// their tops at most `piece_top_difference` apart; and whose points
  /// together show that velocity (window_velocity five standard errors from
  /// zero, within 30 % of the centroids'), are one object.
  bool link_pieces = true;
  float piece_min_speed = 3.0f;   ///< [m/s] (0, 100]
  float piece_max_speed = 30.0f;  ///< [m/s] [piece_min_speed, 100]
  double piece_gap = 0.25;        ///< [s] [0, 10]
  double piece_overlap = 0.05;    ///< [s] [0, 10]
  float piece_min_height = 0.3f;      ///< [m] [0, 100]
  float piece_top_difference = 1.0f;  ///< [m] [0, 100]
  float piece_max_clearance = 1.5f;   ///< [m] [0, 100]

  /// Throws std::invalid_argument naming the first setting out of range.
  void validate() const {
    fit.validate();
    velocity.validate();
    auto check = [](bool ok, const char* name, double value, const char* allowed) {
      streamclust::detail::require_parameter(ok, "ObjectBoxParams", name, value, allowed);
    };
    check(min_points >= 1 && min_points <= 100000, "min_points", static_cast<double>(min_points), "[1, 100000]");
    check(compensate_speed >= 0.0f && compensate_speed <= 100.0f, "compensate_speed", compensate_speed,
          "[0, 100] m/s");
    check(ground_margin >= 0.0f && ground_margin <= 10.0f, "ground_margin", ground_margin, "[0, 10] m");
    check(lookup_reuse_seconds >= 0.0 && lookup_reuse_seconds <= 10.0, "lookup_reuse_seconds", lookup_reuse_seconds,
          "[0, 10] s");
    check(lookup_reuse_shift >= 0.0f && lookup_reuse_shift <= 10.0f, "lookup_reuse_shift", lookup_reuse_shift,
          "[0, 10] m");
    check(piece_min_speed > 0.0f && piece_min_speed <= 100.0f, "piece_min_speed", piece_min_speed, "(0, 100] m/s");
    check(piece_max_speed >= piece_min_speed && piece_max_speed <= 100.0f, "piece_max_speed", piece_max_speed,
          "[piece_min_speed, 100] m/s");
    check(piece_gap >= 0.0 && piece_gap <= 10.0, "piece_gap", piece_gap, "[0, 10] s");
    check(piece_overlap >= 0.0 && piece_overlap <= 10.0, "piece_overlap", piece_overlap, "[0, 10] s");
    check(piece_min_height >= 0.0f && piece_min_height <= 100.0f, "piece_min_height", piece_min_height,
          "[0, 100] m");
    check(piece_max_clearance >= 0.0f && piece_max_clearance <= 100.0f, "piece_max_clearance",
          piece_max_clearance, "[0, 100] m");
    check(piece_top_difference >= 0.0f && piece_top_difference <= 100.0f, "piece_top_difference",
          piece_top_difference, "[0, 100] m");
  }
};

/// The objects of a retrieval: per component of at least `min_points`
/// points, its in-window velocity, then its oriented box from its points
/// (moved to the retrieval's time when the velocity is clear), standing on
/// the ground the engine's ground policy sees under it (when the policy
/// tells heights: has_ground_height_v), under the ceiling it sees over it
/// (has_ceiling_height_v).
///
/// \code
///   streamclust::tracking::ObjectBoxes boxes;
///   const auto& result = engine.retrieve();
///   for (const auto& o : boxes.update(engine, result)) {
///     use(o.id, o.box.center, o.box.yaw, o.velocity.velocity);
///   }
/// \endcode
///
/// update(): O(window points + components x log components + boxed points
/// + boxed objects x 32 x search_points); after the first calls no
/// allocation (scratch keeps its capacity). Thread safety: none; one
/// ObjectBoxes per engine.
class ObjectBoxes {
 public:
  explicit ObjectBoxes(const ObjectBoxParams& params = {}) : params_(params), piece_velocity_(params.velocity) {
    params_.validate();
    piece_velocity_.slice_seconds *= 0.5;
  }

  /// The objects of `result`, which must be `engine`'s last retrieval
  /// (std::logic_error otherwise: its points and the window's differ in
  /// number), in component id order. The reference stays valid until the
  /// next call.
  template <class Engine>
  const std::vector<ObjectObservation>& update(const Engine& engine, const Clustering& result) {
    gather(engine, result);
    using Ground = typename Engine::ground_type;
    GroundLookup lookup{&engine.ground()};
    if constexpr (has_ground_height_v<Ground>) {
      lookup.height_near = [](const void* g, float x, float y, float radius) {
        return static_cast<const Ground*>(g)->ground_height_near(x, y, radius);
      };
    }
    if constexpr (has_ceiling_height_v<Ground>) {
      lookup.ceiling_near = [](const void* g, float x, float y, float radius) {
        return static_cast<const Ground*>(g)->ceiling_height_near(x, y, radius);
      };
    }
    return fit(result, lookup);
  }

  /// The last update's objects.
  const std::vector<ObjectObservation>& observations() const { return observations_; }
  const ObjectBoxParams& params() const { return params_; }

 private:
  /// Groups the window's points of every component with min_points into
  /// points_[slot] / times_[slot], slot in component order.
  template <class Engine>
  void gather(const Engine& engine, const Clustering& result) {
    const std::vector<ComponentSummary>& comps = result.components;
    viewpoint_.reset();
    slot_of_.assign(comps.size(), kNoSlot);
    slot_component_.clear();
    for (std::size_t i = 0; i < comps.size(); ++i) {
      if (comps[i].size < params_.min_points) continue;
      slot_of_[i] = static_cast<std::uint32_t>(slot_component_.size());
      slot_component_.push_back(i);
    }
    if (points_.size() < slot_component_.size()) {
      points_.resize(slot_component_.size());
      times_.resize(slot_component_.size());
    }
    for (std::size_t s = 0; s < slot_component_.size(); ++s) {
      points_[s].clear();
      times_[s].clear();
    }
    // Window positions: the result's points and the engine's ring, both
    // oldest first; a point's sample is read only when its component is boxed.
    // No component (an empty window, or the result of a retrieval while
    // the engine calibrates, which holds no point): nothing to gather.
    if (slot_component_.empty()) return;
    const std::size_t n = result.points.size();
    if (engine.size() != n) throw std::logic_error("ObjectBoxes::update: the result is not the engine's last retrieval");
    std::size_t cached = 0;
    double newest = -std::numeric_limits<double>::infinity();
    PointHandle newest_handle = kNoPoint;
    for (std::size_t pos = 0; pos < n; ++pos) {
      const PointLabel& p = result.points[pos];
      if (cached >= comps.size() || comps[cached].id != p.label) {
        const auto it = std::lower_bound(comps.begin(), comps.end(), p.label,
                                         [](const ComponentSummary& c, ComponentId id) { return c.id < id; });
        if (it == comps.end() || it->id != p.label) continue;
        cached = static_cast<std::size_t>(it - comps.begin());
      }
      const std::uint32_t slot = slot_of_[cached];
      if (slot == kNoSlot) continue;
      const PointHandle h = engine.handle_at(pos);
      if (engine.stream_index(h) != p.stream_index) {
        throw std::logic_error("ObjectBoxes::update: the result is not the engine's last retrieval");
      }
      const Sample sample = engine.sample(h);
      points_[slot].push_back(sample.position);
      times_[slot].push_back(sample.time);
      if (sample.time >= newest) {
        newest = sample.time;
        newest_handle = h;
      }
    }
    if (newest > -std::numeric_limits<double>::infinity()) {  // the sensor: back along that point's ray
      const Sample sample = engine.sample(newest_handle);
      viewpoint_ = Eigen::Vector3f(sample.position - sample.direction * sample.range);
    }
  }

  /// The ground policy's ground_height_near and ceiling_height_near,
  /// type-erased (a call or two per box; null when the policy has none):
  /// the fit below is compiled once, not once per engine type.
  struct GroundLookup {
    const void* ground = nullptr;
    std::optional<float> (*height_near)(const void*, float, float, float) = nullptr;
    std::optional<float> (*ceiling_near)(const void*, float, float, float) = nullptr;
    std::optional<float> operator()(float x, float y, float radius) const {
      if (!height_near) return std::nullopt;
      return height_near(ground, x, y, radius);
    }
    std::optional<float> ceiling(float x, float y, float radius) const {
      if (!ceiling_near) return std::nullopt;
      return ceiling_near(ground, x, y, radius);
    }
  };

  /// The ground and ceiling around a component's footprint, as last looked
  /// up (lookup_reuse_seconds).
  struct FootprintLookup {
    ComponentId id = kNoComponent;
    Eigen::Vector2f mid = Eigen::Vector2f::Zero();  ///< [m] the footprint's centre
    float reach = 0.0f;                             ///< [m] half its larger side plus ground_margin
    double time = 0.0;                              ///< [s] the retrieval it was looked up at
    std::optional<float> ground, ground_z, ceiling_z;
  };

  /// The lookups of component `id` with footprint centre `mid` and `reach`
  /// at `time`: last update's when they may be used again, else new ones.
  /// `reused_` walks last update's lookups, sorted by id; ids must come in
  /// increasing order within an update. Amortized O(1) plus the lookups.
  FootprintLookup look_up(ComponentId id, const Eigen::Vector2f& mid, float reach, double time,
                          const GroundLookup& ground_near) {
    while (reused_ < last_lookups_.size() && last_lookups_[reused_].id < id) ++reused_;
    if (reused_ < last_lookups_.size()) {
      const FootprintLookup& last = last_lookups_[reused_];
      const float shift = params_.lookup_reuse_shift;
      if (last.id == id && time >= last.time && time - last.time < params_.lookup_reuse_seconds &&
          (last.mid - mid).norm() <= shift && std::fabs(last.reach - reach) <= shift) {
        return last;
      }
    }
    FootprintLookup fresh;
    fresh.id = id;
    fresh.mid = mid;
    fresh.reach = reach;
    fresh.time = time;
    fresh.ground = ground_near(mid.x(), mid.y(), reach);
    fresh.ground_z = fresh.ground ? fresh.ground : ground_near(mid.x(), mid.y(), reach + 4.0f);
    fresh.ceiling_z = ground_near.ceiling(mid.x(), mid.y(), reach);
    return fresh;
  }

  /// What the linking of pieces reads of a gathered component.
  struct SlotSummary {
    double t_min = 0.0, t_max = 0.0, t_mean = 0.0;  ///< [s] capture times
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();  ///< [m] ground plane
    float z_lo = 0.0f, z_hi = 0.0f;                   ///< [m] height range
    float radius = 0.0f;                              ///< [m] half the larger side of its axis-aligned footprint
    int grounded = -1;                                ///< stands on its ground: 1, 0, or -1 not looked up yet
    WindowVelocity velocity;
    bool moves = false;  ///< its own window velocity is clear (compensated alone)
  };

  bool clear_motion(const WindowVelocity& v) const {
    const float speed = v.velocity.norm();
    return v.valid && speed >= params_.compensate_speed && speed >= 3.0f * v.error;
  }

  /// Velocity, pieces, compensation and box of every gathered component.
  const std::vector<ObjectObservation>& fit(const Clustering& result, const GroundLookup& ground_near) {
    observations_.clear();
    const std::size_t slots = slot_component_.size();
    summaries_.resize(slots);
    for (std::size_t slot = 0; slot < slots; ++slot) summarize(slot);
    link(slots, ground_near);
    reused_ = 0;
    lookups_.clear();
    for (std::size_t slot = 0; slot < slots; ++slot) {
      if (group_of_[slot] != slot) continue;  // a piece of an object emitted at its largest piece
      const ComponentSummary& c = result.components[slot_component_[slot]];
      ObjectObservation o;
      o.time = result.time;
      o.time_begin = c.time_begin;
      std::vector<Eigen::Vector3f>* xyz_in = &points_[slot];
      const std::vector<double>* t_in = &times_[slot];
      o.velocity = summaries_[slot].velocity;
      if (group_size_[slot] > 1) {
        gather_group(slot);
        for (std::size_t m = 0; m < slots; ++m) {
          if (group_of_[m] != slot) continue;
          o.time_begin = std::min(o.time_begin, result.components[slot_component_[m]].time_begin);
        }
        xyz_in = &group_points_;
        t_in = &group_times_;
        o.velocity = group_velocity_[slot];
        o.pieces = group_size_[slot];
      }
      o.id = c.id;
      std::vector<Eigen::Vector3f>& xyz = *xyz_in;
      const std::vector<double>& t = *t_in;
      if (clear_motion(o.velocity)) {
        for (std::size_t i = 0; i < xyz.size(); ++i) {
          const auto dt = static_cast<float>(result.time - t[i]);
          xyz[i].head<2>() += o.velocity.velocity * dt;
        }
        o.compensated = true;
      }
      Eigen::Vector2f lo = xyz.front().head<2>(), hi = lo;
      for (const Eigen::Vector3f& p : xyz) {
        lo = lo.cwiseMin(p.head<2>());
        hi = hi.cwiseMax(p.head<2>());
      }
      const Eigen::Vector2f mid = 0.5f * (lo + hi);
      const float reach = 0.5f * (hi - lo).maxCoeff() + params_.ground_margin;
      lookups_.push_back(look_up(o.id, mid, reach, result.time, ground_near));
      const FootprintLookup& around = lookups_.back();
      o.box = fit_oriented_box(xyz, around.ground, params_.fit, fit_scratch_);
      o.ground_z = around.ground_z;
      o.ceiling_z = around.ceiling_z;
      o.viewpoint = viewpoint_;
      observations_.push_back(o);
    }
    lookups_.swap(last_lookups_);
    return observations_;
  }

  /// summaries_[slot] of points_[slot] / times_[slot]. O(points).
  void summarize(std::size_t slot) {
    SlotSummary& s = summaries_[slot];
    const std::vector<Eigen::Vector3f>& xyz = points_[slot];
    const std::vector<double>& t = times_[slot];
    s.velocity = window_velocity(xyz, t, params_.velocity, velocity_scratch_);
    s.moves = clear_motion(s.velocity);
    s.t_min = s.t_max = t.front();
    s.z_lo = s.z_hi = xyz.front().z();
    double sum_t = 0.0;
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    Eigen::Vector2f lo = xyz.front().head<2>(), hi = lo;
    for (std::size_t i = 0; i < xyz.size(); ++i) {
      lo = lo.cwiseMin(xyz[i].head<2>());
      hi = hi.cwiseMax(xyz[i].head<2>());
      s.t_min = std::min(s.t_min, t[i]);
      s.t_max = std::max(s.t_max, t[i]);
      s.z_lo = std::min(s.z_lo, xyz[i].z());
      s.z_hi = std::max(s.z_hi, xyz[i].z());
      sum_t += t[i];
      sum += xyz[i].head<2>().cast<double>();
    }
    const auto n = static_cast<double>(xyz.size());
    s.t_mean = sum_t / n;
    s.centroid = sum / n;
    s.radius = 0.5f * (hi - lo).maxCoeff();
    s.grounded = -1;
  }

  /// group_of_[slot]: the slot of the largest piece of the object `slot`
  /// belongs to (itself when alone); group_size_[root]: its pieces. Pairs of
  /// components without motion of their own are linked when they pass the
  /// pieces' rules (ObjectBoxParams::link_pieces); a group whose points
  /// together show no clear motion is split again. O(candidates^2 + linked
  /// points).
  void link(std::size_t slots, const GroundLookup& ground_near) {
    group_of_.resize(slots);
    group_size_.assign(slots, 1);
    for (std::size_t i = 0; i < slots; ++i) group_of_[i] = i;
    if (!params_.link_pieces) return;
    candidates_.clear();
    for (std::size_t i = 0; i < slots; ++i) {
      if (!summaries_[i].moves) candidates_.push_back(i);
    }
    std::sort(candidates_.begin(), candidates_.end(),
              [&](std::size_t a, std::size_t b) { return summaries_[a].t_mean < summaries_[b].t_mean; });
    bool linked = false;
    for (std::size_t ai = 0; ai < candidates_.size(); ++ai) {
      const std::size_t a = candidates_[ai];
      const SlotSummary& sa = summaries_[a];
      for (std::size_t bi = ai + 1; bi < candidates_.size(); ++bi) {
        const std::size_t b = candidates_[bi];
        const SlotSummary& sb = summaries_[b];
        if (sb.t_min < sa.t_max - params_.piece_overlap || sb.t_min - sa.t_max > params_.piece_gap) continue;
        const double dt = sb.t_mean - sa.t_mean;
        if (!(dt > 0.02)) continue;
        const Eigen::Vector2d v = (sb.centroid - sa.centroid) / dt;
        const double speed = v.norm();
        if (speed < params_.piece_min_speed || speed > params_.piece_max_speed) continue;
        if (sa.z_hi - sa.z_lo < params_.piece_min_height || sb.z_hi - sb.z_lo < params_.piece_min_height) continue;
        const float shared_height = std::min(sa.z_hi, sb.z_hi) - std::max(sa.z_lo, sb.z_lo);
        if (shared_height < 0.5f * std::min(sa.z_hi - sa.z_lo, sb.z_hi - sb.z_lo)) continue;
        if (std::abs(sa.z_hi - sb.z_hi) > params_.piece_top_difference) continue;
        if (!grounded(a, ground_near) || !grounded(b, ground_near)) continue;
        if (find(a) == find(b)) continue;
        group_points_.assign(points_[a].begin(), points_[a].end());
        group_points_.insert(group_points_.end(), points_[b].begin(), points_[b].end());
        group_times_.assign(times_[a].begin(), times_[a].end());
        group_times_.insert(group_times_.end(), times_[b].begin(), times_[b].end());
        if (!consistent(window_velocity(group_points_, group_times_, piece_velocity_, velocity_scratch_), v)) {
          continue;
        }
        group_of_[find(b)] = find(a);
        linked = true;
      }
    }
    if (!linked) return;
    // Roots: each group's largest piece (ties: the older component).
    for (std::size_t i = 0; i < slots; ++i) group_of_[i] = find(i);
    root_of_group_.assign(slots, kNoSlotIndex);
    for (std::size_t i = 0; i < slots; ++i) {
      std::size_t& root = root_of_group_[group_of_[i]];
      if (root == kNoSlotIndex || points_[i].size() > points_[root].size()) root = i;
    }
    for (std::size_t i = 0; i < slots; ++i) group_of_[i] = root_of_group_[group_of_[i]];
    group_size_.assign(slots, 0);
    for (std::size_t i = 0; i < slots; ++i) ++group_size_[group_of_[i]];
    // Each group's velocity from all its points; a group of three or more
    // whose points together show no clear motion falls apart into its pieces.
    group_velocity_.resize(slots);
    for (std::size_t root = 0; root < slots; ++root) {
      if (group_of_[root] != root || group_size_[root] < 2) continue;
      gather_group(root);
      group_velocity_[root] = window_velocity(group_points_, group_times_, piece_velocity_, velocity_scratch_);
      if (clear_motion(group_velocity_[root])) continue;
      for (std::size_t m = 0; m < slots; ++m) {
        if (group_of_[m] == root && m != root) {
          group_of_[m] = m;
          group_size_[m] = 1;
        }
      }
      group_size_[root] = 1;
    }
  }

  /// group_points_ / group_times_: the points of every piece of the object
  /// whose largest piece is `root`. O(slots + its points).
  void gather_group(std::size_t root) {
    group_points_.clear();
    group_times_.clear();
    for (std::size_t m = 0; m < group_of_.size(); ++m) {
      if (group_of_[m] != root) continue;
      group_points_.insert(group_points_.end(), points_[m].begin(), points_[m].end());
      group_times_.insert(group_times_.end(), times_[m].begin(), times_[m].end());
    }
  }

  /// The points of linked pieces show the pieces' velocity `v`, five
  /// standard errors from zero.
  bool consistent(const WindowVelocity& joint, const Eigen::Vector2d& v) const {
    return clear_motion(joint) && joint.velocity.norm() >= 5.0f * joint.error &&
           (joint.velocity.cast<double>() - v).norm() <= 0.3 * v.norm();
  }

  /// The piece `slot` reaches down to within piece_max_clearance of the
  /// ground near it (looked up once per retrieval). A piece hanging higher
  /// is the top of a structure, not a mover.
  bool grounded(std::size_t slot, const GroundLookup& ground_near) {
    SlotSummary& s = summaries_[slot];
    if (s.grounded < 0) {
      const std::optional<float> ground =
          ground_near(static_cast<float>(s.centroid.x()), static_cast<float>(s.centroid.y()),
                      s.radius + params_.ground_margin);
      s.grounded = (!ground || s.z_lo - *ground <= params_.piece_max_clearance) ? 1 : 0;
    }
    return s.grounded == 1;
  }

  /// The group of `i` while linking (path halving).
  std::size_t find(std::size_t i) {
    while (group_of_[i] != i) {
      group_of_[i] = group_of_[group_of_[i]];
      i = group_of_[i];
    }
    return i;
  }

  static constexpr std::uint32_t kNoSlot = 0xffffffffu;
  static constexpr std::size_t kNoSlotIndex = static_cast<std::size_t>(-1);
  ObjectBoxParams params_;
  /// The velocity of linked pieces: slices of half the length (two pieces of
  /// 0.05-0.1 s with a gap between them fill too few slices of 0.1 s).
  WindowVelocityParams piece_velocity_;
  std::vector<std::uint32_t> slot_of_;          // per component index
  std::vector<std::size_t> slot_component_;     // per slot: component index
  std::vector<std::vector<Eigen::Vector3f>> points_;
  std::vector<std::vector<double>> times_;
  std::vector<ObjectObservation> observations_;
  std::optional<Eigen::Vector3f> viewpoint_;  ///< [m] the sensor at the newest gathered point (gather)
  std::vector<SlotSummary> summaries_;          // per slot
  std::vector<std::size_t> group_of_;           // per slot: the slot of its object's largest piece
  std::vector<std::size_t> group_size_;         // per slot: pieces of the object it is the largest of
  std::vector<std::size_t> root_of_group_;      // scratch of link()
  std::vector<WindowVelocity> group_velocity_;  // per slot that is a group's largest piece: all its points
  std::vector<std::size_t> candidates_;         // slots without motion of their own, by mean time
  std::vector<Eigen::Vector3f> group_points_;   // the points of linked pieces
  std::vector<double> group_times_;
  BoxFitScratch fit_scratch_;
  WindowVelocityScratch velocity_scratch_;
  std::vector<FootprintLookup> lookups_;       // this update's, by id
  std::vector<FootprintLookup> last_lookups_;  // the last update's, by id
  std::size_t reused_ = 0;                     // look_up's place in last_lookups_
};

}  // namespace tracking
}  // namespace streamclust
