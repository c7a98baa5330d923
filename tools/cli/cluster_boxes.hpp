// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// What the viewers show of a labelled window: each component's
/// axis-aligned box and the colour of every label (components by the
/// writers' label colour, ground brown, ceiling pale blue, unlabelled grey).
/// Shared by the Foxglove outputs (`--mcap`, the live view) and the ROS 2
/// node's markers and detections.

#include "cli/structure_labels.hpp"

#include <streamclust/io/record.hpp>
#include <streamclust/io/writers.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

namespace streamclust::cli {

/// One component's axis-aligned extent.
struct ClusterBox {
  std::int64_t label = 0;
  std::array<double, 3> center{}, size{};  ///< [m]; sizes at least 5 cm (a box stays visible)
  std::size_t points = 0;
};

/// The boxes of the components (labels >= 0, finite points) of a
/// labelled window, in label order. O(n log components).
inline void cluster_boxes(const std::vector<io::Record>& points, const std::vector<std::int64_t>& labels,
                          std::vector<ClusterBox>& out) {
  struct Extent {
    std::array<float, 3> lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::max()};
    std::array<float, 3> hi{-std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                            -std::numeric_limits<float>::max()};
    std::size_t n = 0;
  };
  std::map<std::int64_t, Extent> extents;
  for (std::size_t i = 0; i < points.size() && i < labels.size(); ++i) {
    const io::Record& p = points[i];
    if (labels[i] < 0 || !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    Extent& e = extents[labels[i]];
    const float v[3] = {p.x, p.y, p.z};
    for (int k = 0; k < 3; ++k) {
      e.lo[k] = std::min(e.lo[k], v[k]);
      e.hi[k] = std::max(e.hi[k], v[k]);
    }
    ++e.n;
  }
  out.clear();
  for (const auto& [label, e] : extents) {
    ClusterBox b;
    b.label = label;
    b.points = e.n;
    for (int k = 0; k < 3; ++k) {
      b.center[k] = 0.5 * (static_cast<double>(e.lo[k]) + static_cast<double>(e.hi[k]));
      b.size[k] = std::max(0.05, static_cast<double>(e.hi[k]) - static_cast<double>(e.lo[k]));
    }
    out.push_back(b);
  }
}

/// The display colour of a label (RGB).
inline std::array<std::uint8_t, 3> label_display_color(std::int64_t label) {
  if (label == kGroundLabel) return {140, 105, 70};
  if (label == kCeilingLabel) return {170, 190, 215};
  if (label == kWallLabel) return {200, 200, 185};
  return io::label_color(label);
}

}  // namespace streamclust::cli
