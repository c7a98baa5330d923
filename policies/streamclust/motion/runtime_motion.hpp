// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// RuntimeMotion: PosedMotion or no motion, chosen at run time (command-line
/// tools) without a template instantiation per choice.

#include <streamclust/concepts/motion.hpp>
#include <streamclust/detail/sampled_timer.hpp>
#include <streamclust/motion/posed_motion.hpp>
#include <streamclust/types.hpp>

#include <Eigen/Core>

namespace streamclust {

/// Forwards to PosedMotion when `enabled`, else copies the point (the
/// sensor frame is the world, as NoMotion; the samples equal NoMotion's bit
/// for bit). One predictable branch per point. With `timed`, the placement
/// is timed (`elapsed_us`: one point in 16, detail::SampledTimer). Thread
/// safety: as PosedMotion.
class RuntimeMotion {
 public:
  struct Params {
    bool enabled = false;         ///< false: no motion policy
    PosedMotion::Params posed{};  ///< the poses and mount when enabled
    bool timed = false;           ///< sum the placement's time into elapsed_us()
  };
  static constexpr bool identity = false;

  explicit RuntimeMotion(const Params& params)
      : posed_(params.enabled ? params.posed : PosedMotion::Params{}), enabled_(params.enabled), timed_(params.timed) {}

  RejectReason place(const Eigen::Vector3f& p, double time, PlacedPoint& placed) {
    if (!enabled_) {
      placed.world = p;
      placed.ray = p;
      return RejectReason::accepted;
    }
    if (!timed_) return posed_.place(p, time, placed);
    return timer_.run([&] { return posed_.place(p, time, placed); });
  }

  bool enabled() const { return enabled_; }
  /// Time spent placing points since construction [us], estimated from one
  /// point in 16 (with `timed`; else 0).
  double elapsed_us() const { return timer_.elapsed_us(); }

 private:
  PosedMotion posed_;  // unused unless enabled (a member, not an optional: no allocation either way)
  bool enabled_ = false;
  bool timed_ = false;
  detail::SampledTimer timer_;
};

}  // namespace streamclust
