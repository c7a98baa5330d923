// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// EuclideanLinkage: link two points closer than a fixed distance.

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/types.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace streamclust {

/// Links a and b iff |a.position - b.position|^2 <= max_distance^2.
///
/// The classic fixed-radius criterion: simple and scale-true, but a fixed
/// threshold over-segments far objects (sparser returns) and under-segments
/// near ones; see AngularLinkage for the range-independent alternative.
///
/// Symmetric bitwise (the difference only changes sign). O(1), no sqrt.
///
/// Compact payload (concepts/linkage.hpp): the criterion reads only the
/// position, stored as a 16-byte `Payload` (padded, so the engine's payload
/// ring never has a candidate straddling two cache lines). The Sample
/// operator is the payload operator on `make_payload(a)`, `make_payload(b)`.
/// Thread safety: immutable; `operator()` is const and thread-safe.
///
/// Usage:
/// \code
///   streamclust::EuclideanLinkage link{{0.3f}};  // 30 cm
///   bool joined = link(sample_a, sample_b);
/// \endcode
class EuclideanLinkage {
 public:
  struct Params {
    float max_distance = 0.5f;  ///< [m], finite, > 0
  };

  /// Throws std::invalid_argument unless max_distance is finite and > 0.
  explicit EuclideanLinkage(const Params& params) : params_(params) {
    if (!std::isfinite(params.max_distance) || !(params.max_distance > 0.0f)) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(params.max_distance));
      throw std::invalid_argument(std::string("EuclideanLinkage: parameter max_distance = ") + buf +
                                  " is invalid; allowed: finite, > 0 m");
    }
    max_distance_sq_ = params.max_distance * params.max_distance;
  }

  /// What the criterion reads of a point: its position. 16 bytes (the
  /// fourth float is padding, always 0), 16-aligned, trivially copyable.
  struct alignas(16) Payload {
    float position[3];  ///< [m] sensor frame (Sample::position)
    float padding;      ///< unused, 0
  };

  /// The payload of `s`: a copy of its position. O(1).
  static Payload make_payload(const Sample& s) {
    return Payload{{s.position.x(), s.position.y(), s.position.z()}, 0.0f};
  }

  /// True iff the squared distance is <= max_distance^2. O(1). Defined as
  /// the payload operator on the two payloads.
  bool operator()(const Sample& a, const Sample& b) const { return (*this)(make_payload(a), make_payload(b)); }

  /// True iff the squared distance is <= max_distance^2. O(1). Eigen's
  /// squaredNorm on mapped arrays: the same float operations as on the
  /// Samples' Eigen::Vector3f positions.
  bool operator()(const Payload& a, const Payload& b) const {
    const Eigen::Map<const Eigen::Vector3f> pa(a.position);
    const Eigen::Map<const Eigen::Vector3f> pb(b.position);
    return (pa - pb).squaredNorm() <= max_distance_sq_;
  }

  const Params& params() const { return params_; }

 private:
  Params params_;
  float max_distance_sq_ = 0.0f;
};

}  // namespace streamclust

static_assert(streamclust::is_linkage_policy_v<streamclust::EuclideanLinkage>,
              "STREAMCLUST_LINKAGE_POLICY_INVALID: EuclideanLinkage");
static_assert(streamclust::has_linkage_payload_v<streamclust::EuclideanLinkage> &&
                  streamclust::is_linkage_payload_valid_v<streamclust::EuclideanLinkage> &&
                  sizeof(streamclust::EuclideanLinkage::Payload) == 16,
              "STREAMCLUST_LINKAGE_PAYLOAD_INVALID: EuclideanLinkage");
