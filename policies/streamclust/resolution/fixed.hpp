// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// FixedResolution: a grid size chosen by the user.

#include <streamclust/concepts/resolution.hpp>
#include <streamclust/types.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {

/// Fixed grid of `rows` x `cols` cells; no calibration (the engine starts
/// clustering with the first point). `calibrate` is accepted and returns the
/// grid unchanged.
///
/// O(1). Thread safety: immutable; const members are thread-safe.
///
/// Usage:
/// \code
///   streamclust::FixedResolution res{{64, 1024}};
///   streamclust::GridSize g = res.grid();  // {64, 1024}
/// \endcode
class FixedResolution {
 public:
  struct Params {
    std::uint32_t rows = 64;    ///< [cells] vertical, >= 1
    std::uint32_t cols = 1024;  ///< [cells] horizontal, >= 1; rows x cols <= 2^31
  };

  /// Throws std::invalid_argument for a zero dimension or more than 2^31 cells.
  explicit FixedResolution(const Params& params) : grid_{params.rows, params.cols} {
    if (params.rows < 1)
      throw std::invalid_argument("FixedResolution: parameter rows = 0 is invalid; allowed: >= 1 cells");
    if (params.cols < 1)
      throw std::invalid_argument("FixedResolution: parameter cols = 0 is invalid; allowed: >= 1 cells");
    const std::uint64_t cells = std::uint64_t{params.rows} * params.cols;
    if (cells > (std::uint64_t{1} << 31))
      throw std::invalid_argument("FixedResolution: parameter rows x cols = " + std::to_string(cells) +
                                  " is invalid; allowed: [1, 2^31] cells");
  }

  /// Always false.
  bool needs_calibration() const { return false; }

  /// The configured grid.
  GridSize grid() const { return grid_; }

  /// Returns grid() unchanged; the coordinates are ignored.
  GridSize calibrate(const std::vector<Projected>& /*coords*/, float /*fov_aspect*/) { return grid_; }

 private:
  GridSize grid_;
};

}  // namespace streamclust

static_assert(streamclust::is_resolution_policy_v<streamclust::FixedResolution>,
              "STREAMCLUST_RESOLUTION_POLICY_INVALID: FixedResolution");
