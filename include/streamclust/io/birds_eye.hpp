// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A bird's-eye picture of a labelled window (x to the right, y up): one
/// colour per cluster, its box, a metre scale and the sensor's origin. Used
/// by `cluster --png` and the README's demo.
///
///     const io::RgbImage img = io::render_birds_eye(points, labels, {});
///     io::write_png("window.png", img);
///
/// Colours: clusters of at least `object_points` points in bright colours by
/// size rank (golden-angle hues) with their boxes; clusters above
/// `structure_fraction` of the window dimmed (walls, floor); smaller
/// fragments grey; ground (label -2) dark brown, ceiling (-3) dark blue,
/// unlabelled (-1) not drawn.

#include <streamclust/io/png_writer.hpp>
#include <streamclust/io/record.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace streamclust::io {

/// How render_birds_eye draws.
struct BirdsEyeOptions {
  std::size_t long_side_px = 900;   ///< pixels along the longer side of the points' extent
  float margin_m = 0.5f;            ///< [m] around the points
  std::size_t object_points = 20;   ///< clusters this large are objects: bright, with a box
  double structure_fraction = 0.05;  ///< clusters above this fraction of the window are dimmed
};

namespace detail {

/// A bright colour per rank (golden-angle hue steps: neighbours in rank
/// differ most), from HSV with S = 0.75, V = 1.
inline RgbImage::Color rank_color(std::size_t rank) {
  const double hue = std::fmod(static_cast<double>(rank) * 137.508, 360.0) / 60.0;
  const double f = hue - std::floor(hue);
  const auto level = [](double v) { return static_cast<std::uint8_t>(std::lround(255.0 * v)); };
  const std::uint8_t hi = 255, lo = level(0.25), down = level(1.0 - 0.75 * f), up = level(0.25 + 0.75 * f);
  switch (static_cast<int>(hue)) {
    case 0: return {hi, up, lo};
    case 1: return {down, hi, lo};
    case 2: return {lo, hi, up};
    case 3: return {lo, down, hi};
    case 4: return {up, lo, hi};
    default: return {hi, lo, down};
  }
}

/// 3 x 5 pixel glyphs of the digits and 'm' (rows top to bottom, 3 bits each).
inline const std::array<std::uint16_t, 5>& glyph(char c) {
  static const std::map<char, std::array<std::uint16_t, 5>> font = {
      {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
      {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
      {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'m', {0, 0, 7, 7, 5}}, {' ', {0, 0, 0, 0, 0}}};
  const auto it = font.find(c);
  return it == font.end() ? font.at(' ') : it->second;
}

/// Draws `text` with its top-left corner at (x, y), each font pixel `scale` pixels.
inline void draw_text(RgbImage& img, long x, long y, const std::string& text, long scale, RgbImage::Color c) {
  for (const char ch : text) {
    const auto& g = glyph(ch);
    for (long row = 0; row < 5; ++row)
      for (long col = 0; col < 3; ++col)
        if ((g[static_cast<std::size_t>(row)] >> (2 - col)) & 1u)
          for (long dy = 0; dy < scale; ++dy)
            for (long dx = 0; dx < scale; ++dx) img.set(x + col * scale + dx, y + row * scale + dy, c);
    x += 4 * scale;
  }
}

}  // namespace detail

/// The picture of `points` with `labels` (one per point; see the file
/// comment). Points with non-finite coordinates are skipped. O(n log n) for
/// n points (clusters ranked by size) plus O(pixels).
inline RgbImage render_birds_eye(const std::vector<Record>& points, const std::vector<std::int64_t>& labels,
                                 const BirdsEyeOptions& options = {}) {
  const auto finite = [](const Record& p) { return std::isfinite(p.x) && std::isfinite(p.y); };
  float x_min = 0, x_max = 0, y_min = 0, y_max = 0;  // the sensor's origin is always in view
  std::map<std::int64_t, std::size_t> sizes;
  std::map<std::int64_t, std::array<float, 4>> boxes;  // x_min, x_max, y_min, y_max
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Record& p = points[i];
    if (!finite(p)) continue;
    x_min = std::min(x_min, p.x);
    x_max = std::max(x_max, p.x);
    y_min = std::min(y_min, p.y);
    y_max = std::max(y_max, p.y);
    const std::int64_t l = i < labels.size() ? labels[i] : -1;
    if (l < 0) continue;
    ++sizes[l];
    auto [it, fresh] = boxes.try_emplace(l, std::array<float, 4>{p.x, p.x, p.y, p.y});
    if (!fresh) {
      auto& b = it->second;
      b = {std::min(b[0], p.x), std::max(b[1], p.x), std::min(b[2], p.y), std::max(b[3], p.y)};
    }
  }
  x_min -= options.margin_m;
  x_max += options.margin_m;
  y_min -= options.margin_m;
  y_max += options.margin_m;
  const float scale = static_cast<float>(options.long_side_px) / std::max(x_max - x_min, y_max - y_min);  // [px/m]
  const auto w = static_cast<std::size_t>(std::ceil((x_max - x_min) * scale));
  const auto h = static_cast<std::size_t>(std::ceil((y_max - y_min) * scale));
  RgbImage img(std::clamp<std::size_t>(w, 1, 65535), std::clamp<std::size_t>(h, 1, 65535), {16, 16, 20});
  const auto px = [&](float x) { return std::lround((x - x_min) * scale); };
  const auto py = [&](float y) { return std::lround((y_max - y) * scale); };

  // Clusters ranked by size, largest first.
  std::vector<std::pair<std::size_t, std::int64_t>> by_size;
  for (const auto& [label, n] : sizes) by_size.emplace_back(n, label);
  std::sort(by_size.begin(), by_size.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  std::map<std::int64_t, std::size_t> rank;
  for (std::size_t r = 0; r < by_size.size(); ++r) rank[by_size[r].second] = r;
  const auto large = static_cast<std::size_t>(options.structure_fraction * static_cast<double>(points.size()));
  const auto color = [&](std::int64_t label) -> RgbImage::Color {
    if (label == -2) return {70, 52, 35};
    if (label == -3) return {40, 55, 80};
    const std::size_t n = sizes[label];
    RgbImage::Color c = detail::rank_color(rank[label]);
    if (n > large) {
      for (auto& v : c) v = static_cast<std::uint8_t>(v / 3);
    } else if (n < options.object_points) {
      c = {90, 90, 90};
    }
    return c;
  };
  // Structure and large clusters first, then objects on top (2 x 2 pixels).
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      const std::int64_t l = i < labels.size() ? labels[i] : -1;
      if (l == -1 || !finite(points[i])) continue;
      const bool object = l >= 0 && sizes[l] >= options.object_points && sizes[l] <= large;
      if (object != (pass == 1)) continue;
      const RgbImage::Color c = color(l);
      const long x = px(points[i].x), y = py(points[i].y);
      for (long d = 0; d < (object ? 4 : 1); ++d) img.set(x + d % 2, y + d / 2, c);
    }
  }
  // Object boxes.
  for (const auto& [label, b] : boxes) {
    if (sizes[label] < options.object_points || sizes[label] > large) continue;
    const RgbImage::Color c = color(label);
    const long x0 = px(b[0]) - 2, x1 = px(b[1]) + 3, y0 = py(b[3]) - 2, y1 = py(b[2]) + 3;
    for (long x = x0; x <= x1; ++x) {
      img.set(x, y0, c);
      img.set(x, y1, c);
    }
    for (long y = y0; y <= y1; ++y) {
      img.set(x0, y, c);
      img.set(x1, y, c);
    }
  }
  // The sensor: a white cross at the origin.
  for (long d = -8; d <= 8; ++d) {
    img.set(px(0) + d, py(0), {255, 255, 255});
    img.set(px(0), py(0) + d, {255, 255, 255});
  }
  // A metre scale, bottom left: the largest of 1, 2, 5 x 10^k m up to a fifth of the width.
  const double fifth = (x_max - x_min) / 5.0;
  double bar = 1;
  for (double unit = 0.01; unit <= 1e6; unit *= 10)
    for (const double f : {1.0, 2.0, 5.0})
      if (f * unit <= fifth) bar = f * unit;
  const long bx0 = 12, by = static_cast<long>(img.height()) - 14;
  const long bx1 = bx0 + std::lround(bar * scale);
  for (long x = bx0; x <= bx1; ++x)
    for (long t = 0; t < 3; ++t) img.set(x, by + t, {255, 255, 255});
  for (long t = -6; t < 3; ++t) {
    img.set(bx0, by + t, {255, 255, 255});
    img.set(bx1, by + t, {255, 255, 255});
  }
  const std::string text = (bar >= 1 ? std::to_string(std::lround(bar)) : "0") + "m";
  if (bar >= 1) detail::draw_text(img, bx0, by - 18, text, 2, {255, 255, 255});
  return img;
}

}  // namespace streamclust::io
