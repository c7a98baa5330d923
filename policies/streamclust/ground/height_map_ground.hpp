// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// HeightMapGround: continuous ground, wall and ceiling removal from a
/// height map and a voxel map of the sliding window; no scan lines, no
/// per-frame refit.

#include <streamclust/concepts/ground.hpp>
#include <streamclust/detail/parameter_check.hpp>
#include <streamclust/ground/cell_table.hpp>
#include <streamclust/ground/height_column.hpp>
#include <streamclust/ground/wall_model.hpp>
#include <streamclust/surface_class.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace streamclust {

/// The window's points in a horizontal grid of `cell_size` cells (world x,
/// y; gravity along -z), each cell a histogram of heights (HeightColumn,
/// bins of `bin_height`). The model holds every window point, objects
/// included, and per cell how many of them were classed ground; it follows
/// the window (points are counted at insertion and uncounted at eviction).
///
/// Ground. The ground surface under a cell is its lowest supported layer:
/// the lowest bin that holds, with the bin above, `support` points or more;
/// its height is the mean of the densest bin within `layer_thickness` above
/// it (the range noise scatters a surface's points over a bin or two, a few
/// below it).
/// Its bound at a point of cell c is
///
///     G = min(layer(c), min over the 8 neighbours j of layer(j) + tan(max_slope) cell_size)
///
/// (the neighbours catch a cell covered by an object, whose lowest layer is
/// the object's underside: the ground next to it bounds it). When no
/// neighbour has a layer (a cold cell, or the top of an object seen over the
/// shadow of another), the nearest ring of cells out to `search_radius`
/// that has one bounds it too: G = min(layer(c), min of layer(j) +
/// tan(max_slope) ring distance). With `sensor_height` known, G is also at most the ground
/// under the sensor plus tan(max_slope) times the horizontal distance from
/// it (a cone): near a sensor that cannot see the ground (a level Mid-360
/// sees the floor from 8 m on), the lowest layer of a cell is an object's
/// bottom, which the cone keeps an object. With `lowest_ray_elevation_deg`
/// too, a bound no higher than `blind_margin` above where the lowest ray
/// reaches (sensor z + tan(lowest elevation) x distance) is where the field
/// of view cuts an object off: the ground is hidden, taken level with the
/// ground under the sensor. A point is ground iff z <= top +
/// ground_tolerance, top the higher of G + the rise of the local slope across
/// a cell (from the neighbours' layers where they rise monotonically through
/// the cell) and the highest neighbouring layer at most `step_height` above
/// G that is a surface (peaked like a ceiling, `step_peak_ratio`: a kerb's
/// face or a step's riser joins the ground, an object's bottom does not);
/// with no layer within reach it is an object (a cold start costs
/// coverage of the ground, never objects). With `surface_evidence`, ground
/// also needs a solid surface within reach: a lowest layer in the 3 x 3
/// cells that is a surface (peaked, as for a step) holding
/// `surface_min_points` in its two bins and more than the 0.5 m above them,
/// else the nearest ring out to `search_radius` holding one (whose layers
/// bound G too); with none, an object. A far object whose foot is behind a
/// crest or too sparse to show has a few points of its own as its cells'
/// lowest layers, which would bound G at its own bottom and take its lowest
/// layer as ground; they are no solid surface. Where the lowest ray passes above
/// level ground (a level Mid-360 out to 8 m), ground in view must have risen
/// into view: the straight rise from the sensor's foot to the point is out
/// of view one cell nearer the sensor, or that nearer cell holds points
/// classed ground (a desk top there has empty cells in front of it; a ramp
/// is ground from the row where it comes into view outwards). The tolerance
/// is what an object on level ground loses at its foot: 3 cm covers twice
/// the height noise of ground 2 cm noisy along the ray and seen at up to 45
/// degrees of incidence; rough ground (grass, gravel) wants 5-10 cm.
///
/// Walls (`detect_walls`, decided after the ceiling and before the ground:
/// a wall's foot would pass for ground where the floor is out of view):
/// WallModel (wall_model.hpp) with `walls`, large vertical planes; a point
/// within its tolerance of one is wall.
///
/// Ceiling (`detect_ceiling`, decided before the ground: near a sensor that
/// sees the ceiling but not the floor, the ceiling is a cell's only layer).
/// A point at least `ceiling_clearance` above the sensor, within
/// `ceiling_tolerance` of its cell's highest supported layer, is ceiling
/// when that layer is a surface seen from below (its two bins hold
/// `ceiling_peak_ratio` times the points per bin of the 0.5 m below them:
/// the top of a cabinet's side does not), level and wide: at least
/// `ceiling_min_agreement` of the cells within two rings have a highest
/// layer within `ceiling_flatness` of it (a tree's crown is curved and a
/// slope rises: both fail this; a ceiling passes).
///
/// Cost per point: one column update and 9 layer lookups (25 more for a
/// ceiling candidate, at most 2 for a ground candidate out of view of level
/// ground; up to 9 surface tests of 12 bins each for a ground candidate), a
/// ring search only in cells without a neighbouring layer or solid surface; with
/// walls, the wall model's voxel update and its refreshes. Memory: about
/// 1 KiB per live cell plus the table, and the wall model's voxels (104
/// bytes each). Thread safety: none.
///
/// \code
/// struct ObjectsConfig : streamclust::CArcFastConfig {
///   using ground = streamclust::HeightMapGround;
/// };
/// streamclust::ClustererParams<ObjectsConfig> params;
/// params.ground.sensor_height = 1.2f;  // [m]
/// \endcode
class HeightMapGround {
 public:
  struct Params {
    float cell_size = 0.5f;            ///< [m] horizontal cell edge, (0.05, 10]
    float bin_height = 0.05f;          ///< [m] height bin, (0.005, 1]
    float ground_tolerance = 0.03f;    ///< [m] above the ground bound still ground, [0, 2]
    float max_slope_deg = 15.0f;       ///< [deg] steepest ground between neighbouring cells, [0, 60]
    float search_radius = 2.0f;        ///< [m] how far a cold cell looks for ground, [0, 50]
    std::uint32_t support = 2;         ///< points that make a layer, [1, 1000]
    float layer_thickness = 0.1f;      ///< [m] a layer's height is its densest bin's within this, [bin_height, 1]
    float sensor_height = 0.0f;        ///< [m] sensor above the ground under it, [0, 100]; 0: unknown (no cone)
    /// [deg] elevation of the sensor's lowest ray in world orientation (a
    /// level Mid-360: -7), [-90, 90]; -90: off. Needs sensor_height.
    float lowest_ray_elevation_deg = -90.0f;
    float blind_margin = 0.15f;        ///< [m] a layer this close above the lowest ray's reach is a cut-off, [0, 2]
    float step_height = 0.16f;         ///< [m] a neighbouring surface this far above the bound lifts it (kerbs), [0, 1]
    float step_peak_ratio = 2.0f;      ///< such a surface's two bins hold this times the points per bin above, [0, 100]
    bool detect_ceiling = true;        ///< class level layers overhead as ceiling
    float ceiling_clearance = 0.1f;    ///< [m] a ceiling point is at least this far above the sensor, [0, 100]
    float ceiling_tolerance = 0.2f;    ///< [m] below the cell's highest layer still ceiling, [0, 2]
    float ceiling_flatness = 0.1f;     ///< [m] a neighbour's highest layer this close agrees, [0, 2]
    float ceiling_min_agreement = 0.75f;  ///< fraction of the cells within two rings that agree, (0, 1]
    float ceiling_peak_ratio = 3.0f;   ///< points per bin of the layer over those of the 0.5 m below it, [0, 100]
    /// Ground needs a solid surface within reach (see the class comment);
    /// off: any lowest layer bounds the ground.
    bool surface_evidence = true;
    std::uint32_t surface_min_points = 3;  ///< points in a solid surface's two bins, [1, 1000]
    bool detect_walls = true;          ///< class points on large vertical planes as wall
    WallModel::Params walls;           ///< the wall model's (wall_model.hpp)
  };

  static constexpr bool enabled = true;

  HeightMapGround() : HeightMapGround(Params{}) {}
  /// Throws std::invalid_argument naming a parameter outside its range.
  explicit HeightMapGround(const Params& params) : params_(params), walls_(params.walls) {
    check(params.cell_size > 0.05f && params.cell_size <= 10.0f, "cell_size", params.cell_size, "(0.05, 10] m");
    check(params.bin_height > 0.005f && params.bin_height <= 1.0f, "bin_height", params.bin_height, "(0.005, 1] m");
    check(params.ground_tolerance >= 0.0f && params.ground_tolerance <= 2.0f, "ground_tolerance",
          params.ground_tolerance, "[0, 2] m");
    check(params.max_slope_deg >= 0.0f && params.max_slope_deg <= 60.0f, "max_slope_deg", params.max_slope_deg,
          "[0, 60] degrees");
    check(params.search_radius >= 0.0f && params.search_radius <= 50.0f, "search_radius", params.search_radius,
          "[0, 50] m");
    check(params.support >= 1 && params.support <= 1000, "support", static_cast<float>(params.support), "[1, 1000]");
    check(params.layer_thickness >= params.bin_height && params.layer_thickness <= 1.0f, "layer_thickness",
          params.layer_thickness, "[bin_height, 1] m");
    check(params.ceiling_clearance >= 0.0f && params.ceiling_clearance <= 100.0f, "ceiling_clearance",
          params.ceiling_clearance, "[0, 100] m");
    check(params.ceiling_tolerance >= 0.0f && params.ceiling_tolerance <= 2.0f, "ceiling_tolerance",
          params.ceiling_tolerance, "[0, 2] m");
    check(params.ceiling_flatness >= 0.0f && params.ceiling_flatness <= 2.0f, "ceiling_flatness",
          params.ceiling_flatness, "[0, 2] m");
    check(params.lowest_ray_elevation_deg >= -90.0f && params.lowest_ray_elevation_deg <= 90.0f,
          "lowest_ray_elevation_deg", params.lowest_ray_elevation_deg, "[-90, 90] degrees");
    check(params.step_height >= 0.0f && params.step_height <= 1.0f, "step_height", params.step_height, "[0, 1] m");
    check(params.step_peak_ratio >= 0.0f && params.step_peak_ratio <= 100.0f, "step_peak_ratio", params.step_peak_ratio,
          "[0, 100]");
    check(params.blind_margin >= 0.0f && params.blind_margin <= 2.0f, "blind_margin", params.blind_margin, "[0, 2] m");
    check(params.sensor_height >= 0.0f && params.sensor_height <= 100.0f, "sensor_height", params.sensor_height,
          "[0, 100] m (0: unknown)");
    check(params.ceiling_peak_ratio >= 0.0f && params.ceiling_peak_ratio <= 100.0f, "ceiling_peak_ratio",
          params.ceiling_peak_ratio, "[0, 100]");
    check(params.ceiling_min_agreement > 0.0f && params.ceiling_min_agreement <= 1.0f, "ceiling_min_agreement",
          params.ceiling_min_agreement, "(0, 1]");
    check(params.surface_min_points >= 1 && params.surface_min_points <= 1000, "surface_min_points",
          static_cast<float>(params.surface_min_points), "[1, 1000]");
    inverse_cell_ = 1.0f / params.cell_size;
    inverse_bin_ = 1.0f / params.bin_height;
    slope_ = std::tan(params.max_slope_deg * 0.01745329252f);
    // -90 degrees: no cut-off (a ray straight down reaches everything).
    lowest_ray_slope_ = params.lowest_ray_elevation_deg <= -89.9f
                            ? -1e30f
                            : std::tan(params.lowest_ray_elevation_deg * 0.01745329252f);
    rise_per_cell_ = slope_ * params.cell_size;
    early_margin_ = std::max(rise_per_cell_, params.step_height);
    layer_bins_ = std::max<std::int32_t>(1, static_cast<std::int32_t>(std::lround(params.layer_thickness * inverse_bin_)));
    search_rings_ = static_cast<std::int32_t>(std::ceil(params.search_radius * inverse_cell_));
  }

  /// Counts the point, then classes it (see the class comment). Amortised O(1).
  SurfaceClass classify(const Eigen::Vector3f& world, const Eigen::Vector3f& ray) {
    const Key k = key_of(world);
    const Height h = height_of(world.z());
    const std::uint32_t c = cells_.find_or_create(k.ix, k.iy);
    cells_[c].heights.add(h.bin, h.fraction);
    const WallModel::Entry wall = params_.detect_walls ? walls_.enter(world) : WallModel::Entry{};
    const SurfaceClass surface = decide(k, world, ray, wall.on_wall);
    sensor_ = world - ray;
    has_sensor_ = true;
    if (surface == SurfaceClass::ground) ++cells_[c].ground_points;
    if (params_.detect_walls && in_wall_lines(surface)) walls_.add_to_line(wall, world);
    return surface;
  }

  /// Uncounts a point `classify` counted and classed `surface`. O(1) expected.
  void forget(const Eigen::Vector3f& world, SurfaceClass surface) {
    const Key k = key_of(world);
    const std::uint32_t c = cells_.find(k.ix, k.iy);
    Cell& cell = cells_[c];
    const Height h = height_of(world.z());
    cell.heights.remove(h.bin, h.fraction);
    if (surface == SurfaceClass::ground) --cell.ground_points;
    if (cell.heights.points() == 0) cells_.release(k.ix, k.iy);
    if (params_.detect_walls) walls_.forget(world, in_wall_lines(surface));
  }

  /// The ground's height around (x, y) [m], for what reads the window after
  /// a retrieval (an object box's bottom): the mean of the lowest layers that
  /// are solid surfaces (solid_surface) holding points classified ground
  /// (indoors a cell under the ceiling alone is no ground) in the square of cells within
  /// `radius` [m] of (x, y) (at most 10 m), each bounded from the last
  /// point's sensor as the classification bounds it (a ceiling patch over a
  /// floor out of view is no ground); when none is, in the zone near
  /// the sensor where its field of view cannot reach level ground, the
  /// ground under the sensor (sensor_height, lowest_ray_elevation_deg; the
  /// level the classification takes there), else nullopt. A wide square is
  /// sampled on a grid of at most 5 x 5 of its cells.
  /// At most 25 lookups.
  std::optional<float> ground_height_near(float x, float y, float radius) const {
    if (!std::isfinite(x) || !std::isfinite(y) || std::abs(x) > 1e6f || std::abs(y) > 1e6f) return std::nullopt;
    const std::optional<float> ground = mean_over_cells(x, y, radius, [&](std::int32_t ix, std::int32_t iy) {
      const std::optional<float> layer = lowest_layer(ix, iy);
      if (!layer || !solid_surface(ix, iy) || !holds_ground(ix, iy)) return std::optional<float>{};
      if (!has_sensor_ || params_.sensor_height <= 0.0f) return layer;
      const float cx = (static_cast<float>(ix) + 0.5f) * params_.cell_size - sensor_.x();
      const float cy = (static_cast<float>(iy) + 0.5f) * params_.cell_size - sensor_.y();
      return std::optional<float>{bounded_from_sensor(*layer, sensor_.z(), std::hypot(cx, cy))};
    });
    return ground ? ground : blind_ground_near(x, y, radius);
  }

  /// The ceiling's height over (x, y) [m], for what reads the window after a
  /// retrieval (a box that reaches it hangs from it or is a piece of it): the
  /// mean of the highest layers the classification takes for ceiling
  /// (is_ceiling: peaked, level with its neighbours), at least
  /// `ceiling_clearance` above the last point's sensor, in the square of
  /// cells within `radius` [m] of (x, y) (at most 10 m, sampled as
  /// ground_height_near samples it); nullopt when none is, or without
  /// `detect_ceiling`. Each cell's highest layer is looked up once, when
  /// first needed, into a table on the stack while the square and the two
  /// rings around it are at most kTopsSide cells wide (within 3 m on 0.5 m
  /// cells); a wider one takes at most 25 cells of 26 lookups each.
  std::optional<float> ceiling_height_near(float x, float y, float radius) const {
    if (!params_.detect_ceiling || !std::isfinite(x) || !std::isfinite(y) || std::abs(x) > 1e6f ||
        std::abs(y) > 1e6f) {
      return std::nullopt;
    }
    auto ceiling_top = [&](Key k, const auto& top_at) {
      const std::optional<float> top = top_at(0, 0);
      if (!top || (has_sensor_ && *top < sensor_.z() + params_.ceiling_clearance) ||
          !ceiling_shaped(k, *top, top_at)) {
        return std::optional<float>{};
      }
      return top;
    };
    const Key centre = key_of(Eigen::Vector3f(x, y, 0.0f));
    const std::int32_t reach = rings_within(radius) + 2;
    const std::int32_t side = 2 * reach + 1;
    if (side > kTopsSide) {
      return mean_over_cells(x, y, radius, [&](std::int32_t ix, std::int32_t iy) {
        return ceiling_top(Key{ix, iy}, highest_layers_around(Key{ix, iy}));
      });
    }
    // NaN: not looked up yet; -infinity: the cell has no layer.
    constexpr float kUnread = std::numeric_limits<float>::quiet_NaN();
    constexpr float kNone = -std::numeric_limits<float>::infinity();
    std::array<float, static_cast<std::size_t>(kTopsSide * kTopsSide)> tops;
    std::fill_n(tops.begin(), side * side, kUnread);
    return mean_over_cells(x, y, radius, [&](std::int32_t ix, std::int32_t iy) {
      return ceiling_top(Key{ix, iy}, [&](std::int32_t dx, std::int32_t dy) {
        const std::int32_t i = ix + dx - centre.ix + reach, j = iy + dy - centre.iy + reach;
        float& top = tops[static_cast<std::size_t>(j * side + i)];
        if (std::isnan(top)) top = highest_layer(ix + dx, iy + dy).value_or(kNone);
        return top == kNone ? std::optional<float>{} : std::optional<float>{top};
      });
    });
  }

  std::size_t heap_bytes() const { return cells_.heap_bytes() + walls_.heap_bytes(); }
  /// Cells holding window points.
  std::size_t live_cells() const { return cells_.size(); }
  /// Wall model voxels holding window points (0 without walls).
  std::size_t live_wall_voxels() const { return walls_.live_voxels(); }
  const Params& params() const { return params_; }

 private:
  struct Key {
    std::int32_t ix, iy;
  };

  /// A ground bound `bound` [m] `distance` [m] from a sensor at height
  /// `sensor_z` [m] with sensor_height known: a layer no higher than the
  /// lowest ray reaches there is where the field of view cuts an object off,
  /// not a surface (the ground is hidden below it, taken as level with the
  /// ground under the sensor), and the ground rises at most max_slope from
  /// the ground under the sensor (the cone). O(1).
  float bounded_from_sensor(float bound, float sensor_z, float distance) const {
    const float foot = sensor_z - params_.sensor_height;
    if (bound <= sensor_z + lowest_ray_slope_ * distance + params_.blind_margin) bound = std::min(bound, foot);
    return std::min(bound, foot + slope_ * distance);
  }

  /// Rings of cells within `radius` [m] (clamped to [0, 10] m). O(1).
  std::int32_t rings_within(float radius) const {
    return static_cast<std::int32_t>(std::ceil(std::clamp(radius, 0.0f, 10.0f) * inverse_cell_));
  }

  /// The mean of `cell_height(ix, iy)` (a std::optional<float>) over the
  /// cells it has a value for, in the square of cells within `radius` [m] of
  /// (x, y) (at most 10 m) sampled on a grid of at most 5 x 5 of them;
  /// nullopt when it has none. (x, y) finite. At most 25 calls.
  template <class HeightOf>
  std::optional<float> mean_over_cells(float x, float y, float radius, const HeightOf& cell_height) const {
    const Key k = key_of(Eigen::Vector3f(x, y, 0.0f));
    const std::int32_t rings = rings_within(radius);
    const std::int32_t stride = std::max<std::int32_t>(1, (2 * rings + 1 + 4) / 5);
    double sum = 0.0;
    int cells = 0;
    for (std::int32_t iy = k.iy - rings; iy <= k.iy + rings; iy += stride) {
      for (std::int32_t ix = k.ix - rings; ix <= k.ix + rings; ix += stride) {
        const std::optional<float> height = cell_height(ix, iy);
        if (!height) continue;
        sum += static_cast<double>(*height);
        ++cells;
      }
    }
    if (cells == 0) return std::nullopt;
    return static_cast<float>(sum / cells);
  }

  /// Where no surface is seen: the ground under the last point's sensor
  /// when (x, y), or the square of `radius` around it, reaches into the
  /// zone that sensor cannot see level ground in (nearer than sensor_height
  /// over the lowest ray's downward slope), as decide() takes it there; else
  /// nullopt. Needs sensor_height and lowest_ray_elevation_deg. O(1).
  std::optional<float> blind_ground_near(float x, float y, float radius) const {
    if (!has_sensor_ || params_.sensor_height <= 0.0f || lowest_ray_slope_ <= -1e29f) return std::nullopt;
    const float distance = std::hypot(x - sensor_.x(), y - sensor_.y()) - std::max(radius, 0.0f);
    const bool blind = lowest_ray_slope_ >= 0.0f || distance * -lowest_ray_slope_ < params_.sensor_height;
    if (!blind) return std::nullopt;
    return sensor_.z() - params_.sensor_height;
  }

  static void check(bool ok, const char* name, float value, const char* allowed) {
    detail::require_parameter(ok, "HeightMapGround", name, static_cast<double>(value), allowed);
  }

  Key key_of(const Eigen::Vector3f& p) const {
    return Key{static_cast<std::int32_t>(std::floor(p.x() * inverse_cell_)),
               static_cast<std::int32_t>(std::floor(p.y() * inverse_cell_))};
  }
  /// A height as its bin and its position within it (HeightColumn's units).
  struct Height {
    std::int32_t bin, fraction;
  };
  Height height_of(float z) const {
    const float scaled = z * inverse_bin_;
    const float bin = std::floor(scaled);
    const auto fraction = static_cast<std::int32_t>((scaled - bin) * HeightColumn::kFractionUnits);
    return Height{static_cast<std::int32_t>(bin), std::clamp(fraction, 0, HeightColumn::kFractionUnits - 1)};
  }

  /// The points a wall's line is fitted to: objects and walls (a floor or
  /// a ceiling fills a voxel's footprint).
  static bool in_wall_lines(SurfaceClass surface) {
    return surface == SurfaceClass::object || surface == SurfaceClass::wall;
  }

  /// The class of a point already counted in cell k; `on_wall`: the wall
  /// model's decision.
  SurfaceClass decide(Key k, const Eigen::Vector3f& world, const Eigen::Vector3f& ray, bool on_wall) const {
    if (params_.detect_ceiling && ray.z() >= params_.ceiling_clearance && is_ceiling(k, world.z())) {
      return SurfaceClass::ceiling;
    }
    if (on_wall) return SurfaceClass::wall;
    // The bound is at most the cell's own layer and the top at most
    // max(rise_per_cell_, step_height) above it: a point well above its
    // cell's layer is an object without looking at the neighbours (most
    // object points).
    Neighbourhood n = neighbourhood(k);
    if (n.layer[4] && world.z() > *n.layer[4] + params_.ground_tolerance + early_margin_) return SurfaceClass::object;
    std::optional<float> bound = ground_bound(k, n);
    if (!bound) return SurfaceClass::object;
    const bool sensor_known = params_.sensor_height > 0.0f;
    float sensor_z = 0.0f, distance = 0.0f;
    if (sensor_known) {
      sensor_z = world.z() - ray.z();
      distance = std::sqrt(ray.x() * ray.x() + ray.y() * ray.y());
      bound = bounded_from_sensor(*bound, sensor_z, distance);
    }
    if (world.z() > surface_top(k, *bound, n) + params_.ground_tolerance) return SurfaceClass::object;
    return !sensor_known || rises_into_view(k, world, ray, sensor_z, distance) ? SurfaceClass::ground : SurfaceClass::object;
  }

  /// Where level ground would be out of view (the lowest ray passes above
  /// it), ground in view must rise from the sensor's foot, and in view it
  /// rises on from where it came into view: a ground point there lies where
  /// the straight rise from the foot would still be out of view one cell
  /// nearer the sensor, or the cell one step nearer holds ground points
  /// (a desk top in the blind zone of a level Mid-360 has empty cells in
  /// front of it). Elsewhere always true. At most 2 lookups.
  bool rises_into_view(Key k, const Eigen::Vector3f& world, const Eigen::Vector3f& ray, float sensor_z,
                       float distance) const {
    const float foot = sensor_z - params_.sensor_height;
    if (foot >= sensor_z + lowest_ray_slope_ * distance) return true;  // level ground in view here
    const float nearer = distance - params_.cell_size;
    if (nearer <= 0.0f) return true;
    const float rise_line = foot + (world.z() - foot) * nearer / distance;
    if (rise_line <= sensor_z + lowest_ray_slope_ * nearer) return true;  // where ground comes into view
    // The cell one step towards the sensor (a diagonal step can stay in k).
    for (const float steps : {1.0f, 1.5f}) {
      const float scale = steps * params_.cell_size / distance;
      const Key in = key_of(Eigen::Vector3f(world.x() - ray.x() * scale, world.y() - ray.y() * scale, world.z()));
      if (in.ix == k.ix && in.iy == k.iy) continue;
      return holds_ground(in.ix, in.iy);
    }
    return false;
  }

  /// Height of the lowest supported layer of cell (ix, iy) [m]: the mean
  /// height of the densest bin within `layer_thickness` of its lowest
  /// supported bin (a level surface piles its points into a bin or two; an
  /// object standing on it spreads its points over many).
  std::optional<float> lowest_layer(std::int32_t ix, std::int32_t iy) const {
    const std::uint32_t c = cells_.find(ix, iy);
    if (c == CellTable<Cell>::kNone) return std::nullopt;
    const HeightColumn& column = cells_[c].heights;
    const std::optional<std::int32_t> b = column.lowest_supported(params_.support);
    if (!b) return std::nullopt;
    const std::int32_t densest = column.densest(*b, *b + layer_bins_ - 1);
    return static_cast<float>(*column.mean_bin(densest, densest)) * params_.bin_height;
  }
  /// Height of the highest supported layer [m]: as lowest_layer, from the
  /// highest supported bin down.
  std::optional<float> highest_layer(std::int32_t ix, std::int32_t iy) const {
    const std::uint32_t c = cells_.find(ix, iy);
    if (c == CellTable<Cell>::kNone) return std::nullopt;
    const HeightColumn& column = cells_[c].heights;
    const std::optional<std::int32_t> b = column.highest_supported(params_.support);
    if (!b) return std::nullopt;
    const std::int32_t densest = column.densest(*b - layer_bins_ + 1, *b);
    return static_cast<float>(*column.mean_bin(densest, densest)) * params_.bin_height;
  }

  /// The lowest layers of cell k and its 8 neighbours (index 3 (dy + 1) +
  /// (dx + 1); 4 is k), lazily: only the centre is looked up at first.
  struct Neighbourhood {
    std::array<std::optional<float>, 9> layer;
  };
  Neighbourhood neighbourhood(Key k) const {
    Neighbourhood n;
    n.layer[4] = lowest_layer(k.ix, k.iy);
    return n;
  }
  /// Fills the 8 neighbours of `n` (cell k). 8 lookups.
  void fill_ring(Key k, Neighbourhood& n) const {
    for (std::int32_t dy = -1; dy <= 1; ++dy) {
      for (std::int32_t dx = -1; dx <= 1; ++dx) {
        if (dx != 0 || dy != 0) n.layer[static_cast<std::size_t>(3 * (dy + 1) + dx + 1)] = lowest_layer(k.ix + dx, k.iy + dy);
      }
    }
  }

  /// The ground bound G at cell k, or nullopt when no layer is within
  /// reach; fills the ring of `n`.
  std::optional<float> ground_bound(Key k, Neighbourhood& n) const {
    fill_ring(k, n);
    std::optional<float> bound = n.layer[4];
    bool neighbour = false;
    for (std::size_t i = 0; i < 9; ++i) {
      if (i == 4 || !n.layer[i]) continue;
      neighbour = true;
      if (!bound || *n.layer[i] + rise_per_cell_ < *bound) bound = *n.layer[i] + rise_per_cell_;
    }
    // Rings beyond the first only while none held a layer: around a cell
    // with no neighbours (cold, or an object's top seen over a shadow) the
    // nearest layers bound it.
    if (!neighbour) bound_from_rings(k, bound, [](std::int32_t, std::int32_t) { return true; });
    if (bound && params_.surface_evidence) return with_surface_evidence(k, n, *bound);
    return bound;
  }

  /// Searches the rings 2 to search_radius around cell k, nearest first, up
  /// to the first holding a layer that `accept(ix, iy)` takes; each such
  /// layer plus the slope's allowance for its ring lowers `bound`. True
  /// when one was found. O(search_rings^2) lookups at most.
  template <class Accept>
  bool bound_from_rings(Key k, std::optional<float>& bound, Accept&& accept) const {
    for (std::int32_t ring = 2; ring <= search_rings_; ++ring) {
      const float allowance = rise_per_cell_ * static_cast<float>(ring);
      bool found = false;
      for (std::int32_t dy = -ring; dy <= ring; ++dy) {
        const bool edge_row = dy == -ring || dy == ring;
        for (std::int32_t dx = -ring; dx <= ring; dx += edge_row ? 1 : 2 * ring) {
          const std::optional<float> layer = lowest_layer(k.ix + dx, k.iy + dy);
          if (!layer || !accept(k.ix + dx, k.iy + dy)) continue;
          found = true;
          if (!bound || *layer + allowance < *bound) bound = *layer + allowance;
        }
      }
      if (found) return true;
    }
    return false;
  }

  /// `bound` where a solid surface (solid_surface) is within reach of cell
  /// k, nullopt where none is: a layer in k or its 8 neighbours, else the
  /// nearest ring out to `search_radius` holding one, whose layers also
  /// bound the ground as in ground_bound. A far object's sparse points, or
  /// its bottom seen over a crest, make a lowest layer but no surface.
  /// O(1) where a neighbour is solid; a ring search otherwise.
  std::optional<float> with_surface_evidence(Key k, const Neighbourhood& n, float bound) const {
    // The cell itself first: a ground point's own cell is most often solid.
    if (n.layer[4] && solid_surface(k.ix, k.iy)) return bound;
    for (std::size_t i = 0; i < 9; ++i) {
      const std::int32_t dx = static_cast<std::int32_t>(i % 3) - 1, dy = static_cast<std::int32_t>(i / 3) - 1;
      if (i != 4 && n.layer[i] && solid_surface(k.ix + dx, k.iy + dy)) return bound;
    }
    std::optional<float> lowered = bound;
    if (!bound_from_rings(k, lowered, [this](std::int32_t ix, std::int32_t iy) { return solid_surface(ix, iy); })) {
      return std::nullopt;
    }
    return lowered;
  }

  /// The highest ground in cell k whose ground bound is `bound` [m]: the
  /// bound plus the local slope's rise, or a neighbour's layer up to
  /// `step_height` above the bound when that layer is a surface (a kerb's
  /// face, a step's riser; not an object's bottom). O(1).
  float surface_top(Key k, float bound, const Neighbourhood& n) const {
    float top = bound + slope_rise(n);
    for (std::size_t i = 0; i < 9; ++i) {
      if (i == 4 || !n.layer[i] || *n.layer[i] <= top || *n.layer[i] > bound + params_.step_height) continue;
      const std::int32_t dx = static_cast<std::int32_t>(i % 3) - 1, dy = static_cast<std::int32_t>(i / 3) - 1;
      if (is_surface(k.ix + dx, k.iy + dy)) top = *n.layer[i];
    }
    return top;
  }

  /// True when the lowest layer of cell (ix, iy) is a surface seen from
  /// above: its two bins hold `step_peak_ratio` times the points per bin of
  /// the 0.5 m above them (an object's bottom spreads its points upwards).
  bool is_surface(std::int32_t ix, std::int32_t iy) const {
    return lowest_layer_counts(ix, iy).peaked(params_.step_peak_ratio);
  }
  /// True when the lowest layer of cell (ix, iy) is a surface (is_surface)
  /// with `surface_min_points` in its two bins and more than in the 0.5 m
  /// above: a surface seen, not a few stray returns or an object's bottom
  /// (at 35 m a Mid-360 puts about 0.1 returns a window into a ground cell,
  /// so sparse far ground has too few points for a lowest layer at all).
  bool solid_surface(std::int32_t ix, std::int32_t iy) const {
    const PeakAndSpan counts = lowest_layer_counts(ix, iy);
    return counts.peak >= params_.surface_min_points && counts.peak > counts.span &&
           counts.peaked(params_.step_peak_ratio);
  }

  /// True when cell (ix, iy) holds window points classified ground. O(1) expected.
  bool holds_ground(std::int32_t ix, std::int32_t iy) const {
    const std::uint32_t c = cells_.find(ix, iy);
    return c != CellTable<Cell>::kNone && cells_[c].ground_points > 0;
  }

  /// Points in a layer's two bins and in the kPeakSpan bins beside it.
  struct PeakAndSpan {
    double peak, span;
    /// The two bins hold `ratio` times the points per bin of the span (a
    /// surface's layer against the side of what stands on it or hangs from it).
    bool peaked(float ratio) const { return peak / 2.0 >= ratio * span / kPeakSpan; }
  };
  /// Bins `b` and `next`, and the kPeakSpan bins from `span_first` up. O(kPeakSpan).
  static PeakAndSpan peak_and_span(const HeightColumn& column, std::int32_t b, std::int32_t next,
                                   std::int32_t span_first) {
    PeakAndSpan counts{static_cast<double>(column.count(b)) + column.count(next), 0.0};
    for (std::int32_t i = span_first; i < span_first + kPeakSpan; ++i) counts.span += column.count(i);
    return counts;
  }
  /// The peak and span counts of the lowest supported layer of cell (ix, iy),
  /// which must have one. O(kPeakSpan).
  PeakAndSpan lowest_layer_counts(std::int32_t ix, std::int32_t iy) const {
    const HeightColumn& column = cells_[cells_.find(ix, iy)].heights;
    const std::int32_t b = *column.lowest_supported(params_.support);
    return peak_and_span(column, b, b + 1, b + 2);
  }

  /// How much a slope through cell k rises across a cell [m], from the
  /// layers of its four neighbours; an axis counts only where
  /// the layers rise (or fall) monotonically through k, by the smaller of
  /// the two steps (an object's cell beside level ground is no slope). At
  /// most tan(max_slope) x cell_size. O(1).
  float slope_rise(const Neighbourhood& n) const {
    const std::optional<float>& centre = n.layer[4];
    if (!centre) return 0.0f;
    auto gradient = [&](std::int32_t dx, std::int32_t dy) {
      const std::optional<float>& before = n.layer[static_cast<std::size_t>(4 - 3 * dy - dx)];
      const std::optional<float>& after = n.layer[static_cast<std::size_t>(4 + 3 * dy + dx)];
      if (!before || !after) return 0.0f;
      const float d1 = *centre - *before, d2 = *after - *centre;
      if (d1 * d2 <= 0.0f) return 0.0f;
      return std::min(std::fabs(d1), std::fabs(d2));
    };
    const float gx = gradient(1, 0), gy = gradient(0, 1);  // [m per cell]
    return std::min(rise_per_cell_, std::sqrt(gx * gx + gy * gy));
  }

  bool is_ceiling(Key k, float z) const {
    const std::optional<float> top = highest_layer(k.ix, k.iy);
    if (!top || z < *top - params_.ceiling_tolerance) return false;
    return ceiling_shaped(k, *top, highest_layers_around(k));
  }

  /// `top_at(dx, dy)` for ceiling_shaped: the highest layer of the cell
  /// (dx, dy) from k, looked up at each call.
  struct HighestLayersAround {
    const HeightMapGround* ground;
    Key k;
    std::optional<float> operator()(std::int32_t dx, std::int32_t dy) const {
      return ground->highest_layer(k.ix + dx, k.iy + dy);
    }
  };
  HighestLayersAround highest_layers_around(Key k) const { return HighestLayersAround{this, k}; }

  /// True when cell k's highest layer, at `top` [m], is shaped like a
  /// ceiling: peaked, and level with ceiling_min_agreement of the 24 cells
  /// within two rings, whose highest layers `top_at(dx, dy)` gives. At most
  /// 24 calls of top_at.
  template <class TopAt>
  bool ceiling_shaped(Key k, float top, const TopAt& top_at) const {
    // A surface seen from below piles its points into its bins; the top of a
    // tall object's side does not (its points spread evenly over heights).
    const HeightColumn& column = cells_[cells_.find(k.ix, k.iy)].heights;
    const std::int32_t b = *column.highest_supported(params_.support);
    if (!peak_and_span(column, b, b - 1, b - 2 - kPeakSpan).peaked(params_.ceiling_peak_ratio)) return false;
    // The 24 cells within two rings; stops once the outcome is certain.
    constexpr int kCells = 24;
    const float needed = params_.ceiling_min_agreement * static_cast<float>(kCells);
    int agreeing = 0;
    int left = kCells;
    for (std::int32_t dy = -2; dy <= 2; ++dy) {
      for (std::int32_t dx = -2; dx <= 2; ++dx) {
        if (dx == 0 && dy == 0) continue;
        --left;
        const std::optional<float> other = top_at(dx, dy);
        if (other && std::fabs(*other - top) <= params_.ceiling_flatness) ++agreeing;
        if (static_cast<float>(agreeing) >= needed) return true;
        if (static_cast<float>(agreeing + left) < needed) return false;
      }
    }
    return false;
  }

  /// Bins below a ceiling layer its peak is compared with.
  static constexpr std::int32_t kPeakSpan = 10;
  /// Side of the largest square of highest layers ceiling_height_near
  /// reads into a table on the stack (cells).
  static constexpr std::int32_t kTopsSide = 17;

  /// A cell's heights and how many of its points were classed ground.
  struct Cell {
    HeightColumn heights;
    std::uint32_t ground_points = 0;
  };

  Params params_;
  CellTable<Cell> cells_;
  WallModel walls_;
  float inverse_cell_ = 2.0f;
  float inverse_bin_ = 20.0f;
  float slope_ = 0.27f;
  float lowest_ray_slope_ = -1e30f;
  Eigen::Vector3f sensor_ = Eigen::Vector3f::Zero();  // the last classified point's sensor, world frame
  bool has_sensor_ = false;
  float rise_per_cell_ = 0.13f;
  float early_margin_ = 0.16f;
  std::int32_t search_rings_ = 4;
  std::int32_t layer_bins_ = 3;
};

}  // namespace streamclust
