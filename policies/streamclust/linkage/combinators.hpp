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
#include <type_traits>
#include <utility>

namespace streamclust {
namespace detail {
/// The payload shared by linkages `Ls...`: their common `Payload` type when
/// every one has the compact-payload capability with the SAME payload type
/// (then `make_payload` is the same static function of the Sample for all),
/// else void. `first` is the first linkage (void for none).
template <class... Ls>
struct common_linkage_payload {
  using type = void;
  using first = void;
};
template <class L, class... Ls>
struct common_linkage_payload<L, Ls...> {
  static constexpr bool shared = (has_linkage_payload_v<L> && ... && has_linkage_payload_v<Ls>)&&(
      std::is_same_v<linkage_payload_t<L>, linkage_payload_t<Ls>> && ...);
  using type = std::conditional_t<shared, linkage_payload_t<L>, void>;
  using first = L;
};

/// Declares `Payload` and `make_payload` for a combinator whose children
/// share payload type P (nothing when P is void: the combinator then stays
/// on the Sample path).
template <class P, class First>
struct CombinatorPayload {
  using Payload = P;
  /// The children's common payload of `s`. O(1).
  static Payload make_payload(const Sample& s) { return First::make_payload(s); }
  /// The ray back from the payload, when the children's payload carries it
  /// (`has_linkage_ray_payload_v`). O(1).
  template <class F = First>
  static auto restore_ray(const Payload& p, Sample& s) -> decltype(F::restore_ray(p, s)) {
    F::restore_ray(p, s);
  }
};
template <class First>
struct CombinatorPayload<void, First> {};
}  // namespace detail

/// Links a and b iff EVERY child linkage does (short-circuit, left to right).
///
/// `Params` is `std::tuple<typename Ls::Params...>`, default- and
/// brace-constructible: `AllOf<A, B>::Params{{...A params...}, {...B params...}}`.
/// Children are held by value and built from their Params (each validates its
/// own and throws std::invalid_argument). Symmetric if every child is.
/// `AllOf<>` links everything.
///
/// Compact payload: when every child has it with the same `Payload` type
/// (e.g. `AllOf<AngularLinkage, AngularLinkage>`), AllOf has it too and its
/// Sample operator is its payload operator on the two payloads; otherwise
/// (mixed payloads, or a child without one) it stays on the Sample path.
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
class AllOf : public detail::CombinatorPayload<typename detail::common_linkage_payload<Ls...>::type,
                                               typename detail::common_linkage_payload<Ls...>::first> {
  using payload_type = typename detail::common_linkage_payload<Ls...>::type;  // void: none

 public:
  using Params = std::tuple<typename Ls::Params...>;

  explicit AllOf(const Params& params) : AllOf(params, std::index_sequence_for<Ls...>{}) {}

  /// True iff all children link a and b. Short-circuits.
  bool operator()(const Sample& a, const Sample& b) const {
    if constexpr (!std::is_void_v<payload_type>) {
      return (*this)(this->make_payload(a), this->make_payload(b));
    } else {
      return std::apply([&](const auto&... l) { return (true && ... && static_cast<bool>(l(a, b))); }, children_);
    }
  }

  /// True iff all children link the two payloads. Short-circuits. Only when
  /// the children share a payload type P.
  template <class P, std::enable_if_t<std::is_same_v<P, payload_type>, int> = 0>
  bool operator()(const P& a, const P& b) const {
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
/// Compact payload: as AllOf (only when every child has one, of the same
/// type). `AngularOrEuclidean` mixes two payloads (direction + range,
/// position): together 28 bytes, over the 16-byte limit, so it stays on the
/// Sample path.
///
/// Complexity: the sum of the children's, at most. Thread safety: as the children.
///
/// Usage:
/// \code
///   streamclust::AnyOf<streamclust::AngularLinkage, streamclust::EuclideanLinkage> link{{{10.0f, 0.0f}, {0.1f}}};
/// \endcode
template <class... Ls>
class AnyOf : public detail::CombinatorPayload<typename detail::common_linkage_payload<Ls...>::type,
                                               typename detail::common_linkage_payload<Ls...>::first> {
  using payload_type = typename detail::common_linkage_payload<Ls...>::type;  // void: none

 public:
  using Params = std::tuple<typename Ls::Params...>;

  explicit AnyOf(const Params& params) : AnyOf(params, std::index_sequence_for<Ls...>{}) {}

  /// True iff at least one child links a and b. Short-circuits.
  bool operator()(const Sample& a, const Sample& b) const {
    if constexpr (!std::is_void_v<payload_type>) {
      return (*this)(this->make_payload(a), this->make_payload(b));
    } else {
      return std::apply([&](const auto&... l) { return (false || ... || static_cast<bool>(l(a, b))); }, children_);
    }
  }

  /// True iff at least one child links the two payloads. Short-circuits.
  /// Only when the children share a payload type P.
  template <class P, std::enable_if_t<std::is_same_v<P, payload_type>, int> = 0>
  bool operator()(const P& a, const P& b) const {
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
/// 10 cm). The angular child is evaluated first. No compact payload (the
/// children's payloads differ, 28 bytes together): the Sample path.
using AngularOrEuclidean = AnyOf<AngularLinkage, EuclideanLinkage>;

}  // namespace streamclust

static_assert(streamclust::is_linkage_policy_v<streamclust::AngularOrEuclidean>,
              "STREAMCLUST_LINKAGE_POLICY_INVALID: AngularOrEuclidean");
static_assert(streamclust::is_linkage_policy_v<
                  streamclust::AllOf<streamclust::AngularLinkage, streamclust::EuclideanLinkage>>,
              "STREAMCLUST_LINKAGE_POLICY_INVALID: AllOf");
static_assert(!streamclust::has_linkage_payload_v<streamclust::AngularOrEuclidean>,
              "AngularOrEuclidean mixes two payloads: the Sample path");
static_assert(streamclust::has_linkage_payload_v<
                  streamclust::AllOf<streamclust::AngularLinkage, streamclust::AngularLinkage>>,
              "STREAMCLUST_LINKAGE_PAYLOAD_INVALID: AllOf of one payload type");
