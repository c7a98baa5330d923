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
#include <limits>
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
/// sidewalks, each on its own line), and one car ("car") pulling out of a
/// free parking space in the y < 0 row 18-33 m ahead: standing until the
/// way is clear (from 1 s on, in steps of 0.1 s), then swinging out into
/// the y = -2 lane over 9 m, at 2.5 m/s^2 up to 10 m/s, and on along it to
/// x = -140 where it stops.
/// Objects on loops interpenetrate only during the U-turns, >= 100 m from
/// the origin; short of them, the departing car keeps 1 m from every other
/// car and cyclist; no moving object comes within 0.3 m of a parked car or
/// a pole.
/// The parking space and the departing car draw from a random stream of
/// their own, so every other object is where it is without them.
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

  // The free parking space in the y < 0 row: no parked car within 7 m
  // ahead of a nominal spot (toward -x, where the departing car swings
  // out) nor 0.6 m behind it; the departing car stands 0.6-1.5 m ahead of
  // the first parked car behind the space.
  detail::SplitMix64 departure_rng = detail::make_rng(seed, 0xDE9A27);
  const float nominal_x = departure_rng.uniform(19.0f, 26.0f);  // [m]
  const float departing_l = departure_rng.uniform(4.2f, 4.8f);
  const float departing_w = departure_rng.uniform(1.75f, 1.9f);
  const float departing_h = departure_rng.uniform(1.4f, 1.6f);
  const float departing_gap = departure_rng.uniform(0.6f, 1.5f);
  const float space_lo = nominal_x - 0.5f * departing_l - 7.0f;
  const float space_hi = nominal_x + 0.5f * departing_l + 0.6f;
  const auto in_space = [&](float side, float lo, float hi) { return side < 0.0f && hi > space_lo && lo < space_hi; };
  float behind_space = std::numeric_limits<float>::infinity();  // [m] x of the first parked car's body behind it

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
    bool by_space;  // a car beside it may be missing for the free parking space
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
      if (!in_space(side, x, x + l)) {
        scene.add_object("parked_car", detail::car_shapes(base, yaw, l, w, h));
        if (side < 0.0f && x >= space_hi) behind_space = std::min(behind_space, x);
      }
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
        const bool by_space = in_space(side, x, x + l) || in_space(side, x + l + gap, x + l + gap + 4.8f);
        pole_spots.push_back(PoleSpot{pole_x, side * y, side, by_space});
        next_pole = pole_x + rng.uniform(10.0f, 20.0f);
      }
      x += l + gap;
    }
  }

  // Lamp poles: a thin cylinder and an arm reaching over the parked cars;
  // none by the free parking space.
  for (const PoleSpot& spot : pole_spots) {
    const float r = rng.uniform(0.08f, 0.12f);
    const float h = rng.uniform(6.0f, 8.0f);
    if (spot.by_space) continue;
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

  // Footprints of the cars and cyclists on the road, for the departing
  // car's clear way: half extents along x and y (heading ignored) [m].
  struct RoadUser {
    int instance;
    Eigen::Vector2f half;
  };
  std::vector<RoadUser> road_users;

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
      const int car = scene.add_moving_object("car", detail::car_shapes(Eigen::Vector3f::Zero(), 0.0f, l, w, h), std::move(lane));
      road_users.push_back(RoadUser{car, Eigen::Vector2f(0.5f * l, 0.5f * w)});
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
      const int cyclist = scene.add_moving_object(
          "cyclist", bike,
          Trajectory::loop({{-loop_x, 3.8f, 0.0f}, {loop_x, 3.8f, 0.0f}, {loop_x, -3.8f, 0.0f}, {-loop_x, -3.8f, 0.0f}}, 5.0f,
                           phase0 + 0.5f * loop_len * static_cast<float>(i) + rng.uniform(-20.0f, 20.0f)));
      road_users.push_back(RoadUser{cyclist, Eigen::Vector2f(0.85f, 0.22f)});
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

  // The departing car: out of its space along a half cosine from the
  // parked row to the lane over 9 m (at most 31 degrees off the kerb; its
  // corners stay >= 1 m from the car parked ahead and inside the kerb),
  // then along the lane. It sets off at the first start time whose whole
  // way keeps 1 m from every road user's footprint (headings ignored)
  // until |x| = 95, short of the U-turns.
  {
    const float c = std::min(behind_space, 60.0f) - departing_gap - 0.5f * departing_l;
    constexpr float kSwing = 9.0f;  // [m] along x from the parked row to the lane
    constexpr int kSteps = 18;
    std::vector<Eigen::Vector3f> way;
    for (int k = 0; k <= kSteps; ++k) {
      const float u = static_cast<float>(k) / kSteps;
      const float y = -kParkedY + (kParkedY - 2.0f) * 0.5f * (1.0f - std::cos(detail::kPi * u));
      way.emplace_back(c - kSwing * u, y, 0.0f);
    }
    way.emplace_back(-140.0f, -2.0f, 0.0f);
    constexpr float kTopSpeed = 10.0f;     // [m/s]
    constexpr float kAcceleration = 2.5f;  // [m/s^2]
    const Eigen::Vector2f half(0.5f * departing_l, 0.5f * departing_w);
    const auto clear_from = [&](double start) {
      const Trajectory trial = Trajectory::depart(way, start, kTopSpeed, kAcceleration);
      for (double t = start;; t += 0.05) {
        const Eigen::Vector2f p = trial.position(t).head<2>();
        if (p.x() < -95.0f) return true;  // the loops' U-turns lie beyond |x| = 100
        for (const RoadUser& user : road_users) {
          const Eigen::Vector2f gap =
              ((scene.position(user.instance, t).head<2>() - p).cwiseAbs() - half - user.half).cwiseMax(0.0f);
          if (gap.norm() < 1.0f) return false;
        }
      }
    };
    double start = 1.0;
    while (start < 60.0 && !clear_from(start)) start += 0.1;
    scene.add_moving_object("car", detail::car_shapes(Eigen::Vector3f::Zero(), 0.0f, departing_l, departing_w, departing_h),
                            Trajectory::depart(std::move(way), start, kTopSpeed, kAcceleration));
  }
  return scene;
}

}  // namespace streamclust::sim
