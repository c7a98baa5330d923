// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// NoGround: no structure removal; every accepted point is an object point.

#include <streamclust/concepts/ground.hpp>
#include <streamclust/surface_class.hpp>

#include <Eigen/Core>

#include <cstddef>

namespace streamclust {

/// The default ground policy: classes every point as an object. The engine
/// skips the stage (`enabled` is false). Stateless.
class NoGround {
 public:
  struct Params {};
  explicit NoGround(const Params& = Params{}) {}
  static constexpr bool enabled = false;

  SurfaceClass classify(const Eigen::Vector3f& /*world*/, const Eigen::Vector3f& /*ray*/) { return SurfaceClass::object; }
  void forget(const Eigen::Vector3f& /*world*/, SurfaceClass /*surface*/) {}
  std::size_t heap_bytes() const { return 0; }
};

}  // namespace streamclust
