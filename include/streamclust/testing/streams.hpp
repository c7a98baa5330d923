// SPDX-License-Identifier: MIT
#pragma once
// Random and adversarial point streams for the property tests.

#include <streamclust/point_traits.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <random>
#include <vector>

namespace streamclust::testing {

enum class StreamKind {
  blobs,            // a few compact objects plus clutter
  one_cell,         // all points along almost the same ray
  seam,             // around azimuth +-180 degrees
  fov_borders,      // on and just beyond the FOV bounds
  duplicates,       // the same points again and again
  bursts,           // many points with one timestamp
  quiet_gaps,       // long pauses that empty the window
  invalid_mixed,    // NaN, inf, zero range and backwards time among good points
  count_,
};

/// Offers stream[first, last) to `engine`: point by point with insert() when
/// `packet_max` is 0, else through insert_batch in packets of 1 to
/// `packet_max` points (sizes drawn from `rng`). Returns the points accepted.
/// With `reasons`, appends what the engine returned for each point (the
/// batches then go through insert_batch's reason-reporting overload).
template <class Engine, class Rng>
std::size_t offer(Engine& engine, const std::vector<Point>& stream, std::size_t first, std::size_t last,
                  std::size_t packet_max, Rng& rng, std::vector<RejectReason>* reasons = nullptr) {
  std::size_t accepted = 0;
  if (packet_max == 0) {
    for (std::size_t i = first; i < last; ++i) {
      const RejectReason r = engine.insert(stream[i]);
      accepted += r == RejectReason::accepted;
      if (reasons) reasons->push_back(r);
    }
    return accepted;
  }
  while (first < last) {
    const std::size_t end = std::min(last, first + 1 + static_cast<std::size_t>(rng() % packet_max));
    const auto from = stream.begin() + static_cast<std::ptrdiff_t>(first);
    const auto to = stream.begin() + static_cast<std::ptrdiff_t>(end);
    if (reasons) {
      const std::size_t before = reasons->size();
      engine.insert_batch(from, to, std::back_inserter(*reasons));
      accepted += static_cast<std::size_t>(
          std::count(reasons->begin() + static_cast<std::ptrdiff_t>(before), reasons->end(), RejectReason::accepted));
    } else {
      accepted += engine.insert_batch(from, to);
    }
    first = end;
  }
  return accepted;
}

inline const char* to_string(StreamKind k) {
  static const char* names[] = {"blobs", "one_cell", "seam", "fov_borders", "duplicates", "bursts", "quiet_gaps",
                                "invalid_mixed"};
  return names[static_cast<int>(k)];
}

inline Point point_at(float azimuth_deg, float elevation_deg, float range, double t) {
  constexpr float kDeg = 3.14159265358979f / 180.0f;
  const float a = azimuth_deg * kDeg;
  const float e = elevation_deg * kDeg;
  return Point{range * std::cos(e) * std::cos(a), range * std::cos(e) * std::sin(a), range * std::sin(e), 0.0f, t};
}

/// `n` points of the given kind, in stream order, with times advancing at
/// about `rate` points per second.
inline std::vector<Point> make_stream(StreamKind kind, std::size_t n, std::uint64_t seed, double rate = 1000.0) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  auto uni = [&](float lo, float hi) { return lo + (hi - lo) * unit(rng); };
  std::vector<Point> out;
  out.reserve(n);
  double t = 0.0;
  const double dt = 1.0 / rate;

  struct Blob {
    float az, el, range, spread;
  };
  std::vector<Blob> blobs;
  const int blob_count = 2 + static_cast<int>(rng() % 5);
  for (int i = 0; i < blob_count; ++i) blobs.push_back({uni(-180, 180), uni(-20, 40), uni(1, 20), uni(1, 8)});

  for (std::size_t i = 0; i < n; ++i) {
    t += dt * uni(0.2f, 1.8f);
    switch (kind) {
      case StreamKind::blobs: {
        if (rng() % 5 == 0) {
          out.push_back(point_at(uni(-180, 180), uni(-40, 60), uni(0.5f, 30), t));
        } else {
          const Blob& b = blobs[rng() % blobs.size()];
          out.push_back(point_at(b.az + uni(-b.spread, b.spread), b.el + uni(-b.spread, b.spread),
                                 b.range + uni(-0.3f, 0.3f), t));
        }
        break;
      }
      case StreamKind::one_cell:
        out.push_back(point_at(12.0f + uni(-0.01f, 0.01f), 5.0f + uni(-0.01f, 0.01f), uni(2, 6), t));
        break;
      case StreamKind::seam:
        out.push_back(point_at((rng() % 2 ? 180.0f : -180.0f) + uni(-3, 3), uni(-5, 5), uni(3, 5), t));
        break;
      case StreamKind::fov_borders: {
        static const float az[] = {-180.0f, 180.0f, -60.0f, 60.0f, -60.01f, 60.01f, 0.0f};
        static const float el[] = {-30.0f, 50.0f, -30.01f, 50.01f, 0.0f, -90.0f, 90.0f};
        out.push_back(point_at(az[rng() % 7] + uni(-0.5f, 0.5f) * float(rng() % 2), el[rng() % 7], uni(2, 4), t));
        break;
      }
      case StreamKind::duplicates:
        if (out.empty() || rng() % 4 == 0) {
          out.push_back(point_at(uni(-30, 30), uni(-10, 10), uni(2, 3), t));
        } else {
          Point p = out[rng() % out.size()];
          p.t = t;
          out.push_back(p);
        }
        break;
      case StreamKind::bursts: {
        if (rng() % 20 != 0) t -= dt;  // stays on the same timestamp most of the time
        const Blob& b = blobs[rng() % blobs.size()];
        out.push_back(point_at(b.az + uni(-b.spread, b.spread), b.el + uni(-2, 2), b.range + uni(-0.2f, 0.2f), t));
        break;
      }
      case StreamKind::quiet_gaps: {
        if (rng() % 40 == 0) t += uni(0.5f, 5.0f);
        const Blob& b = blobs[rng() % blobs.size()];
        out.push_back(point_at(b.az + uni(-b.spread, b.spread), b.el + uni(-2, 2), b.range + uni(-0.2f, 0.2f), t));
        break;
      }
      case StreamKind::invalid_mixed: {
        const Blob& b = blobs[rng() % blobs.size()];
        Point p = point_at(b.az + uni(-b.spread, b.spread), b.el + uni(-2, 2), b.range + uni(-0.2f, 0.2f), t);
        switch (rng() % 12) {
          case 0: p.x = std::numeric_limits<float>::quiet_NaN(); break;
          case 1: p.y = std::numeric_limits<float>::infinity(); break;
          case 2: p.x = p.y = p.z = 0.0f; break;
          case 3: p.t = t - 0.5; break;  // backwards in time
          case 4: p.t = std::numeric_limits<double>::quiet_NaN(); break;
          default: break;
        }
        out.push_back(p);
        break;
      }
      case StreamKind::count_: break;
    }
  }
  return out;
}

}  // namespace streamclust::testing
