// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// HeightMapGround: continuous ground and ceiling removal from a height map
/// of the sliding window; no scan lines, no per-frame refit.

#include <streamclust/concepts/ground.hpp>
#include <streamclust/ground/cell_table.hpp>
#include <streamclust/ground/height_column.hpp>
#include <streamclust/surface_class.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

namespace streamclust {

/// The window's points in a horizontal grid of `cell_size` cells (world x,
/// y; gravity along -z), each cell a histogram of heights (HeightColumn,
/// bins of `bin_height`). The model holds every window point, objects
/// included: a point's decision never feeds the model, so a mistake cannot
/// reinforce itself; the model follows the window (points are counted at
/// insertion and uncounted at eviction).
///
/// Ground. The ground surface under a cell is its lowest supported layer:
/// the lowest bin that holds, with the bin above, `support` points or more.
/// Its bound at a point of cell c is
///
///     G = min(layer(c), min over the 8 neighbours j of layer(j) + tan(max_slope) cell_size)
///
/// (the neighbours catch a cell covered by an object, whose lowest layer is
/// the object's underside: the ground next to it bounds it). When neither c
/// nor a neighbour has a layer, the nearest ring of cells out to
/// `search_radius` that has one gives G = min of layer(j) + tan(max_slope)
/// ring distance. With `sensor_height` known, G is also at most the ground
/// under the sensor plus tan(max_slope) times the horizontal distance from
/// it (a cone): near a sensor that cannot see the ground (a level Mid-360
/// sees the floor from 8 m on), the lowest layer of a cell is an object's
/// bottom, which the cone keeps an object. With `lowest_ray_elevation_deg`
/// too, a bound no higher than `blind_margin` above where the lowest ray
/// reaches (sensor z + tan(lowest elevation) x distance) is where the field
/// of view cuts an object off: the ground is hidden, taken level with the
/// ground under the sensor. A point is ground iff
/// z <= G + ground_tolerance; with no layer within reach it is an object (a
/// cold start costs coverage of the ground, never objects). The tolerance
/// absorbs the rise of a slope within a cell (tan(15 deg) x 0.5 m =
/// 0.13 m), the bin and the range noise; kerbs and steps lower than the
/// tolerance plus one cell's slope allowance join the ground.
///
/// Ceiling (`detect_ceiling`, decided before the ground: near a sensor that
/// sees the ceiling but not the floor, the ceiling is a cell's only layer).
/// A point at least `ceiling_clearance` above the sensor, within
/// `ceiling_tolerance` of its cell's highest supported layer, is ceiling
/// when that layer is level and wide: at least `ceiling_min_agreement` of
/// the cells within two rings have a highest layer within
/// `ceiling_flatness` of it (a tree's crown is curved and a slope rises:
/// both fail this; a ceiling passes).
///
/// Cost per point: one column update and 9 layer lookups (25 more for a
/// ceiling candidate), a ring search only in cold cells. Memory: 528 bytes
/// per live cell plus the table. Thread safety: none.
///
/// \code
/// struct ObjectsConfig : streamclust::CArcFastConfig {
///   using ground = streamclust::HeightMapGround;
/// };
/// streamclust::ClustererParams<ObjectsConfig> params;
/// params.ground.ground_tolerance = 0.15f;
/// \endcode
class HeightMapGround {
 public:
  struct Params {
    float cell_size = 0.5f;            ///< [m] horizontal cell edge, (0.05, 10]
    float bin_height = 0.05f;          ///< [m] height bin, (0.005, 1]
    float ground_tolerance = 0.2f;     ///< [m] above the ground bound still ground, [0, 2]
    float max_slope_deg = 15.0f;       ///< [deg] steepest ground between neighbouring cells, [0, 60]
    float search_radius = 2.0f;        ///< [m] how far a cold cell looks for ground, [0, 50]
    std::uint32_t support = 2;         ///< points that make a layer, [1, 1000]
    float sensor_height = 0.0f;        ///< [m] sensor above the ground under it, [0, 100]; 0: unknown (no cone)
    /// [deg] elevation of the sensor's lowest ray in world orientation (a
    /// level Mid-360: -7), [-90, 90]; -90: off. Needs sensor_height.
    float lowest_ray_elevation_deg = -90.0f;
    float blind_margin = 0.15f;        ///< [m] a layer this close above the lowest ray's reach is a cut-off, [0, 2]
    bool detect_ceiling = true;        ///< class level layers overhead as ceiling
    float ceiling_clearance = 0.5f;    ///< [m] a ceiling point is at least this far above the sensor, [0, 100]
    float ceiling_tolerance = 0.2f;    ///< [m] below the cell's highest layer still ceiling, [0, 2]
    float ceiling_flatness = 0.1f;     ///< [m] a neighbour's highest layer this close agrees, [0, 2]
    float ceiling_min_agreement = 0.6f;  ///< fraction of the cells within two rings that agree, (0, 1]
  };

  static constexpr bool enabled = true;

  HeightMapGround() : HeightMapGround(Params{}) {}
  /// Throws std::invalid_argument naming a parameter outside its range.
  explicit HeightMapGround(const Params& params) : params_(params) {
    check(params.cell_size > 0.05f && params.cell_size <= 10.0f, "cell_size", params.cell_size, "(0.05, 10] m");
    check(params.bin_height > 0.005f && params.bin_height <= 1.0f, "bin_height", params.bin_height, "(0.005, 1] m");
    check(params.ground_tolerance >= 0.0f && params.ground_tolerance <= 2.0f, "ground_tolerance",
          params.ground_tolerance, "[0, 2] m");
    check(params.max_slope_deg >= 0.0f && params.max_slope_deg <= 60.0f, "max_slope_deg", params.max_slope_deg,
          "[0, 60] degrees");
    check(params.search_radius >= 0.0f && params.search_radius <= 50.0f, "search_radius", params.search_radius,
          "[0, 50] m");
    check(params.support >= 1 && params.support <= 1000, "support", static_cast<float>(params.support), "[1, 1000]");
    check(params.ceiling_clearance >= 0.0f && params.ceiling_clearance <= 100.0f, "ceiling_clearance",
          params.ceiling_clearance, "[0, 100] m");
    check(params.ceiling_tolerance >= 0.0f && params.ceiling_tolerance <= 2.0f, "ceiling_tolerance",
          params.ceiling_tolerance, "[0, 2] m");
    check(params.ceiling_flatness >= 0.0f && params.ceiling_flatness <= 2.0f, "ceiling_flatness",
          params.ceiling_flatness, "[0, 2] m");
    check(params.lowest_ray_elevation_deg >= -90.0f && params.lowest_ray_elevation_deg <= 90.0f,
          "lowest_ray_elevation_deg", params.lowest_ray_elevation_deg, "[-90, 90] degrees");
    check(params.blind_margin >= 0.0f && params.blind_margin <= 2.0f, "blind_margin", params.blind_margin, "[0, 2] m");
    check(params.sensor_height >= 0.0f && params.sensor_height <= 100.0f, "sensor_height", params.sensor_height,
          "[0, 100] m (0: unknown)");
    check(params.ceiling_min_agreement > 0.0f && params.ceiling_min_agreement <= 1.0f, "ceiling_min_agreement",
          params.ceiling_min_agreement, "(0, 1]");
    inverse_cell_ = 1.0f / params.cell_size;
    inverse_bin_ = 1.0f / params.bin_height;
    slope_ = std::tan(params.max_slope_deg * 0.01745329252f);
    // -90 degrees: no cut-off (a ray straight down reaches everything).
    lowest_ray_slope_ = params.lowest_ray_elevation_deg <= -89.9f
                            ? -1e30f
                            : std::tan(params.lowest_ray_elevation_deg * 0.01745329252f);
    rise_per_cell_ = slope_ * params.cell_size;
    search_rings_ = static_cast<std::int32_t>(std::ceil(params.search_radius * inverse_cell_));
  }

  /// Counts the point, then classes it (see the class comment). Amortised O(1).
  SurfaceClass classify(const Eigen::Vector3f& world, const Eigen::Vector3f& ray) {
    const Key k = key_of(world);
    const std::int32_t bin = bin_of(world.z());
    cells_[cells_.find_or_create(k.ix, k.iy)].add(bin);
    if (params_.detect_ceiling && ray.z() >= params_.ceiling_clearance && is_ceiling(k, world.z())) {
      return SurfaceClass::ceiling;
    }
    std::optional<float> bound = ground_bound(k);
    if (!bound) return SurfaceClass::object;
    if (params_.sensor_height > 0.0f) {
      const float sensor_z = world.z() - ray.z();
      const float under_sensor = sensor_z - params_.sensor_height;
      const float distance = std::sqrt(ray.x() * ray.x() + ray.y() * ray.y());
      // A layer no higher than the lowest ray reaches here is where the
      // field of view cuts an object off, not a surface: the ground is
      // hidden below it, taken as level with the ground under the sensor.
      if (*bound <= sensor_z + lowest_ray_slope_ * distance + params_.blind_margin) {
        bound = std::min(*bound, under_sensor);
      }
      // The cone from the ground under the sensor.
      bound = std::min(*bound, under_sensor + slope_ * distance);
    }
    return world.z() <= *bound + params_.ground_tolerance ? SurfaceClass::ground : SurfaceClass::object;
  }

  /// Uncounts a point `classify` counted. O(1) expected.
  void forget(const Eigen::Vector3f& world) {
    const Key k = key_of(world);
    const std::uint32_t c = cells_.find(k.ix, k.iy);
    HeightColumn& column = cells_[c];
    column.remove(bin_of(world.z()));
    if (column.points() == 0) cells_.release(k.ix, k.iy);
  }

  std::size_t heap_bytes() const { return cells_.heap_bytes(); }
  /// Cells holding window points.
  std::size_t live_cells() const { return cells_.size(); }
  const Params& params() const { return params_; }

 private:
  struct Key {
    std::int32_t ix, iy;
  };

  static void check(bool ok, const char* name, float value, const char* allowed) {
    if (ok) return;
    throw std::invalid_argument(std::string("HeightMapGround: ") + name + " = " + std::to_string(value) +
                                " is invalid, expected " + allowed);
  }

  Key key_of(const Eigen::Vector3f& p) const {
    return Key{static_cast<std::int32_t>(std::floor(p.x() * inverse_cell_)),
               static_cast<std::int32_t>(std::floor(p.y() * inverse_cell_))};
  }
  std::int32_t bin_of(float z) const { return static_cast<std::int32_t>(std::floor(z * inverse_bin_)); }

  /// Height of the lowest supported layer of cell (ix, iy) [m].
  std::optional<float> lowest_layer(std::int32_t ix, std::int32_t iy) const {
    const std::uint32_t c = cells_.find(ix, iy);
    if (c == CellTable<HeightColumn>::kNone) return std::nullopt;
    const std::optional<std::int32_t> b = cells_[c].lowest_supported(params_.support);
    if (!b) return std::nullopt;
    return static_cast<float>(*b) * params_.bin_height;
  }
  std::optional<float> highest_layer(std::int32_t ix, std::int32_t iy) const {
    const std::uint32_t c = cells_.find(ix, iy);
    if (c == CellTable<HeightColumn>::kNone) return std::nullopt;
    const std::optional<std::int32_t> b = cells_[c].highest_supported(params_.support);
    if (!b) return std::nullopt;
    return static_cast<float>(*b + 1) * params_.bin_height;
  }

  /// The ground bound G at cell k, or nullopt when no layer is within reach.
  std::optional<float> ground_bound(Key k) const {
    std::optional<float> bound = lowest_layer(k.ix, k.iy);
    for (std::int32_t ring = 1; ring <= std::max<std::int32_t>(1, search_rings_); ++ring) {
      if (ring > 1 && bound) break;  // a ring beyond the first only for a cold neighbourhood
      const float allowance = rise_per_cell_ * static_cast<float>(ring);
      for (std::int32_t dy = -ring; dy <= ring; ++dy) {
        const bool edge_row = dy == -ring || dy == ring;
        for (std::int32_t dx = -ring; dx <= ring; dx += edge_row ? 1 : 2 * ring) {
          const std::optional<float> layer = lowest_layer(k.ix + dx, k.iy + dy);
          if (layer && (!bound || *layer + allowance < *bound)) bound = *layer + allowance;
        }
      }
    }
    return bound;
  }

  bool is_ceiling(Key k, float z) const {
    const std::optional<float> top = highest_layer(k.ix, k.iy);
    if (!top || z < *top - params_.ceiling_tolerance) return false;
    int agreeing = 0;
    int cells = 0;
    for (std::int32_t dy = -2; dy <= 2; ++dy) {
      for (std::int32_t dx = -2; dx <= 2; ++dx) {
        if (dx == 0 && dy == 0) continue;
        ++cells;
        const std::optional<float> other = highest_layer(k.ix + dx, k.iy + dy);
        if (other && std::fabs(*other - *top) <= params_.ceiling_flatness) ++agreeing;
      }
    }
    return static_cast<float>(agreeing) >= params_.ceiling_min_agreement * static_cast<float>(cells);
  }

  Params params_;
  CellTable<HeightColumn> cells_;
  float inverse_cell_ = 2.0f;
  float inverse_bin_ = 20.0f;
  float slope_ = 0.27f;
  float lowest_ray_slope_ = -1e30f;
  float rise_per_cell_ = 0.13f;
  std::int32_t search_rings_ = 4;
};

}  // namespace streamclust
