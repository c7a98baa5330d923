// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// RuntimeGround: HeightMapGround or no structure removal, chosen at run time
/// (command-line tools) without a template instantiation per choice.

#include <streamclust/concepts/ground.hpp>
#include <streamclust/ground/height_map_ground.hpp>
#include <streamclust/surface_class.hpp>

#include <Eigen/Core>

#include <streamclust/detail/sampled_timer.hpp>

#include <cstddef>
#include <optional>

namespace streamclust {

/// Forwards to HeightMapGround when `use_height_map`, else classes every
/// point as an object (as NoGround, at the cost of the engine's structure
/// stage: a branch and an empty ring per point). With `timed`, the model's
/// work is timed (`elapsed_us`: one call in 16, detail::SampledTimer), for a
/// tool's report when its engine configuration is not timed. Thread safety:
/// none.
class RuntimeGround {
 public:
  struct Params {
    bool use_height_map = false;             ///< false: no structure removal
    HeightMapGround::Params height_map{};   ///< the model's parameters when used
    bool timed = false;                      ///< sum the model's time into elapsed_us()
  };
  static constexpr bool enabled = true;

  explicit RuntimeGround(const Params& params)
      : model_(params.use_height_map ? params.height_map : HeightMapGround::Params{}),
        used_(params.use_height_map),
        timed_(params.timed) {}

  SurfaceClass classify(const Eigen::Vector3f& world, const Eigen::Vector3f& ray) {
    if (!used_) return SurfaceClass::object;
    if (!timed_) return model_.classify(world, ray);
    return timer_.run([&] { return model_.classify(world, ray); });
  }
  void forget(const Eigen::Vector3f& world, SurfaceClass surface) {
    if (!used_) return;
    if (!timed_) return model_.forget(world, surface);
    timer_.run([&] { model_.forget(world, surface); });
  }
  /// Time spent in the model since construction [us], estimated from one
  /// call in 16 (with `timed`; else 0).
  double elapsed_us() const { return timer_.elapsed_us(); }
  /// HeightMapGround::ground_height_near when used, else nullopt.
  std::optional<float> ground_height_near(float x, float y, float radius) const {
    if (!used_) return std::nullopt;
    return model_.ground_height_near(x, y, radius);
  }
  /// HeightMapGround::ceiling_height_near when used, else nullopt.
  std::optional<float> ceiling_height_near(float x, float y, float radius) const {
    if (!used_) return std::nullopt;
    return model_.ceiling_height_near(x, y, radius);
  }
  std::size_t heap_bytes() const { return used_ ? model_.heap_bytes() : 0; }
  bool uses_height_map() const { return used_; }

 private:
  HeightMapGround model_;  // unused unless used_ (holds no heap until it counts a point)
  bool used_ = false;
  bool timed_ = false;
  detail::SampledTimer timer_;
};

}  // namespace streamclust
