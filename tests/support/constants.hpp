// SPDX-License-Identifier: MIT
#pragma once
// Numeric constants of the geometry tests and of the checks on non-finite input.

#include <limits>

namespace streamclust::test {

/// pi in float, for angles computed in float [rad].
inline constexpr float kPi = 3.14159265358979323846f;

/// Radians per degree, in double.
inline constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// A quiet NaN in float.
inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// Positive infinity in float.
inline constexpr float kInf = std::numeric_limits<float>::infinity();

}  // namespace streamclust::test
