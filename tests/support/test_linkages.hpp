// SPDX-License-Identifier: MIT
#pragma once
// Linkages written only for the tests: each is in the Linkages list
// (policy_lists.hpp), so it runs the oracle, the linkage contract tests and
// the microbenchmarks without any line of its own there.

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/types.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>

namespace streamclust::test {

/// Links a and b iff they lie within an axis-aligned cube of half-width
/// `half_width` of each other: max(|dx|, |dy|, |dz|) <= half_width (the
/// Chebyshev distance). A linkage WITHOUT an angle parameter, with the
/// compact payload (the position) and its own scalar `link_many`, so that the
/// engine's payload and one-against-many paths run on a second geometry.
/// Symmetric bit for bit (|x - y| == |y - x| in floats). O(1) per pair.
/// Thread safety: immutable; const members are thread-safe.
class BoxLinkage {
 public:
  struct Params {
    float half_width = 0.3f;  ///< [m], finite, > 0
  };

  /// Throws std::invalid_argument unless half_width is finite and > 0.
  explicit BoxLinkage(const Params& params) : params_(params) {
    if (!std::isfinite(params.half_width) || !(params.half_width > 0.0f))
      throw std::invalid_argument("BoxLinkage: parameter half_width is invalid; allowed: finite, > 0 m");
  }

  /// The position, padded to 16 bytes.
  struct alignas(16) Payload {
    float position[3];  ///< [m] sensor frame
    float padding;      ///< unused, 0
  };

  /// The payload of `s`: a copy of its position. O(1).
  static Payload make_payload(const Sample& s) {
    return Payload{{s.position.x(), s.position.y(), s.position.z()}, 0.0f};
  }

  /// True iff the Chebyshev distance is <= half_width. O(1).
  bool operator()(const Payload& a, const Payload& b) const {
    return std::fabs(a.position[0] - b.position[0]) <= params_.half_width &&
           std::fabs(a.position[1] - b.position[1]) <= params_.half_width &&
           std::fabs(a.position[2] - b.position[2]) <= params_.half_width;
  }

  /// The payload operator on the two payloads. O(1).
  bool operator()(const Sample& a, const Sample& b) const { return (*this)(make_payload(a), make_payload(b)); }

  /// `linked[k] = (*this)(a, ring[slots[k]])` for k < count. O(count).
  void link_many(const Payload& a, const Payload* ring, const std::uint32_t* slots, std::size_t count,
                 std::uint8_t* linked) const {
    for (std::size_t k = 0; k < count; ++k) linked[k] = (*this)(a, ring[slots[k]]) ? 1u : 0u;
  }

  const Params& params() const { return params_; }

 private:
  Params params_;
};

static_assert(is_linkage_policy_v<BoxLinkage> && has_linkage_link_many_v<BoxLinkage> &&
              is_linkage_payload_valid_v<BoxLinkage> && !has_linkage_ray_payload_v<BoxLinkage>);

}  // namespace streamclust::test
