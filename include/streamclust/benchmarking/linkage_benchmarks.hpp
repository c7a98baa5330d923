// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Google Benchmark helpers for linkages: a linkage's paths (the Sample
/// path, the payload path, `link_many`) over realistic candidate pairs, and
/// a linkage against a reference linkage timed alternately in the same run.
///
/// ```cpp
/// #include <streamclust/benchmarking/linkage_benchmarks.hpp>
/// namespace bk = streamclust::benchmarking;
/// [[maybe_unused]] const bool registered = [] {
///   bk::register_linkage_comparison<MyLinkage, streamclust::EuclideanLinkage>("MyLinkage", {}, {});
///   return true;
/// }();
/// BENCHMARK_MAIN();
/// ```
/// Benchmarks are named `<name>/<path>/<pairs>` (path: sample, payload,
/// link_many) and `<name>_vs_reference/<path>/<pairs>` (path: sample, engine
/// = the path the engine takes for each linkage); items are pairs
/// (items_per_second), `linked_share` the share of pairs linked. A
/// comparison reports `ns_per_pair` and `reference_ns_per_pair` (medians
/// over the iterations) and `over_reference` = their ratio: below 1 the
/// policy is faster. Before timing, each path is checked to link as many
/// pairs as the Sample path; a linkage whose paths disagree is reported as
/// an error and STREAMCLUST_BENCHMARK_MAIN() then exits with 1.
///
/// Thread-safety: registration is not thread-safe (Google Benchmark's
/// registry); run from main or a static initialiser.

#include <streamclust/benchmarking/candidate_pairs.hpp>
#include <streamclust/concepts/linkage.hpp>
#include <streamclust/percentiles.hpp>

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::benchmarking {

/// A named, lazily built set of candidate pairs (built when a benchmark
/// using it first runs, so filtered-out benchmarks cost nothing).
struct PairSource {
  std::string name;
  std::function<const CandidatePairs&()> pairs;
};

/// What a 5 x 5 mask offers in 0.1 s of the Mid-360 and of the Avia in the
/// office (mask_candidates).
inline std::vector<PairSource> mask_pair_sources(double seconds = 0.1, int mask_size = 5) {
  std::vector<PairSource> out;
  for (const Scenario& s : office_scenarios()) {
    out.push_back({s.name() + "_mask" + std::to_string(mask_size),
                   [s, seconds, mask_size]() -> const CandidatePairs& { return mask_candidates(s, seconds, mask_size); }});
  }
  return out;
}

/// A linkage's path to a verdict on a pair.
enum class LinkagePath {
  sample,     ///< operator()(const Sample&, const Sample&)
  payload,    ///< operator()(const Payload&, const Payload&) on a payload ring
  link_many,  ///< link_many: one call per query over its candidates' slots
  engine,     ///< the path the engine takes: link_many, else payload, else sample
};

inline const char* path_name(LinkagePath p) {
  switch (p) {
    case LinkagePath::sample: return "sample";
    case LinkagePath::payload: return "payload";
    case LinkagePath::link_many: return "link_many";
    case LinkagePath::engine: return "engine";
  }
  return "?";
}

/// True when linkage `L` has path `p`.
template <class L>
constexpr bool has_path(LinkagePath p) {
  switch (p) {
    case LinkagePath::payload: return has_linkage_payload_v<L>;
    case LinkagePath::link_many: return has_linkage_link_many_v<L>;
    default: return true;
  }
}

/// One linkage over one set of candidate pairs, by any of its paths. Holds
/// the payload ring (built at construction, untimed) and the verdict buffer.
template <class Linkage>
class LinkageRunner {
 public:
  LinkageRunner(const Linkage& linkage, const CandidatePairs& pairs)
      : linkage_(linkage), pairs_(pairs), linked_(pairs.max_candidates + 1) {
    if constexpr (has_linkage_payload_v<Linkage>) {
      ring_.reserve(pairs.samples.size());
      for (const Sample& s : pairs.samples) ring_.push_back(linkage_.make_payload(s));
    }
  }

  /// Every pair by path `p` (which Linkage must have); returns the pairs linked.
  std::size_t run(LinkagePath p) {
    if (p == LinkagePath::engine) {
      p = has_linkage_link_many_v<Linkage> ? LinkagePath::link_many
          : has_linkage_payload_v<Linkage> ? LinkagePath::payload
                                           : LinkagePath::sample;
    }
    const std::size_t n = pairs_.samples.size();
    const std::uint32_t* first = pairs_.first.data();
    const std::uint32_t* slots = pairs_.slots.data();
    std::size_t linked = 0;
    if (p == LinkagePath::sample) {
      const Sample* samples = pairs_.samples.data();
      for (std::size_t i = 0; i < n; ++i) {
        for (std::uint32_t k = first[i]; k < first[i + 1]; ++k) linked += linkage_(samples[i], samples[slots[k]]) ? 1u : 0u;
      }
    }
    if constexpr (has_linkage_payload_v<Linkage>) {
      const auto* ring = ring_.data();
      if (p == LinkagePath::payload) {
        for (std::size_t i = 0; i < n; ++i) {
          for (std::uint32_t k = first[i]; k < first[i + 1]; ++k) linked += linkage_(ring[i], ring[slots[k]]) ? 1u : 0u;
        }
      }
      if constexpr (has_linkage_link_many_v<Linkage>) {
        if (p == LinkagePath::link_many) {
          std::uint8_t* out = linked_.data();
          for (std::size_t i = 0; i < n; ++i) {
            const std::size_t count = first[i + 1] - first[i];
            linkage_.link_many(ring[i], ring, slots + first[i], count, out);
            for (std::size_t k = 0; k < count; ++k) linked += out[k];
          }
        }
      }
    }
    return linked;
  }

 private:
  Linkage linkage_;
  const CandidatePairs& pairs_;
  std::vector<linkage_payload_t<Linkage>> ring_;
  std::vector<std::uint8_t> linked_;
};

/// The number of failed checks of this process's kit benchmarks (read by
/// run_benchmarks, main.hpp, for the exit code). Not thread-safe.
inline int& failed_checks() {
  static int failed = 0;
  return failed;
}

/// Before timing: the path must link as many pairs as the Sample path (the
/// linkage contract: payload and `link_many` decide as the Sample path).
/// Otherwise the benchmark is skipped with the counts and the failure
/// counted. Returns true when they agree. O(pairs).
template <class Linkage>
bool paths_agree(benchmark::State& state, LinkageRunner<Linkage>& runner, LinkagePath path, const char* what) {
  const std::size_t by_sample = runner.run(LinkagePath::sample);
  const std::size_t by_path = runner.run(path);
  if (by_path == by_sample) return true;
  const std::string message = std::string(what) + ": the " + path_name(path) + " path links " +
                              std::to_string(by_path) + " pairs, the sample path " + std::to_string(by_sample) +
                              ": they must decide alike";
  state.SkipWithError(message.c_str());
  ++failed_checks();
  return false;
}

/// The benchmark body: every pair of `pairs` by `path`, items = pairs.
template <class Linkage>
void run_linkage(benchmark::State& state, const Linkage& linkage, const CandidatePairs& pairs, LinkagePath path) {
  LinkageRunner<Linkage> runner(linkage, pairs);
  if (!paths_agree(state, runner, path, "linkage")) return;
  std::size_t linked = 0;
  for (auto _ : state) linked += runner.run(path);
  // `linked` feeds a counter, so it is not dead code: no DoNotOptimize on it
  // (Google Benchmark 1.7's read-write DoNotOptimize can clobber a live
  // integer under g++ 12).
  const auto total = static_cast<double>(pairs.pair_count()) * static_cast<double>(state.iterations());
  state.SetItemsProcessed(static_cast<std::int64_t>(total));
  state.counters["linked_share"] = total > 0.0 ? static_cast<double>(linked) / total : 0.0;
}

/// Registers `<name>/<path>/<pairs>` for each path Linkage has (sample,
/// payload, link_many) and each source. Returns the benchmarks (to set
/// units, repetitions, ...).
template <class Linkage>
std::vector<benchmark::internal::Benchmark*> register_linkage(const std::string& name,
                                                              const typename Linkage::Params& params = {},
                                                              const std::vector<PairSource>& sources = mask_pair_sources()) {
  std::vector<benchmark::internal::Benchmark*> out;
  const Linkage linkage{params};
  for (const PairSource& source : sources) {
    for (const LinkagePath path : {LinkagePath::sample, LinkagePath::payload, LinkagePath::link_many}) {
      if (!has_path<Linkage>(path)) continue;
      out.push_back(benchmark::RegisterBenchmark(
          (name + "/" + path_name(path) + "/" + source.name).c_str(),
          [linkage, source, path](benchmark::State& state) { run_linkage(state, linkage, source.pairs(), path); }));
    }
  }
  return out;
}

/// The comparison body: per iteration, the policy then the reference over
/// every pair (the order alternates), each timed; iteration time = the
/// policy's (register with UseManualTime, done by register_linkage_comparison).
template <class Policy, class Reference>
void run_linkage_comparison(benchmark::State& state, const Policy& policy, const Reference& reference,
                            const CandidatePairs& pairs, LinkagePath path) {
  LinkageRunner<Policy> a(policy, pairs);
  LinkageRunner<Reference> b(reference, pairs);
  if (!paths_agree(state, a, path, "policy") || !paths_agree(state, b, path, "reference")) return;
  std::vector<double> a_s, b_s;
  std::size_t linked = 0;
  const auto seconds = [](auto t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  bool policy_first = true;
  for (auto _ : state) {
    for (int turn = 0; turn < 2; ++turn) {
      const auto t0 = std::chrono::steady_clock::now();
      if ((turn == 0) == policy_first) {
        linked += a.run(path);
        a_s.push_back(seconds(t0));
      } else {
        benchmark::DoNotOptimize(b.run(path));
        b_s.push_back(seconds(t0));
      }
    }
    state.SetIterationTime(a_s.back());
    policy_first = !policy_first;
  }
  const auto n = static_cast<double>(pairs.pair_count());
  const double a_median = percentile(a_s, 50.0);
  const double b_median = percentile(b_s, 50.0);
  state.SetItemsProcessed(static_cast<std::int64_t>(n * static_cast<double>(state.iterations())));
  state.counters["ns_per_pair"] = n > 0.0 ? a_median * 1e9 / n : 0.0;
  state.counters["reference_ns_per_pair"] = n > 0.0 ? b_median * 1e9 / n : 0.0;
  state.counters["over_reference"] = b_median > 0.0 ? a_median / b_median : 0.0;
  state.counters["linked_share"] = n > 0.0 ? static_cast<double>(linked) / (n * static_cast<double>(a_s.size())) : 0.0;
}

/// Registers `<name>_vs_reference/<path>/<pairs>`: Policy against Reference
/// on each source, by the Sample path and by each one's engine path (the
/// latter only when either has a payload). Returns the benchmarks.
template <class Policy, class Reference>
std::vector<benchmark::internal::Benchmark*> register_linkage_comparison(
    const std::string& name, const typename Policy::Params& policy_params = {},
    const typename Reference::Params& reference_params = {},
    const std::vector<PairSource>& sources = mask_pair_sources()) {
  std::vector<benchmark::internal::Benchmark*> out;
  const Policy policy{policy_params};
  const Reference reference{reference_params};
  constexpr bool any_payload = has_linkage_payload_v<Policy> || has_linkage_payload_v<Reference>;
  for (const PairSource& source : sources) {
    for (const LinkagePath path : {LinkagePath::sample, LinkagePath::engine}) {
      if (path == LinkagePath::engine && !any_payload) continue;
      out.push_back(benchmark::RegisterBenchmark((name + "_vs_reference/" + path_name(path) + "/" + source.name).c_str(),
                                                 [policy, reference, source, path](benchmark::State& state) {
                                                   run_linkage_comparison(state, policy, reference, source.pairs(), path);
                                                 })
                        ->UseManualTime());
    }
  }
  return out;
}

}  // namespace streamclust::benchmarking
