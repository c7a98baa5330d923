// SPDX-License-Identifier: MIT
#pragma once
// Parameters of the C-ARC presets for short test streams.

#include <streamclust/presets.hpp>

namespace streamclust::test {

/// A C-ARC preset with a 50 ms time window and the adaptive resolution
/// starting from an 8 x 32 grid: the first window (and so the calibration)
/// completes after a few hundred points of a 4 kHz stream.
template <class Preset>
ClustererParams<Preset> short_window_params() {
  auto params = to_clusterer_params<Preset>(CArcParams{});
  params.window.duration = 0.05;  // [s]
  params.resolution.initial_rows = 8;
  params.resolution.initial_cols = 32;
  return params;
}

}  // namespace streamclust::test
