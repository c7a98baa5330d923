// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A latency histogram of fixed memory (160 kB) for runs of any length:
/// the live status's packet latencies and a long run's cycle latencies.
/// Not thread-safe.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace streamclust::cli {

/// A latency histogram [ms]: 0.1 ms bins to 2 s, and one bin beyond.
class LatencyHistogram {
 public:
  static constexpr double kBinMs = 0.1;
  static constexpr std::size_t kBins = 20000;

  void add(double ms) {
    const double bin = ms / kBinMs;
    const std::size_t i = !(bin >= 0.0) ? 0 : bin >= static_cast<double>(kBins) ? kBins : static_cast<std::size_t>(bin);
    ++counts_[i];
    ++total_;
    max_ = std::max(max_, ms);
  }
  std::uint64_t count() const noexcept { return total_; }
  double max() const noexcept { return max_; }
  /// The nearest-rank percentile [ms], as the upper edge of its bin (the
  /// maximum for the overflow bin); 0 when empty.
  double percentile(double p) const {
    if (total_ == 0) return 0.0;
    const auto rank = static_cast<std::uint64_t>(std::max(1.0, std::ceil(p / 100.0 * static_cast<double>(total_))));
    std::uint64_t seen = 0;
    for (std::size_t i = 0; i <= kBins; ++i) {
      seen += counts_[i];
      if (seen >= rank) return i == kBins ? max_ : std::min(max_, static_cast<double>(i + 1) * kBinMs);
    }
    return max_;
  }

 private:
  std::array<std::uint64_t, kBins + 1> counts_{};
  std::uint64_t total_ = 0;
  double max_ = 0.0;
};

}  // namespace streamclust::cli
