// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Random candidate pairs for the linkage laws, of the kinds a mask search
/// meets, and pairs placed on a linkage's decision boundary by bisection
/// (a few ulps either side of its threshold, whatever the threshold is).
/// Realistic pairs from simulated Livox scans: livox_streams.hpp.

#include <streamclust/types.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace streamclust::testing {

/// The Sample at `range` [m] along the ray of azimuth / elevation [deg]
/// (direction computed in double).
inline Sample sample_on_ray(double azimuth_deg, double elevation_deg, double range) {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  const double a = azimuth_deg * kDeg;
  const double e = elevation_deg * kDeg;
  const Eigen::Vector3d d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
  const Eigen::Vector3f p = (d * range).cast<float>();
  return make_sample(p, p.norm(), 0.0f, 0.0);
}

/// `count` random pairs, cycling through five kinds: anything (azimuth
/// -180..180, elevation -30..30 deg, range 0.5..80 m), neighbours (rays
/// 0.1 deg and 1 % of range apart), revisits of almost the same ray with
/// 2 cm of range noise, equal ranges on rays up to 2 deg apart, and the same
/// point twice. Deterministic for a seed.
inline std::vector<std::pair<Sample, Sample>> random_candidate_pairs(std::uint32_t seed, std::size_t count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> az(-180.0, 180.0);
  std::uniform_real_distribution<double> el(-30.0, 30.0);
  std::uniform_real_distribution<double> range(0.5, 80.0);
  std::uniform_real_distribution<double> small(-2.0, 2.0);
  std::uniform_real_distribution<double> tiny(-0.02, 0.02);
  std::vector<std::pair<Sample, Sample>> pairs;
  pairs.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    // draw in a fixed order (argument evaluation order is unspecified)
    const double az0 = az(rng), el0 = el(rng), r0 = range(rng);
    const double x1 = az(rng), x2 = el(rng), x3 = range(rng);
    const double s1 = small(rng), s2 = small(rng), s3 = small(rng), t1 = tiny(rng);
    const Sample a = sample_on_ray(az0, el0, r0);
    Sample b;
    switch (i % 5) {
      case 0: b = sample_on_ray(x1, x2, x3); break;
      case 1: b = sample_on_ray(az0 + 0.1 * s1, el0 + 0.1 * s2, r0 * (1.0 + 0.01 * s3)); break;
      case 2: b = sample_on_ray(az0 + 0.01 * s1, el0 + 0.01 * s2, r0 + t1); break;
      case 3: b = sample_on_ray(az0 + s1, el0, r0); b.range = a.range; break;
      default: b = a; break;
    }
    pairs.emplace_back(a, b);
  }
  return pairs;
}

/// The Sample a fraction `t` of the way from `a` to `b` (position, intensity
/// and time interpolated; range and direction from the position: a point
/// seen from the origin).
inline Sample sample_between(const Sample& a, const Sample& b, float t) {
  const Eigen::Vector3f p = a.position + t * (b.position - a.position);
  return make_sample(p, p.norm(), a.intensity + t * (b.intensity - a.intensity), a.time + t * (b.time - a.time));
}

/// Pairs on `link`'s decision boundary: for each pair (a, b) of `pairs`
/// whose decision differs between (a, a') and (a, b) (a' = a as seen from
/// the origin), 40 bisection steps along a' -> b find the last linked and
/// the first split point; both pairs are returned. At most `max_pairs`.
/// O(pairs x 40) predicate calls.
template <class L>
std::vector<std::pair<Sample, Sample>> boundary_pairs(const L& link,
                                                      const std::vector<std::pair<Sample, Sample>>& pairs,
                                                      std::size_t max_pairs) {
  std::vector<std::pair<Sample, Sample>> out;
  for (const auto& [a, b] : pairs) {
    if (out.size() + 2 > max_pairs) break;
    const bool at0 = link(a, sample_between(a, b, 0.0f));
    if (at0 == link(a, sample_between(a, b, 1.0f))) continue;
    float lo = 0.0f;  // decides as at0
    float hi = 1.0f;  // decides otherwise
    for (int step = 0; step < 40; ++step) {
      const float mid = 0.5f * (lo + hi);
      if (mid == lo || mid == hi) break;
      (link(a, sample_between(a, b, mid)) == at0 ? lo : hi) = mid;
    }
    out.emplace_back(a, sample_between(a, b, lo));
    out.emplace_back(a, sample_between(a, b, hi));
  }
  return out;
}

}  // namespace streamclust::testing
