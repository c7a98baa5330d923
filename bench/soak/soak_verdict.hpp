// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The soak's targets and its verdict on a run: the resident set flat after
/// the first window, the P99 cycle latency stable from the first minute to
/// the last, no engine allocation in steady state. O(cycles log cycles),
/// after the run. Thread-safe (pure functions of the series).

#include "soak_series.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace streamclust::bench {

struct SoakTargets {
  /// Largest resident-set growth after the first window, as a fraction of
  /// the resident set then.
  double max_rss_growth = 0.01;
  /// Largest rise of the last minute's P99 over the first's, as a fraction:
  /// the shared machine's phases alone move a P99 by about 20 % between
  /// runs (docs/performance.md), so a rise within it is no drift.
  double max_p99_rise = 0.20;
  /// Engine allocations allowed after the warm-up.
  std::uint64_t max_steady_allocations = 0;
};

/// Latency of the steady cycles of one period (a minute of stream time).
struct PeriodLatency {
  double start_s = 0.0, end_s = 0.0;  ///< stream time span [s]
  std::size_t cycles = 0;
  double median_ms = 0.0, p99_ms = 0.0, max_ms = 0.0, cpu_p99_ms = 0.0;
  std::uint64_t edges_found = 0;  ///< the engine's work in the period (host-independent)
  double host_probe_us = 0.0;     ///< median of the period's CPU probes [us] (the host's speed)
  double memory_probe_us = 0.0;   ///< median of the period's memory probes [us] (the host's caches and memory)
};

struct SoakVerdict {
  // Resident set: the sample at the end of the first window against every later one.
  bool rss_judged = false, rss_ok = true;
  std::uint32_t rss_baseline_second = 0, rss_max_second = 0;
  std::uint64_t rss_baseline_kib = 0, rss_max_after_kib = 0, rss_end_kib = 0;
  SecondSample rss_baseline_sample, rss_max_sample;  ///< the two samples compared (anonymous and file-backed parts)
  double rss_growth = 0.0;                           ///< (max after - baseline) / baseline
  // Latency by period.
  bool p99_judged = false, p99_ok = true;
  double period_s = 60.0;
  std::vector<PeriodLatency> periods;           ///< periods holding steady cycles, in time order
  double p99_ratio = 0.0, cpu_p99_ratio = 0.0;  ///< last period over first
  // Allocations after the warm-up.
  bool allocations_judged = false, allocations_ok = true;
  double warmup_s = 0.0;
  std::uint64_t warmup_allocations = 0, steady_allocations = 0, steady_cycles_with_allocations = 0;
  double last_steady_allocation_s = 0.0;  ///< stream time of the last cycle that allocated after the warm-up

  bool pass() const { return rss_ok && p99_ok && allocations_ok; }
};

namespace detail {

inline double rank_of_sorted(const std::vector<double>& v, double p) {
  if (v.empty()) return 0.0;
  const auto rank = static_cast<std::size_t>(std::max(1.0, std::ceil(p / 100.0 * static_cast<double>(v.size()))));
  return v[std::min(rank, v.size()) - 1];
}

}  // namespace detail

/// Judges a run of `seconds` of stream time with a window of `window_s`:
/// - resident set: baseline at the end of stream second max(1, ceil(2 T_B))
///   (the calibration window and the first clustered window), growth = the
///   largest later sample over it;
/// - latency: periods of 60 s (half the run when shorter than 2 minutes),
///   steady cycles only; the last period's P99 against the first's;
/// - allocations: the cycles ending after `warmup_s`.
inline SoakVerdict judge_soak(const SoakSeries& series, double seconds, double window_s, double warmup_s,
                              const SoakTargets& targets) {
  SoakVerdict v;
  v.warmup_s = warmup_s;

  v.rss_baseline_second = static_cast<std::uint32_t>(std::max(1.0, std::ceil(2.0 * window_s - 1e-9)));
  bool have_baseline = false;
  for (const SecondSample* s = series.seconds_begin(); s != series.seconds_end(); ++s) {
    v.rss_end_kib = s->rss_kib;
    if (s->second == v.rss_baseline_second) {
      v.rss_baseline_kib = s->rss_kib;
      v.rss_baseline_sample = *s;
      have_baseline = true;
    } else if (have_baseline && s->second > v.rss_baseline_second) {
      if (!v.rss_judged || s->rss_kib > v.rss_max_after_kib) {
        v.rss_max_after_kib = s->rss_kib;
        v.rss_max_second = s->second;
        v.rss_max_sample = *s;
      }
      v.rss_judged = true;
    }
  }
  if (v.rss_judged && v.rss_baseline_kib > 0) {
    v.rss_growth = (static_cast<double>(v.rss_max_after_kib) - static_cast<double>(v.rss_baseline_kib)) /
                   static_cast<double>(v.rss_baseline_kib);
    v.rss_ok = v.rss_growth < targets.max_rss_growth;
  }

  v.period_s = seconds >= 120.0 ? 60.0 : seconds / 2.0;
  const auto period_count = static_cast<std::size_t>(std::ceil(seconds / v.period_s - 1e-9));
  std::vector<std::vector<double>> wall(period_count), cpu(period_count);
  std::vector<std::uint64_t> edges(period_count, 0);
  for (const CycleRecord* c = series.cycles_begin(); c != series.cycles_end(); ++c) {
    const bool steady = c->time > warmup_s + 1e-9;
    if (!steady) {
      v.warmup_allocations += c->allocations;
      continue;
    }
    v.allocations_judged = true;
    v.steady_allocations += c->allocations;
    if (c->allocations > 0) {
      ++v.steady_cycles_with_allocations;
      v.last_steady_allocation_s = c->time;
    }
    if (!c->retrieved) continue;
    const auto k = std::min(period_count - 1, static_cast<std::size_t>(std::max(0.0, (c->time - 1e-9) / v.period_s)));
    wall[k].push_back(c->latency_us / 1000.0);
    cpu[k].push_back(c->cpu_us / 1000.0);
    edges[k] += c->edges_found;
  }
  v.allocations_ok = v.steady_allocations <= targets.max_steady_allocations;
  std::vector<std::vector<double>> probes(period_count), memory_probes(period_count);
  for (const SecondSample* s = series.seconds_begin(); s != series.seconds_end(); ++s) {
    const double t = static_cast<double>(s->second);
    if (t <= warmup_s + 1e-9) continue;
    const std::size_t k = std::min(period_count - 1, static_cast<std::size_t>((t - 1e-9) / v.period_s));
    probes[k].push_back(s->host_probe_us);
    memory_probes[k].push_back(s->memory_probe_us);
  }
  for (std::size_t k = 0; k < period_count; ++k) {
    if (wall[k].empty()) continue;
    std::sort(wall[k].begin(), wall[k].end());
    std::sort(cpu[k].begin(), cpu[k].end());
    PeriodLatency p;
    p.start_s = static_cast<double>(k) * v.period_s;
    p.end_s = std::min(seconds, p.start_s + v.period_s);
    p.cycles = wall[k].size();
    p.median_ms = detail::rank_of_sorted(wall[k], 50.0);
    p.p99_ms = detail::rank_of_sorted(wall[k], 99.0);
    p.max_ms = wall[k].back();
    p.cpu_p99_ms = detail::rank_of_sorted(cpu[k], 99.0);
    p.edges_found = edges[k];
    if (!probes[k].empty()) {
      std::sort(probes[k].begin(), probes[k].end());
      p.host_probe_us = detail::rank_of_sorted(probes[k], 50.0);
      std::sort(memory_probes[k].begin(), memory_probes[k].end());
      p.memory_probe_us = detail::rank_of_sorted(memory_probes[k], 50.0);
    }
    v.periods.push_back(p);
  }
  if (v.periods.size() >= 2) {
    v.p99_judged = true;
    v.p99_ratio = v.periods.back().p99_ms / v.periods.front().p99_ms;
    v.cpu_p99_ratio = v.periods.back().cpu_p99_ms / v.periods.front().cpu_p99_ms;
    v.p99_ok = v.p99_ratio <= 1.0 + targets.max_p99_rise;
  }
  return v;
}

/// Prints the verdict's figures and one line per target to `out`.
inline void print_verdict(std::FILE* out, const SoakVerdict& v, const SoakTargets& t) {
  const auto verdict = [](bool judged, bool ok) {
    return !judged ? "not judged (run too short)" : ok ? "met" : "MISSED";
  };
  const auto mib = [](std::uint64_t kib) { return static_cast<double>(kib) / 1024.0; };
  std::fprintf(
      out,
      "  RSS          %.2f MiB at the end of second %u (the first window); max afterwards %.2f MiB (second %u), "
      "end %.2f MiB: growth %+.3f %% (target < %.1f %%): %s\n",
      mib(v.rss_baseline_kib), v.rss_baseline_second, mib(v.rss_max_after_kib), v.rss_max_second, mib(v.rss_end_kib),
      100.0 * v.rss_growth, 100.0 * t.max_rss_growth, verdict(v.rss_judged, v.rss_ok));
  if (v.rss_judged) {
    const SecondSample& a = v.rss_baseline_sample;
    const SecondSample& b = v.rss_max_sample;
    std::fprintf(out,
                 "               anonymous %.2f -> %.2f MiB, file-backed %.2f -> %.2f MiB, "
                 "engine heap capacities %.2f -> %.2f MiB\n",
                 mib(a.rss_anon_kib), mib(b.rss_anon_kib), mib(a.rss_file_kib), mib(b.rss_file_kib), mib(a.engine_kib),
                 mib(b.engine_kib));
  }
  std::fprintf(out, "  P99 by %.0f s (steady cycles; ms, CPU in brackets):", v.period_s);
  for (const PeriodLatency& p : v.periods) std::fprintf(out, " %.2f [%.2f]", p.p99_ms, p.cpu_p99_ms);
  std::fprintf(out, "\n");
  // The work the cycles did, which the host cannot move: a P99 that rises
  // while this stays flat is the machine's, not the engine's.
  std::fprintf(out, "  work by %.0f s (edges found per steady cycle):", v.period_s);
  for (const PeriodLatency& p : v.periods)
    std::fprintf(out, " %.0f", p.cycles > 0 ? static_cast<double>(p.edges_found) / static_cast<double>(p.cycles) : 0.0);
  std::fprintf(out, "\n");
  // Fixed work timed once a second (proc_stats.hpp): the host's CPU speed and
  // its caches and memory. A P99 that rises with them is the machine's.
  std::fprintf(out, "  host by %.0f s (median probes, CPU / memory, us):", v.period_s);
  for (const PeriodLatency& p : v.periods) {
    if (p.host_probe_us > 0.0)
      std::fprintf(out, " %.0f/%.0f", p.host_probe_us, p.memory_probe_us);
    else
      std::fprintf(out, " -");  // no second of the period after the warm-up
  }
  std::fprintf(out, "\n");
  if (!v.periods.empty()) {
    const PeriodLatency& a = v.periods.front();
    const PeriodLatency& b = v.periods.back();
    std::fprintf(
        out,
        "  P99          first period (%.0f-%.0f s, %zu cycles) %.2f ms, last (%.0f-%.0f s, %zu cycles) %.2f ms: "
        "x%.3f (CPU x%.3f; target at most x%.2f): %s\n",
        std::max(a.start_s, v.warmup_s), a.end_s, a.cycles, a.p99_ms, b.start_s, b.end_s, b.cycles, b.p99_ms,
        v.p99_ratio, v.cpu_p99_ratio, 1.0 + t.max_p99_rise, verdict(v.p99_judged, v.p99_ok));
  }
  std::fprintf(
      out, "  allocations  %llu in the warm-up (first %.0f s); %llu after it, in %llu cycles (target %llu): %s\n",
      static_cast<unsigned long long>(v.warmup_allocations), v.warmup_s,
      static_cast<unsigned long long>(v.steady_allocations),
      static_cast<unsigned long long>(v.steady_cycles_with_allocations),
      static_cast<unsigned long long>(t.max_steady_allocations), verdict(v.allocations_judged, v.allocations_ok));
  if (v.steady_allocations > 0)
    std::fprintf(out, "               (last allocating cycle at %.2f s)\n", v.last_steady_allocation_s);
}

}  // namespace streamclust::bench
