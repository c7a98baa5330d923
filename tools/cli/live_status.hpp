// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// What `streamclust live` measures while it runs: the latency from a
/// packet's arrival to the retrieval that first contains its points (a
/// histogram of 0.1 ms bins up to 2 s: fixed memory for any run length),
/// the recent cycles' latencies, and the one-line terminal status.
/// Not thread-safe: the engine thread owns it.

#include "cli/latency_histogram.hpp"
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
