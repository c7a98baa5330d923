// SPDX-License-Identifier: MIT
#pragma once
// Points of hand-made input streams.

#include <streamclust/point_traits.hpp>

namespace streamclust::test {

/// The point (x, y, 0) with intensity 0 at time `t` [s].
inline Point at(float x, float y, double t) { return Point{x, y, 0.0f, 0.0f, t}; }

}  // namespace streamclust::test
