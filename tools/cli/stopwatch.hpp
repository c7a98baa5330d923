// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Elapsed time on the steady clock, for the evaluations' cost columns.

#include <chrono>

namespace streamclust::cli {

/// Milliseconds elapsed on the steady clock since `t0`.
inline double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace streamclust::cli
