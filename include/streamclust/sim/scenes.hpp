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
///
/// One header per scene in `sim/scenes/`; this header includes them all and
/// adds `make_scene`, the scene by name.

#include <streamclust/sim/scene.hpp>
#include <streamclust/sim/scenes/forest.hpp>
#include <streamclust/sim/scenes/hills.hpp>
#include <streamclust/sim/scenes/office.hpp>
#include <streamclust/sim/scenes/street.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace streamclust::sim {

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
