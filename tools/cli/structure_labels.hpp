// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The labels the tool's outputs give structure points (docs/cli.md); -1 is
/// an unlabelled (rejected) record, components are 0 and up.

#include <cstdint>

namespace streamclust::cli {

inline constexpr std::int64_t kGroundLabel = -2;
inline constexpr std::int64_t kCeilingLabel = -3;
inline constexpr std::int64_t kWallLabel = -4;

}  // namespace streamclust::cli
