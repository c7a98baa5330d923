// SPDX-License-Identifier: MIT
#pragma once
// Tolerances of the checks on computed floating-point values.

#include <doctest/doctest.h>

namespace streamclust::test {

/// `v` within a relative 1e-12: equal up to the rounding of a long computation.
inline doctest::Approx near(double v) { return doctest::Approx(v).epsilon(1e-12); }

}  // namespace streamclust::test
