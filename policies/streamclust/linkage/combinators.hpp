// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Linkage combinators: AllOf (logical AND) and AnyOf (logical OR) of linkage
/// policies, plus the AngularOrEuclidean preset.

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/types.hpp>

#include <cstddef>
#include <tuple>
#include <utility>

namespace streamclust {

/// Links a and b iff EVERY child linkage does (short-circuit, left to right).
///
/// `Params` is `std::tuple<typename Ls::Params...>`, default- and
/// brace-constructible: `AllOf<A, B>::Params{{...A params...}, {...B params...}}`.
/// Children are held by value and built from their Params (each validates its
/// own and throws std::invalid_argument). Symmetric if every child is.
/// `AllOf<>` links everything.
///
/// Complexity: the sum of the children's, at most. Thread safety: as the
/// children (the standard ones are immutable and thread-safe).
///
/// Usage:
/// \code
///   // angular criterion, but never across more than 1 m
///   streamclust::AllOf<streamclust::AngularLinkage, streamclust::EuclideanLinkage> link{{{10.0f, 0.2f}, {1.0f}}};
/// \endcode
template <class... Ls>
class AllOf {
 public:
  using Params = std::tuple<typename Ls::Params...>;

  explicit AllOf(const Params& params) : AllOf(params, std::index_sequence_for<Ls...>{}) {}

  /// True iff all children link a and b. Short-circuits.
  bool operator()(const Sample& a, const Sample& b) const {
    return std::apply([&](const auto&... l) { return (true && ... && static_cast<bool>(l(a, b))); }, children_);
  }

  /// The I-th child linkage.
  template <std::size_t I>
  const auto& child() const {
    return std::get<I>(children_);
  }

 private:
  template <std::size_t... I>
  AllOf(const Params& params, std::index_sequence<I...>) : children_(Ls{std::get<I>(params)}...) {}

  std::tuple<Ls...> children_;
};

/// Links a and b iff ANY child linkage does (short-circuit, left to right:
/// put the cheapest or most often true criterion first).
///
/// `Params` is `std::tuple<typename Ls::Params...>`, default- and
/// brace-constructible. Children held by value. Symmetric if every child is.
/// `AnyOf<>` links nothing.
///
/// Complexity: the sum of the children's, at most. Thread safety: as the children.
///
/// Usage:
/// \code
///   streamclust::AnyOf<streamclust::AngularLinkage, streamclust::EuclideanLinkage> link{{{10.0f, 0.0f}, {0.1f}}};
/// \endcode
template <class... Ls>
class AnyOf {
 public:
  using Params = std::tuple<typename Ls::Params...>;

  explicit AnyOf(const Params& params) : AnyOf(params, std::index_sequence_for<Ls...>{}) {}

  /// True iff at least one child links a and b. Short-circuits.
  bool operator()(const Sample& a, const Sample& b) const {
    return std::apply([&](const auto&... l) { return (false || ... || static_cast<bool>(l(a, b))); }, children_);
  }

  /// The I-th child linkage.
  template <std::size_t I>
  const auto& child() const {
    return std::get<I>(children_);
  }

 private:
  template <std::size_t... I>
  AnyOf(const Params& params, std::index_sequence<I...>) : children_(Ls{std::get<I>(params)}...) {}

  std::tuple<Ls...> children_;
};

/// The angular criterion OR a small Euclidean distance: the second remedy for
/// near-coincident rays (field notes 2.7). Two points closer than the
/// Euclidean threshold are linked whatever their beta, so revisits of the same
/// surface with range noise stay connected; farther pairs use the
/// range-independent angular test. The Euclidean default (0.5 m) is the
/// EuclideanLinkage default and is large for this purpose: pick a few times
/// the range noise, e.g.
/// `AngularOrEuclidean{{{10.0f, 0.0f}, {0.1f}}}` (theta 10 deg, no alpha floor,
/// 10 cm). The angular child is evaluated first.
using AngularOrEuclidean = AnyOf<AngularLinkage, EuclideanLinkage>;

}  // namespace streamclust

static_assert(streamclust::is_linkage_policy_v<streamclust::AngularOrEuclidean>,
              "STREAMCLUST_LINKAGE_POLICY_INVALID: AngularOrEuclidean");
static_assert(streamclust::is_linkage_policy_v<
                  streamclust::AllOf<streamclust::AngularLinkage, streamclust::EuclideanLinkage>>,
              "STREAMCLUST_LINKAGE_POLICY_INVALID: AllOf");
