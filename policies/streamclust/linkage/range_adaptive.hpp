// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// RangeAdaptiveLinkage: a Euclidean radius that grows with range, so that
/// it holds on dense near surfaces and on sparse far objects alike.

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/detail/blocks_of_four.hpp>
#include <streamclust/detail/hints.hpp>
#include <streamclust/detail/rounded.hpp>
#include <streamclust/types.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace streamclust {

/// Links a and b iff
///
///     |a.position - b.position| <= max(min_distance, range_factor * min(a.range, b.range))
///
/// The radius is the lateral spacing of the returns at the nearer point's
/// range (a sensor's angular spacing of about range_factor radians) with a
/// floor for the range noise near the sensor. Unlike the angular criterion
/// it does not depend on the depth difference of neighbouring returns
/// relative to their spacing, so near-coincident rays with range noise (the
/// Avia's dense centre) stay linked; unlike a fixed radius it widens with
/// the spacing of far returns (a Mid-360 at 20-30 m). The numbers behind
/// the defaults: docs/design-decisions.md (a linkage for dense and sparse
/// regions).
///
/// What it reads: `position` (the point; in the world frame when the
/// stream is motion-compensated) and `range` (the length of the ray the
/// sensor measured it on). It never rebuilds one from the other.
///
/// Exactly symmetric, bit for bit, whatever the compiler contracts: the
/// threshold reads min(range), the same value in either order; a and b only
/// swap the sign of each coordinate difference, which its square does not
/// see; the three squares are summed in one fixed order, each product
/// rounded on its own (detail/rounded.hpp), so no FMA fuses one order and
/// not the other.
///
/// Compact payload (concepts/linkage.hpp): position and range, 16 bytes,
/// kept by the engine in its payload ring (it carries no direction, so the
/// engine keeps full Samples beside it). The Sample operator is the payload
/// operator on `make_payload(a)`, `make_payload(b)`. `link_many` tests four
/// candidates at a time with SSE2, with the operations of the pairwise
/// operator in the same order: the same decisions bit for bit.
///
/// Complexity: O(1) per pair: three differences, three squares, a min, a
/// max, no sqrt. Samples are assumed finite (the projection rejects
/// NaN/inf). Thread safety: immutable; const members are thread-safe.
///
/// Usage:
/// \code
///   streamclust::RangeAdaptiveLinkage link{{0.2f, 0.05f}};  // 20 cm, 5 cm per metre of range
///   bool joined = link(sample_a, sample_b);    // at 25 m: within 1.25 m
///   float radius = link.radius(10.0f, 12.0f);  // 0.5 m
/// \endcode
class RangeAdaptiveLinkage {
 public:
  struct Params {
    /// [m] radius near the sensor (the floor), finite, in (0, 100]
    float min_distance = 0.2f;
    /// [m per m of range] growth of the radius with the nearer range, finite,
    /// in [0, 1]; 0 = a fixed radius of min_distance (EuclideanLinkage)
    float range_factor = 0.05f;
  };

  /// Throws std::invalid_argument naming the parameter, its value and the
  /// allowed range.
  explicit RangeAdaptiveLinkage(const Params& params) : params_(params) {
    if (!std::isfinite(params.min_distance) || !(params.min_distance > 0.0f) || params.min_distance > 100.0f)
      throw error("min_distance", params.min_distance, "finite, in (0, 100] m");
    if (!std::isfinite(params.range_factor) || params.range_factor < 0.0f || params.range_factor > 1.0f)
      throw error("range_factor", params.range_factor, "finite, in [0, 1] m per m of range");
  }

  /// What the criterion reads of a point: position and range. 16 bytes,
  /// 16-aligned (never straddles a cache line), trivially copyable.
  struct alignas(16) Payload {
    float position[3];  ///< [m] Sample::position
    float range;        ///< [m] Sample::range, the measured ray's length
  };

  /// The payload of `s`: copies of its position and range. O(1).
  static Payload make_payload(const Sample& s) {
    return Payload{{s.position.x(), s.position.y(), s.position.z()}, s.range};
  }

  /// The link radius [m] of two points at ranges `range_a`, `range_b` [m]:
  /// max(min_distance, range_factor * min(range_a, range_b)). O(1).
  float radius(float range_a, float range_b) const {
    return std::max(params_.min_distance, params_.range_factor * std::min(range_a, range_b));
  }

  /// True iff |a - b| <= radius(a.range, b.range). O(1). Defined as the
  /// payload operator on the two payloads.
  STREAMCLUST_ALWAYS_INLINE bool operator()(const Sample& a, const Sample& b) const {
    return (*this)(make_payload(a), make_payload(b));
  }

  /// True iff |a - b| <= radius(a.range, b.range), compared squared. O(1).
  STREAMCLUST_ALWAYS_INLINE bool operator()(const Payload& a, const Payload& b) const {
    using detail::rounded;  // every product that feeds a sum: never fused (detail/rounded.hpp)
    const float dx = a.position[0] - b.position[0];
    const float dy = a.position[1] - b.position[1];
    const float dz = a.position[2] - b.position[2];
    const float squared = (rounded(dx * dx) + rounded(dy * dy)) + rounded(dz * dz);
    const float r = radius(a.range, b.range);
    return squared <= r * r;
  }

  /// Optional capability (concepts/linkage.hpp): linked[k] = (*this)(a,
  /// ring[slots[k]]) for k < count. With SSE2 (every x86-64) four candidates
  /// at a time, the last count % 4 in one more block padded with repeats of
  /// their first slot: the pairwise operator's operations in its order
  /// (IEEE single precision, no product fused). Without SSE2 the pairwise
  /// operator. O(count).
  void link_many(const Payload& a, const Payload* ring, const std::uint32_t* slots, std::size_t count,
                 std::uint8_t* linked) const {
#if defined(__SSE2__)
    const Lanes lanes(a, params_);
    detail::in_blocks_of_four(slots, count, linked, [&](const std::uint32_t* four, std::uint8_t* out) {
      link_four(lanes, ring, four, out);
    });
#else
    for (std::size_t k = 0; k < count; ++k) linked[k] = (*this)(a, ring[slots[k]]) ? 1u : 0u;
#endif
  }

  const Params& params() const { return params_; }

 private:
#if defined(__SSE2__)
  /// link_many's subject and parameters, one per SSE lane.
  struct Lanes {
    __m128 ax, ay, az, ar, min_distance, range_factor;
    Lanes(const Payload& a, const Params& p)
        : ax(_mm_set1_ps(a.position[0])),
          ay(_mm_set1_ps(a.position[1])),
          az(_mm_set1_ps(a.position[2])),
          ar(_mm_set1_ps(a.range)),
          min_distance(_mm_set1_ps(p.min_distance)),
          range_factor(_mm_set1_ps(p.range_factor)) {}
  };

  /// linked[i] = the decision of the subject in `l` against ring[slots[i]],
  /// for i < 4: the pairwise operator, lane by lane. O(1).
  STREAMCLUST_ALWAYS_INLINE static void link_four(const Lanes& l, const Payload* ring, const std::uint32_t* slots,
                                                  std::uint8_t* linked) {
    const detail::FourColumns b = detail::load_four_columns(ring, slots);  // x, y, z, range
    const __m128 squared = detail::squared_distances_four(l.ax, l.ay, l.az, b);
    // radius(): std::max(min_distance, factor * std::min(ra, rb)). On finite
    // operands minps / maxps give the same value as std::min / std::max
    // (equal operands are equal floats; ranges are > 0, so no +0/-0 tie).
    const __m128 r = _mm_max_ps(l.min_distance, _mm_mul_ps(l.range_factor, _mm_min_ps(l.ar, b.w)));
    detail::store_four_decisions(_mm_movemask_ps(_mm_cmple_ps(squared, _mm_mul_ps(r, r))), linked);
  }
#endif

  static std::invalid_argument error(const char* name, float value, const char* allowed) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(value));
    return std::invalid_argument(std::string("RangeAdaptiveLinkage: parameter ") + name + " = " + buf +
                                 " is invalid; allowed: " + allowed);
  }

  Params params_;
};

}  // namespace streamclust

static_assert(streamclust::is_linkage_policy_v<streamclust::RangeAdaptiveLinkage>,
              "STREAMCLUST_LINKAGE_POLICY_INVALID: RangeAdaptiveLinkage");
static_assert(streamclust::has_linkage_payload_v<streamclust::RangeAdaptiveLinkage> &&
                  streamclust::is_linkage_payload_valid_v<streamclust::RangeAdaptiveLinkage> &&
                  streamclust::has_linkage_link_many_v<streamclust::RangeAdaptiveLinkage> &&
                  !streamclust::has_linkage_ray_payload_v<streamclust::RangeAdaptiveLinkage> &&
                  sizeof(streamclust::RangeAdaptiveLinkage::Payload) == 16,
              "STREAMCLUST_LINKAGE_PAYLOAD_INVALID: RangeAdaptiveLinkage");
