// SPDX-License-Identifier: MIT
// foxglove_serve: the live view's server with known content, for the test
// foxglove_live (tests/scripts/check_foxglove_live.mjs drives it with the
// reference client). Serves /streamclust/points, /streamclust/clusters and
// /streamclust/raw at RATE Hz on 127.0.0.1 (an ephemeral port) until stdin
// ends or SECONDS pass. The window: POINTS points, a quarter each in
// cluster 0 (a 1 m cube at x 10..11), cluster 1 (at y 20..21), ground (-2)
// and unlabelled (-1); intensity is the point's index modulo 256.
// Prints {"port": P} first, then at the end one JSON line: the frames
// published, the achieved rate, publish() call times [us] and the server's
// counters.
// Usage: foxglove_serve [--points N] [--rate HZ] [--seconds S] [--limit BYTES]
#include "cli/foxglove_frames.hpp"
#include "live/foxglove_server.hpp"

#include <streamclust/io/foxglove_messages.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace streamclust;
using Clock = std::chrono::steady_clock;

std::atomic<bool> input_ended{false};  // stdin reached its end: stop serving

struct Args {
  std::size_t points = 10000;
  double rate = 20;      // [Hz] frames (three messages each)
  double seconds = 60;   // [s] at most
  std::size_t limit = 1'000'000;  // [bytes] per-client send buffer
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    const double v = std::atof(argv[i + 1]);
    if (flag == "--points") a.points = static_cast<std::size_t>(v);
    else if (flag == "--rate") a.rate = v;
    else if (flag == "--seconds") a.seconds = v;
    else if (flag == "--limit") a.limit = static_cast<std::size_t>(v);
    else {
      std::cerr << "foxglove_serve: unknown option " << flag << "\n";
      std::exit(2);
    }
  }
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = parse(argc, argv);
  std::vector<io::Record> window(args.points);
  std::vector<std::int64_t> labels(args.points);
  for (std::size_t i = 0; i < args.points; ++i) {
    const float u = static_cast<float>(i % 97) / 97.0f, v = static_cast<float>(i % 89) / 89.0f;
    const float w = static_cast<float>(i % 83) / 83.0f;
    const std::size_t quarter = 4 * i / args.points;
    io::Record& p = window[i];
    p.intensity = static_cast<float>(i % 256);
    static constexpr std::int64_t kQuarterLabel[4] = {0, 1, -2, -1};
    labels[i] = kQuarterLabel[quarter];
    p.x = quarter == 0 ? 10 + u : quarter == 2 ? 5 * u : quarter == 3 ? -5 - u : u;
    p.y = quarter == 1 ? 20 + v : quarter == 2 ? 5 * v : quarter == 3 ? -v : v;
    p.z = quarter == 2 ? -1.5f : w;
  }

  std::vector<double> call_us;  // [us] each publish() call
  double elapsed = 0;           // [s]
  std::size_t frames = 0;
  live::FoxgloveServer::Stats stats;
  const Clock::time_point stop_start = [&] {
    live::FoxgloveServer server({"127.0.0.1", 0, "streamclust-test", args.limit});
    const auto channel = [&](const char* topic, const char* schema, const char* type) {
      return server.advertise({0, topic, "cdr", schema, io::foxglove::ros2_definition(type), "ros2msg"});
    };
    using F = cli::FoxgloveFrames;
    const auto points = channel(F::kPointsTopic, F::kPointCloudSchema, F::kPointCloudType);
    const auto clusters = channel(F::kClustersTopic, F::kSceneUpdateSchema, F::kSceneUpdateType);
    const auto raw = channel(F::kRawTopic, F::kPointCloudSchema, F::kPointCloudType);
    std::cout << "{\"port\": " << server.port() << "}" << std::endl;

    std::thread stdin_watch([] {
      std::string line;
      while (std::getline(std::cin, line)) {
      }
      input_ended = true;
    });
    stdin_watch.detach();  // blocked in a read until stdin ends; the process exits with it

    F frames_builder;
    const auto period = std::chrono::duration<double>(1.0 / args.rate);
    const Clock::time_point start = Clock::now();
    const std::uint64_t base_ns = 1'700'000'000'000'000'000ull;
    while (!input_ended && Clock::now() - start < std::chrono::duration<double>(args.seconds)) {
      const std::uint64_t log_ns = base_ns + static_cast<std::uint64_t>(static_cast<double>(frames) * (1e9 / args.rate));
      frames_builder.build(window, labels, log_ns);
      frames_builder.build_raw(window, log_ns);
      const auto publish = [&](std::uint32_t id, const std::vector<std::uint8_t>& bytes) {
        const Clock::time_point t0 = Clock::now();
        server.publish(id, log_ns, bytes.data(), bytes.size());
        call_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
      };
      publish(points, frames_builder.point_cloud());
      publish(clusters, frames_builder.scene_update());
      publish(raw, frames_builder.raw_cloud());
      ++frames;
      std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(period * frames));
    }
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    stats = server.stats();
    return Clock::now();
  }();
  const double shutdown_ms = std::chrono::duration<double, std::milli>(Clock::now() - stop_start).count();

  std::sort(call_us.begin(), call_us.end());
  const auto quantile = [&](double q) {
    return call_us.empty() ? 0.0 : call_us[static_cast<std::size_t>(q * static_cast<double>(call_us.size() - 1))];
  };
  std::printf(
      "{\"frames\": %zu, \"seconds\": %.3f, \"rate\": %.2f, \"publish_us_median\": %.1f, \"publish_us_p99\": %.1f, "
      "\"publish_us_max\": %.1f, \"shutdown_ms\": %.1f, \"messages_published\": %llu, \"messages_sent\": %llu, "
      "\"messages_dropped\": %llu, \"publishes_dropped\": %llu, \"bytes_sent\": %llu}\n",
      frames, elapsed, static_cast<double>(frames) / elapsed, quantile(0.5), quantile(0.99), quantile(1.0),
      shutdown_ms, static_cast<unsigned long long>(stats.messages_published),
      static_cast<unsigned long long>(stats.messages_sent), static_cast<unsigned long long>(stats.messages_dropped),
      static_cast<unsigned long long>(stats.publishes_dropped), static_cast<unsigned long long>(stats.bytes_sent));
  return 0;
}
