// SPDX-License-Identifier: MIT
#pragma once
// Checks on simulated or recorded sensor rays shared by the sensor tests.

#include <streamclust/sim/ray.hpp>
#include <streamclust/sim/sensors/pattern_stats.hpp>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace streamclust::test {

/// Every 1-degree azimuth bin is hit within each 0.1 s window of the first
/// 0.5 s of `rays` (in time order). O(rays).
inline bool azimuth_full_every_100ms(const std::vector<sim::Ray>& rays) {
  for (int w = 0; w < 5; ++w) {
    std::vector<bool> bin(360, false);
    for (const sim::Ray& r : rays) {
      if (r.time - rays.front().time < 0.1 * w || r.time - rays.front().time >= 0.1 * (w + 1)) continue;
      const double a = sim::azimuth_deg(r.direction) + 180.0;
      bin[static_cast<std::size_t>(std::min(359.0, std::max(0.0, a)))] = true;
    }
    for (bool b : bin)
      if (!b) return false;
  }
  return true;
}

}  // namespace streamclust::test
