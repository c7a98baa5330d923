// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// EuclideanLinkage: link two points closer than a fixed distance.

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/types.hpp>

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

  /// True iff the squared distance is <= max_distance^2. O(1).
  bool operator()(const Sample& a, const Sample& b) const {
    return (a.position - b.position).squaredNorm() <= max_distance_sq_;
  }

  const Params& params() const { return params_; }

 private:
  Params params_;
  float max_distance_sq_ = 0.0f;
};

}  // namespace streamclust

static_assert(streamclust::is_linkage_policy_v<streamclust::EuclideanLinkage>,
              "STREAMCLUST_LINKAGE_POLICY_INVALID: EuclideanLinkage");
