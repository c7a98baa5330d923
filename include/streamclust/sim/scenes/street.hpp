// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The ready-made street (`street_scene`).

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

/// A street along the x axis (see the file comment for the cross-section).
/// Structure: road plane, two sidewalk slabs (x in [-150, 150]) and
/// building blocks on both sides (6-20 m tall, occasional 2-5 m alleys).
/// Objects in this order: parked cars ("parked_car", two unbroken rows at
/// |y| = 5.5 for |x| <= 60, 0.6-1.5 m between consecutive bodies), lamp
/// poles ("pole", every 10-20 m in a gap between two parked cars, on the
/// sidewalk by the kerb, 0.9-1.0 m from the nearest car body), street trees
/// ("tree", every 10-20 m at |y| = 10.8), 4-6 moving cars ("car", 10 m/s on
/// a loop y = +2 going +x and y = -2 going -x with U-turns at |x| = 100), 2
/// cyclists ("cyclist", 5 m/s, loop at y = +-3.8 with U-turns at |x| =
/// 120), 4-6 pedestrians ("pedestrian", 1.1-1.5 m/s back and forth on the
/// sidewalks, each on its own line). Objects on loops interpenetrate only
/// during the U-turns, >= 100 m from the origin; no moving object comes
/// within 0.3 m of a parked car or a pole.
inline Scene street_scene(std::uint64_t seed) {
  detail::SplitMix64 rng = detail::make_rng(seed, 0x57EE7);
  constexpr float kRoad = 7.0f;
  constexpr float kFacade = 12.0f;
  constexpr float kCurb = 0.15f;
  constexpr float kLength = 150.0f;

  Scene scene;
  scene.set_material_seed(seed);
  detail::SplitMix64 looks = detail::material_rng(seed);
  constexpr Material kFacades[] = {Material::concrete, Material::brick, Material::painted_wall, Material::glass};
  scene.add_structure(ShapeSet().add(Plane::infinite({0, 0, 1}, {0, 0, 0}), Material::asphalt), SurfaceClass::ground);  // road
  for (float side : {-1.0f, 1.0f}) {
    const float y0 = side * kRoad;
    const float y1 = side * kFacade;
    // Sidewalk: its top and its kerb face are ground.
    scene.add_structure(
        ShapeSet().add(Box::aligned({-kLength, std::min(y0, y1), -0.05f}, {kLength, std::max(y0, y1), kCurb}),
                       Material::concrete),
        SurfaceClass::ground);
    // Buildings.
    float x = -kLength;
    while (x < kLength) {
      const float width = rng.uniform(8.0f, 25.0f);
      const float setback = rng.uniform_int(0, 2) == 0 ? rng.uniform(0.0f, 1.0f) : 0.0f;
      const float height = rng.uniform(6.0f, 20.0f);
      const float x1 = std::min(x + width, kLength);
      const float ya = side * (kFacade + setback);
      const float yb = side * (kFacade + setback + 10.0f);
      const Material facade = kFacades[looks.below(4)];
      scene.add_structure(
          ShapeSet().add(Box::aligned({x, std::min(ya, yb), 0.0f}, {x1, std::max(ya, yb), height}), facade),
          SurfaceClass::wall);
      x = x1 + (rng.uniform_int(0, 3) == 0 ? rng.uniform(2.0f, 5.0f) : 0.0f);
    }
  }

  // Parked cars: two unbroken rows, 0.6-1.5 m between consecutive bodies.
  // Every 10-20 m a lamp pole stands in a gap, on the sidewalk by the kerb,
  // `kPoleClearance` from the nearest car body (its corner across the gap)
  // or a little more where the kerb keeps it back: the poles are added after
  // the cars (object ids: cars first).
  constexpr float kParkedY = 5.5f;
  constexpr float kPoleClearance = 0.9f;  // [m] pole surface to the nearest car body
  struct PoleSpot {
    float x, y;  // [m] axis
    float side;
  };
  std::vector<PoleSpot> pole_spots;
  for (float side : {-1.0f, 1.0f}) {
    float x = -60.0f + rng.uniform(0.0f, 2.0f);
    float next_pole = -60.0f + rng.uniform(0.0f, 10.0f);
    while (true) {
      const float l = rng.uniform(4.2f, 4.8f);
      if (x + l > 60.0f) break;
      const Eigen::Vector3f base(x + 0.5f * l, side * kParkedY, 0.0f);
      const float yaw = side > 0 ? 0.0f : detail::kPi;
      const float w = rng.uniform(1.75f, 1.9f);
      const float h = rng.uniform(1.4f, 1.6f);
      scene.add_object("parked_car", detail::car_shapes(base, yaw, l, w, h));
      const float gap = rng.uniform(0.6f, 1.5f);
      const float pole_x = x + l + 0.5f * gap;
      if (pole_x >= next_pole && pole_x + 0.5f * gap + 4.8f <= 60.0f) {
        // The nearest car body is a corner 0.5 gap away along x; the next
        // car's width is not drawn yet, so both are taken at the widest car
        // (1.9 m) and the pole at its thickest (r 0.12 m).
        const float r_max = 0.12f;
        const float reach = kPoleClearance + r_max;
        const float beside = std::sqrt(reach * reach - 0.25f * gap * gap);
        const float y = std::max(kParkedY + 0.95f + beside, kRoad + r_max + 0.03f);
        pole_spots.push_back(PoleSpot{pole_x, side * y, side});
        next_pole = pole_x + rng.uniform(10.0f, 20.0f);
      }
      x += l + gap;
    }
  }

  // Lamp poles: a thin cylinder and an arm reaching over the parked cars.
  for (const PoleSpot& spot : pole_spots) {
    const float r = rng.uniform(0.08f, 0.12f);
    const float h = rng.uniform(6.0f, 8.0f);
    const float x = spot.x;
    const float y = spot.y;
    const float side = spot.side;
    ShapeSet pole;
    pole.add(Cylinder{x, y, r, 0.0f, h}, Material::metal);
    pole.add(Box::aligned({x - 0.06f, std::min(y, y - side * 1.4f), h - 0.12f}, {x + 0.06f, std::max(y, y - side * 1.4f), h}),
             Material::metal);
    pole.add(Box::aligned({x - 0.25f, side * 5.9f - 0.15f, h - 0.25f}, {x + 0.25f, side * 5.9f + 0.15f, h - 0.1f}),
             Material::glass);
    scene.add_object("pole", pole);
  }

  // Street trees.
  for (float side : {-1.0f, 1.0f}) {
    for (float x = -60.0f + rng.uniform(0.0f, 10.0f); x < 60.0f; x += rng.uniform(10.0f, 20.0f)) {
      const float y = side * 10.8f;
      const float h = rng.uniform(3.5f, 4.5f);
      const float rh = rng.uniform(0.8f, 1.1f);
      const float rv = rng.uniform(1.0f, 1.5f);
      ShapeSet tree;
      tree.add(Cylinder{x, y, rng.uniform(0.12f, 0.25f), 0.0f, h}, Material::bark);
      tree.add(Ellipsoid{{x, y, h}, {rh, rh, rv}}, Material::foliage);
      scene.add_object("tree", tree);
    }
  }

  // Moving cars on the lane loop, evenly spaced with jitter.
  {
    const float loop_x = 100.0f;
    const float loop_len = 2.0f * (2.0f * loop_x) + 2.0f * 4.0f;
    const int n = rng.uniform_int(4, 6);
    const float base_phase = rng.uniform(0.0f, loop_len);
    for (int i = 0; i < n; ++i) {
      const float phase = base_phase + loop_len * (static_cast<float>(i) + rng.uniform(-0.2f, 0.2f)) / static_cast<float>(n);
      Trajectory lane = Trajectory::loop({{-loop_x, 2.0f, 0.0f}, {loop_x, 2.0f, 0.0f}, {loop_x, -2.0f, 0.0f}, {-loop_x, -2.0f, 0.0f}},
                                         10.0f, phase);
      const float l = rng.uniform(4.2f, 4.8f);
      const float w = rng.uniform(1.75f, 1.9f);
      const float h = rng.uniform(1.4f, 1.6f);
      scene.add_moving_object("car", detail::car_shapes(Eigen::Vector3f::Zero(), 0.0f, l, w, h), std::move(lane));
    }
  }

  // Cyclists: rider capsule above a thin bike box.
  {
    const float loop_x = 120.0f;
    const float loop_len = 2.0f * (2.0f * loop_x) + 2.0f * 7.6f;
    const float phase0 = rng.uniform(0.0f, loop_len);
    for (int i = 0; i < 2; ++i) {
      ShapeSet bike;
      bike.add(Box::aligned({-0.85f, -0.08f, 0.0f}, {0.85f, 0.08f, 1.0f}), Material::metal);
      bike.add(Capsule{0.0f, 0.0f, 0.22f, 1.05f, 1.55f}, Material::fabric);
      scene.add_moving_object(
          "cyclist", bike,
          Trajectory::loop({{-loop_x, 3.8f, 0.0f}, {loop_x, 3.8f, 0.0f}, {loop_x, -3.8f, 0.0f}, {-loop_x, -3.8f, 0.0f}}, 5.0f,
                           phase0 + 0.5f * loop_len * static_cast<float>(i) + rng.uniform(-20.0f, 20.0f)));
    }
  }

  // Pedestrians: each on its own line along a sidewalk.
  {
    const float lines[3] = {8.2f, 8.9f, 9.6f};
    const int n = rng.uniform_int(4, 6);
    for (int i = 0; i < n; ++i) {
      const float side = i % 2 == 0 ? 1.0f : -1.0f;
      const float y = side * lines[i / 2];
      const float len = rng.uniform(10.0f, 30.0f);
      const float x0 = rng.uniform(-40.0f, 40.0f - len);
      const float height = rng.uniform(1.6f, 1.85f);
      const float speed = rng.uniform(1.1f, 1.5f);
      const float phase = rng.uniform(0.0f, 2.0f * len);
      scene.add_moving_object("pedestrian", detail::person_shapes(Eigen::Vector3f::Zero(), height, 0.3f),
                              Trajectory::back_and_forth({x0, y, kCurb}, {x0 + len, y, kCurb}, speed, phase));
    }
  }
  return scene;
}

}  // namespace streamclust::sim
