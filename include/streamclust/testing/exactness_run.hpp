// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The exactness check: after every retrieval the continuous engine's
/// partition equals the partition the batch clusterer computes from scratch
/// on the same window (with a ground or motion policy: on the window's
/// object points as offered, oracle_input.hpp), over many seeds of streams
/// from the given sources. A failure names the configuration, the seed, the
/// stream and its length, the first mismatching retrieval, and the smallest
/// stream found that still fails (shortened to that retrieval, then points
/// dropped while the mismatch stays), with its points, to paste into a test.
///
/// This header runs streams it is given (random ones: streams.hpp);
/// testing/exactness.hpp adds simulated Livox streams and is the entry point
/// for a configuration of your own.
///
/// Seed k (0-based from `first_seed`): parameters from `draw(rng)` with rng =
/// std::mt19937_64(k * 7919 + 13); the stream of source k mod S (S sources)
/// with min_length + k mod (max_length - min_length + 1) points; fed point
/// by point, or (when (k / S) is odd and `packets`) through insert_batch in
/// packets of 1 to `max_packet` points; retrievals after a random 1 to
/// `max_retrieval_gap` points (the same rng), after every point, or once at
/// the end. Deterministic: a seed reproduces its run.
/// Cost: O(seeds x retrievals x window) plus the batch runs. Not thread-safe
/// (one call per thread).

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/detail/hints.hpp>
#include <streamclust/stream_clusterer.hpp>
#include <streamclust/testing/law_result.hpp>
#include <streamclust/testing/oracle.hpp>
#include <streamclust/testing/oracle_input.hpp>
#include <streamclust/testing/streams.hpp>
#include <streamclust/testing/type_name.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace streamclust::testing {

/// When the check retrieves and compares.
enum class ExactnessSchedule {
  random,       ///< after a random 1 to max_retrieval_gap points
  every_point,  ///< after every point
  at_end,       ///< once, after the whole stream
};

/// A named generator of point streams: `make(seed, length)` returns `length`
/// points in stream order (sensor frame, times in seconds), the same for the
/// same arguments.
struct StreamSource {
  std::string name;
  std::function<std::vector<Point>(std::uint64_t seed, std::size_t length)> make;
};

/// One source per kind of random and adversarial stream (streams.hpp):
/// blobs, one cell, the seam, FOV borders, duplicates, bursts, quiet gaps,
/// invalid points mixed in.
inline std::vector<StreamSource> random_stream_sources() {
  std::vector<StreamSource> sources;
  for (int k = 0; k < static_cast<int>(StreamKind::count_); ++k) {
    const auto kind = static_cast<StreamKind>(k);
    sources.push_back({to_string(kind), [kind](std::uint64_t seed, std::size_t length) {
                         return make_stream(kind, length, seed);
                       }});
  }
  return sources;
}

/// What the exactness check runs.
struct ExactnessOptions {
  std::uint64_t first_seed = 0;
  std::uint64_t seeds = 80;
  std::size_t min_length = 120;  ///< points per stream, at least
  std::size_t max_length = 319;  ///< points per stream, at most (>= min_length)
  ExactnessSchedule schedule = ExactnessSchedule::random;
  std::size_t max_retrieval_gap = 40;  ///< points between retrievals, at most (random schedule)
  bool packets = true;                 ///< half the seeds through insert_batch
  std::size_t max_packet = 100;        ///< points per insert_batch call, at most
  bool shrink = true;                  ///< on failure, look for a smaller failing stream
  std::size_t max_shrink_runs = 2000;  ///< runs the shrinking may take
  /// The streams; empty: random_stream_sources() here, and also the
  /// simulated Livox streams in check_exactness (testing/exactness.hpp).
  std::vector<StreamSource> streams;
};

/// The check's result: a LawResult, and what was compared (a check that
/// compared nothing proves nothing; the caller may require counts).
struct ExactnessReport : LawResult {
  std::uint64_t comparisons = 0;  ///< retrievals compared with the batch clusterer (not those while calibrating)
  std::uint64_t folds = 0;        ///< RetrievalStats::forest_folds summed over every retrieval
};

/// One run of one stream.
struct ExactnessRun {
  std::string mismatch;         ///< empty: every retrieval agreed
  std::size_t retrieval = 0;    ///< the failing retrieval, 1-based
  std::size_t after_point = 0;  ///< the stream position it followed
  std::string state;            ///< grid, mask and window at the failure
  std::uint64_t comparisons = 0;
  std::uint64_t folds = 0;
};

namespace internal {

template <class Config>
inline constexpr bool compares_on_input_v =
    config_traits<Config>::ground::enabled || !config_traits<Config>::motion::identity;

/// The engine's last retrieval against the batch clusterer; "" on agreement.
template <class Config>
std::string compare_retrieval(const StreamClusterer<Config>& engine, BatchClusterer<Config>& batch,
                              const std::vector<Point>& stream) {
  if constexpr (compares_on_input_v<Config>) {
    return compare_with_batch_on_input(engine, batch, stream);
  } else {
    if (engine.calibrating())
      return engine.last_result().points.empty() ? "" : "labels while the first window is buffered";
    return compare_with_batch(engine, batch);
  }
}

/// The report of a failing seed: the configuration, the seed, the stream,
/// how it was fed, the first mismatching retrieval and, when `shrunk`, the
/// smallest failing stream found (listed when it has at most 40 points).
inline std::string exactness_failure_message(const std::string& config, std::uint64_t seed,
                                             const std::string& source, std::size_t length, std::size_t packet_max,
                                             const ExactnessRun& run, bool shrunk, const std::vector<Point>& small,
                                             const ExactnessRun& small_run) {
  std::ostringstream os;
  os << "exactness of " << config << ": seed " << seed << ", stream '" << source << "' of " << length << " points, "
     << (packet_max == 0 ? std::string("point by point")
                         : "through insert_batch in packets of at most " + std::to_string(packet_max))
     << ": retrieval " << run.retrieval << " (after point " << run.after_point
     << ") differs from the batch partition of its window: " << run.mismatch;
  if (!run.state.empty()) os << " [" << run.state << "]";
  if (shrunk) {
    os << "\n  shrunk to " << small.size() << " points (same parameters and schedule): retrieval "
       << small_run.retrieval << " (after point " << small_run.after_point << "): " << small_run.mismatch;
    if (!small_run.state.empty()) os << " [" << small_run.state << "]";
    if (small.size() <= 40) {
      os << "\n  points {x, y, z, intensity, t}:";
      for (const Point& p : small) os << "\n    " << describe(p);
    }
  }
  return os.str();
}

}  // namespace internal

/// Runs `stream` through a StreamClusterer<Config> built from `params`,
/// comparing every retrieval with the batch clusterer; stops at the first
/// mismatch. `packet_max` 0 offers point by point. `rng` draws the
/// retrieval gaps and packet sizes. An exception from either clusterer is a
/// mismatch that quotes it. Not inlined: the check and the shrinking share
/// one copy of the engine loop per configuration (compile time).
template <class Config>
STREAMCLUST_NOINLINE ExactnessRun run_exactness(const ClustererParams<Config>& params, const std::vector<Point>& stream,
                           ExactnessSchedule schedule, std::size_t packet_max, std::mt19937_64 rng,
                           std::size_t max_retrieval_gap = 40) {
  ExactnessRun run;
  try {
    StreamClusterer<Config> engine(params);
    BatchClusterer<Config> batch(params);
    const std::size_t gap = std::max<std::size_t>(1, max_retrieval_gap);
    std::size_t next_retrieval = schedule == ExactnessSchedule::every_point ? 1 : 1 + rng() % gap;
    for (std::size_t offered = 0; offered < stream.size();) {
      const std::size_t stop =
          schedule == ExactnessSchedule::at_end ? stream.size() : std::min(next_retrieval, stream.size());
      offer(engine, stream, offered, stop, packet_max, rng);
      offered = stop;
      engine.retrieve();
      ++run.retrieval;
      run.folds += engine.last_stats().forest_folds;
      const bool calibrating = engine.calibrating();  // no labels yet: nothing to compare
      run.mismatch = internal::compare_retrieval(engine, batch, stream);
      if (!run.mismatch.empty()) {
        run.after_point = offered - 1;
        run.state = "grid " + std::to_string(engine.grid().rows) + "x" + std::to_string(engine.grid().cols) +
                    ", mask " + std::to_string(params.mask_size) + ", window " + std::to_string(engine.size()) +
                    " points";
        return run;
      }
      run.comparisons += calibrating ? 0u : 1u;
      next_retrieval += schedule == ExactnessSchedule::every_point ? 1 : 1 + rng() % gap;
    }
  } catch (const std::exception& e) {
    run.mismatch = std::string("threw: ") + e.what();
    run.after_point = stream.empty() ? 0 : stream.size() - 1;
  }
  return run;
}

/// The smallest failing stream found from a failing `stream`: first cut after
/// the failing retrieval, then chunks of halving size dropped while a
/// mismatch stays (at most `max_runs` runs). Returns the stream and its run.
template <class Config>
std::pair<std::vector<Point>, ExactnessRun> shrink_exactness_failure(const ClustererParams<Config>& params,
                                                                     std::vector<Point> stream, ExactnessRun failed,
                                                                     ExactnessSchedule schedule,
                                                                     std::size_t packet_max,
                                                                     const std::mt19937_64& rng,
                                                                     std::size_t max_retrieval_gap,
                                                                     std::size_t max_runs) {
  std::size_t runs = 0;
  const auto fails = [&](const std::vector<Point>& candidate, ExactnessRun& out) {
    ++runs;
    out = run_exactness<Config>(params, candidate, schedule, packet_max, rng, max_retrieval_gap);
    return !out.mismatch.empty();
  };
  ExactnessRun run;
  std::vector<Point> cut(stream.begin(), stream.begin() + static_cast<std::ptrdiff_t>(failed.after_point + 1));
  if (cut.size() < stream.size() && fails(cut, run)) {
    stream = std::move(cut);
    failed = run;
  }
  for (std::size_t chunk = std::max<std::size_t>(1, stream.size() / 2); chunk >= 1 && runs < max_runs;
       chunk /= 2) {
    for (std::size_t start = 0; start < stream.size() && stream.size() > 1 && runs < max_runs;) {
      std::vector<Point> candidate(stream.begin(), stream.begin() + static_cast<std::ptrdiff_t>(start));
      candidate.insert(candidate.end(),
                       stream.begin() + static_cast<std::ptrdiff_t>(std::min(stream.size(), start + chunk)),
                       stream.end());
      if (fails(candidate, run)) {
        stream = std::move(candidate);
        failed = run;
      } else {
        start += chunk;
      }
    }
    if (chunk == 1) break;
  }
  return {std::move(stream), std::move(failed)};
}

/// The exactness check of `Config` over `options.seeds` seeds, parameters
/// from `draw(std::mt19937_64&) -> ClustererParams<Config>` (for example
/// random_params<Config>, testing/random_params.hpp, or a lambda returning
/// fixed parameters). Stops at the first failing seed.
template <class Config, class Draw>
ExactnessReport check_exactness_on(Draw&& draw, const ExactnessOptions& options) {
  ExactnessReport report;
  const std::vector<StreamSource> sources = options.streams.empty() ? random_stream_sources() : options.streams;
  const std::size_t span = options.max_length >= options.min_length ? options.max_length - options.min_length + 1 : 1;
  for (std::uint64_t k = 0; k < options.seeds; ++k) {
    const std::uint64_t seed = options.first_seed + k;
    std::mt19937_64 rng(seed * 7919 + 13);
    ClustererParams<Config> params;
    try {
      params = draw(rng);
    } catch (const std::exception& e) {
      return {{false, "exactness of " + type_name<Config>() + ": drawing the parameters of seed " +
                          std::to_string(seed) + " threw: " + e.what()}};
    }
    const StreamSource& source = sources[static_cast<std::size_t>(seed % sources.size())];
    const std::size_t length = options.min_length + static_cast<std::size_t>(seed % span);
    const std::vector<Point> stream = source.make(seed, length);
    const std::size_t packet_max =
        options.packets && (seed / sources.size()) % 2 == 1 ? std::max<std::size_t>(1, options.max_packet) : 0;
    const ExactnessRun run =
        run_exactness<Config>(params, stream, options.schedule, packet_max, rng, options.max_retrieval_gap);
    report.comparisons += run.comparisons;
    report.folds += run.folds;
    if (run.mismatch.empty()) continue;

    std::vector<Point> small;
    ExactnessRun small_run;
    if (options.shrink) {
      std::tie(small, small_run) = shrink_exactness_failure<Config>(
          params, stream, run, options.schedule, packet_max, rng, options.max_retrieval_gap, options.max_shrink_runs);
    }
    report.message = internal::exactness_failure_message(type_name<Config>(), seed, source.name, stream.size(),
                                                         packet_max, run, options.shrink, small, small_run);
    report.passed = false;
    return report;
  }
  report.message = "exactness of " + type_name<Config>() + ": " + std::to_string(options.seeds) + " seeds, " +
                   std::to_string(report.comparisons) + " retrievals compared";
  return report;
}

}  // namespace streamclust::testing
