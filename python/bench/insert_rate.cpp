// SPDX-License-Identifier: MIT
// The C++ side of python/bench/throughput.py: the rate of
// StreamClusterer::insert_batch on a recorded stream, in packets of P points
// from a std::vector<Point>, for the configuration of a preset.
//
//   streamclust_py_insert_rate FILE [--preset carc-mid360] [--packet 10000] [--repeat 5]
//
// Prints one JSON line: {"points": N, "packet": P, "seconds": [...], "median_points_per_second": R}.
// Only presets that compile to CliConfig<Spherical, Bucket, Angular, Time,
// SpanningForest> (carc, carc-mid360, carc-avia) are accepted: one
// instantiation keeps this program quick to build.

#include "cli/engine_config.hpp"
#include "cli/options.hpp"
#include "cli/run_setup.hpp"

#include <streamclust/io/reader.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace sc = streamclust;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: streamclust_py_insert_rate FILE [--preset NAME] [--packet N] [--repeat R]\n";
    return 2;
  }
  std::string preset = "carc-mid360";
  std::size_t packet = 10000, repeat = 5;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--preset") preset = argv[i + 1];
    else if (a == "--packet") packet = std::stoul(argv[i + 1]);
    else if (a == "--repeat") repeat = std::stoul(argv[i + 1]);
    else {
      std::cerr << "unknown option " << a << "\n";
      return 2;
    }
  }
  sc::cli::ClusterOptions o = sc::cli::parse_cluster_options({"--preset", preset, argv[1]});
  if (o.index != "bucket" || o.linkage != "angular" || o.window_is_count || o.projection != "spherical" ||
      o.connectivity != "forest") {
    std::cerr << "preset " << preset << " is not compiled into this benchmark\n";
    return 2;
  }
  std::ostringstream notes;
  o.quiet = true;
  o.setup = std::make_shared<const sc::cli::RunSetup>(sc::cli::make_run_setup(o, false, notes));
  using Config = sc::cli::CliConfig<sc::SphericalProjection, sc::BucketGrid, sc::AngularLinkage, sc::TimeWindow>;
  const sc::ClustererParams<Config> params = sc::cli::make_params<Config>(o);

  std::vector<sc::Point> points;
  {
    auto reader = sc::io::open_reader(argv[1], o.read);
    std::vector<sc::io::Record> chunk;
    while (chunk.clear(), reader->read(chunk, 65536) > 0) {
      for (const auto& r : chunk) points.push_back(sc::Point{r.x, r.y, r.z, r.intensity, r.t});
    }
  }
  std::vector<double> seconds;
  std::size_t accepted = 0;
  for (std::size_t rep = 0; rep < repeat; ++rep) {
    sc::StreamClusterer<Config> engine(params);
    double total = 0.0;
    for (std::size_t from = 0; from < points.size(); from += packet) {
      const std::size_t to = std::min(points.size(), from + packet);
      const auto t0 = std::chrono::steady_clock::now();
      accepted += engine.insert_batch(points.begin() + static_cast<std::ptrdiff_t>(from),
                                      points.begin() + static_cast<std::ptrdiff_t>(to));
      total += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    seconds.push_back(total);
  }
  std::vector<double> sorted = seconds;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2];
  std::printf("{\"points\": %zu, \"packet\": %zu, \"accepted\": %zu, \"seconds\": [", points.size(), packet,
              accepted / std::max<std::size_t>(repeat, 1));
  for (std::size_t i = 0; i < seconds.size(); ++i) std::printf("%s%.6f", i ? ", " : "", seconds[i]);
  std::printf("], \"median_points_per_second\": %.1f}\n", static_cast<double>(points.size()) / median);
  return 0;
}
