// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// RuntimeResolution: a fixed grid or the adaptive loop, chosen at run time.

#include <streamclust/concepts/resolution.hpp>
#include <streamclust/resolution/adaptive.hpp>
#include <streamclust/resolution/fixed.hpp>

#include <vector>

namespace streamclust {

/// Forwards to FixedResolution or AdaptiveResolution. Not thread-safe
/// (calibrate mutates).
class RuntimeResolution {
 public:
  struct Params {
    bool adaptive = true;
    FixedResolution::Params fixed{};
    AdaptiveResolution::Params adaptive_loop{};
  };

  explicit RuntimeResolution(const Params& params)
      : adaptive_(params.adaptive), fixed_(params.fixed), loop_(params.adaptive_loop) {}

  bool needs_calibration() const { return adaptive_ && loop_.needs_calibration(); }
  GridSize grid() const { return adaptive_ ? loop_.grid() : fixed_.grid(); }
  GridSize calibrate(const std::vector<Projected>& coords, float fov_aspect) {
    return adaptive_ ? loop_.calibrate(coords, fov_aspect) : fixed_.calibrate(coords, fov_aspect);
  }
  bool adaptive() const { return adaptive_; }
  /// The adaptive loop's iterations (empty for a fixed grid).
  const std::vector<AdaptiveStep>& trace() const { return loop_.trace(); }
  /// Why the adaptive loop stopped (`not_run` for a fixed grid).
  AdaptiveStop stop_reason() const { return loop_.stop_reason(); }

 private:
  bool adaptive_;
  FixedResolution fixed_;
  AdaptiveResolution loop_;
};

static_assert(is_resolution_policy_v<RuntimeResolution>);

}  // namespace streamclust
