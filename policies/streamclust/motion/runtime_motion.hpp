// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// RuntimeMotion: PosedMotion or no motion, chosen at run time (command-line
/// tools) without a template instantiation per choice.

#include <streamclust/concepts/motion.hpp>
#include <streamclust/motion/posed_motion.hpp>
#include <streamclust/types.hpp>

#include <Eigen/Core>

#include <optional>

namespace streamclust {

/// Forwards to PosedMotion when `enabled`, else copies the point (the
/// sensor frame is the world, as NoMotion; the samples equal NoMotion's bit
/// for bit). One predictable branch per point. Thread safety: as PosedMotion.
class RuntimeMotion {
 public:
  struct Params {
    bool enabled = false;         ///< false: no motion policy
    PosedMotion::Params posed{};  ///< the poses and mount when enabled
  };
  static constexpr bool identity = false;

  explicit RuntimeMotion(const Params& params) {
    if (params.enabled) posed_.emplace(params.posed);
  }

  RejectReason place(const Eigen::Vector3f& p, double time, PlacedPoint& placed) {
    if (!posed_) {
      placed.world = p;
      placed.ray = p;
      return RejectReason::accepted;
    }
    return posed_->place(p, time, placed);
  }

  bool enabled() const { return posed_.has_value(); }

 private:
  std::optional<PosedMotion> posed_;
};

}  // namespace streamclust
