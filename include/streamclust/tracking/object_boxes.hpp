// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// ObjectBoxes: after a retrieval, each component of enough points as an
/// observed object: its oriented box at the retrieval's time and the
/// velocity its points show within the window. What a tracker consumes.

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
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {
namespace tracking {

/// One component seen as an object in one retrieval.
struct ObjectObservation {
  ComponentId id = kNoComponent;  ///< the component's stable id
  OrientedBox box;                ///< at `time`; the motion within the window undone when it was measured
  WindowVelocity velocity;        ///< from the points' capture times (window_velocity)
  bool compensated = false;       ///< the points were moved to `time` along `velocity` before the box fit
  double time = 0.0;              ///< [s] the retrieval's time (its newest point)
  double time_begin = 0.0;        ///< [s] the component's oldest point
  /// [m] the ground near the object, when the ground policy knows it: under
  /// the footprint and ground_margin around (the box's bottom stands on that),
  /// else up to 4 m further (a far object beyond sparse ground).
  std::optional<float> ground_z;
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
  }
};

/// The objects of a retrieval: per component of at least `min_points`
/// points, its in-window velocity, then its oriented box from its points
/// (moved to the retrieval's time when the velocity is clear), standing on
/// the ground the engine's ground policy sees under it (when the policy
/// tells heights: has_ground_height_v).
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
  explicit ObjectBoxes(const ObjectBoxParams& params = {}) : params_(params) { params_.validate(); }

  /// The objects of `result`, which must be `engine`'s last retrieval
  /// (std::logic_error otherwise: its points and the window's differ in
  /// number), in component id order. The reference stays valid until the
  /// next call.
  template <class Engine>
  const std::vector<ObjectObservation>& update(const Engine& engine, const Clustering& result) {
    gather(engine, result);
    using Ground = typename Engine::ground_type;
    if constexpr (has_ground_height_v<Ground>) {
      const GroundLookup lookup{&engine.ground(), [](const void* g, float x, float y, float radius) {
                                  return static_cast<const Ground*>(g)->ground_height_near(x, y, radius);
                                }};
      return fit(result, lookup);
    } else {
      return fit(result, GroundLookup{});
    }
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
    }
  }

  /// The ground policy's ground_height_near, type-erased (one call per box):
  /// the fit below is compiled once, not once per engine type.
  struct GroundLookup {
    const void* ground = nullptr;
    std::optional<float> (*height_near)(const void*, float, float, float) = nullptr;
    std::optional<float> operator()(float x, float y, float radius) const {
      if (!height_near) return std::nullopt;
      return height_near(ground, x, y, radius);
    }
  };

  /// Velocity, compensation and box of every gathered component.
  const std::vector<ObjectObservation>& fit(const Clustering& result, const GroundLookup& ground_near) {
    observations_.clear();
    for (std::size_t slot = 0; slot < slot_component_.size(); ++slot) {
      const ComponentSummary& c = result.components[slot_component_[slot]];
      ObjectObservation o;
      o.id = c.id;
      o.time = result.time;
      o.time_begin = c.time_begin;
      std::vector<Eigen::Vector3f>& xyz = points_[slot];
      const std::vector<double>& t = times_[slot];
      o.velocity = window_velocity(xyz, t, params_.velocity, velocity_scratch_);
      const float speed = o.velocity.velocity.norm();
      if (o.velocity.valid && speed >= params_.compensate_speed && speed >= 3.0f * o.velocity.error) {
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
      const std::optional<float> ground = ground_near(mid.x(), mid.y(), reach);
      o.box = fit_oriented_box(xyz, ground, params_.fit, fit_scratch_);
      o.ground_z = ground ? ground : ground_near(mid.x(), mid.y(), reach + 4.0f);
      observations_.push_back(o);
    }
    return observations_;
  }

  static constexpr std::uint32_t kNoSlot = 0xffffffffu;
  ObjectBoxParams params_;
  std::vector<std::uint32_t> slot_of_;          // per component index
  std::vector<std::size_t> slot_component_;     // per slot: component index
  std::vector<std::vector<Eigen::Vector3f>> points_;
  std::vector<std::vector<double>> times_;
  std::vector<ObjectObservation> observations_;
  BoxFitScratch fit_scratch_;
  WindowVelocityScratch velocity_scratch_;
};

}  // namespace tracking
}  // namespace streamclust
