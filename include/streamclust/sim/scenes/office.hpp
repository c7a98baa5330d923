// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The ready-made office room (`office_scene`).

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

/// An office room of 20 x 12 x 3 m (x in [-10, 10], y in [-6, 6], z in
/// [0, 3]); floor, ceiling and walls are structure (instance 0). Objects,
/// ids in this order: 2-4 pillars ("pillar", floor to ceiling cylinders, r
/// 0.25-0.4 m), 6-10 desks ("desk": top at 0.75 m plus two side panels; 2-3
/// of them pushed against a wall, 2-5 cm from it, the others free), 3-5
/// cabinets ("cabinet", 2 cm from a wall, 1.0-2.0 m tall), 2-4 bookshelves
/// ("bookshelf", 2-5 cm from a wall, 1.6-2.0 m tall, 0.3-0.4 m deep,
/// 0.8-1.6 m wide), 2-3 people ("person", capsules 1.7 m x 0.3 m at 1.2
/// m/s, back and forth along a straight path or, for a third person, around
/// a circle). Walking paths never cross furniture.
inline Scene office_scene(std::uint64_t seed) {
  detail::SplitMix64 rng = detail::make_rng(seed, 0x0FF1CE);
  constexpr float kHalfX = 10.0f;
  constexpr float kHalfY = 6.0f;
  constexpr float kHeight = 3.0f;
  constexpr float kPersonR = 0.3f;
  detail::Layout layout(1.0f);

  // People first: their corridors must stay clear of furniture.
  struct Walker {
    Trajectory trajectory;
  };
  std::vector<Walker> walkers;
  const int n_people = rng.uniform_int(2, 3);
  for (int attempt = 0; static_cast<int>(walkers.size()) < n_people && attempt < 10000; ++attempt) {
    const bool is_circle = n_people == 3 && walkers.empty();  // the third walker circles; placed first
    if (is_circle) {
      const float radius = rng.uniform(1.5f, 2.5f);
      const Eigen::Vector2f c = detail::uniform2(rng, -kHalfX + radius + 0.8f, kHalfX - radius - 0.8f,
                                                 -kHalfY + radius + 0.8f, kHalfY - radius - 0.8f);
      if (!layout.free_disc(c, radius + kPersonR + 0.2f)) continue;
      layout.occupy_disc(c, radius + kPersonR + 0.2f);
      const float speed = rng.uniform_int(0, 1) ? 1.2f : -1.2f;
      walkers.push_back(Walker{Trajectory::circle({c.x(), c.y(), 0.0f}, radius, speed, rng.uniform(0.0f, 2.0f * detail::kPi))});
      continue;
    }
    Eigen::Vector2f a, b;
    if (rng.uniform_int(0, 1)) {  // along x
      const float len = rng.uniform(8.0f, 14.0f);
      const float x0 = rng.uniform(-kHalfX + 0.8f, kHalfX - 0.8f - len);
      const float y = rng.uniform(-kHalfY + 0.8f, kHalfY - 0.8f);
      a = {x0, y};
      b = {x0 + len, y};
    } else {  // along y
      const float len = rng.uniform(6.0f, 9.5f);
      const float y0 = rng.uniform(-kHalfY + 0.8f, kHalfY - 0.8f - len);
      const float x = rng.uniform(-kHalfX + 0.8f, kHalfX - 0.8f);
      a = {x, y0};
      b = {x, y0 + len};
    }
    if (!layout.free_corridor(a, b, kPersonR + 0.2f)) continue;
    layout.occupy_corridor(a, b, kPersonR + 0.2f);
    const float length = (b - a).norm();
    walkers.push_back(Walker{Trajectory::back_and_forth({a.x(), a.y(), 0.0f}, {b.x(), b.y(), 0.0f}, 1.2f,
                                                        rng.uniform(0.0f, 2.0f * length))});
  }
  detail::require_count(static_cast<int>(walkers.size()), n_people, "person");

  Scene scene;
  scene.set_material_seed(seed);
  detail::SplitMix64 looks = detail::material_rng(seed);
  scene.add_structure(ShapeSet().add(Plane::infinite({0, 0, 1}, {0, 0, 0}), Material::floor), SurfaceClass::ground);
  scene.add_structure(ShapeSet().add(Plane::infinite({0, 0, 1}, {0, 0, kHeight}), Material::ceiling_tile),
                      SurfaceClass::ceiling);
  scene.add_structure(ShapeSet()
                          .add(Plane::infinite({1, 0, 0}, {-kHalfX, 0, 0}), Material::painted_wall)
                          .add(Plane::infinite({1, 0, 0}, {kHalfX, 0, 0}), Material::painted_wall)
                          .add(Plane::infinite({0, 1, 0}, {0, -kHalfY, 0}), Material::painted_wall)
                          .add(Plane::infinite({0, 1, 0}, {0, kHalfY, 0}), Material::painted_wall),
                      SurfaceClass::wall);

  // Pillars.
  const int n_pillars = rng.uniform_int(2, 4);
  int placed = 0;
  for (int attempt = 0; placed < n_pillars && attempt < 10000; ++attempt) {
    const float r = rng.uniform(0.25f, 0.4f);
    const Eigen::Vector2f c = detail::uniform2(rng, -kHalfX + 1.5f, kHalfX - 1.5f, -kHalfY + 1.5f, kHalfY - 1.5f);
    if (!layout.free_disc(c, r, 0.6f)) continue;
    layout.occupy_disc(c, r);
    scene.add_object("pillar", ShapeSet().add(Cylinder{c.x(), c.y(), r, 0.0f, kHeight}, Material::painted_wall));
    ++placed;
  }
  detail::require_count(placed, n_pillars, "pillar");

  // A footprint against one of the four walls: `along` wide (along the
  // wall), `depth` deep, `gap` from it; its centre drawn along the wall.
  struct Footprint {
    Eigen::Vector2f centre, half;  // [m]
  };
  const auto against_wall = [&rng](float along, float depth, float gap) {
    const int wall = rng.uniform_int(0, 3);
    Footprint f;
    if (wall < 2) {  // y walls
      const float sy = wall == 0 ? -1.0f : 1.0f;
      f.centre = {rng.uniform(-kHalfX + along, kHalfX - along), sy * (kHalfY - 0.5f * depth - gap)};
      f.half = {0.5f * along, 0.5f * depth};
    } else {  // x walls
      const float sx = wall == 2 ? -1.0f : 1.0f;
      f.centre = {sx * (kHalfX - 0.5f * depth - gap), rng.uniform(-kHalfY + along, kHalfY - along)};
      f.half = {0.5f * depth, 0.5f * along};
    }
    return f;
  };

  // Desks: grid-aligned (yaw 0 or 90 degrees), top 0.72-0.75 m, two side
  // panels; the first 2-3 pushed against a wall (a long side 2-5 cm from it).
  const int n_desks = rng.uniform_int(6, 10);
  const int n_wall_desks = rng.uniform_int(2, 3);
  placed = 0;
  for (int attempt = 0; placed < n_desks && attempt < 20000; ++attempt) {
    const float l = rng.uniform(1.4f, 1.8f);
    const float w = rng.uniform(0.7f, 0.9f);
    float yaw = 0.0f;
    Eigen::Vector2f c;
    if (placed < n_wall_desks) {
      const float gap = rng.uniform(0.02f, 0.05f);
      const Footprint f = against_wall(l, w, gap);
      c = f.centre;
      yaw = f.half.x() > f.half.y() ? 0.0f : 0.5f * detail::kPi;  // the long side along the wall
    } else {
      yaw = rng.uniform_int(0, 1) ? 0.5f * detail::kPi : 0.0f;
      const float half_diagonal = 0.5f * std::hypot(l, w);
      c = detail::uniform2(rng, -kHalfX + half_diagonal + 0.3f, kHalfX - half_diagonal - 0.3f,
                           -kHalfY + half_diagonal + 0.3f, kHalfY - half_diagonal - 0.3f);
    }
    const float r = 0.5f * std::hypot(l, w);
    if (!layout.free_disc(c, r, placed < n_wall_desks ? 0.3f : 0.4f)) continue;
    layout.occupy_disc(c, r);
    const Eigen::Vector3f base(c.x(), c.y(), 0.0f);
    ShapeSet desk;
    desk.add(Box::rotated(detail::place(base, yaw, 0, 0, 0.735f), {0.5f * l, 0.5f * w, 0.015f}, yaw), Material::wood);
    const Material panels = looks.below(2) == 0 ? Material::wood : Material::metal;
    for (float side : {-1.0f, 1.0f})
      desk.add(Box::rotated(detail::place(base, yaw, side * (0.5f * l - 0.03f), 0, 0.36f), {0.015f, 0.5f * w - 0.02f, 0.36f},
                            yaw),
               panels);
    scene.add_object("desk", desk);
    ++placed;
  }
  detail::require_count(placed, n_desks, "desk");

  // Upright boxes against a wall: `draw()` gives a candidate's size and gap,
  // `material()` is drawn once it is placed.
  struct WallBox {
    float width, depth, height, gap;  // [m] width along the wall, gap from it
  };
  const auto place_wall_boxes = [&](const char* name, int count, auto&& draw, auto&& material) {
    int done = 0;
    for (int attempt = 0; done < count && attempt < 20000; ++attempt) {
      const WallBox b = draw();
      const Footprint f = against_wall(b.width, b.depth, b.gap);
      const float r = f.half.norm();
      if (!layout.free_disc(f.centre, r, 0.3f)) continue;
      layout.occupy_disc(f.centre, r);
      scene.add_object(name, ShapeSet().add(Box::aligned({f.centre.x() - f.half.x(), f.centre.y() - f.half.y(), 0.0f},
                                                         {f.centre.x() + f.half.x(), f.centre.y() + f.half.y(), b.height}),
                                            material()));
      ++done;
    }
    detail::require_count(done, count, name);
  };
  // Cabinets, 2 cm from a wall, 1.0-2.0 m tall.
  place_wall_boxes(
      "cabinet", rng.uniform_int(3, 5),
      [&] { return WallBox{rng.uniform(0.8f, 1.2f), rng.uniform(0.45f, 0.6f), rng.uniform(1.0f, 2.0f), 0.02f}; },
      [&] { return looks.below(2) == 0 ? Material::wood : Material::metal; });
  // Bookshelves, 2-5 cm from a wall: tall, shallow boxes.
  place_wall_boxes(
      "bookshelf", rng.uniform_int(2, 4),
      [&] {
        return WallBox{rng.uniform(0.8f, 1.6f), rng.uniform(0.3f, 0.4f), rng.uniform(1.6f, 2.0f), rng.uniform(0.02f, 0.05f)};
      },
      [] { return Material::wood; });

  for (Walker& w : walkers)
    scene.add_moving_object("person", detail::person_shapes(Eigen::Vector3f::Zero(), 1.7f, kPersonR), std::move(w.trajectory));
  return scene;
}

}  // namespace streamclust::sim
