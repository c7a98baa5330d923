// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The one percentile definition of the project (nearest rank), and the
/// latency summary reported by the command-line tool and the benchmarks.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace streamclust {

/// Nearest-rank percentile of an ascending-sorted sample, `p` in [0, 100]:
/// the smallest value with at least p % of the sample at or below it (p = 0
/// gives the minimum, p = 100 the maximum). 0 for an empty sample. O(1).
/// Thread-safe (pure).
inline double percentile_sorted(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0.0;
  const double rank = std::ceil(p / 100.0 * static_cast<double>(sorted.size()));
  const auto i = static_cast<std::size_t>(std::max(rank, 1.0)) - 1;
  return sorted[std::min(i, sorted.size() - 1)];
}

/// Nearest-rank percentile (`p` in [0, 100]) of an unsorted sample (copied
/// and sorted). 0 for an empty sample. O(n log n).
inline double percentile(std::vector<double> sample, double p) {
  std::sort(sample.begin(), sample.end());
  return percentile_sorted(sample, p);
}

/// The percentiles reported for a latency sample (same unit as the sample).
struct LatencySummary {
  std::size_t count = 0;
  double p1 = 0.0, q1 = 0.0, median = 0.0, q3 = 0.0, p95 = 0.0, p99 = 0.0, p999 = 0.0, max = 0.0, mean = 0.0;
};

/// Nearest-rank summary of an unsorted sample (all zero when empty).
/// O(n log n).
inline LatencySummary summarize(std::vector<double> v) {
  LatencySummary s;
  s.count = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.p1 = percentile_sorted(v, 1.0);
  s.q1 = percentile_sorted(v, 25.0);
  s.median = percentile_sorted(v, 50.0);
  s.q3 = percentile_sorted(v, 75.0);
  s.p95 = percentile_sorted(v, 95.0);
  s.p99 = percentile_sorted(v, 99.0);
  s.p999 = percentile_sorted(v, 99.9);
  s.max = v.back();
  double sum = 0.0;
  for (const double x : v) sum += x;
  s.mean = sum / static_cast<double>(v.size());
  return s;
}

}  // namespace streamclust
