// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// NoMotion: the world is the sensor frame (a sensor at rest, mounted level).

#include <streamclust/concepts/motion.hpp>
#include <streamclust/types.hpp>

#include <Eigen/Core>

namespace streamclust {

/// The default motion policy: no poses, no mount; the world frame is the
/// sensor frame (+z up), the sensor at its origin. `place` copies the point.
/// O(1). Thread safety: stateless.
class NoMotion {
 public:
  struct Params {};
  explicit NoMotion(const Params& = Params{}) {}
  static constexpr bool identity = true;

  RejectReason place(const Eigen::Vector3f& p, double /*time*/, PlacedPoint& placed) const {
    placed.world = p;
    placed.ray = p;
    return RejectReason::accepted;
  }
};

}  // namespace streamclust
