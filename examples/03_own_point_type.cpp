// SPDX-License-Identifier: MIT
// Example 3: clustering a user's own point struct. This one looks like a
// Livox driver's raw point: position in millimetres and a timestamp in
// nanoseconds. Specialising streamclust::point_traits is all it takes.

#include <streamclust/streamclust.hpp>

#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

struct LivoxRawPoint {
  std::int32_t x_mm, y_mm, z_mm;
  std::uint8_t reflectivity;
  std::uint64_t timestamp_ns;
};

template <>
struct streamclust::point_traits<LivoxRawPoint> {
  static Eigen::Vector3f position(const LivoxRawPoint& p) {
    return Eigen::Vector3f(static_cast<float>(p.x_mm), static_cast<float>(p.y_mm), static_cast<float>(p.z_mm)) * 1e-3f;
  }
  static double stamp(const LivoxRawPoint& p) { return static_cast<double>(p.timestamp_ns) * 1e-9; }
  static float intensity(const LivoxRawPoint& p) { return p.reflectivity; }
};

int main() {
  // Two boxes of 0.4 m, 5 m ahead and 3 m to the left, sampled at 100 kHz.
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::int32_t> jitter(0, 400);
  std::vector<LivoxRawPoint> points;
  for (std::uint64_t i = 0; i < 4000; ++i) {
    const std::int32_t x0 = i % 2 == 0 ? 5000 : 1000;
    const std::int32_t y0 = i % 2 == 0 ? -200 : 3000;
    points.push_back({x0 + jitter(rng), y0 + jitter(rng), jitter(rng) - 200, 40, i * 10000});
  }
  // C-ARC on a fixed 64 x 720 grid (0.5 degree cells), window of 20 ms.
  streamclust::CArcParams carc;
  carc.window_seconds = 0.02;
  auto params = streamclust::to_clusterer_params<streamclust::CArcFixedConfig>(carc);
  params.resolution = {64, 720};
  streamclust::StreamClusterer<streamclust::CArcFixedConfig> engine(params);
  for (const auto& p : points) engine.insert(p);
  const auto& result = engine.retrieve();
  std::printf("own point type: %zu points in the window, %zu components\n", result.points.size(),
              result.components.size());
  return result.components.size() == 2 ? 0 : 1;
}
