// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The vocabulary shared by the scan simulator's sensor models and scenes.
///
/// A sensor model is any type with `Ray next()` returning the next firing in
/// order (unit direction in the sensor frame: x forward, z up; stream time in
/// seconds, non-decreasing) and `double point_rate() const` [Hz]. A scene
/// answers `std::optional<Hit> cast(const Eigen::Vector3f& origin, const
/// Eigen::Vector3f& direction, double time) const` in the world frame.

#include <streamclust/sim/materials.hpp>
#include <streamclust/surface_class.hpp>

#include <Eigen/Core>

#include <cstdint>

namespace streamclust::sim {

/// One firing of a sensor.
struct Ray {
  Eigen::Vector3f direction = Eigen::Vector3f::UnitX();  ///< unit vector, sensor frame
  double time = 0.0;                                     ///< stream time [s]
  int laser = 0;                                         ///< emitter index
};

/// The first surface a ray meets.
struct Hit {
  float range = 0.0f;  ///< distance along the ray [m]
  int instance = 0;    ///< ground-truth instance id; 0 = structure (ground, walls, ceiling)
  SurfaceClass surface = SurfaceClass::object;  ///< ground-truth class: `object` for instance > 0, else the structure's
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();  ///< unit surface normal at the hit, world frame (either side)
  Material material = Material::generic;              ///< what the surface hit is made of
  float reflectance = 0.0f;  ///< the surface's reflectance there (materials.hpp: drawn value x texture), >= 0
};

/// A simulated point with its ground truth, in the sensor frame at capture time.
struct SimPoint {
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;
  float intensity = 0.0f;
  double t = 0.0;    ///< stream time [s]
  int instance = 0;  ///< ground truth: 0 structure, > 0 object instance
  SurfaceClass surface = SurfaceClass::object;  ///< ground truth: `object` for instance > 0, else ground, wall or ceiling
};

}  // namespace streamclust::sim
