// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// RuntimeLinkage: angular, Euclidean or range-adaptive linkage chosen at run
/// time (configuration files) without a template instantiation per choice.
/// One predictable branch per pair.

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/linkage/range_adaptive.hpp>
#include <streamclust/types.hpp>

namespace streamclust {

/// Forwards to AngularLinkage, EuclideanLinkage or RangeAdaptiveLinkage.
/// Every child is built (and validates its Params) whatever the kind.
/// Thread safety: const, may be called concurrently. O(1).
class RuntimeLinkage {
 public:
  enum class Kind { angular, euclidean, range_adaptive };
  struct Params {
    Kind kind = Kind::angular;
    AngularLinkage::Params angular{};
    EuclideanLinkage::Params euclidean{};
    RangeAdaptiveLinkage::Params range_adaptive{};
  };

  explicit RuntimeLinkage(const Params& params)
      : kind_(params.kind),
        angular_(params.angular),
        euclidean_(params.euclidean),
        range_adaptive_(params.range_adaptive) {}

  bool operator()(const Sample& a, const Sample& b) const {
    switch (kind_) {
      case Kind::euclidean: return euclidean_(a, b);
      case Kind::range_adaptive: return range_adaptive_(a, b);
      case Kind::angular: break;
    }
    return angular_(a, b);
  }
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
  AngularLinkage angular_;
  EuclideanLinkage euclidean_;
  RangeAdaptiveLinkage range_adaptive_;
};

static_assert(is_linkage_policy_v<RuntimeLinkage>);

}  // namespace streamclust
