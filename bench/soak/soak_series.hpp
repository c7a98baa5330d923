// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The soak's measurements: one record per 20 Hz cycle and one sample per
/// second of stream time, stored in tables sized (and their pages touched)
/// up front, so that recording allocates nothing and does not grow the
/// resident set it samples. Written out as CSV at the end.
/// Not thread-safe: one series per run, filled from the driving thread.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::bench {

/// One cycle: the points of a 50 ms slice inserted, then (once the grid is
/// calibrated) a retrieval.
struct CycleRecord {
  double time = 0.0;              ///< stream time at the end of the slice [s]
  double latency_us = 0.0;        ///< wall time of insertion + retrieval [us]
  double cpu_us = 0.0;            ///< this thread's CPU time of the same work [us]
  std::uint32_t inserted = 0;     ///< points offered in the slice
  std::uint32_t allocations = 0;  ///< the engine's operator new calls in the cycle
  /// The engine's work in the cycle, independent of the host: edges from the
  /// inserted points to older neighbours (RetrievalStats::edges_found).
  std::uint32_t edges_found = 0;
  bool retrieved = false;         ///< false while the first window is buffered for the grid
};

/// One second of stream time.
struct SecondSample {
  std::uint32_t second = 0;         ///< stream second that ended [s]
  double wall_s = 0.0;              ///< wall time since the stream started [s]
  std::uint64_t rss_kib = 0;        ///< resident set at the end of the second [KiB]
  std::uint64_t rss_anon_kib = 0;   ///< of which anonymous (heap, stacks) [KiB]
  std::uint64_t rss_file_kib = 0;   ///< of which file-backed (code and data of the binary and libraries) [KiB]
  std::uint64_t engine_kib = 0;     ///< the engine's heap capacities (memory_usage().total()) [KiB]
  double load1 = 0.0;               ///< one-minute load average of the machine
  std::uint32_t cycles = 0;         ///< cycles with a retrieval in the second
  std::uint64_t points = 0;         ///< points offered in the second
  std::uint64_t window_points = 0;  ///< object + structure points in the window at the end
  /// Cycle latency of the second's cycles [ms], nearest rank (the P99 of 20 is the max).
  double median_ms = 0.0, p99_ms = 0.0, max_ms = 0.0;
  double cpu_p99_ms = 0.0;          ///< CPU-time P99 of the same cycles [ms]
  std::uint64_t allocations = 0;    ///< the engine's operator new calls in the second
  std::uint64_t edges_found = 0;    ///< the engine's edges found in the second (host-independent work)
  double host_probe_us = 0.0;       ///< host_probe_us() at the end of the second [us]
  double memory_probe_us = 0.0;     ///< MemoryProbe::run_us() at the end of the second [us]
};

class SoakSeries {
 public:
  /// Room for `cycles` cycles and `seconds` samples, touched now.
  SoakSeries(std::size_t cycles, std::size_t seconds, std::size_t cycles_per_second)
      : cycles_(cycles), seconds_(seconds), wall_(cycles_per_second), cpu_(cycles_per_second) {}

  /// Records a cycle. O(1); throws std::length_error past the sized room.
  void add_cycle(const CycleRecord& c) {
    if (cycle_count_ == cycles_.size()) throw std::length_error("SoakSeries: more cycles than sized");
    cycles_[cycle_count_++] = c;
  }

  /// Closes a second: summarizes the cycles recorded since the previous
  /// call and stores the sample. O(cycles per second x log).
  void close_second(SecondSample s) {
    if (second_count_ == seconds_.size()) throw std::length_error("SoakSeries: more seconds than sized");
    std::size_t n = 0;
    for (std::size_t i = second_first_cycle_; i < cycle_count_; ++i) {
      const CycleRecord& c = cycles_[i];
      s.points += c.inserted;
      s.allocations += c.allocations;
      s.edges_found += c.edges_found;
      if (!c.retrieved || n == wall_.size()) continue;
      wall_[n] = c.latency_us / 1000.0;
      cpu_[n] = c.cpu_us / 1000.0;
      ++n;
    }
    second_first_cycle_ = cycle_count_;
    s.cycles = static_cast<std::uint32_t>(n);
    if (n > 0) {
      std::sort(wall_.begin(), wall_.begin() + static_cast<std::ptrdiff_t>(n));
      std::sort(cpu_.begin(), cpu_.begin() + static_cast<std::ptrdiff_t>(n));
      s.median_ms = nearest_rank(wall_, n, 50.0);
      s.p99_ms = nearest_rank(wall_, n, 99.0);
      s.max_ms = wall_[n - 1];
      s.cpu_p99_ms = nearest_rank(cpu_, n, 99.0);
    }
    seconds_[second_count_++] = s;
  }

  const CycleRecord* cycles_begin() const { return cycles_.data(); }
  const CycleRecord* cycles_end() const { return cycles_.data() + cycle_count_; }
  const SecondSample* seconds_begin() const { return seconds_.data(); }
  const SecondSample* seconds_end() const { return seconds_.data() + second_count_; }

  /// Writes the per-second table (header + one row per second). Throws
  /// std::runtime_error when the file cannot be written.
  void write_seconds_csv(const std::string& path) const {
    std::ofstream f(path);
    f << "second,wall_s,rss_kib,rss_anon_kib,rss_file_kib,engine_kib,load1,cycles,points,window_points,"
         "median_ms,p99_ms,max_ms,cpu_p99_ms,allocations,edges_found,host_probe_us,memory_probe_us\n";
    for (const SecondSample* s = seconds_begin(); s != seconds_end(); ++s) {
      f << s->second << ',' << s->wall_s << ',' << s->rss_kib << ',' << s->rss_anon_kib << ',' << s->rss_file_kib << ','
        << s->engine_kib << ',' << s->load1 << ',' << s->cycles << ',' << s->points << ',' << s->window_points << ','
        << s->median_ms << ',' << s->p99_ms << ',' << s->max_ms << ',' << s->cpu_p99_ms << ',' << s->allocations
        << ',' << s->edges_found << ',' << s->host_probe_us << ',' << s->memory_probe_us << '\n';
    }
    finish(f, path);
  }

  /// Writes the per-cycle table (header + one row per cycle).
  void write_cycles_csv(const std::string& path) const {
    std::ofstream f(path);
    f << "time_s,latency_us,cpu_us,inserted,allocations,edges_found,retrieved\n";
    for (const CycleRecord* c = cycles_begin(); c != cycles_end(); ++c) {
      f << c->time << ',' << c->latency_us << ',' << c->cpu_us << ',' << c->inserted << ',' << c->allocations << ','
        << c->edges_found << ',' << (c->retrieved ? 1 : 0) << '\n';
    }
    finish(f, path);
  }

 private:
  static double nearest_rank(const std::vector<double>& sorted, std::size_t n, double p) {
    const auto rank = static_cast<std::size_t>(std::max(1.0, std::ceil(p / 100.0 * static_cast<double>(n))));
    return sorted[std::min(rank, n) - 1];
  }

  static void finish(std::ofstream& f, const std::string& path) {
    f.flush();
    if (!f) throw std::runtime_error("cannot write '" + path + "'");
  }

  std::vector<CycleRecord> cycles_;
  std::vector<SecondSample> seconds_;
  std::vector<double> wall_, cpu_;  // one second's latencies, sorted in place
  std::size_t cycle_count_ = 0, second_count_ = 0, second_first_cycle_ = 0;
};

}  // namespace streamclust::bench
