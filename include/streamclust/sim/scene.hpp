// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A ray-castable world for the scan simulator: static structure (instance
/// 0, each piece with its surface class: ground, wall or ceiling), static
/// objects and moving objects, each object a set of analytic shapes
/// (shapes.hpp, terrain.hpp) with a unique ground-truth instance id > 0 and
/// the class `object`.
///
/// \code
/// namespace sim = streamclust::sim;
/// sim::Scene scene;
/// scene.add_structure(sim::ShapeSet().add(sim::Plane::infinite({0, 0, 1}, {0, 0, 0})),
///                     streamclust::SurfaceClass::ground);  // id 0
/// const int box = scene.add_object("box", sim::ShapeSet().add(sim::Box::aligned({4, -1, 0}, {5, 1, 1})));
/// const int walker = scene.add_moving_object(
///     "person", sim::ShapeSet().add(sim::Capsule::standing(0, 0, 0, 1.7f, 0.3f)),  // local frame, feet at 0
///     sim::Trajectory::back_and_forth({3, -4, 0}, {3, 4, 0}, 1.2f));
/// std::optional<sim::Hit> hit = scene.cast({0, 0, 1}, {1, 0, 0}, /*time=*/0.5);  // world frame
/// \endcode
///
/// Thread safety: `cast` and every other const member are safe to call
/// concurrently; building (the `add_*` members) is not.

#include <streamclust/detail/split_mix.hpp>
#include <streamclust/sim/materials.hpp>
#include <streamclust/sim/ray.hpp>
#include <streamclust/sim/shapes.hpp>
#include <streamclust/sim/terrain.hpp>
#include <streamclust/sim/trajectory.hpp>
#include <streamclust/surface_class.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::sim {

namespace detail {

using streamclust::detail::SplitMix64;

/// Seeds a generator from a user seed and a stream tag, so that different
/// consumers of the same seed get unrelated streams.
inline SplitMix64 make_rng(std::uint64_t seed, std::uint64_t tag) {
  SplitMix64 mix(seed ^ (tag * 0xD1B54A32D192ED03ull));
  return SplitMix64(mix.next());
}

}  // namespace detail

/// Which shape of a ShapeSet a ray hit (ShapeSet::nearest), for
/// ShapeSet::surface_at.
struct ShapePick {
  std::uint8_t kind = 0;    ///< internal: the shape family
  std::uint32_t index = 0;  ///< internal: the shape within its family
};

/// The normal and material at a point of a ShapeSet (ShapeSet::surface_at).
struct SurfacePoint {
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();  ///< unit, the set's frame, either side
  Material material = Material::generic;
};

/// A set of shapes hit as one body: `nearest` returns the closest hit over
/// all of them. Its bounds are kept up to date as shapes are added
/// (infinite planes make them unbounded). Each shape has a material
/// (materials.hpp; `generic` unless given), and decals (flat rectangles on
/// a surface: licence plates, a car's roof) give the hits within 1 cm of
/// them their own material; neither changes where rays hit.
class ShapeSet {
 public:
  ShapeSet& add(const Plane& p, Material m = Material::generic) {
    planes_.push_back(Part<Plane>{p, m});
    if (p.bounded) {
      bounds_.extend(p.bounds());
    } else {
      unbounded_ = true;
    }
    return *this;
  }
  ShapeSet& add(const Box& b, Material m = Material::generic) { return push(boxes_, b, m); }
  ShapeSet& add(const Cylinder& c, Material m = Material::generic) { return push(cylinders_, c, m); }
  ShapeSet& add(const Sphere& s, Material m = Material::generic) { return push(spheres_, s, m); }
  ShapeSet& add(const Ellipsoid& e, Material m = Material::generic) { return push(ellipsoids_, e, m); }
  ShapeSet& add(const Capsule& c, Material m = Material::generic) { return push(capsules_, c, m); }
  ShapeSet& add(const Terrain& t, Material m = Material::generic) { return push(terrains_, t, m); }

  /// All shapes and decals of `other`, in their coordinates and materials.
  ShapeSet& add(const ShapeSet& other) {
    for (const Part<Plane>& p : other.planes_) add(p.shape, p.material);
    for (const Part<Box>& b : other.boxes_) add(b.shape, b.material);
    for (const Part<Cylinder>& c : other.cylinders_) add(c.shape, c.material);
    for (const Part<Sphere>& s : other.spheres_) add(s.shape, s.material);
    for (const Part<Ellipsoid>& e : other.ellipsoids_) add(e.shape, e.material);
    for (const Part<Capsule>& c : other.capsules_) add(c.shape, c.material);
    for (const Part<Terrain>& t : other.terrains_) add(t.shape, t.material);
    decals_.insert(decals_.end(), other.decals_.begin(), other.decals_.end());
    return *this;
  }

  /// A decal: hits within 1 cm of the rectangle `patch` (Plane::rectangle)
  /// take `m` instead of their shape's material. Adds no geometry; the last
  /// decal added wins where decals overlap.
  ShapeSet& decal(const Plane& patch, Material m) {
    decals_.push_back(Part<Plane>{patch, m});
    return *this;
  }

  /// Bounds of the bounded shapes; see `unbounded()`.
  const Aabb& bounds() const { return bounds_; }

  /// The support function of the bounded shapes' footprint: the largest
  /// u . (x, y) over their points for the horizontal unit direction `u` [m].
  /// Exact for boxes, cylinders, spheres, ellipsoids and capsules;
  /// rectangles and terrain count by their bounds' corners. O(shapes).
  float reach(const Eigen::Vector2f& u) const {
    float best = -std::numeric_limits<float>::infinity();
    const auto take = [&](float v) { best = std::max(best, v); };
    const auto corners = [&](const Aabb& b) {
      if (b.lo.x() > b.hi.x()) return;
      take(std::max(u.x() * b.lo.x(), u.x() * b.hi.x()) + std::max(u.y() * b.lo.y(), u.y() * b.hi.y()));
    };
    for (const Part<Plane>& p : planes_) corners(p.shape.bounds());
    for (const Part<Box>& b : boxes_) {
      const Box& x = b.shape;
      const float along = u.x() * x.cos_yaw + u.y() * x.sin_yaw;   // u . box x axis
      const float across = -u.x() * x.sin_yaw + u.y() * x.cos_yaw;  // u . box y axis
      take(u.x() * x.center.x() + u.y() * x.center.y() + std::abs(along) * x.half.x() + std::abs(across) * x.half.y());
    }
    for (const Part<Cylinder>& c : cylinders_) take(u.x() * c.shape.x + u.y() * c.shape.y + c.shape.radius);
    for (const Part<Sphere>& s : spheres_) take(u.dot(s.shape.center.head<2>()) + s.shape.radius);
    for (const Part<Ellipsoid>& e : ellipsoids_) {
      const Eigen::Vector2f scaled(u.x() * e.shape.radii.x(), u.y() * e.shape.radii.y());
      take(u.dot(e.shape.center.head<2>()) + scaled.norm());
    }
    for (const Part<Capsule>& c : capsules_) take(u.x() * c.shape.x + u.y() * c.shape.y + c.shape.radius);
    for (const Part<Terrain>& t : terrains_) corners(t.shape.bounds());
    return best;
  }

  /// The headings of the boxes [rad] (candidate axes of a footprint).
  std::vector<float> box_yaws() const {
    std::vector<float> yaws;
    for (const Part<Box>& b : boxes_) yaws.push_back(std::atan2(b.shape.sin_yaw, b.shape.cos_yaw));
    return yaws;
  }
  /// True when the set holds an infinite plane.
  bool unbounded() const { return unbounded_; }
  std::size_t size() const {
    return planes_.size() + boxes_.size() + cylinders_.size() + spheres_.size() + ellipsoids_.size() + capsules_.size() +
           terrains_.size();
  }
  bool empty() const { return size() == 0; }

  /// The nearest hit distance over all shapes if below `best`, else `best`;
  /// `pick`, when given, is set to the shape hit when the result is below
  /// `best`. `direction` should be a unit vector. O(size()), a height field
  /// O(its marching steps).
  float nearest(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
                float best = std::numeric_limits<float>::infinity(), ShapePick* pick = nullptr) const {
    consider(planes_, 0, origin, direction, best, pick);
    consider(boxes_, 1, origin, direction, best, pick);
    consider(cylinders_, 2, origin, direction, best, pick);
    consider(spheres_, 3, origin, direction, best, pick);
    consider(ellipsoids_, 4, origin, direction, best, pick);
    consider(capsules_, 5, origin, direction, best, pick);
    for (std::size_t i = 0; i < terrains_.size(); ++i) {
      const std::optional<float> hit = terrains_[i].shape.intersect(origin, direction, best);
      if (hit && *hit < best) {
        best = *hit;
        if (pick) *pick = ShapePick{6, static_cast<std::uint32_t>(i)};
      }
    }
    return best;
  }

  /// The nearest hit distance, or nothing.
  std::optional<float> intersect(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) const {
    const float t = nearest(origin, direction);
    if (t < std::numeric_limits<float>::infinity()) return t;
    return std::nullopt;
  }

  /// Normal and material at `point` (the set's frame) on the shape `pick`
  /// (from `nearest`). O(1) plus O(decals); a height field O(its terms).
  SurfacePoint surface_at(const ShapePick& pick, const Eigen::Vector3f& point) const {
    SurfacePoint out;
    switch (pick.kind) {
      case 0: out = at(planes_, pick.index, point); break;
      case 1: out = at(boxes_, pick.index, point); break;
      case 2: out = at(cylinders_, pick.index, point); break;
      case 3: out = at(spheres_, pick.index, point); break;
      case 4: out = at(ellipsoids_, pick.index, point); break;
      case 5: out = at(capsules_, pick.index, point); break;
      default:
        if (pick.index < terrains_.size()) {
          out = SurfacePoint{terrains_[pick.index].shape.normal_at(point), terrains_[pick.index].material};
        }
        break;
    }
    for (const Part<Plane>& d : decals_) {
      const Plane& r = d.shape;
      const Eigen::Vector3f q = point - r.center;
      if (std::abs(q.dot(r.normal)) <= 0.01f && std::abs(q.dot(r.u_axis)) <= r.half_u &&
          std::abs(q.dot(r.v_axis)) <= r.half_v) {
        out.material = d.material;
      }
    }
    return out;
  }

 private:
  template <class S>
  struct Part {
    S shape;
    Material material;
  };

  template <class S>
  ShapeSet& push(std::vector<Part<S>>& v, const S& s, Material m) {
    v.push_back(Part<S>{s, m});
    bounds_.extend(s.bounds());
    return *this;
  }
  template <class S>
  static void consider(const std::vector<Part<S>>& v, std::uint8_t kind, const Eigen::Vector3f& o,
                       const Eigen::Vector3f& d, float& best, ShapePick* pick) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::optional<float> t = sim::intersect(v[i].shape, o, d);
      if (t && *t < best) {
        best = *t;
        if (pick) *pick = ShapePick{kind, static_cast<std::uint32_t>(i)};
      }
    }
  }
  template <class S>
  static SurfacePoint at(const std::vector<Part<S>>& v, std::uint32_t i, const Eigen::Vector3f& point) {
    if (i >= v.size()) return SurfacePoint{};
    return SurfacePoint{normal_at(v[i].shape, point), v[i].material};
  }

  std::vector<Part<Plane>> planes_;
  std::vector<Part<Box>> boxes_;
  std::vector<Part<Cylinder>> cylinders_;
  std::vector<Part<Sphere>> spheres_;
  std::vector<Part<Ellipsoid>> ellipsoids_;
  std::vector<Part<Capsule>> capsules_;
  std::vector<Part<Terrain>> terrains_;
  std::vector<Part<Plane>> decals_;
  Aabb bounds_;
  bool unbounded_ = false;
};

/// An object's box: a footprint rectangle turned by `yaw` about +z and a
/// height range.
struct ObjectBox {
  Eigen::Vector3f center = Eigen::Vector3f::Zero();  ///< [m] box centre
  float yaw = 0.0f;     ///< [rad] heading of the length axis
  float length = 0.0f;  ///< [m] along yaw (>= width)
  float width = 0.0f;   ///< [m]
  float height = 0.0f;  ///< [m]
};

/// The smallest-area footprint of `shapes` among the headings of its boxes
/// and 0 (a car's body, a desk's top, a round tree's axes), with the height
/// range of its bounds; length >= width, yaw in (-pi/2, pi/2]. Empty set:
/// a zero box. O(shapes x boxes).
inline ObjectBox smallest_footprint(const ShapeSet& shapes) {
  constexpr float kHalfPi = 1.57079632679489661923f;
  ObjectBox best;
  if (shapes.empty() || shapes.unbounded()) return best;
  std::vector<float> yaws = shapes.box_yaws();
  yaws.push_back(0.0f);
  float best_area = std::numeric_limits<float>::infinity();
  for (const float yaw : yaws) {
    const Eigen::Vector2f u(std::cos(yaw), std::sin(yaw));
    const Eigen::Vector2f v(-u.y(), u.x());
    const float u_hi = shapes.reach(u), u_lo = -shapes.reach(-u);
    const float v_hi = shapes.reach(v), v_lo = -shapes.reach(-v);
    const float area = (u_hi - u_lo) * (v_hi - v_lo);
    if (!(area < best_area - 1e-6f)) continue;
    best_area = area;
    const float cu = 0.5f * (u_hi + u_lo), cv = 0.5f * (v_hi + v_lo);
    best.center.head<2>() = cu * u + cv * v;
    best.yaw = yaw;
    best.length = u_hi - u_lo;
    best.width = v_hi - v_lo;
  }
  if (best.width > best.length) {
    std::swap(best.width, best.length);
    best.yaw += kHalfPi;
  }
  best.yaw = std::remainder(best.yaw, 2.0f * kHalfPi);  // the axis, not a direction: modulo pi
  if (best.yaw <= -kHalfPi) best.yaw += 2.0f * kHalfPi;
  const Aabb& b = shapes.bounds();
  best.center.z() = 0.5f * (b.lo.z() + b.hi.z());
  best.height = b.hi.z() - b.lo.z();
  return best;
}

/// Ground truth of one object at one time (world frame).
struct ObjectState {
  int instance = 0;
  bool moving = false;
  ObjectBox box;                                     ///< a moving object's yaw: its heading plus its body's
  Eigen::Vector3f velocity = Eigen::Vector3f::Zero();  ///< [m/s] of the box centre
};

/// What a scene knows about one of its objects (for tests, ground truth
/// summaries and tools; not used when casting).
struct ObjectInfo {
  int instance = 0;     ///< > 0, unique in the scene
  std::string label;    ///< e.g. "desk", "person", "trunk"
  bool moving = false;  ///< true: follows a trajectory
  Aabb bounds;          ///< world bounds over all times (swept along the trajectory)
};

/// A world of analytic shapes with ground-truth instance ids. See the file
/// comment for an example and thread safety.
class Scene {
 public:
  /// Adds structure (instance 0) of one surface class: `ground` (floors,
  /// roads, terrain, kerbs, steps, sidewalks), `wall` (walls, facades,
  /// fences) or `ceiling`. Infinite planes are tested for every ray; bounded
  /// shapes are culled by bounds. Throws std::invalid_argument for the
  /// class `object` (objects have their own ids: add_object).
  void add_structure(const ShapeSet& shapes, SurfaceClass surface) {
    if (surface == SurfaceClass::object) {
      throw std::invalid_argument(
          "Scene::add_structure: surface = object is invalid, expected ground, wall or ceiling (objects: add_object)");
    }
    if (shapes.empty()) return;
    const std::int64_t owner = -(++structure_pieces_);
    if (shapes.unbounded()) {
      unbounded_.push_back(Body{shapes.bounds(), shapes, 0, surface, owner});
    } else {
      statics_.push_back(Body{shapes.bounds(), shapes, 0, surface, owner});
    }
  }

  /// Adds `terrain` (of `material`) as ground structure and makes it the scene's ground
  /// height (`ground_height`, which a simulated vehicle follows; the last
  /// terrain added wins).
  void add_terrain(const Terrain& terrain, Material material = Material::generic) {
    add_structure(ShapeSet().add(terrain, material), SurfaceClass::ground);
    ground_ = terrain;
  }

  /// The height [m] of the scene's terrain under (x, y), clamped into its
  /// rectangle; nothing for a scene without one (add_terrain). O(terrain terms).
  std::optional<float> ground_height(float x, float y) const {
    if (!ground_) return std::nullopt;
    const Aabb b = ground_->bounds();
    return ground_->height(std::clamp(x, b.lo.x(), b.hi.x()), std::clamp(y, b.lo.y(), b.hi.y()));
  }

  /// Adds a static object in world coordinates; returns its instance id
  /// (1, 2, ... in order of addition). Throws std::invalid_argument for an
  /// empty or unbounded set.
  int add_object(std::string label, const ShapeSet& shapes) {
    check_object(shapes, "add_object");
    const int id = next_id_++;
    statics_.push_back(Body{shapes.bounds(), shapes, id, SurfaceClass::object, id});
    infos_.push_back(ObjectInfo{id, std::move(label), false, shapes.bounds()});
    anchors_.push_back(shapes.bounds().center());
    footprints_.push_back(smallest_footprint(shapes));
    return id;
  }

  /// Adds a moving object: `local` is given in the object's frame, whose
  /// origin follows `trajectory` and whose +x axis points along the motion
  /// when `face_motion` (otherwise it stays parallel to world +x). Returns
  /// its instance id.
  int add_moving_object(std::string label, const ShapeSet& local, Trajectory trajectory, bool face_motion = true) {
    check_object(local, "add_moving_object");
    const int id = next_id_++;
    Mover m{local, std::move(trajectory), face_motion, {}, Eigen::Vector3f::Zero(), 0.0f, id};
    const Aabb& lb = local.bounds();
    m.local_center = lb.center();
    m.local_radius = 0.5f * (lb.hi - lb.lo).norm();
    // Swept bounds: every position, plus the local body rotated anywhere.
    const float reach = m.local_center.head<2>().norm() + m.local_radius;
    const Aabb path = m.trajectory.swept_bounds();
    m.swept.lo = path.lo - Eigen::Vector3f(reach, reach, -lb.lo.z());
    m.swept.hi = path.hi + Eigen::Vector3f(reach, reach, lb.hi.z());
    if (!face_motion) {
      m.swept.lo = path.lo + lb.lo;
      m.swept.hi = path.hi + lb.hi;
    }
    infos_.push_back(ObjectInfo{id, std::move(label), true, m.swept});
    anchors_.push_back(Eigen::Vector3f::Zero());
    footprints_.push_back(smallest_footprint(local));  // in the object's frame
    movers_.push_back(std::move(m));
    return id;
  }

  /// The first surface along the ray from `origin` in `direction` (world
  /// frame; normalized here if it is not a unit vector) at stream time
  /// `time` [s]: its distance [m], instance id (0 for structure), surface
  /// class, and at the hit point its normal (world frame), material and
  /// reflectance (`surface_reflectance` of the owner's material times the
  /// texture factor; a `generic` structure shape takes its class's default
  /// material, `default_material`), or nothing. Shapes containing the origin
  /// are ignored (shapes.hpp). O(objects) bound tests plus the shapes of the
  /// objects whose bounds the ray crosses. Thread-safe.
  std::optional<Hit> cast(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction, double time) const {
    Eigen::Vector3f d = direction;
    const float n2 = d.squaredNorm();
    if (!(n2 > 1e-24f) || !std::isfinite(n2) || !origin.allFinite()) return std::nullopt;
    if (std::abs(n2 - 1.0f) > 1e-5f) d /= std::sqrt(n2);
    const Eigen::Vector3f inv = detail::safe_inverse(d);

    float best = std::numeric_limits<float>::infinity();
    int instance = -1;
    SurfaceClass surface = SurfaceClass::object;
    // What was hit, for the surface properties once the nearest hit is known.
    const Body* hit_body = nullptr;
    const Mover* hit_mover = nullptr;
    ShapePick pick, candidate;
    float hit_c = 1.0f, hit_s = 0.0f;
    Eigen::Vector3f hit_lo = Eigen::Vector3f::Zero(), hit_ld = Eigen::Vector3f::UnitX();
    const auto take = [&](float t, const Body& b) {
      if (t < best) {
        best = t;
        instance = b.instance;
        surface = b.surface;
        hit_body = &b;
        hit_mover = nullptr;
        pick = candidate;
      }
    };
    for (const Body& b : unbounded_) take(b.shapes.nearest(origin, d, best, &candidate), b);
    for (const Body& b : statics_) {
      if (!detail::ray_hits_aabb(b.bounds, origin, inv, best)) continue;
      take(b.shapes.nearest(origin, d, best, &candidate), b);
    }
    for (const Mover& m : movers_) {
      if (!detail::ray_hits_aabb(m.swept, origin, inv, best)) continue;
      const ObjectPose p = m.trajectory.pose(time);
      const float c = m.face_motion ? p.cos_yaw : 1.0f;
      const float s = m.face_motion ? p.sin_yaw : 0.0f;
      // Into the object frame: rotate by -yaw about the trajectory position.
      const Eigen::Vector3f r = origin - p.position;
      const Eigen::Vector3f lo(c * r.x() + s * r.y(), -s * r.x() + c * r.y(), r.z());
      const Eigen::Vector3f ld(c * d.x() + s * d.y(), -s * d.x() + c * d.y(), d.z());
      // Bounding sphere (unit direction): closest approach and reach.
      const Eigen::Vector3f oc = lo - m.local_center;
      const float tc = -oc.dot(ld);
      const float dist2 = (oc + tc * ld).squaredNorm();
      if (dist2 > m.local_radius * m.local_radius || tc + m.local_radius < 0.0f || tc - m.local_radius > best) {
        continue;
      }
      const float t = m.shapes.nearest(lo, ld, best, &candidate);
      if (t < best) {
        best = t;
        instance = m.instance;
        surface = SurfaceClass::object;
        hit_body = nullptr;
        hit_mover = &m;
        pick = candidate;
        hit_c = c;
        hit_s = s;
        hit_lo = lo;
        hit_ld = ld;
      }
    }
    if (instance < 0) return std::nullopt;
    Hit hit{best, instance, surface};
    // Surface properties at the hit, in the frame of the shapes (texture
    // cells move with a moving object).
    Eigen::Vector3f point;
    SurfacePoint sp;
    std::int64_t owner = instance;
    if (hit_mover) {
      point = hit_lo + best * hit_ld;
      sp = hit_mover->shapes.surface_at(pick, point);
      const Eigen::Vector3f& n = sp.normal;
      sp.normal = Eigen::Vector3f(hit_c * n.x() - hit_s * n.y(), hit_s * n.x() + hit_c * n.y(), n.z());
    } else {
      point = origin + best * d;
      sp = hit_body->shapes.surface_at(pick, point);
      owner = hit_body->owner;
    }
    if (sp.material == Material::generic && surface != SurfaceClass::object) sp.material = default_material(surface);
    hit.normal = sp.normal;
    hit.material = sp.material;
    hit.reflectance = surface_reflectance(material_seed_, owner, sp.material) *
                      texture_factor(material_seed_, owner, sp.material, point);
    return hit;
  }

  /// The material a structure shape added without one is made of: ground
  /// concrete, walls painted, ceilings tiles (objects stay `generic`).
  static Material default_material(SurfaceClass surface) {
    switch (surface) {
      case SurfaceClass::ground: return Material::concrete;
      case SurfaceClass::wall: return Material::painted_wall;
      case SurfaceClass::ceiling: return Material::ceiling_tile;
      case SurfaceClass::object: break;
    }
    return Material::generic;
  }

  /// The seed of every surface's reflectance draw and texture
  /// (materials.hpp; 0 unless set; the ready-made scenes use their seed).
  /// Changes no geometry.
  void set_material_seed(std::uint64_t seed) { material_seed_ = seed; }
  std::uint64_t material_seed() const { return material_seed_; }

  /// The objects, in order of instance id (1, 2, ...). Structure is not listed.
  const std::vector<ObjectInfo>& objects() const { return infos_; }
  /// Number of objects (= the largest instance id).
  std::size_t object_count() const { return infos_.size(); }

  /// A reference point of object `instance` at `time`: the trajectory
  /// position (the local origin, e.g. between a person's feet) for a moving
  /// object, the bounds center for a static one. Throws std::out_of_range
  /// for an unknown id.
  Eigen::Vector3f position(int instance, double time) const {
    if (instance < 1 || instance > static_cast<int>(infos_.size())) {
      std::string msg("Scene::position: unknown instance ");
      msg.append(std::to_string(instance));
      throw std::out_of_range(msg);
    }
    const auto k = static_cast<std::size_t>(instance - 1);
    if (!infos_[k].moving) return anchors_[k];
    return mover(instance).trajectory.position(time);
  }

  /// The box and velocity of object `instance` at stream time `time` [s]:
  /// a static object's smallest footprint (smallest_footprint), a moving
  /// one's body footprint carried along its trajectory, its velocity by a
  /// central difference over +-1 ms. Throws std::out_of_range for an
  /// unknown id. O(trajectory points).
  ObjectState object_state(int instance, double time) const {
    const Eigen::Vector3f anchor = position(instance, time);  // checks the id
    const auto k = static_cast<std::size_t>(instance - 1);
    ObjectState state;
    state.instance = instance;
    state.moving = infos_[k].moving;
    state.box = footprints_[k];
    if (!state.moving) return state;
    const Mover& m = mover(instance);
    const ObjectPose pose = m.trajectory.pose(time);
    const float c = m.face_motion ? pose.cos_yaw : 1.0f;
    const float s = m.face_motion ? pose.sin_yaw : 0.0f;
    const Eigen::Vector3f& local = footprints_[k].center;
    state.box.center = anchor + Eigen::Vector3f(c * local.x() - s * local.y(), s * local.x() + c * local.y(), local.z());
    state.box.yaw = std::remainder(footprints_[k].yaw + std::atan2(s, c), 6.283185307179586f);
    constexpr double kStep = 1e-2;  // [s]
    state.velocity = (m.trajectory.position(time + kStep) - m.trajectory.position(time - kStep)) /
                     static_cast<float>(2.0 * kStep);
    return state;
  }

 private:
  struct Body {
    Aabb bounds;
    ShapeSet shapes;
    int instance = 0;
    SurfaceClass surface = SurfaceClass::object;
    std::int64_t owner = 0;  // the surfaces' owner for materials: the instance, or -(n-th piece of structure)
  };
  struct Mover {
    ShapeSet shapes;  // local frame
    Trajectory trajectory;
    bool face_motion = true;
    Aabb swept;
    Eigen::Vector3f local_center;
    float local_radius = 0.0f;
    int instance = 0;
  };

  const Mover& mover(int instance) const {
    for (const Mover& m : movers_)
      if (m.instance == instance) return m;
    throw std::out_of_range("Scene: instance " + std::to_string(instance) + " does not move");
  }

  static void check_object(const ShapeSet& shapes, const char* where) {
    if (shapes.empty() || shapes.unbounded()) {
      std::string msg("Scene::");
      msg.append(where);
      msg.append(": an object needs at least one shape and no infinite plane");
      throw std::invalid_argument(msg);
    }
  }

  std::vector<Body> unbounded_;
  std::vector<Body> statics_;
  std::vector<Mover> movers_;
  std::vector<ObjectInfo> infos_;
  std::vector<Eigen::Vector3f> anchors_;
  std::vector<ObjectBox> footprints_;  // per object: world frame, a moving one's in its own frame
  std::optional<Terrain> ground_;
  int next_id_ = 1;
  std::int64_t structure_pieces_ = 0;
  std::uint64_t material_seed_ = 0;
};

}  // namespace streamclust::sim
