// SPDX-License-Identifier: MIT
// Example 5: a real-time loop. The sensor delivers packets of 96 points (a
// Livox UDP packet); the engine is sized up front with reserve() for the
// most points its window can hold (rate x T_B + 1), gets each packet with
// insert_batch() and publishes clusters at 20 Hz. Prints the engine's time
// per cycle (insertion and retrieval; the simulated sensor not counted) and
// checks that the window's storage never grew after the reservation (exit
// code 1 if it did). Usage: example_05_realtime_packets [seconds]

#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/streamclust.hpp>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 1.0;
  if (!(seconds > 0.0)) {
    std::fprintf(stderr, "usage: %s [seconds > 0]\n", argv[0]);
    return 2;
  }
  const streamclust::SyntheticStream::Params sensor{};  // 200 kHz of stream time
  streamclust::SyntheticStream stream(sensor);
  const double point_rate = sensor.point_rate;  // [points/s]
  streamclust::CArcParams carc = streamclust::carc_mid360_params();
  carc.window_seconds = 0.2;  // T_B [s]
  streamclust::StreamClusterer<streamclust::CArcCappedFastConfig> engine(
      streamclust::to_clusterer_params<streamclust::CArcCappedFastConfig>(carc));
  // Before the loop: the window can never hold more than the points of T_B.
  engine.reserve(static_cast<std::size_t>(point_rate * carc.window_seconds) + 1);
  const std::size_t reserved_ring = engine.memory_usage().point_ring;  // [bytes]

  std::array<streamclust::SyntheticPoint, 96> packet{};  // one sensor packet
  const double period = 1.0 / 20.0;                      // publication at 20 Hz of stream time [s]
  double next_retrieval = period;
  std::size_t ring_growths = 0;
  std::printf("%8s %8s %10s %12s %10s\n", "time[s]", "window", "components", "engine[ms]", "ring[MB]");
  using Clock = std::chrono::steady_clock;
  Clock::duration engine_time{};  // insertion and retrieval of the current cycle
  while (stream.time() < seconds) {
    for (auto& p : packet) p = stream.next();
    const auto start = Clock::now();
    engine.insert_batch(packet.begin(), packet.end());
    engine_time += Clock::now() - start;
    if (packet.back().t < next_retrieval) continue;
    next_retrieval += period;
    const auto retrieval_start = Clock::now();
    const streamclust::Clustering& result = engine.retrieve();
    engine_time += Clock::now() - retrieval_start;
    const double ms = std::chrono::duration<double, std::milli>(engine_time).count();
    engine_time = Clock::duration{};
    const std::size_t ring = engine.memory_usage().point_ring;
    ring_growths += ring != reserved_ring ? 1 : 0;
    std::printf("%8.3f %8zu %10zu %12.3f %10.2f\n", result.time, result.points.size(), result.components.size(), ms,
                static_cast<double>(ring) / 1e6);
  }
  if (ring_growths > 0) {
    std::fprintf(stderr, "error: the point rings grew after reserve() in %zu cycles\n", ring_growths);
    return 1;
  }
  std::printf("the point rings kept their reserved %.2f MB in every cycle\n", static_cast<double>(reserved_ring) / 1e6);
  return 0;
}
