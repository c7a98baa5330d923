// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Ready-made scenes for the scan simulator, each placed deterministically
/// from a seed (the same seed gives the same scene on every platform):
///
/// - `office_scene`: a 20 x 12 x 3 m room (x in [-10, 10], y in [-6, 6],
///   z in [0, 3]) with 6-10 desks, 3-5 cabinets against the walls, 2-4
///   pillars and 2-3 people walking at 1.2 m/s.
/// - `forest_scene`: a gently sloped ground (slope <= 3 % each way, z = 0 at
///   the origin), 30-60 trees (trunk radius 0.1-0.4 m, height 6-12 m, with
///   an ellipsoid crown starting >= 3 m above ground) in [-30, 30]^2, 10-20
///   bushes, 2-4 walking pedestrians and 2 parked vehicles.
/// - `street_scene`: a street along x: road (z = 0, |y| < 7), raised
///   sidewalks (7 <= |y| <= 12, 0.15 m), building facades from |y| = 12 with
///   alleys between buildings, parked cars (|y| = 5.5), moving cars on two
///   lanes (y = +-2, 10 m/s), cyclists (y = +-3.8, 5 m/s), pedestrians on the
///   sidewalks, lamp poles and street trees.
/// - `hills_scene`: rolling terrain over [-60, 60]^2 (z = 0 at the origin,
///   slopes below 15 deg) with a ramp, a raised strip with two 0.15 m kerbs
///   and a single step; trees, parked cars, boxes, poles, standing and
///   walking people on the terrain; no walls.
///
/// Ground, floor, walls, ceiling, road, sidewalks, terrain and facades are
/// structure (instance 0) with their surface class (ground: floor, road,
/// sidewalks with their kerbs, terrain; wall: walls, building blocks;
/// ceiling); every other object has its own id > 0, the class `object` and
/// a label (`Scene::objects()`). The sensor is expected to start near
/// (0, 0, z) with 0.3 <= z <= 2 (above the ground): in every scene nothing
/// ever enters the vertical column of radius 1 m around the z axis below
/// 2.5 m above the ground.

#include <streamclust/sim/scene.hpp>
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
#include <string_view>
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
/// (footprint center), facing `yaw`: lower body, cabin and four wheels.
inline ShapeSet car_shapes(const Eigen::Vector3f& base, float yaw, float l, float w, float h) {
  ShapeSet s;
  const float body_low = 0.3f;
  const float body_high = 0.55f * h + 0.1f;
  s.add(Box::rotated(place(base, yaw, 0.0f, 0.0f, 0.5f * (body_low + body_high)),
                     Eigen::Vector3f(0.5f * l, 0.5f * w, 0.5f * (body_high - body_low)), yaw));
  const float cabin_l = 0.55f * l;
  s.add(Box::rotated(place(base, yaw, -0.05f * l, 0.0f, 0.5f * (body_high + h)),
                     Eigen::Vector3f(0.5f * cabin_l, 0.45f * w, 0.5f * (h - body_high)), yaw));
  for (float fx : {-0.32f, 0.32f})
    for (float fy : {-1.0f, 1.0f}) {
      s.add(Box::rotated(place(base, yaw, fx * l, fy * (0.5f * w - 0.12f), 0.32f), Eigen::Vector3f(0.32f, 0.11f, 0.32f),
                         yaw));
    }
  return s;
}

/// A standing person (capsule, feet at `base`).
inline ShapeSet person_shapes(const Eigen::Vector3f& base, float height = 1.7f, float radius = 0.3f) {
  return ShapeSet().add(Capsule::standing(base.x(), base.y(), base.z(), height, radius));
}

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

/// An office room of 20 x 12 x 3 m (x in [-10, 10], y in [-6, 6], z in
/// [0, 3]); floor, ceiling and walls are structure (instance 0). Objects,
/// ids in this order: 2-4 pillars ("pillar", floor to ceiling cylinders, r
/// 0.25-0.4 m), 6-10 desks ("desk": top at 0.75 m plus two side panels),
/// 3-5 cabinets ("cabinet", against a wall, 1.0-2.0 m tall), 2-3 people
/// ("person", capsules 1.7 m x 0.3 m at 1.2 m/s, back and forth along a
/// straight path or, for a third person, around a circle). Walking paths
/// never cross furniture.
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
  scene.add_structure(ShapeSet().add(Plane::infinite({0, 0, 1}, {0, 0, 0})), SurfaceClass::ground);
  scene.add_structure(ShapeSet().add(Plane::infinite({0, 0, 1}, {0, 0, kHeight})), SurfaceClass::ceiling);
  scene.add_structure(ShapeSet()
                          .add(Plane::infinite({1, 0, 0}, {-kHalfX, 0, 0}))
                          .add(Plane::infinite({1, 0, 0}, {kHalfX, 0, 0}))
                          .add(Plane::infinite({0, 1, 0}, {0, -kHalfY, 0}))
                          .add(Plane::infinite({0, 1, 0}, {0, kHalfY, 0})),
                      SurfaceClass::wall);

  // Pillars.
  const int n_pillars = rng.uniform_int(2, 4);
  int placed = 0;
  for (int attempt = 0; placed < n_pillars && attempt < 10000; ++attempt) {
    const float r = rng.uniform(0.25f, 0.4f);
    const Eigen::Vector2f c = detail::uniform2(rng, -kHalfX + 1.5f, kHalfX - 1.5f, -kHalfY + 1.5f, kHalfY - 1.5f);
    if (!layout.free_disc(c, r, 0.6f)) continue;
    layout.occupy_disc(c, r);
    scene.add_object("pillar", ShapeSet().add(Cylinder{c.x(), c.y(), r, 0.0f, kHeight}));
    ++placed;
  }
  detail::require_count(placed, n_pillars, "pillar");

  // Desks: grid-aligned (yaw 0 or 90 degrees), top 0.72-0.75 m, two side panels.
  const int n_desks = rng.uniform_int(6, 10);
  placed = 0;
  for (int attempt = 0; placed < n_desks && attempt < 20000; ++attempt) {
    const float l = rng.uniform(1.4f, 1.8f);
    const float w = rng.uniform(0.7f, 0.9f);
    const float yaw = rng.uniform_int(0, 1) ? 0.5f * detail::kPi : 0.0f;
    const float r = 0.5f * std::hypot(l, w);
    const Eigen::Vector2f c =
        detail::uniform2(rng, -kHalfX + r + 0.3f, kHalfX - r - 0.3f, -kHalfY + r + 0.3f, kHalfY - r - 0.3f);
    if (!layout.free_disc(c, r, 0.4f)) continue;
    layout.occupy_disc(c, r);
    const Eigen::Vector3f base(c.x(), c.y(), 0.0f);
    ShapeSet desk;
    desk.add(Box::rotated(detail::place(base, yaw, 0, 0, 0.735f), {0.5f * l, 0.5f * w, 0.015f}, yaw));
    for (float side : {-1.0f, 1.0f})
      desk.add(Box::rotated(detail::place(base, yaw, side * (0.5f * l - 0.03f), 0, 0.36f), {0.015f, 0.5f * w - 0.02f, 0.36f},
                            yaw));
    scene.add_object("desk", desk);
    ++placed;
  }
  detail::require_count(placed, n_desks, "desk");

  // Cabinets against a wall.
  const int n_cabinets = rng.uniform_int(3, 5);
  placed = 0;
  for (int attempt = 0; placed < n_cabinets && attempt < 20000; ++attempt) {
    const float width = rng.uniform(0.8f, 1.2f);
    const float depth = rng.uniform(0.45f, 0.6f);
    const float height = rng.uniform(1.0f, 2.0f);
    const int wall = rng.uniform_int(0, 3);
    Eigen::Vector2f c, half;
    if (wall < 2) {  // y walls
      const float sy = wall == 0 ? -1.0f : 1.0f;
      c = {rng.uniform(-kHalfX + width, kHalfX - width), sy * (kHalfY - 0.5f * depth - 0.02f)};
      half = {0.5f * width, 0.5f * depth};
    } else {  // x walls
      const float sx = wall == 2 ? -1.0f : 1.0f;
      c = {sx * (kHalfX - 0.5f * depth - 0.02f), rng.uniform(-kHalfY + width, kHalfY - width)};
      half = {0.5f * depth, 0.5f * width};
    }
    const float r = half.norm();
    if (!layout.free_disc(c, r, 0.3f)) continue;
    layout.occupy_disc(c, r);
    scene.add_object("cabinet", ShapeSet().add(Box::aligned({c.x() - half.x(), c.y() - half.y(), 0.0f},
                                                            {c.x() + half.x(), c.y() + half.y(), height})));
    ++placed;
  }
  detail::require_count(placed, n_cabinets, "cabinet");

  for (Walker& w : walkers)
    scene.add_moving_object("person", detail::person_shapes(Eigen::Vector3f::Zero(), 1.7f, kPersonR), std::move(w.trajectory));
  return scene;
}

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
  scene.add_structure(ShapeSet().add(Plane::infinite({-sx, -sy, 1.0f}, {0, 0, 0})), SurfaceClass::ground);

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
    tree.add(Cylinder{c.x(), c.y(), r, z0 - 0.1f, z0 + height});
    tree.add(Ellipsoid{{c.x(), c.y(), z0 + height - 0.5f * crown_v}, {crown_h, crown_h, crown_v}});
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
    bush.add(Ellipsoid{{p0.x(), p0.y(), ground(p0.x(), p0.y()) + 0.6f * rv}, {rh, 0.8f * rh, rv}});
    if (twin) {
      const Eigen::Vector2f p1 = c + offset;
      bush.add(Ellipsoid{{p1.x(), p1.y(), ground(p1.x(), p1.y()) + 0.5f * rv}, {0.8f * rh, rh, 0.8f * rv}});
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

/// A street along the x axis (see the file comment for the cross-section).
/// Structure: road plane, two sidewalk slabs (x in [-150, 150]) and
/// building blocks on both sides (6-20 m tall, occasional 2-5 m alleys).
/// Objects in this order: parked cars ("parked_car", |x| <= 60), lamp poles
/// ("pole", every 18-28 m at |y| = 7.4), street trees ("tree", every 10-20
/// m at |y| = 10.8), 4-6 moving cars ("car", 10 m/s on a loop y = +2 going
/// +x and y = -2 going -x with U-turns at |x| = 100), 2 cyclists
/// ("cyclist", 5 m/s, loop at y = +-3.8 with U-turns at |x| = 120), 4-6
/// pedestrians ("pedestrian", 1.1-1.5 m/s back and forth on the sidewalks,
/// each on its own line). Objects on loops interpenetrate only during the
/// U-turns, >= 100 m from the origin.
inline Scene street_scene(std::uint64_t seed) {
  detail::SplitMix64 rng = detail::make_rng(seed, 0x57EE7);
  constexpr float kRoad = 7.0f;
  constexpr float kFacade = 12.0f;
  constexpr float kCurb = 0.15f;
  constexpr float kLength = 150.0f;

  Scene scene;
  scene.add_structure(ShapeSet().add(Plane::infinite({0, 0, 1}, {0, 0, 0})), SurfaceClass::ground);  // road
  for (float side : {-1.0f, 1.0f}) {
    const float y0 = side * kRoad;
    const float y1 = side * kFacade;
    // Sidewalk: its top and its kerb face are ground.
    scene.add_structure(
        ShapeSet().add(Box::aligned({-kLength, std::min(y0, y1), -0.05f}, {kLength, std::max(y0, y1), kCurb})),
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
      scene.add_structure(ShapeSet().add(Box::aligned({x, std::min(ya, yb), 0.0f}, {x1, std::max(ya, yb), height})),
                          SurfaceClass::wall);
      x = x1 + (rng.uniform_int(0, 3) == 0 ? rng.uniform(2.0f, 5.0f) : 0.0f);
    }
  }

  // Parked cars.
  for (float side : {-1.0f, 1.0f}) {
    float x = -60.0f + rng.uniform(0.0f, 5.0f);
    while (true) {
      const float l = rng.uniform(4.2f, 4.8f);
      if (x + l > 60.0f) break;
      if (rng.uniform_int(0, 9) < 7) {
        const Eigen::Vector3f base(x + 0.5f * l, side * 5.5f, 0.0f);
        const float yaw = side > 0 ? 0.0f : detail::kPi;
        const float w = rng.uniform(1.75f, 1.9f);
        const float h = rng.uniform(1.4f, 1.6f);
        scene.add_object("parked_car", detail::car_shapes(base, yaw, l, w, h));
      }
      x += l + rng.uniform(1.0f, 6.0f);
    }
  }

  // Lamp poles: a thin cylinder and an arm reaching over the road.
  for (float side : {-1.0f, 1.0f}) {
    for (float x = -60.0f + rng.uniform(0.0f, 10.0f); x < 60.0f; x += rng.uniform(18.0f, 28.0f)) {
      const float r = rng.uniform(0.08f, 0.12f);
      const float h = rng.uniform(6.0f, 8.0f);
      const float y = side * 7.4f;
      ShapeSet pole;
      pole.add(Cylinder{x, y, r, 0.0f, h});
      pole.add(Box::aligned({x - 0.06f, std::min(y, y - side * 1.4f), h - 0.12f}, {x + 0.06f, std::max(y, y - side * 1.4f), h}));
      pole.add(Box::aligned({x - 0.25f, side * 5.9f - 0.15f, h - 0.25f}, {x + 0.25f, side * 5.9f + 0.15f, h - 0.1f}));
      scene.add_object("pole", pole);
    }
  }

  // Street trees.
  for (float side : {-1.0f, 1.0f}) {
    for (float x = -60.0f + rng.uniform(0.0f, 10.0f); x < 60.0f; x += rng.uniform(10.0f, 20.0f)) {
      const float y = side * 10.8f;
      const float h = rng.uniform(3.5f, 4.5f);
      const float rh = rng.uniform(0.8f, 1.1f);
      const float rv = rng.uniform(1.0f, 1.5f);
      ShapeSet tree;
      tree.add(Cylinder{x, y, rng.uniform(0.12f, 0.25f), 0.0f, h});
      tree.add(Ellipsoid{{x, y, h}, {rh, rh, rv}});
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
      bike.add(Box::aligned({-0.85f, -0.08f, 0.0f}, {0.85f, 0.08f, 1.0f}));
      bike.add(Capsule{0.0f, 0.0f, 0.22f, 1.05f, 1.55f});
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
  scene.add_terrain(terrain);

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
    tree.add(Cylinder{c.x(), c.y(), r, z0, z0 + height});
    tree.add(Ellipsoid{{c.x(), c.y(), z0 + height - 0.5f * crown_v}, {crown_h, crown_h, crown_v}});
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
    scene.add_object("box", ShapeSet().add(Box::rotated({c.x(), c.y(), z0 + 0.5f * sz}, {0.5f * sx, 0.5f * sy, 0.5f * sz}, yaw)));
  }
  const int n_poles = rng.uniform_int(4, 8);
  for (int i = 0; i < n_poles; ++i) {
    const float r = rng.uniform(0.05f, 0.12f);
    const float height = rng.uniform(2.5f, 6.0f);
    if (!place(r, false, 0.5f, c)) detail::require_count(i, n_poles, "pole");
    const float z0 = detail::footprint_base(terrain, c, r);
    scene.add_object("pole", ShapeSet().add(Cylinder{c.x(), c.y(), r, z0, z0 + height}));
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

/// The names of the ready-made scenes, as tools spell them.
inline constexpr const char* kSceneNames[] = {"office", "forest", "street", "hills"};

/// The ready-made scene called `name` (one of kSceneNames) for `seed`.
/// Throws std::invalid_argument for another name.
inline Scene make_scene(std::string_view name, std::uint64_t seed) {
  if (name == "office") return office_scene(seed);
  if (name == "forest") return forest_scene(seed);
  if (name == "street") return street_scene(seed);
  if (name == "hills") return hills_scene(seed);
  std::string msg("make_scene: unknown scene '");
  msg.append(name);
  msg.append("', expected office, forest, street or hills");
  throw std::invalid_argument(msg);
}

}  // namespace streamclust::sim
