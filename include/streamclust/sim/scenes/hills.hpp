// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The ready-made rolling terrain (`hills_scene`), with the terrain-aware
/// placement helpers it uses.

#include <streamclust/sim/scene.hpp>
#include <streamclust/sim/scene_building.hpp>
#include <streamclust/sim/shapes.hpp>
#include <streamclust/sim/terrain.hpp>
#include <streamclust/surface_class.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::sim {

namespace detail {

/// The lowest terrain height under a disc footprint (center and 8 points on
/// its rim): an upright object based there never floats.
inline float footprint_base(const Terrain& terrain, const Eigen::Vector2f& c, float r) {
  float z = terrain.height(c.x(), c.y());
  for (int k = 0; k < 8; ++k) {
    const float a = 0.25f * kPi * static_cast<float>(k);
    z = std::min(z, terrain.height(c.x() + r * std::cos(a), c.y() + r * std::sin(a)));
  }
  return z;
}

/// True when the disc (c, r) keeps `margin` from every step edge (no object
/// straddles a kerb) and, with `off_ramps`, from every ramp band.
inline bool clear_of_edges(const Terrain& terrain, const Eigen::Vector2f& c, float r, float margin, bool off_ramps) {
  for (const TerrainStep& s : terrain.params().steps) {
    const float u = s.direction.dot(c);
    if (std::abs(u - s.from) < r + margin) return false;
    if (std::isfinite(s.to) && std::abs(u - s.to) < r + margin) return false;
  }
  if (off_ramps) {
    for (const TerrainRamp& m : terrain.params().ramps) {
      const float u = m.direction.dot(c);
      if (u > m.start - r - margin && u < m.start + m.length + r + margin) return false;
    }
  }
  return true;
}

/// True when no step edge lies between a and b (a straight walk stays on one level).
inline bool same_level(const Terrain& terrain, const Eigen::Vector2f& a, const Eigen::Vector2f& b) {
  for (const TerrainStep& s : terrain.params().steps) {
    const float ua = s.direction.dot(a);
    const float ub = s.direction.dot(b);
    if ((ua >= s.from) != (ub >= s.from)) return false;
    if (std::isfinite(s.to) && (ua >= s.to) != (ub >= s.to)) return false;
  }
  return true;
}

}  // namespace detail

/// Rolling open terrain without walls (see the file comment). Structure
/// (all ground): one Terrain over [-60, 60]^2, z = 0 at the origin, made of
/// three waves (wavelengths 20-60 m, smooth slope bound 0.07-0.10), one
/// ramp band (6-10 m long, slope 0.12-0.16, i.e. up to 9.1 deg, rising or
/// falling, starting 12-20 m from the origin), a raised strip 0.12-0.18 m
/// high and 3-5 m wide starting 6-10 m from the origin (two kerbs) and a
/// single step of 0.1-0.2 m up or down 10-16 m away the other way; the
/// total slope bound stays below 15 deg. Objects in this order, all within
/// [-40, 40]^2, upright, based at the lowest terrain height under their
/// footprint, none straddling a kerb, cars and boxes off the ramp: 8-14
/// "tree" (trunk r 0.12-0.3 m, 5-9 m, ellipsoid crown), 3-5 "car" (parked,
/// any yaw), 4-8 "box" (0.4-1.2 m, yawed), 4-8 "pole" (r 0.05-0.12 m, 2.5-6
/// m), 3-6 standing "person" and 2-3 walking "person" (1.0-1.4 m/s back and
/// forth on straight paths sampled every <= 1 m on the terrain, never over
/// a kerb). A lane |y| < 2.5 along x is kept free of objects for a
/// vehicle driving along +x; the scene's ground height (Scene::ground_height)
/// is the terrain's.
inline Scene hills_scene(std::uint64_t seed) {
  detail::SplitMix64 rng = detail::make_rng(seed, 0x4111E5);
  constexpr float kHalf = 60.0f;
  constexpr float kPlace = 40.0f;
  constexpr float kLane = 2.5f;
  constexpr float kTwoPi = 2.0f * detail::kPi;

  Terrain::Params tp;
  tp.lo = {-kHalf, -kHalf};
  tp.hi = {kHalf, kHalf};
  float bound = 0.0f;
  for (int i = 0; i < 3; ++i) {
    const float wavelength = rng.uniform(20.0f, 60.0f);
    const float heading = rng.uniform(0.0f, kTwoPi);
    const float amplitude = rng.uniform(0.3f, 1.2f);
    const float phase = rng.uniform(0.0f, kTwoPi);
    const float k = kTwoPi / wavelength;
    tp.waves.push_back(TerrainWave{amplitude, k * std::cos(heading), k * std::sin(heading), phase});
    bound += amplitude * k;
  }
  const float rolling = rng.uniform(0.07f, 0.10f);
  for (TerrainWave& w : tp.waves) w.amplitude *= rolling / bound;
  {
    const float heading = rng.uniform(0.0f, kTwoPi);
    const float start = rng.uniform(12.0f, 20.0f);
    const float length = rng.uniform(6.0f, 10.0f);
    const float slope = rng.uniform(0.12f, 0.16f);
    const float sign = rng.uniform_int(0, 1) ? 1.0f : -1.0f;
    tp.ramps.push_back(TerrainRamp{{std::cos(heading), std::sin(heading)}, start, length, sign * slope * length});
  }
  const float strip_heading = rng.uniform(0.0f, kTwoPi);
  {
    const float from = rng.uniform(6.0f, 10.0f);
    const float width = rng.uniform(3.0f, 5.0f);
    const float height = rng.uniform(0.12f, 0.18f);
    tp.steps.push_back(TerrainStep{{std::cos(strip_heading), std::sin(strip_heading)}, from, from + width, height});
  }
  {
    const float heading = strip_heading + detail::kPi + rng.uniform(-0.5f, 0.5f);
    const float from = rng.uniform(10.0f, 16.0f);
    const float height = rng.uniform(0.1f, 0.2f);
    const float sign = rng.uniform_int(0, 1) ? 1.0f : -1.0f;
    tp.steps.push_back(TerrainStep{{std::cos(heading), std::sin(heading)}, from,
                                   std::numeric_limits<float>::infinity(), sign * height});
  }
  tp.base_height = -Terrain(tp).height(0.0f, 0.0f);
  const Terrain terrain(tp);

  detail::Layout layout(1.5f);
  layout.occupy_corridor({-kHalf, 0.0f}, {kHalf, 0.0f}, kLane);

  // Walking paths first (their corridors must stay clear), off the lane, on one level.
  std::vector<Trajectory> walks;
  const int n_walkers = rng.uniform_int(2, 3);
  for (int attempt = 0; static_cast<int>(walks.size()) < n_walkers && attempt < 10000; ++attempt) {
    const Eigen::Vector2f a = detail::uniform2(rng, -kPlace + 2, kPlace - 2, -kPlace + 2, kPlace - 2);
    const float heading = rng.uniform(0.0f, kTwoPi);
    const float len = rng.uniform(8.0f, 20.0f);
    const float speed = rng.uniform(1.0f, 1.4f);
    const float phase = rng.uniform(0.0f, 2.0f * len);
    const Eigen::Vector2f b = a + len * Eigen::Vector2f(std::cos(heading), std::sin(heading));
    if (std::abs(b.x()) > kPlace - 2 || std::abs(b.y()) > kPlace - 2) continue;
    if (std::min(std::abs(a.y()), std::abs(b.y())) < kLane + 0.6f || (a.y() > 0) != (b.y() > 0)) continue;
    if (!detail::same_level(terrain, a, b) || !detail::clear_of_edges(terrain, a, 0.3f, 0.2f, false) ||
        !detail::clear_of_edges(terrain, b, 0.3f, 0.2f, false)) {
      continue;
    }
    if (!layout.free_corridor(a, b, 0.6f)) continue;
    layout.occupy_corridor(a, b, 0.6f);
    // Out along samples <= 1 m apart on the terrain, and back.
    const int n = static_cast<int>(std::ceil(len));
    std::vector<Eigen::Vector3f> path;
    for (int i = 0; i <= n; ++i) {
      const Eigen::Vector2f q = a + (static_cast<float>(i) / static_cast<float>(n)) * (b - a);
      path.emplace_back(q.x(), q.y(), terrain.height(q.x(), q.y()));
    }
    for (int i = n - 1; i >= 1; --i) path.push_back(path[static_cast<std::size_t>(i)]);
    walks.push_back(Trajectory::loop(std::move(path), speed, phase));
  }
  detail::require_count(static_cast<int>(walks.size()), n_walkers, "walking person");

  Scene scene;
  scene.set_material_seed(seed);
  scene.add_terrain(terrain, Material::grass);

  // Static objects: place(r, off_ramps, gap) finds a footprint center.
  const auto place = [&](float r, bool off_ramps, float gap, Eigen::Vector2f& c) {
    for (int attempt = 0; attempt < 20000; ++attempt) {
      c = detail::uniform2(rng, -kPlace + r, kPlace - r, -kPlace + r, kPlace - r);
      if (!detail::clear_of_edges(terrain, c, r, 0.2f, off_ramps) || !layout.free_disc(c, r, gap)) continue;
      layout.occupy_disc(c, r);
      return true;
    }
    return false;
  };
  Eigen::Vector2f c;
  // Trees and cars are drawn before any is added, so that ids stay grouped by label.
  struct Parked {
    Eigen::Vector3f base;
    float yaw, l, w, h;
  };
  std::vector<Parked> cars;
  const int n_cars = rng.uniform_int(3, 5);
  for (int i = 0; i < n_cars; ++i) {
    const float l = rng.uniform(4.2f, 4.8f);
    const float w = rng.uniform(1.75f, 1.9f);
    const float h = rng.uniform(1.4f, 1.6f);
    const float yaw = rng.uniform(0.0f, kTwoPi);
    const float r = 0.5f * std::hypot(l, w);
    if (!place(r, true, 0.6f, c)) detail::require_count(i, n_cars, "car");
    cars.push_back(Parked{{c.x(), c.y(), detail::footprint_base(terrain, c, r)}, yaw, l, w, h});
  }
  const int n_trees = rng.uniform_int(8, 14);
  for (int i = 0; i < n_trees; ++i) {
    const float r = rng.uniform(0.12f, 0.3f);
    const float height = rng.uniform(5.0f, 9.0f);
    const float crown_v = std::min(rng.uniform(1.2f, 2.5f), (height - 2.5f) / 1.5f);
    const float crown_h = rng.uniform(1.0f, 2.0f);
    if (!place(r, false, 1.2f, c)) detail::require_count(i, n_trees, "tree");
    const float z0 = detail::footprint_base(terrain, c, r);
    ShapeSet tree;
    tree.add(Cylinder{c.x(), c.y(), r, z0, z0 + height}, Material::bark);
    tree.add(Ellipsoid{{c.x(), c.y(), z0 + height - 0.5f * crown_v}, {crown_h, crown_h, crown_v}}, Material::foliage);
    scene.add_object("tree", tree);
  }
  for (const Parked& p : cars) scene.add_object("car", detail::car_shapes(p.base, p.yaw, p.l, p.w, p.h));
  const int n_boxes = rng.uniform_int(4, 8);
  for (int i = 0; i < n_boxes; ++i) {
    const float sx = rng.uniform(0.4f, 1.2f);
    const float sy = rng.uniform(0.4f, 1.2f);
    const float sz = rng.uniform(0.4f, 1.2f);
    const float yaw = rng.uniform(0.0f, kTwoPi);
    const float r = 0.5f * std::hypot(sx, sy);
    if (!place(r, true, 0.4f, c)) detail::require_count(i, n_boxes, "box");
    const float z0 = detail::footprint_base(terrain, c, r);
    scene.add_object("box", ShapeSet().add(Box::rotated({c.x(), c.y(), z0 + 0.5f * sz}, {0.5f * sx, 0.5f * sy, 0.5f * sz}, yaw),
                                           Material::wood));
  }
  const int n_poles = rng.uniform_int(4, 8);
  for (int i = 0; i < n_poles; ++i) {
    const float r = rng.uniform(0.05f, 0.12f);
    const float height = rng.uniform(2.5f, 6.0f);
    if (!place(r, false, 0.5f, c)) detail::require_count(i, n_poles, "pole");
    const float z0 = detail::footprint_base(terrain, c, r);
    scene.add_object("pole", ShapeSet().add(Cylinder{c.x(), c.y(), r, z0, z0 + height}, Material::metal));
  }
  const int n_standing = rng.uniform_int(3, 6);
  for (int i = 0; i < n_standing; ++i) {
    const float height = rng.uniform(1.6f, 1.85f);
    if (!place(0.3f, false, 0.4f, c)) detail::require_count(i, n_standing, "person");
    const float z0 = detail::footprint_base(terrain, c, 0.3f);
    scene.add_object("person", detail::person_shapes({c.x(), c.y(), z0}, height, 0.3f));
  }
  for (Trajectory& walk : walks) {
    const float height = rng.uniform(1.6f, 1.85f);
    scene.add_moving_object("person", detail::person_shapes(Eigen::Vector3f::Zero(), height, 0.3f), std::move(walk));
  }
  return scene;
}

}  // namespace streamclust::sim
