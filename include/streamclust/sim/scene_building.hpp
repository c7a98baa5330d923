// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Helpers the ready-made scenes (`sim/scenes/`) place their objects with:
/// rejection-sampling bookkeeping of footprints, yawed placement, car and
/// person shape sets, sequenced uniform draws, and the check that a scene
/// placed as many objects as it promised. Deterministic given the RNG.

#include <streamclust/sim/scene.hpp>
#include <streamclust/sim/shapes.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::sim {

namespace detail {

inline constexpr float kPi = 3.14159265358979323846f;

/// Rejection-sampling bookkeeping for object footprints in the xy plane:
/// discs (static objects, circular paths) and corridors (straight paths).
class Layout {
 public:
  explicit Layout(float origin_clearance) : clearance_(origin_clearance) {}

  bool free_disc(const Eigen::Vector2f& c, float r, float gap = 0.0f) const {
    if (c.norm() < clearance_ + r) return false;
    for (const Disc& d : discs_)
      if ((d.c - c).norm() < d.r + r + gap) return false;
    for (const Corridor& k : corridors_)
      if (segment_distance(c, k.a, k.b) < k.half_width + r + gap) return false;
    return true;
  }
  bool free_corridor(const Eigen::Vector2f& a, const Eigen::Vector2f& b, float half_width) const {
    if (segment_distance(Eigen::Vector2f::Zero(), a, b) < clearance_ + half_width) return false;
    for (const Disc& d : discs_)
      if (segment_distance(d.c, a, b) < d.r + half_width) return false;
    return true;
  }
  void occupy_disc(const Eigen::Vector2f& c, float r) { discs_.push_back(Disc{c, r}); }
  void occupy_corridor(const Eigen::Vector2f& a, const Eigen::Vector2f& b, float half_width) {
    corridors_.push_back(Corridor{a, b, half_width});
  }

  static float segment_distance(const Eigen::Vector2f& p, const Eigen::Vector2f& a, const Eigen::Vector2f& b) {
    const Eigen::Vector2f ab = b - a;
    const float l2 = ab.squaredNorm();
    const float f = l2 > 0.0f ? std::clamp((p - a).dot(ab) / l2, 0.0f, 1.0f) : 0.0f;
    return (a + f * ab - p).norm();
  }

 private:
  struct Disc {
    Eigen::Vector2f c;
    float r;
  };
  struct Corridor {
    Eigen::Vector2f a, b;
    float half_width;
  };
  float clearance_;
  std::vector<Disc> discs_;
  std::vector<Corridor> corridors_;
};

/// Rotates (x, y) by yaw and translates: the world position of a point of a
/// yawed body.
inline Eigen::Vector3f place(const Eigen::Vector3f& center, float yaw, float x, float y, float z) {
  const float c = std::cos(yaw);
  const float s = std::sin(yaw);
  return center + Eigen::Vector3f(c * x - s * y, s * x + c * y, z);
}

/// A car of length l, width w, height h standing on z = 0 at `base`
/// (footprint center), facing `yaw`: lower body (car paint), cabin (glass,
/// with a painted roof decal), four wheels (rubber) and a licence plate
/// front and back (retroreflective decals, 0.52 x 0.12 m, centred 0.5 m up).
inline ShapeSet car_shapes(const Eigen::Vector3f& base, float yaw, float l, float w, float h) {
  ShapeSet s;
  const float body_low = 0.3f;
  const float body_high = 0.55f * h + 0.1f;
  s.add(Box::rotated(place(base, yaw, 0.0f, 0.0f, 0.5f * (body_low + body_high)),
                     Eigen::Vector3f(0.5f * l, 0.5f * w, 0.5f * (body_high - body_low)), yaw),
        Material::car_paint);
  const float cabin_l = 0.55f * l;
  s.add(Box::rotated(place(base, yaw, -0.05f * l, 0.0f, 0.5f * (body_high + h)),
                     Eigen::Vector3f(0.5f * cabin_l, 0.45f * w, 0.5f * (h - body_high)), yaw),
        Material::glass);
  for (float fx : {-0.32f, 0.32f})
    for (float fy : {-1.0f, 1.0f}) {
      s.add(Box::rotated(place(base, yaw, fx * l, fy * (0.5f * w - 0.12f), 0.32f), Eigen::Vector3f(0.32f, 0.11f, 0.32f),
                         yaw),
            Material::rubber);
    }
  const Eigen::Vector3f forward(std::cos(yaw), std::sin(yaw), 0.0f);
  const Eigen::Vector3f left(-std::sin(yaw), std::cos(yaw), 0.0f);
  s.decal(Plane::rectangle(place(base, yaw, -0.05f * l, 0.0f, h), forward, left, 0.5f * cabin_l, 0.45f * w),
          Material::car_paint);
  for (float fx : {-0.5f, 0.5f}) {
    s.decal(Plane::rectangle(place(base, yaw, fx * l, 0.0f, 0.5f), left, Eigen::Vector3f::UnitZ(), 0.26f, 0.06f),
            Material::retroreflector);
  }
  return s;
}

/// A standing person (capsule of clothing fabric, feet at `base`).
inline ShapeSet person_shapes(const Eigen::Vector3f& base, float height = 1.7f, float radius = 0.3f) {
  return ShapeSet().add(Capsule::standing(base.x(), base.y(), base.z(), height, radius), Material::fabric);
}

/// The stream a scene draws its material choices from (which material a
/// cabinet or a facade is made of): its own, so that geometry never depends
/// on it.
inline SplitMix64 material_rng(std::uint64_t seed) { return make_rng(seed, 0x3A7E21A1); }

/// A uniform point of [x_lo, x_hi) x [y_lo, y_hi). Draws are sequenced (x
/// first): never put two draws in one argument list, whose evaluation order
/// is unspecified (GCC and clang differ) and would break determinism.
inline Eigen::Vector2f uniform2(SplitMix64& rng, float x_lo, float x_hi, float y_lo, float y_hi) {
  const float x = rng.uniform(x_lo, x_hi);
  const float y = rng.uniform(y_lo, y_hi);
  return {x, y};
}

inline void require_count(int placed, int wanted, const char* what) {
  if (placed < wanted) {
    std::string msg("scene factory could not place every ");
    msg.append(what);
    throw std::logic_error(msg);
  }
}

}  // namespace detail

}  // namespace streamclust::sim
