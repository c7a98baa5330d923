// SPDX-License-Identifier: MIT
// The bird's-eye picture (io/birds_eye.hpp): where points, boxes, the
// sensor's cross and the metre scale land, and in which colours.

#include <streamclust/io/birds_eye.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace io = streamclust::io;

namespace {

struct Scene {
  std::vector<io::Record> points;
  std::vector<std::int64_t> labels;
  void add(float x, float y, std::int64_t label) {
    points.push_back(io::Record{x, y, 0.0f, 0.0f, 0.0, -1});
    labels.push_back(label);
  }
};

/// The pixel of (x, y) m in a picture of the extent [x0, x1] x [y0, y1] m (margins included).
std::pair<long, long> pixel(float x, float y, float x0, float y1, float scale) {
  return {std::lround((x - x0) * scale), std::lround((y1 - y) * scale)};
}

}  // namespace

TEST_CASE("objects in rank colours with boxes, ground, fragments, the sensor and the scale") {
  Scene s;
  for (int i = 0; i < 30; ++i) s.add(8.0f + 0.02f * static_cast<float>(i % 6), 1.0f + 0.02f * static_cast<float>(i / 6), 7);
  for (int i = 0; i < 25; ++i) s.add(2.0f + 0.02f * static_cast<float>(i % 5), 4.0f + 0.02f * static_cast<float>(i / 5), 3);
  for (int i = 0; i < 3; ++i) s.add(5.0f, -1.0f + 0.1f * static_cast<float>(i), 9);  // a fragment
  s.add(6.0f, 3.0f, -2);                                                          // ground
  s.add(4.0f, 2.0f, -1);                                                          // unlabelled: not drawn
  io::BirdsEyeOptions o;
  o.structure_fraction = 0.9;
  const io::RgbImage img = io::render_birds_eye(s.points, s.labels, o);
  // Extent: x [-0.5, 8.6], y [-1.5, 4.58] with the origin and margins; 900 px on x.
  const float x0 = -0.5f, x1 = 8.1f + 0.5f, y0 = -1.5f, y1 = 4.08f + 0.5f;
  const float scale = 900.0f / (x1 - x0);
  CHECK(img.width() == static_cast<std::size_t>(std::ceil((x1 - x0) * scale)));
  CHECK(img.height() == static_cast<std::size_t>(std::ceil((y1 - y0) * scale)));
  const auto at = [&](float x, float y) {
    const auto [px, py] = pixel(x, y, x0, y1, scale);
    return img.at(static_cast<std::size_t>(px), static_cast<std::size_t>(py));
  };
  CHECK(at(8.0f, 1.0f) == io::detail::rank_color(0));  // the larger object: rank 0
  CHECK(at(2.0f, 4.0f) == io::detail::rank_color(1));
  CHECK(at(5.0f, -1.0f) == io::RgbImage::Color{90, 90, 90});
  CHECK(at(6.0f, 3.0f) == io::RgbImage::Color{70, 52, 35});
  CHECK(at(4.0f, 2.0f) == io::RgbImage::Color{16, 16, 20});
  CHECK(at(0.0f, 0.0f) == io::RgbImage::Color{255, 255, 255});
  // The larger object's box: its left edge 2 pixels left of its leftmost point.
  const auto [bx, by] = pixel(8.0f, 1.05f, x0, y1, scale);
  CHECK(img.at(static_cast<std::size_t>(bx - 2), static_cast<std::size_t>(by)) == io::detail::rank_color(0));
  // The scale: 1 m (a fifth of 9.1 m is 1.82 m), a white bar from x = 12 px, 14 px above the bottom.
  const std::size_t bar_y = img.height() - 14;
  CHECK(img.at(12, bar_y) == io::RgbImage::Color{255, 255, 255});
  CHECK(img.at(12 + static_cast<std::size_t>(std::lround(scale)), bar_y) == io::RgbImage::Color{255, 255, 255});
  CHECK(img.at(12 + static_cast<std::size_t>(std::lround(scale)) + 2, bar_y) == io::RgbImage::Color{16, 16, 20});
}

TEST_CASE("structure-sized clusters are dimmed and get no box; an empty window is the sensor alone") {
  Scene s;
  for (int i = 0; i < 100; ++i) s.add(static_cast<float>(i) * 0.05f, 2.0f, 0);  // a wall: all of the window
  const io::RgbImage img = io::render_birds_eye(s.points, s.labels);
  io::RgbImage::Color dim = io::detail::rank_color(0);
  for (auto& v : dim) v = static_cast<std::uint8_t>(v / 3);
  const float x0 = -0.5f, y1 = 2.5f, scale = 900.0f / (4.95f + 1.0f);
  const auto [px, py] = pixel(1.0f, 2.0f, x0, y1, scale);
  CHECK(img.at(static_cast<std::size_t>(px), static_cast<std::size_t>(py)) == dim);
  CHECK(img.at(static_cast<std::size_t>(px), static_cast<std::size_t>(py - 3)) == io::RgbImage::Color{16, 16, 20});
  const io::RgbImage empty = io::render_birds_eye({}, {});
  CHECK(empty.width() == 900);
}
