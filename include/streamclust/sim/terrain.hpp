// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A height-field shape for outdoor ground: `z = h(x, y)` over an
/// axis-aligned rectangle of the xy plane, the sum of
///
/// - a base height,
/// - waves `amplitude * sin(kx x + ky y + phase)` (rolling terrain),
/// - ramps: `rise * clamp((u - start) / length, 0, 1)` with `u = direction . (x, y)`
///   (a slope band: flat, then rising by `rise` over `length`, then flat),
/// - steps: `height` where `from <= u < to` (a raised strip whose two edges
///   are vertical faces: kerbs; `to = infinity` gives a single step).
///
/// The smooth part (waves and ramps) has a slope bound
/// `sum |amplitude| |k| + sum |rise| / length` (the tangent of the steepest
/// possible slope), which must not exceed `Terrain::kMaxSlope` = tan 15 deg;
/// steps are at most 0.5 m high.
///
/// \code
/// namespace sim = streamclust::sim;
/// sim::Terrain::Params p;
/// p.waves = {{0.8f, 0.2f, 0.05f, 0.0f}};                   // 0.8 m waves, wavelength about 30 m
/// p.ramps = {{{1.0f, 0.0f}, 15.0f, 8.0f, 1.2f}};           // rises 1.2 m over x in [15, 23] (8.5 deg)
/// p.steps = {{{0.0f, 1.0f}, 6.0f, 10.0f, 0.15f}};          // a 0.15 m raised strip for y in [6, 10)
/// const sim::Terrain terrain(p);
/// const float z = terrain.height(3.0f, 7.0f);              // on the strip
/// const std::optional<float> t = terrain.intersect({0, 0, 1.5f}, {0.9f, 0.0f, -0.1f});
/// \endcode
///
/// Ray casting (`intersect`): the ray is clipped to the rectangle and the
/// terrain's height range, cut where it crosses step edges, and marched in
/// each piece with `g(t) = ray z - h`, whose rate of change is at most
/// `L = |d_z| + max_slope() |d_xy|`: a step of `|g| / L` cannot cross the
/// surface, so the march is conservative; steps are at least `min_step`
/// (default 0.05 m along the ray), so a ray dipping below the surface and
/// back within less than that may miss it (grazing rays only). A sign change
/// is refined by bisection to `tolerance` (default 0.1 mm along the ray). A
/// sign change across a step edge is a hit on the vertical face, exact.
/// Cost: O(log) steps near the hit, a few tens for grazing rays, each
/// evaluating every wave and ramp. Origin below the surface (inside the
/// solid): no hit, as for every solid of shapes.hpp. The rectangle has no
/// side walls. Immutable after construction; all members thread-safe.

#include <streamclust/detail/parameter_check.hpp>
#include <streamclust/sim/shapes.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::sim {

/// `amplitude * sin(kx x + ky y + phase)`; wavelength `2 pi / |k|`.
struct TerrainWave {
  float amplitude = 0.0f;  ///< [m]
  float kx = 0.0f;         ///< wave vector [rad/m]
  float ky = 0.0f;         ///< wave vector [rad/m]
  float phase = 0.0f;      ///< [rad]
};

/// A slope band: `rise * clamp((u - start) / length, 0, 1)`, `u = direction . (x, y)`.
struct TerrainRamp {
  Eigen::Vector2f direction{1.0f, 0.0f};  ///< normalized by Terrain
  float start = 0.0f;                      ///< [m] along direction
  float length = 1.0f;                     ///< [m], > 0; slope |rise| / length
  float rise = 0.0f;                       ///< [m], negative: falling
};

/// A raised strip: `height` where `from <= u < to`, `u = direction . (x, y)`;
/// both edges are vertical faces (kerbs).
struct TerrainStep {
  Eigen::Vector2f direction{1.0f, 0.0f};                ///< normalized by Terrain
  float from = 0.0f;                                     ///< [m]
  float to = std::numeric_limits<float>::infinity();    ///< [m], > from; infinity: one step
  float height = 0.15f;                                  ///< [m], |height| <= 0.5, negative: a step down
};

/// The height field described in the file comment; a shape of ShapeSet.
class Terrain {
 public:
  /// Steepest smooth slope allowed: tan 15 deg.
  static constexpr float kMaxSlope = 0.26794919f;
  /// Most steps (edges cut a ray into at most 2 kMaxSteps + 1 pieces).
  static constexpr std::size_t kMaxSteps = 8;
  /// Highest step [m].
  static constexpr float kMaxStepHeight = 0.5f;

  struct Params {
    Eigen::Vector2f lo{-50.0f, -50.0f};  ///< rectangle corner [m], finite, < hi
    Eigen::Vector2f hi{50.0f, 50.0f};    ///< rectangle corner [m]
    float base_height = 0.0f;            ///< [m]
    std::vector<TerrainWave> waves;
    std::vector<TerrainRamp> ramps;
    std::vector<TerrainStep> steps;  ///< at most kMaxSteps
    float min_step = 0.05f;          ///< smallest marching step along the ray [m], in (0, 1]
    float tolerance = 1e-4f;         ///< bisection stops at this interval along the ray [m], in (0, min_step]
  };

  /// Throws std::invalid_argument naming the parameter, its value and the
  /// allowed range (slope bound above kMaxSlope included).
  explicit Terrain(Params params) : p_(std::move(params)) {
    validate();
    for (TerrainRamp& r : p_.ramps) r.direction.normalize();
    for (TerrainStep& s : p_.steps) s.direction.normalize();
    float lo = p_.base_height;
    float hi = p_.base_height;
    for (const TerrainWave& w : p_.waves) {
      lo -= std::abs(w.amplitude);
      hi += std::abs(w.amplitude);
    }
    for (const TerrainRamp& r : p_.ramps) (r.rise < 0.0f ? lo : hi) += r.rise;
    for (const TerrainStep& s : p_.steps) (s.height < 0.0f ? lo : hi) += s.height;
    // Padded against rounding in the sums of height().
    const float pad = 1e-3f + 1e-5f * (std::abs(lo) + std::abs(hi));
    z_lo_ = lo - pad;
    z_hi_ = hi + pad;
  }

  /// The smooth part: base, waves and ramps [m]. O(waves + ramps).
  float smooth_height(float x, float y) const {
    float h = p_.base_height;
    for (const TerrainWave& w : p_.waves) h += w.amplitude * std::sin(w.kx * x + w.ky * y + w.phase);
    for (const TerrainRamp& r : p_.ramps) {
      const float u = r.direction.x() * x + r.direction.y() * y;
      h += r.rise * std::clamp((u - r.start) / r.length, 0.0f, 1.0f);
    }
    return h;
  }

  /// The steps' part at (x, y) [m]. O(steps).
  float step_height(float x, float y) const {
    float h = 0.0f;
    for (const TerrainStep& s : p_.steps) {
      const float u = s.direction.x() * x + s.direction.y() * y;
      if (u >= s.from && u < s.to) h += s.height;
    }
    return h;
  }

  /// The surface height at (x, y) [m] (defined everywhere; the shape only
  /// exists over the rectangle). O(waves + ramps + steps).
  float height(float x, float y) const { return smooth_height(x, y) + step_height(x, y); }

  /// Unit normal at a surface point (a hit): on a step's vertical face (the
  /// point more than 1 cm off the height field) the step's direction, else
  /// the smooth part's normal (central differences over +-2 cm). The side is
  /// unspecified. O(waves + ramps + steps).
  Eigen::Vector3f normal_at(const Eigen::Vector3f& point) const {
    const float x = point.x(), y = point.y();
    if (std::abs(point.z() - height(x, y)) > 0.01f && !p_.steps.empty()) {
      const TerrainStep* nearest = &p_.steps.front();
      float gap = std::numeric_limits<float>::infinity();
      for (const TerrainStep& s : p_.steps) {
        const float u = s.direction.dot(Eigen::Vector2f(x, y));
        const float d = std::min(std::abs(u - s.from), std::isfinite(s.to) ? std::abs(u - s.to) : gap);
        if (d < gap) {
          gap = d;
          nearest = &s;
        }
      }
      return Eigen::Vector3f(nearest->direction.x(), nearest->direction.y(), 0.0f);
    }
    constexpr float kDelta = 0.02f;
    const float gx = (smooth_height(x + kDelta, y) - smooth_height(x - kDelta, y)) / (2.0f * kDelta);
    const float gy = (smooth_height(x, y + kDelta) - smooth_height(x, y - kDelta)) / (2.0f * kDelta);
    return Eigen::Vector3f(-gx, -gy, 1.0f).normalized();
  }

  /// True when (x, y) is over the rectangle.
  bool contains(float x, float y) const { return x >= p_.lo.x() && x <= p_.hi.x() && y >= p_.lo.y() && y <= p_.hi.y(); }

  /// The bound on the smooth part's slope (tangent, <= kMaxSlope).
  float max_slope() const { return slope_bound(p_); }
  /// The same in degrees.
  double max_slope_deg() const { return std::atan(static_cast<double>(max_slope())) * 57.29577951308232; }

  /// The rectangle times the height range (slightly padded).
  Aabb bounds() const {
    return Aabb{Eigen::Vector3f(p_.lo.x(), p_.lo.y(), z_lo_), Eigen::Vector3f(p_.hi.x(), p_.hi.y(), z_hi_)};
  }

  const Params& params() const { return p_; }

  /// The first surface crossing along `origin + t direction`, `0 < t <= t_max`
  /// (units of |direction|), or nothing; see the file comment.
  std::optional<float> intersect(const Eigen::Vector3f& o, const Eigen::Vector3f& d,
                                 float t_max = std::numeric_limits<float>::infinity()) const {
    if (!detail::finite_ray(o, d)) return std::nullopt;
    detail::Interval span;
    span.clip(0.0f, t_max);
    detail::clip_slab(span, o.x(), d.x(), p_.lo.x(), p_.hi.x());
    detail::clip_slab(span, o.y(), d.y(), p_.lo.y(), p_.hi.y());
    detail::clip_slab(span, o.z(), d.z(), z_lo_, z_hi_);
    if (!span.valid || !(span.far < std::numeric_limits<float>::infinity())) return std::nullopt;
    if (contains(o.x(), o.y()) && o.z() <= height(o.x(), o.y())) return std::nullopt;  // inside the solid

    // Pieces between step edges: within one, the steps add a constant.
    float cuts[2 * kMaxSteps + 2];
    std::size_t n = 0;
    cuts[n++] = span.near;
    for (const TerrainStep& s : p_.steps) {
      const float du = s.direction.x() * d.x() + s.direction.y() * d.y();
      if (std::abs(du) < detail::kParallelEpsilon) continue;
      const float u0 = s.direction.x() * o.x() + s.direction.y() * o.y();
      for (const float edge : {s.from, s.to}) {
        const float t = (edge - u0) / du;
        if (t > span.near && t < span.far) cuts[n++] = t;
      }
    }
    cuts[n++] = span.far;
    std::sort(cuts + 1, cuts + n - 1);

    const float norm = d.norm();
    const float lipschitz = std::abs(d.z()) + max_slope() * std::hypot(d.x(), d.y());
    const float min_t = p_.min_step / norm;
    const float tol_t = p_.tolerance / norm;
    bool above_before = false;  // the previous piece ended above the surface
    int iterations = 0;
    for (std::size_t k = 0; k + 1 < n; ++k) {
      const float a = cuts[k];
      const float b = cuts[k + 1];
      if (!(b > a)) continue;
      const float mid = 0.5f * (a + b);
      const float raise = step_height(o.x() + mid * d.x(), o.y() + mid * d.y());
      const auto g = [&](float t) { return o.z() + t * d.z() - (smooth_height(o.x() + t * d.x(), o.y() + t * d.y()) + raise); };
      float t = a;
      float gt = g(a);
      if (above_before && gt <= 0.0f) return a;  // the vertical face of a step edge
      while (t < b) {
        const float step = lipschitz > 0.0f ? std::max(std::abs(gt) / lipschitz, min_t) : b - t;
        const float tn = std::min(t + step, b);
        const float gn = g(tn);
        if (gt > 0.0f && gn <= 0.0f) return bisect(g, t, tn, tol_t);
        if (!(tn > t) || ++iterations > kMaxIterations) return std::nullopt;
        t = tn;
        gt = gn;
      }
      above_before = gt > 0.0f;
    }
    return std::nullopt;
  }

 private:
  static constexpr int kMaxIterations = 100000;

  template <class G>
  static float bisect(const G& g, float lo, float hi, float tol) {
    for (int i = 0; i < 64 && hi - lo > tol; ++i) {
      const float m = 0.5f * (lo + hi);
      if (g(m) > 0.0f) {
        lo = m;
      } else {
        hi = m;
      }
    }
    return 0.5f * (lo + hi);
  }

  static float slope_bound(const Params& p) {
    float s = 0.0f;
    for (const TerrainWave& w : p.waves) s += std::abs(w.amplitude) * std::hypot(w.kx, w.ky);
    for (const TerrainRamp& r : p.ramps) s += std::abs(r.rise) / r.length;
    return s;
  }

  static void require(bool ok, const char* name, double value, const char* allowed) {
    streamclust::detail::require_parameter(ok, "Terrain::Params", name, value, allowed);
  }

  void validate() const {
    require(p_.lo.allFinite(), "lo (a coordinate)", static_cast<double>(p_.lo.sum()), "finite coordinates [m]");
    require(p_.hi.allFinite() && (p_.hi.array() > p_.lo.array()).all(), "hi (a coordinate)",
            static_cast<double>(p_.hi.sum()), "finite coordinates > lo [m]");
    require(std::isfinite(p_.base_height), "base_height", p_.base_height, "a finite value [m]");
    for (const TerrainWave& w : p_.waves) {
      require(std::isfinite(w.amplitude), "waves amplitude", w.amplitude, "a finite value [m]");
      require(std::isfinite(w.kx) && std::isfinite(w.ky), "waves kx or ky", static_cast<double>(w.kx + w.ky),
              "finite values [rad/m]");
      require(std::isfinite(w.phase), "waves phase", w.phase, "a finite value [rad]");
    }
    for (const TerrainRamp& r : p_.ramps) {
      require(r.direction.allFinite() && r.direction.norm() > 1e-6f, "ramps direction (norm)",
              static_cast<double>(r.direction.norm()), "a finite non-zero vector");
      require(std::isfinite(r.start), "ramps start", r.start, "a finite value [m]");
      require(std::isfinite(r.length) && r.length > 0.0f, "ramps length", r.length, "a finite value > 0 [m]");
      require(std::isfinite(r.rise), "ramps rise", r.rise, "a finite value [m]");
    }
    require(p_.steps.size() <= kMaxSteps, "steps (count)", static_cast<double>(p_.steps.size()), "at most 8 steps");
    for (const TerrainStep& s : p_.steps) {
      require(s.direction.allFinite() && s.direction.norm() > 1e-6f, "steps direction (norm)",
              static_cast<double>(s.direction.norm()), "a finite non-zero vector");
      require(std::isfinite(s.from), "steps from", s.from, "a finite value [m]");
      require(s.to > s.from, "steps to", s.to, "a value > from [m] (infinity: a single step)");
      require(std::isfinite(s.height) && std::abs(s.height) <= kMaxStepHeight, "steps height", s.height,
              "a value in [-0.5, 0.5] [m]");
    }
    const float slope = slope_bound(p_);
    require(std::isfinite(slope) && slope <= kMaxSlope, "slope bound (sum |amplitude| |k| + sum |rise| / length)", slope,
            "at most tan 15 deg = 0.268");
    require(std::isfinite(p_.min_step) && p_.min_step > 0.0f && p_.min_step <= 1.0f, "min_step", p_.min_step,
            "a value in (0, 1] [m]");
    require(std::isfinite(p_.tolerance) && p_.tolerance > 0.0f && p_.tolerance <= p_.min_step, "tolerance",
            p_.tolerance, "a value in (0, min_step] [m]");
  }

  Params p_;
  float z_lo_ = 0.0f;
  float z_hi_ = 0.0f;
};

/// Ray-terrain intersection (see Terrain::intersect). O(marching steps).
inline std::optional<float> intersect(const Terrain& terrain, const Eigen::Vector3f& origin,
                                      const Eigen::Vector3f& direction) {
  return terrain.intersect(origin, direction);
}

}  // namespace streamclust::sim
