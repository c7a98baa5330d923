// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The ready-made sloped forest (`forest_scene`).

#include <streamclust/sim/scene.hpp>
#include <streamclust/sim/scene_building.hpp>
#include <streamclust/sim/shapes.hpp>
#include <streamclust/surface_class.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::sim {

/// An outdoor forest: ground plane z = sx x + sy y (|sx|, |sy| <= 0.03,
/// structure), then objects in this order: 30-60 trees ("tree": vertical
/// trunk of radius 0.1-0.4 m and height 6-12 m plus an ellipsoid crown
/// whose bottom is >= 3 m above ground), 10-20 bushes ("bush": one or two
/// ellipsoids up to 1.3 m tall), 2 parked vehicles ("vehicle": ~4.5 x 1.8
/// x 1.5 m, body, cabin and wheels), 2-4 pedestrians ("pedestrian", 1.0-1.5
/// m/s, back and forth along straight paths that follow the ground). All
/// in [-30, 30]^2.
inline Scene forest_scene(std::uint64_t seed) {
  detail::SplitMix64 rng = detail::make_rng(seed, 0xF02E57);
  constexpr float kHalf = 30.0f;
  const float sx = rng.uniform(-0.03f, 0.03f);
  const float sy = rng.uniform(-0.03f, 0.03f);
  const auto ground = [sx, sy](float x, float y) { return sx * x + sy * y; };
  detail::Layout layout(1.5f);

  // Pedestrian paths.
  std::vector<Trajectory> walks;
  const int n_walkers = rng.uniform_int(2, 4);
  for (int attempt = 0; static_cast<int>(walks.size()) < n_walkers && attempt < 10000; ++attempt) {
    const Eigen::Vector2f a = detail::uniform2(rng, -kHalf + 2, kHalf - 2, -kHalf + 2, kHalf - 2);
    const float heading = rng.uniform(0.0f, 2.0f * detail::kPi);
    const float len = rng.uniform(10.0f, 25.0f);
    const Eigen::Vector2f b = a + len * Eigen::Vector2f(std::cos(heading), std::sin(heading));
    if (std::abs(b.x()) > kHalf - 2 || std::abs(b.y()) > kHalf - 2) continue;
    if (!layout.free_corridor(a, b, 0.6f)) continue;
    layout.occupy_corridor(a, b, 0.6f);
    const float speed = rng.uniform(1.0f, 1.5f);
    const float phase = rng.uniform(0.0f, 2.0f * len);
    walks.push_back(Trajectory::back_and_forth({a.x(), a.y(), ground(a.x(), a.y())}, {b.x(), b.y(), ground(b.x(), b.y())},
                                               speed, phase));
  }
  detail::require_count(static_cast<int>(walks.size()), n_walkers, "pedestrian");

  // Vehicles next (large footprints are hardest to place).
  struct Parked {
    Eigen::Vector3f base;
    float yaw;
  };
  std::vector<Parked> vehicles;
  for (int attempt = 0; vehicles.size() < 2 && attempt < 10000; ++attempt) {
    const float dist = rng.uniform(5.0f, 20.0f);
    const float bearing = rng.uniform(0.0f, 2.0f * detail::kPi);
    const Eigen::Vector2f c = dist * Eigen::Vector2f(std::cos(bearing), std::sin(bearing));
    if (!layout.free_disc(c, 2.5f, 0.5f)) continue;
    layout.occupy_disc(c, 2.5f);
    vehicles.push_back(Parked{{c.x(), c.y(), ground(c.x(), c.y()) - 0.03f}, rng.uniform(0.0f, 2.0f * detail::kPi)});
  }
  detail::require_count(static_cast<int>(vehicles.size()), 2, "vehicle");

  Scene scene;
  scene.set_material_seed(seed);
  scene.add_structure(ShapeSet().add(Plane::infinite({-sx, -sy, 1.0f}, {0, 0, 0}), Material::soil), SurfaceClass::ground);

  const int n_trees = rng.uniform_int(30, 60);
  int placed = 0;
  for (int attempt = 0; placed < n_trees && attempt < 20000; ++attempt) {
    const float r = rng.uniform(0.1f, 0.4f);
    const Eigen::Vector2f c = detail::uniform2(rng, -kHalf, kHalf, -kHalf, kHalf);
    if (!layout.free_disc(c, r, 1.2f)) continue;
    layout.occupy_disc(c, r);
    const float height = rng.uniform(6.0f, 12.0f);
    const float z0 = ground(c.x(), c.y());
    const float crown_v = std::min(rng.uniform(1.5f, 3.0f), (height - 3.0f) / 1.5f);
    const float crown_h = rng.uniform(1.0f, 2.5f);
    ShapeSet tree;
    tree.add(Cylinder{c.x(), c.y(), r, z0 - 0.1f, z0 + height}, Material::bark);
    tree.add(Ellipsoid{{c.x(), c.y(), z0 + height - 0.5f * crown_v}, {crown_h, crown_h, crown_v}}, Material::foliage);
    scene.add_object("tree", tree);
    ++placed;
  }
  detail::require_count(placed, n_trees, "tree");

  const int n_bushes = rng.uniform_int(10, 20);
  placed = 0;
  for (int attempt = 0; placed < n_bushes && attempt < 20000; ++attempt) {
    const float rh = rng.uniform(0.4f, 1.2f);
    const float rv = rng.uniform(0.3f, 0.8f);
    const Eigen::Vector2f c = detail::uniform2(rng, -kHalf, kHalf, -kHalf, kHalf);
    const bool twin = rng.uniform_int(0, 1) != 0;
    const Eigen::Vector2f offset = twin ? Eigen::Vector2f(0.6f * rh, 0.0f) : Eigen::Vector2f::Zero();
    const float reach = rh + offset.norm();
    if (!layout.free_disc(c, reach, 0.3f)) continue;
    layout.occupy_disc(c, reach);
    ShapeSet bush;
    const Eigen::Vector2f p0 = c - offset;
    bush.add(Ellipsoid{{p0.x(), p0.y(), ground(p0.x(), p0.y()) + 0.6f * rv}, {rh, 0.8f * rh, rv}}, Material::foliage);
    if (twin) {
      const Eigen::Vector2f p1 = c + offset;
      bush.add(Ellipsoid{{p1.x(), p1.y(), ground(p1.x(), p1.y()) + 0.5f * rv}, {0.8f * rh, rh, 0.8f * rv}},
               Material::foliage);
    }
    scene.add_object("bush", bush);
    ++placed;
  }
  detail::require_count(placed, n_bushes, "bush");

  for (const Parked& v : vehicles) {
    const float l = rng.uniform(4.3f, 4.7f);
    const float w = rng.uniform(1.75f, 1.85f);
    const float h = rng.uniform(1.45f, 1.55f);
    scene.add_object("vehicle", detail::car_shapes(v.base, v.yaw, l, w, h));
  }
  for (Trajectory& walk : walks) {
    const float height = rng.uniform(1.6f, 1.85f);
    scene.add_moving_object("pedestrian", detail::person_shapes(Eigen::Vector3f::Zero(), height, 0.3f), std::move(walk));
  }
  return scene;
}

}  // namespace streamclust::sim
