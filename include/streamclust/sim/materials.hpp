// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Surface materials of the scan simulator: what a surface is made of, the
/// spread of its reflectance among objects, and how much it varies over one
/// surface. The simulator turns a surface's reflectance into the reflectivity
/// a Livox reports (intensity.hpp).
///
/// Reflectance is the diffuse (Lambertian) reflectance at the lidar's near
/// infrared wavelength (905 nm for the Livox sensors), 0..1; for the
/// retroreflector it is the retroreflective gain (1: a return as strong as
/// the brightest reading, 255). Each object (and each piece of structure)
/// draws one reflectance per material from [lo, hi] (uniform, a hash of the
/// scene's material seed, the owner and the material: no random stream is
/// consumed, so geometry never depends on it), then every texture cell
/// (kTextureCell, in the object's own frame) scales it by a factor of mean 1
/// and relative standard deviation `texture` (stains, grain, folds, gaps in
/// foliage). Ranges are typical of the literature for the material class at
/// 905 nm; the point is their width and overlap: two desks, two cars or two
/// people are not told apart by their material.
///
/// Thread safety: pure functions and constants.

#include <streamclust/detail/split_mix.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace streamclust::sim {

/// What a surface is made of. `generic` is the default of a shape added
/// without a material (user scenes).
enum class Material : std::uint8_t {
  generic,         ///< anything: 0.10-0.70
  painted_wall,    ///< light interior paint, plaster
  floor,           ///< carpet, linoleum, laminate
  ceiling_tile,    ///< acoustic tiles, painted ceiling
  concrete,        ///< pavements, kerbs, facades
  brick,           ///< facades
  asphalt,         ///< roads
  soil,            ///< bare ground, leaf litter
  grass,           ///< meadows, verges
  wood,            ///< furniture, boxes, panels
  metal,           ///< painted or bare metal: cabinets, poles, frames
  car_paint,       ///< black to white cars
  glass,           ///< windows: little comes back (transmitted or mirrored away)
  rubber,          ///< tyres
  fabric,          ///< clothing, dark to light
  bark,            ///< tree trunks
  foliage,         ///< crowns and bushes (porous: part of the beam passes)
  retroreflector,  ///< licence plates, signs: reported as 151-255
};

/// Number of materials (the enumerators are 0 .. kMaterialCount - 1).
inline constexpr std::size_t kMaterialCount = static_cast<std::size_t>(Material::retroreflector) + 1;

/// A material's reflectance distribution.
struct MaterialProperties {
  const char* name;      ///< as in the docs
  float lo;              ///< lowest reflectance an object draws (0..1)
  float hi;              ///< highest (0..1)
  float texture;         ///< relative standard deviation over one surface, per texture cell
  bool retroreflective;  ///< true: reported on the retroreflective scale (151-255)
};

/// Edge of the texture cells [m]: one reflectance factor per cell of the
/// object's frame (static objects and structure: the world frame).
inline constexpr float kTextureCell = 0.25f;

/// The properties of `m` (the table of docs/simulation-scenes.md).
inline const MaterialProperties& material_properties(Material m) {
  static constexpr MaterialProperties kTable[kMaterialCount] = {
      {"generic", 0.10f, 0.70f, 0.08f, false},      {"painted_wall", 0.55f, 0.85f, 0.03f, false},
      {"floor", 0.10f, 0.45f, 0.08f, false},        {"ceiling_tile", 0.60f, 0.85f, 0.03f, false},
      {"concrete", 0.20f, 0.40f, 0.08f, false},     {"brick", 0.25f, 0.45f, 0.10f, false},
      {"asphalt", 0.05f, 0.15f, 0.15f, false},      {"soil", 0.15f, 0.35f, 0.20f, false},
      {"grass", 0.30f, 0.55f, 0.20f, false},        {"wood", 0.25f, 0.60f, 0.10f, false},
      {"metal", 0.15f, 0.60f, 0.08f, false},        {"car_paint", 0.05f, 0.60f, 0.05f, false},
      {"glass", 0.02f, 0.10f, 0.30f, false},        {"rubber", 0.02f, 0.06f, 0.10f, false},
      {"fabric", 0.05f, 0.70f, 0.12f, false},       {"bark", 0.15f, 0.35f, 0.15f, false},
      {"foliage", 0.25f, 0.55f, 0.30f, false},      {"retroreflector", 0.60f, 1.00f, 0.05f, true},
  };
  const auto k = static_cast<std::size_t>(m);
  return kTable[k < kMaterialCount ? k : 0];
}

namespace detail {

/// A well-mixed 64-bit hash of a sequence of words (SplitMix64 steps).
inline std::uint64_t hash_words(std::uint64_t seed, std::uint64_t a, std::uint64_t b, std::uint64_t c = 0,
                                std::uint64_t d = 0) {
  std::uint64_t h = seed;
  for (const std::uint64_t w : {a, b, c, d}) h = streamclust::detail::SplitMix64(h ^ (w * 0x9E3779B97F4A7C15ull)).next();
  return h;
}

inline float unit_from_hash(std::uint64_t h) { return static_cast<float>(static_cast<double>(h >> 11) * 0x1.0p-53); }

inline std::uint64_t cell_index(float v) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v / kTextureCell))); }

}  // namespace detail

/// The reflectance an owner's surface of material `m` draws: uniform in
/// [lo, hi] from a hash of (seed, owner, m). `owner` tells surfaces apart:
/// the instance id of an object, another number per piece of structure.
inline float surface_reflectance(std::uint64_t seed, std::int64_t owner, Material m) {
  const MaterialProperties& p = material_properties(m);
  const float u = detail::unit_from_hash(
      detail::hash_words(seed, static_cast<std::uint64_t>(owner), static_cast<std::uint64_t>(m) + 1));
  return p.lo + u * (p.hi - p.lo);
}

/// The texture factor at `point` (the owner's frame [m]): uniform with mean 1
/// and relative standard deviation `material_properties(m).texture`, one
/// value per kTextureCell cube, never negative.
inline float texture_factor(std::uint64_t seed, std::int64_t owner, Material m, const Eigen::Vector3f& point) {
  const float spread = material_properties(m).texture;
  if (!(spread > 0.0f) || !point.allFinite()) return 1.0f;
  const std::uint64_t cell = detail::hash_words(detail::cell_index(point.x()), detail::cell_index(point.y()),
                                                detail::cell_index(point.z()), 0x7E47u);
  const float u = detail::unit_from_hash(
      detail::hash_words(seed, static_cast<std::uint64_t>(owner), static_cast<std::uint64_t>(m) + 1, cell));
  constexpr float kSqrt3 = 1.7320508075688772f;  // a uniform on [-sqrt 3, sqrt 3] has unit variance
  return std::max(0.0f, 1.0f + spread * kSqrt3 * (2.0f * u - 1.0f));
}

}  // namespace streamclust::sim
