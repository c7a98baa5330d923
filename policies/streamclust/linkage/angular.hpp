// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// AngularLinkage: the Bogoslavskyi & Stachniss angle criterion on actual rays.

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/detail/blocks_of_four.hpp>
#include <streamclust/detail/hints.hpp>
#include <streamclust/detail/rounded.hpp>
#include <streamclust/types.hpp>

#include <Eigen/Core>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace streamclust {

/// The angular criterion of Bogoslavskyi & Stachniss (depth_clustering):
///
///     beta = atan2(d2 sin(alpha), d1 - d2 cos(alpha)),  d1 = max(range), d2 = min(range)
///
/// and a, b are linked iff beta > theta. beta is the angle at the farther
/// point between its ray and the segment to the nearer point: small beta means
/// a large jump in depth (different objects), large beta a surface seen
/// roughly face-on. Unlike a distance threshold it does not depend on range.
///
/// alpha is the ACTUAL angle between the two rays (depth_clustering takes it
/// from the fixed beam spacing, which does not exist for non-repetitive scans),
/// computed trig-free from the unit directions: cos(alpha) = u1 . u2,
/// sin(alpha) = |u1 x u2|. With sin/cos of theta precomputed the test is
///
///     d2 sin(alpha) cos(theta) > (d1 - d2 cos(alpha)) sin(theta)
///
/// which equals beta > theta for beta in [0, 180] degrees and theta in (0, 90):
/// when d1 - d2 cos(alpha) <= 0 and sin(alpha) > 0, beta >= 90 > theta and the
/// inequality holds since its right side is <= 0 < left side (with d1 >= d2
/// this only happens through rounding; beta < 90 otherwise).
///
/// Near-coincident rays: with alpha ~ 0 (Livox rosette revisits, several
/// points per cell) beta collapses to ~0 as soon as the two ranges differ by
/// noise, so the pure criterion splits flat surfaces (a wall at 10 m with 2 cm
/// noise gives beta = 5 degrees at alpha = 0.01 degrees). Remedy: alpha is
/// floored at `min_ray_angle_deg` (when sin(alpha) < sin(min) and the rays
/// are less than 90 degrees apart, sin/cos of the minimum are used instead);
/// 0 disables the floor (pure criterion). Choose it near the sensor's angular
/// resolution or the cell size. The other remedy is `AngularOrEuclidean`
/// (combinators.hpp): angular OR a small Euclidean distance.
///
/// Exactly symmetric: the operands are put in a canonical order (larger range
/// first, equal ranges ordered by direction) before any arithmetic, so
/// l(a, b) and l(b, a) evaluate the same float operations even when the
/// compiler contracts `x*y - z*w` into an FMA (which makes a x b and b x a
/// round differently). Any strict order works for equal ranges: operands
/// tied by it have equal payloads (same range, same direction), and then
/// both orders perform the same arithmetic on the same values (equal as
/// floats: +0 and -0 components only flip the sign of zero terms, which no
/// comparison below can see).
///
/// Compact payload (concepts/linkage.hpp): the criterion reads only the unit
/// direction and the range, 16 bytes (`Payload`), which the engine keeps in a
/// dense ring beside its Samples. The Sample operator is the payload operator
/// on `make_payload(a)`, `make_payload(b)`, so both agree bit for bit. The
/// payload carries the ray (`restore_ray`), so the engine stores only the rest
/// of a Sample beside it (24 bytes instead of 40).
///
/// Complexity: O(1): a dot and a cross product, one sqrt, no trigonometry.
/// Samples are assumed finite (the projection rejects NaN/inf).
/// Thread safety: immutable; `operator()` is const and thread-safe.
///
/// Usage:
/// \code
///   streamclust::AngularLinkage link{{10.0f, 0.2f}};  // theta = 10 deg, alpha >= 0.2 deg
///   bool joined = link(sample_a, sample_b);
///   float beta = streamclust::AngularLinkage::beta_deg(sample_a, sample_b);  // reference value
/// \endcode
class AngularLinkage {
 public:
  struct Params {
    float theta_deg = 10.0f;          ///< [deg] threshold theta, in (0, 90); link iff beta > theta
    float min_ray_angle_deg = 0.2f;   ///< [deg] floor on alpha, in [0, 90); 0 = pure criterion
  };

  /// Throws std::invalid_argument for theta outside (0, 90) or a floor
  /// outside [0, 90) degrees.
  explicit AngularLinkage(const Params& params) : params_(params) {
    if (!std::isfinite(params.theta_deg) || !(params.theta_deg > 0.0f) || !(params.theta_deg < 90.0f))
      throw error("theta_deg", params.theta_deg, "(0, 90) degrees");
    if (!std::isfinite(params.min_ray_angle_deg) || params.min_ray_angle_deg < 0.0f ||
        !(params.min_ray_angle_deg < 90.0f))
      throw error("min_ray_angle_deg", params.min_ray_angle_deg, "[0, 90) degrees (0 disables the floor)");
    constexpr double deg = 3.14159265358979323846 / 180.0;
    const double theta = static_cast<double>(params.theta_deg) * deg;
    const double floor = static_cast<double>(params.min_ray_angle_deg) * deg;
    sin_theta_ = static_cast<float>(std::sin(theta));
    cos_theta_ = static_cast<float>(std::cos(theta));
    sin_min_ = static_cast<float>(std::sin(floor));
    cos_min_ = static_cast<float>(std::cos(floor));
  }

  /// What the criterion reads of a point: unit direction and range. 16 bytes,
  /// 16-aligned (never straddles a cache line), trivially copyable.
  struct alignas(16) Payload {
    float direction[3];  ///< unit ray (Sample::direction)
    float range;         ///< [m] (Sample::range)
  };

  /// The payload of `s`: copies of its direction and range. O(1).
  static Payload make_payload(const Sample& s) {
    return Payload{{s.direction.x(), s.direction.y(), s.direction.z()}, s.range};
  }

  /// Writes `s.direction` and `s.range` back from `p` (the copies
  /// make_payload took, so bit for bit). O(1).
  static void restore_ray(const Payload& p, Sample& s) {
    s.direction = Eigen::Vector3f(p.direction[0], p.direction[1], p.direction[2]);
    s.range = p.range;
  }

  /// True iff beta > theta (with alpha floored at min_ray_angle). O(1).
  /// Defined as the payload operator on the two payloads.
  STREAMCLUST_ALWAYS_INLINE bool operator()(const Sample& a, const Sample& b) const {
    return (*this)(make_payload(a), make_payload(b));
  }

  /// True iff beta > theta (with alpha floored at min_ray_angle). O(1).
  ///
  /// The canonical order is applied by selecting operand pointers through a
  /// two-entry table, not by a branch: which operand has the larger range is
  /// random in a neighbour search, and a branch on it mispredicts about
  /// every other pair. Same float operations on the same operands as
  /// `p = precedes(a, b) ? a : b`. Forced inline: it runs ~20-30 times per
  /// inserted point, in the engine's innermost loop.
  STREAMCLUST_ALWAYS_INLINE bool operator()(const Payload& a, const Payload& b) const {
    const Payload* const operands[2] = {&a, &b};
    const unsigned first = precedes(a, b) ? 0u : 1u;
    return decide(*operands[first], *operands[first ^ 1u]);
  }

  /// Optional capability (concepts/linkage.hpp): linked[k] = (*this)(a,
  /// ring[slots[k]]) for k < count. With SSE2 (every x86-64) four candidates
  /// at a time, the last count % 4 in one more block padded with repeats of
  /// their first slot: the same float operations, in the same order, on the
  /// same canonically ordered operands as `decide` (IEEE single precision,
  /// sqrt correctly rounded in both, no product fused: detail/rounded.hpp),
  /// selected lane by lane instead of by a pointer table. Without SSE2 the
  /// pairwise operator. O(count).
  void link_many(const Payload& a, const Payload* ring, const std::uint32_t* slots, std::size_t count,
                 std::uint8_t* linked) const {
#if defined(__SSE2__)
    const Lanes lanes(a, *this);
    detail::in_blocks_of_four(slots, count, linked, [&](const std::uint32_t* four, std::uint8_t* out) {
      link_four(lanes, ring, four, out);
    });
#else
    for (std::size_t k = 0; k < count; ++k) linked[k] = (*this)(a, ring[slots[k]]) ? 1u : 0u;
#endif
  }

  /// Reference beta [deg] of the pure criterion (no floor), computed in
  /// double with real atan2: alpha = atan2(|u1 x u2|, u1 . u2),
  /// beta = atan2(d2 sin(alpha), d1 - d2 cos(alpha)). For tests and docs.
  static float beta_deg(const Sample& a, const Sample& b) {
    const Eigen::Vector3d u1 = a.direction.cast<double>();
    const Eigen::Vector3d u2 = b.direction.cast<double>();
    const Eigen::Vector3d c(u1.y() * u2.z() - u1.z() * u2.y(), u1.z() * u2.x() - u1.x() * u2.z(),
                            u1.x() * u2.y() - u1.y() * u2.x());
    const double alpha = std::atan2(c.norm(), u1.dot(u2));
    const double ra = static_cast<double>(a.range);
    const double rb = static_cast<double>(b.range);
    const double d1 = ra > rb ? ra : rb;
    const double d2 = ra > rb ? rb : ra;
    const double beta = std::atan2(d2 * std::sin(alpha), d1 - d2 * std::cos(alpha));
    return static_cast<float>(std::fabs(beta) * 180.0 / 3.14159265358979323846);
  }

  const Params& params() const { return params_; }

 private:
#if defined(__SSE2__)
  /// link_many's subject and thresholds, one per SSE lane.
  struct Lanes {
    __m128 ax, ay, az, ar, sin_min, cos_min, sin_theta, cos_theta;
    Lanes(const Payload& a, const AngularLinkage& l)
        : ax(_mm_set1_ps(a.direction[0])),
          ay(_mm_set1_ps(a.direction[1])),
          az(_mm_set1_ps(a.direction[2])),
          ar(_mm_set1_ps(a.range)),
          sin_min(_mm_set1_ps(l.sin_min_)),
          cos_min(_mm_set1_ps(l.cos_min_)),
          sin_theta(_mm_set1_ps(l.sin_theta_)),
          cos_theta(_mm_set1_ps(l.cos_theta_)) {}
  };

  /// linked[i] = the decision of the subject in `l` against ring[slots[i]],
  /// for i < 4: `decide`, lane by lane. O(1).
  STREAMCLUST_ALWAYS_INLINE static void link_four(const Lanes& l, const Payload* ring, const std::uint32_t* slots,
                                                  std::uint8_t* linked) {
    const __m128 ax = l.ax, ay = l.ay, az = l.az, ar = l.ar;
    const __m128 sin_min = l.sin_min, cos_min = l.cos_min, sin_theta = l.sin_theta, cos_theta = l.cos_theta;
    const __m128 zero = _mm_setzero_ps();
    const auto select = [](__m128 mask, __m128 yes, __m128 no) {
      return _mm_or_ps(_mm_and_ps(mask, yes), _mm_andnot_ps(mask, no));
    };
    const detail::FourColumns b = detail::load_four_columns(ring, slots);  // direction, range
    const __m128 bx = b.x, by = b.y, bz = b.z, br = b.w;
    // precedes(a, b): larger range, then direction (lexicographic, ties true).
    const __m128 tie_z = _mm_cmpge_ps(az, bz);
    const __m128 tie_y = _mm_or_ps(_mm_cmpgt_ps(ay, by), _mm_and_ps(_mm_cmpeq_ps(ay, by), tie_z));
    const __m128 tie_x = _mm_or_ps(_mm_cmpgt_ps(ax, bx), _mm_and_ps(_mm_cmpeq_ps(ax, bx), tie_y));
    const __m128 a_first = _mm_or_ps(_mm_cmpgt_ps(ar, br), _mm_and_ps(_mm_cmpeq_ps(ar, br), tie_x));
    const __m128 px = select(a_first, ax, bx);
    const __m128 py = select(a_first, ay, by);
    const __m128 pz = select(a_first, az, bz);
    const __m128 d1 = select(a_first, ar, br);
    const __m128 qx = select(a_first, bx, ax);
    const __m128 qy = select(a_first, by, ay);
    const __m128 qz = select(a_first, bz, az);
    const __m128 d2 = select(a_first, br, ar);
    // decide(p, q), operation by operation.
    // (_mm_mul_ps is a plain vector product to GCC: without `mul` it could
    // be fused with the sum that follows, as in the scalar decide.)
    const auto mul = [](__m128 x, __m128 y) { return detail::rounded(_mm_mul_ps(x, y)); };
    __m128 cos_a = _mm_add_ps(mul(px, qx), _mm_add_ps(mul(py, qy), mul(pz, qz)));
    const __m128 cx = _mm_sub_ps(mul(py, qz), mul(pz, qy));
    const __m128 cy = _mm_sub_ps(mul(pz, qx), mul(px, qz));
    const __m128 cz = _mm_sub_ps(mul(px, qy), mul(py, qx));
    __m128 sin_a = _mm_sqrt_ps(_mm_add_ps(_mm_add_ps(mul(cx, cx), mul(cy, cy)), mul(cz, cz)));
    const __m128 floored = _mm_and_ps(_mm_cmplt_ps(sin_a, sin_min), _mm_cmpgt_ps(cos_a, zero));
    sin_a = select(floored, sin_min, sin_a);
    cos_a = select(floored, cos_min, cos_a);
    const __m128 left = _mm_mul_ps(_mm_mul_ps(d2, sin_a), cos_theta);
    const __m128 right = _mm_mul_ps(_mm_sub_ps(d1, mul(d2, cos_a)), sin_theta);
    detail::store_four_decisions(_mm_movemask_ps(_mm_cmpgt_ps(left, right)), linked);
  }
#endif

  /// Strict canonical order: larger range first, then direction
  /// (lexicographic). Equal keys mean equal payloads, so either order is
  /// fine. The range test is written branch-free (ties are rare and predicted).
  static bool precedes(const Payload& a, const Payload& b) {
    const bool larger = a.range > b.range;
    if (a.range != b.range) return larger;
    return precedes_tie(a, b);
  }
  /// precedes() for equal ranges: direction, lexicographic.
  static bool precedes_tie(const Payload& a, const Payload& b) {
    for (int i = 0; i < 3; ++i)
      if (a.direction[i] != b.direction[i]) return a.direction[i] > b.direction[i];
    return true;
  }

  /// The criterion on canonically ordered operands: p first (d1 = p.range
  /// >= d2 = q.range). cos(alpha) = u . v (summed as Eigen's dot of two
  /// 3-vectors sums, so the decisions are those of the Eigen-based versions
  /// before link_many) and sin(alpha) = |u x v| written out, each operation
  /// in the order link_many repeats lane by lane. O(1).
  STREAMCLUST_ALWAYS_INLINE bool decide(const Payload& p, const Payload& q) const {
    const float* const u = p.direction;
    const float* const v = q.direction;
    const float d1 = p.range;
    const float d2 = q.range;
    using detail::rounded;  // every product that feeds a sum: never fused (detail/rounded.hpp)
    float cos_a = rounded(u[0] * v[0]) + (rounded(u[1] * v[1]) + rounded(u[2] * v[2]));  // Eigen's dot order
    const float x = rounded(u[1] * v[2]) - rounded(u[2] * v[1]);
    const float y = rounded(u[2] * v[0]) - rounded(u[0] * v[2]);
    const float z = rounded(u[0] * v[1]) - rounded(u[1] * v[0]);
    float sin_a = std::sqrt((rounded(x * x) + rounded(y * y)) + rounded(z * z));
    if (sin_a < sin_min_ && cos_a > 0.0f) {
      sin_a = sin_min_;
      cos_a = cos_min_;
    }
    return d2 * sin_a * cos_theta_ > (d1 - rounded(d2 * cos_a)) * sin_theta_;
  }

  static std::invalid_argument error(const char* name, float value, const char* allowed) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(value));
    return std::invalid_argument(std::string("AngularLinkage: parameter ") + name + " = " + buf +
                                 " is invalid; allowed: " + allowed);
  }

  Params params_;
  float sin_theta_ = 0.0f;
  float cos_theta_ = 1.0f;
  float sin_min_ = 0.0f;
  float cos_min_ = 1.0f;
};

}  // namespace streamclust

static_assert(streamclust::is_linkage_policy_v<streamclust::AngularLinkage>,
              "STREAMCLUST_LINKAGE_POLICY_INVALID: AngularLinkage");
static_assert(streamclust::has_linkage_payload_v<streamclust::AngularLinkage> &&
                  streamclust::is_linkage_payload_valid_v<streamclust::AngularLinkage> &&
                  streamclust::has_linkage_ray_payload_v<streamclust::AngularLinkage> &&
                  sizeof(streamclust::AngularLinkage::Payload) == 16,
              "STREAMCLUST_LINKAGE_PAYLOAD_INVALID: AngularLinkage");
