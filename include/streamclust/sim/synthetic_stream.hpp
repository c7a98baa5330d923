// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A small built-in point stream for demos, examples and smoke tests: a
/// Mid-360-like non-repetitive scan (full azimuth turn every 1/182 s per
/// laser, elevation oscillating with a 10 Hz fundamental and harmonics,
/// 4 interleaved lasers, 200 kHz) ray-cast against a simple room (floor,
/// ceiling, walls), pillars, boxes and a person walking across. Each point
/// carries the id of the object it hit (0 for structure: floor, ceiling, walls).
///
/// It is a stand-in, not a sensor model: the scan-pattern simulator with
/// validated Livox models and ground truth belongs to streamclust's sim module.
/// Deterministic for a given seed. Not thread-safe (one generator per thread).

#include <streamclust/point_traits.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

namespace streamclust {

/// A point of the synthetic stream: a streamclust::Point plus the id of the
/// object hit (ground truth).
struct SyntheticPoint {
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;
  float intensity = 0.0f;
  double t = 0.0;  ///< stream time [s]
  int object = -1;  ///< 0 ground, >= 1 object id
};

/// Generates the stream point by point.
///
/// \code
/// streamclust::SyntheticStream stream;          // seed 1, 200 kHz
/// while (stream.time() < 1.0) engine.insert(stream.next());
/// \endcode
class SyntheticStream {
 public:
  struct Params {
    double point_rate = 200000.0;  ///< points per second [Hz]
    float max_range = 40.0f;       ///< beyond: no return [m]
    float range_noise = 0.01f;     ///< standard deviation of range noise [m]
    float sensor_height = 1.0f;    ///< above the ground plane [m]
    std::uint64_t seed = 1;
  };

  SyntheticStream() : SyntheticStream(Params{}) {}
  explicit SyntheticStream(const Params& params) : params_(params), rng_(params.seed) {
    // Vertical cylinders: x, y, radius, height.
    pillars_ = {{6.0f, 2.0f, 0.3f, 3.0f}, {-4.0f, 5.0f, 0.4f, 3.0f}, {3.0f, -7.0f, 0.25f, 3.0f}, {-8.0f, -3.0f, 0.5f, 3.0f}};
    // Axis-aligned boxes: min and max corners.
    boxes_ = {{Eigen::Vector3f(9.0f, -2.0f, 0.0f), Eigen::Vector3f(10.5f, 1.0f, 1.2f)},
              {Eigen::Vector3f(-3.0f, -9.0f, 0.0f), Eigen::Vector3f(-1.0f, -8.0f, 0.8f)}};
  }

  /// The next point in firing order; points without a return are skipped.
  SyntheticPoint next() {
    for (;;) {
      const double t = static_cast<double>(index_) / params_.point_rate;
      const int laser = static_cast<int>(index_ % 4);
      ++index_;
      const Eigen::Vector3f dir = direction(t, laser);
      float hit = std::numeric_limits<float>::infinity();
      int object = -1;
      cast(dir, t, hit, object);
      if (object < 0) continue;
      std::normal_distribution<float> noise(0.0f, params_.range_noise);
      const float range = hit + noise(rng_);
      const Eigen::Vector3f p = dir * range;
      return SyntheticPoint{p.x(), p.y(), p.z(), 100.0f, t, object};
    }
  }

  /// Time of the next firing [s].
  double time() const { return static_cast<double>(index_) / params_.point_rate; }

 private:
  struct Pillar {
    float x, y, radius, height;
  };
  struct Box {
    Eigen::Vector3f lo, hi;
  };

  /// Mid-360-like pattern: azimuth turns at 182 rev/s, elevation in about
  /// [-7, 52] degrees with a 10 Hz fundamental and 20/30 Hz harmonics.
  static Eigen::Vector3f direction(double t, int laser) {
    constexpr double kPi = 3.14159265358979323846;
    const double azimuth = 2.0 * kPi * (182.0 * t + 0.25 * laser);
    const double phase = 2.0 * kPi * 10.0 * t;
    const double wobble = 0.55 * std::sin(phase + 0.8 * laser) + 0.3 * std::sin(2.0 * phase + 1.3 * laser) +
                          0.15 * std::sin(3.0 * phase + 0.4 * laser);
    const double elevation = (22.5 + 29.5 * wobble) * kPi / 180.0;
    return Eigen::Vector3f(static_cast<float>(std::cos(elevation) * std::cos(azimuth)),
                           static_cast<float>(std::cos(elevation) * std::sin(azimuth)),
                           static_cast<float>(std::sin(elevation)));
  }

  void consider(float distance, int object, float& hit, int& hit_object) const {
    if (distance > 0.05f && distance < hit && distance <= params_.max_range) {
      hit = distance;
      hit_object = object;
    }
  }

  void cast(const Eigen::Vector3f& d, double t, float& hit, int& object) const {
    const float h = params_.sensor_height;
    // Structure (id 0): floor z = -h, ceiling 3 m above it, walls of a 24 x 16 m room.
    if (d.z() < 0.0f) consider(-h / d.z(), 0, hit, object);
    if (d.z() > 0.0f) consider((3.0f - h) / d.z(), 0, hit, object);
    if (d.x() != 0.0f) consider((d.x() > 0.0f ? 12.0f : -12.0f) / d.x(), 0, hit, object);
    if (d.y() != 0.0f) consider((d.y() > 0.0f ? 8.0f : -8.0f) / d.y(), 0, hit, object);
    int id = 1;
    for (const Pillar& p : pillars_) cast_cylinder(d, p.x, p.y, p.radius, -h, -h + p.height, id++, hit, object);
    for (const Box& b : boxes_) {
      cast_box(d, Eigen::Vector3f(b.lo.x(), b.lo.y(), b.lo.z() - h), Eigen::Vector3f(b.hi.x(), b.hi.y(), b.hi.z() - h),
               id++, hit, object);
    }
    // A person (a slim cylinder) walking across at 1.2 m/s, back and forth.
    const double walk = std::fmod(1.2 * t, 16.0);
    const float py = static_cast<float>(walk < 8.0 ? walk - 4.0 : 12.0 - walk);
    cast_cylinder(d, 4.0f, py, 0.25f, -h, -h + 1.75f, id, hit, object);
  }

  void cast_cylinder(const Eigen::Vector3f& d, float cx, float cy, float r, float z0, float z1, int id, float& hit,
                     int& object) const {
    const float a = d.x() * d.x() + d.y() * d.y();
    if (a < 1e-12f) return;
    const float b = -2.0f * (d.x() * cx + d.y() * cy);
    const float c = cx * cx + cy * cy - r * r;
    const float disc = b * b - 4.0f * a * c;
    if (disc < 0.0f) return;
    const float s = (-b - std::sqrt(disc)) / (2.0f * a);
    const float z = s * d.z();
    if (z >= z0 && z <= z1) consider(s, id, hit, object);
  }

  void cast_box(const Eigen::Vector3f& d, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, int id, float& hit,
                int& object) const {
    float near = 0.0f;
    float far = std::numeric_limits<float>::infinity();
    for (int k = 0; k < 3; ++k) {
      if (std::abs(d[k]) < 1e-9f) {
        if (0.0f < lo[k] || 0.0f > hi[k]) return;
        continue;
      }
      float t0 = lo[k] / d[k];
      float t1 = hi[k] / d[k];
      if (t0 > t1) std::swap(t0, t1);
      near = std::max(near, t0);
      far = std::min(far, t1);
      if (near > far) return;
    }
    consider(near, id, hit, object);
  }

  Params params_;
  std::mt19937_64 rng_;
  std::uint64_t index_ = 0;
  std::vector<Pillar> pillars_;
  std::vector<Box> boxes_;
};

}  // namespace streamclust
