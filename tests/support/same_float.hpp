// SPDX-License-Identifier: MIT
#pragma once
// Equality of float fields of records read back (NaN equals NaN).

#include <cmath>

namespace streamclust::test {

/// True when `a` and `b` are equal or both NaN.
inline bool same_float(float a, float b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

}  // namespace streamclust::test
