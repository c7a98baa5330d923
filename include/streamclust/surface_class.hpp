// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The class of a surface point: an object, or structure (ground, wall,
/// ceiling). The simulator's ground truth, the engine's structure stage and
/// the evaluation metrics speak this one vocabulary. Standard library only.

#include <cstdint>

namespace streamclust {

/// What a point lies on. Numeric values are stable (written to files).
enum class SurfaceClass : std::uint8_t {
  object = 0,   ///< a thing to cluster (person, car, tree, furniture, ...)
  ground = 1,   ///< the ground: floor, road, terrain, kerbs and steps
  wall = 2,     ///< vertical structure: walls, facades
  ceiling = 3,  ///< an indoor ceiling
};
inline constexpr int kSurfaceClassCount = 4;

inline const char* to_string(SurfaceClass c) {
  switch (c) {
    case SurfaceClass::object: return "object";
    case SurfaceClass::ground: return "ground";
    case SurfaceClass::wall: return "wall";
    case SurfaceClass::ceiling: return "ceiling";
  }
  return "unknown";
}

}  // namespace streamclust
