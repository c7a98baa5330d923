// SPDX-License-Identifier: MIT
// Example 1: the C-ARC preset on the built-in synthetic Livox-like stream.
// Streams points at 200 kHz of stream time, retrieves clusters at 20 Hz and
// prints one line per retrieval. Usage: example_01_carc_synthetic [seconds]

#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/streamclust.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 1.0;
  if (!(seconds > 0.0)) {
    std::fprintf(stderr, "usage: %s [seconds > 0]\n", argv[0]);
    return 2;
  }
  streamclust::CArcParams params = streamclust::carc_mid360_params();  // theta 30 deg, w 5, T_M 2
  params.window_seconds = 0.2;                                          // T_B
  auto engine = streamclust::make_carc(params);
  streamclust::SyntheticStream stream;

  const double period = 1.0 / 20.0;  // retrieval at 20 Hz of stream time
  double next_retrieval = period;
  std::printf("%8s %8s %10s %8s %10s\n", "time[s]", "window", "components", ">=20pts", "retrieve[ms]");
  while (stream.time() < seconds) {
    const streamclust::SyntheticPoint p = stream.next();
    engine.insert(p);
    if (p.t < next_retrieval) continue;
    next_retrieval += period;
    const auto start = std::chrono::steady_clock::now();
    const streamclust::Clustering& result = engine.retrieve();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::size_t large = 0;
    for (const auto& c : result.components_with_at_least(20)) large += c.size > 0;
    std::printf("%8.3f %8zu %10zu %8zu %10.3f\n", result.time, result.points.size(), result.components.size(), large,
                ms);
  }
  const auto& grid = engine.grid();
  std::printf("grid %ux%u (adaptive), %llu points offered, %llu rejected\n", grid.rows, grid.cols,
              static_cast<unsigned long long>(engine.offered()),
              static_cast<unsigned long long>(engine.rejections().rejected()));
  return 0;
}
