// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// RuntimeGround: HeightMapGround or no structure removal, chosen at run time
/// (command-line tools) without a template instantiation per choice.

#include <streamclust/concepts/ground.hpp>
#include <streamclust/ground/height_map_ground.hpp>
#include <streamclust/surface_class.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <optional>

namespace streamclust {

/// Forwards to HeightMapGround when `use_height_map`, else classes every
/// point as an object (as NoGround, at the cost of the engine's structure
/// stage: a branch and an empty ring per point). Thread safety: none.
class RuntimeGround {
 public:
  struct Params {
    bool use_height_map = false;             ///< false: no structure removal
    HeightMapGround::Params height_map{};   ///< the model's parameters when used
  };
  static constexpr bool enabled = true;

  explicit RuntimeGround(const Params& params) {
    if (params.use_height_map) model_.emplace(params.height_map);
  }

  SurfaceClass classify(const Eigen::Vector3f& world, const Eigen::Vector3f& ray) {
    return model_ ? model_->classify(world, ray) : SurfaceClass::object;
  }
  void forget(const Eigen::Vector3f& world) {
    if (model_) model_->forget(world);
  }
  std::size_t heap_bytes() const { return model_ ? model_->heap_bytes() : 0; }
  bool uses_height_map() const { return model_.has_value(); }

 private:
  std::optional<HeightMapGround> model_;
};

}  // namespace streamclust
