// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// RuntimeLinkage: angular or Euclidean linkage chosen at run time (command
/// line tools, configuration files) without a template instantiation per
/// choice. One predictable branch per pair.

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/types.hpp>

namespace streamclust {

/// Forwards to AngularLinkage or EuclideanLinkage. Thread safety: const, may
/// be called concurrently. O(1).
class RuntimeLinkage {
 public:
  enum class Kind { angular, euclidean };
  struct Params {
    Kind kind = Kind::angular;
    AngularLinkage::Params angular{};
    EuclideanLinkage::Params euclidean{};
  };

  explicit RuntimeLinkage(const Params& params)
      : kind_(params.kind), angular_(params.angular), euclidean_(params.euclidean) {}

  bool operator()(const Sample& a, const Sample& b) const {
    return kind_ == Kind::angular ? angular_(a, b) : euclidean_(a, b);
  }
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
  AngularLinkage angular_;
  EuclideanLinkage euclidean_;
};

static_assert(is_linkage_policy_v<RuntimeLinkage>);

}  // namespace streamclust
