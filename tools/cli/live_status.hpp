// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// What `streamclust live` measures while it runs: the latency from a
/// packet's arrival to the retrieval that first contains its points (a
/// histogram of 0.1 ms bins up to 2 s: fixed memory for any run length),
/// the recent cycles' latencies, and the one-line terminal status.
/// Not thread-safe: the engine thread owns it.

#include "cli/report.hpp"

#include <streamclust/live/livox_receiver.hpp>
#include <streamclust/live/livox_stream.hpp>
#include <streamclust/percentiles.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <string>
#include <vector>

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

/// The rolling view of the run for the status line.
class LiveStatus {
 public:
  /// After a cycle at stream time `cycle_ns`: every packet handed out whose
  /// last point is at or before it is now in a retrieval.
  /// `measured`: false leaves those packets out of the latency histogram.
  void on_cycle(const CycleReport& c, std::int64_t cycle_ns, std::deque<live::PacketArrival>& arrivals,
                std::int64_t now_steady_ns, bool measured) {
    while (!arrivals.empty() && arrivals.front().last_time_ns <= cycle_ns) {
      if (measured) latency_.add(static_cast<double>(now_steady_ns - arrivals.front().arrival_steady_ns) * 1e-6);
      arrivals.pop_front();
    }
    recent_us_.push_back(c.total_us);
    if (recent_us_.size() > 200) recent_us_.pop_front();
    window_ = c.window + c.structure;
    clusters_ = c.components;
    ++cycles_;
  }

  const LatencyHistogram& latency() const noexcept { return latency_; }
  std::uint64_t cycles() const noexcept { return cycles_; }

  /// "12.5 s  200.0 k pts/s  lost 0  dropped 0  queue 3/4096  window 100,000  57 clusters
  ///  cycle 4.1 / 6.2 ms  latency P99 52.0 ms".
  std::string line(double elapsed_s, std::uint64_t returns, std::uint64_t lost, std::uint64_t dropped,
                   std::size_t queue, std::size_t capacity) {
    const double dt = elapsed_s - last_elapsed_;
    const double rate = dt > 0.0 ? static_cast<double>(returns - last_returns_) / dt : 0.0;
    last_elapsed_ = elapsed_s;
    last_returns_ = returns;
    std::vector<double> recent(recent_us_.begin(), recent_us_.end());
    const LatencySummary s = summarize(recent);
    char text[256];
    std::snprintf(text, sizeof text,
                  "%.1f s  %.1f k pts/s  lost %llu  dropped %llu  queue %zu/%zu  window %zu  %zu clusters  "
                  "cycle %.1f / %.1f ms  latency P99 %.1f ms",
                  elapsed_s, rate / 1000.0, static_cast<unsigned long long>(lost),
                  static_cast<unsigned long long>(dropped), queue, capacity, window_, clusters_, s.median / 1000.0,
                  s.p99 / 1000.0, latency_.percentile(99.0));
    return text;
  }

 private:
  LatencyHistogram latency_;
  std::deque<double> recent_us_;
  std::size_t window_ = 0, clusters_ = 0;
  std::uint64_t cycles_ = 0;
  double last_elapsed_ = 0.0;
  std::uint64_t last_returns_ = 0;
};

}  // namespace streamclust::cli
