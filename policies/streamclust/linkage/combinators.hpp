// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Linkage combinators: AllOf (logical AND) and AnyOf (logical OR) of linkage
/// policies, plus the AngularOrEuclidean preset.

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/combined_payload.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/types.hpp>

#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

namespace streamclust {
namespace detail {
/// Declares `Payload`, `make_payload` and, when the payload carries the ray,
/// `restore_ray` for a combinator of linkages Ls... (combined_payload.hpp);
/// nothing when they have no payload (the combinator then stays on the
/// Sample path). Only members with the capabilities' exact signatures: no
/// near miss (concepts/linkage.hpp).
template <class Combined, class P = typename Combined::type, class Ray = typename Combined::ray_linkage>
struct CombinatorPayload {
  using Payload = P;
  /// The children's payloads of `s`. O(1).
  static Payload make_payload(const Sample& s) { return Combined::make(s); }
  /// The ray back from the payload (the first child with a ray payload). O(1).
  static void restore_ray(const Payload& p, Sample& s) { Ray::restore_ray(Combined::template part_of<Ray>(p), s); }
};
template <class Combined, class P>
struct CombinatorPayload<Combined, P, void> {
  using Payload = P;
  /// The children's payloads of `s`. O(1).
  static Payload make_payload(const Sample& s) { return Combined::make(s); }
};
template <class Combined>
struct CombinatorPayload<Combined, void, void> {};
}  // namespace detail

/// Links a and b iff EVERY child linkage does (short-circuit, left to right).
///
/// `Params` is `std::tuple<typename Ls::Params...>`, default- and
/// brace-constructible: `AllOf<A, B>::Params{{...A params...}, {...B params...}}`.
/// Children are held by value and built from their Params (each validates its
/// own and throws std::invalid_argument). Symmetric if every child is.
/// `AllOf<>` links everything.
///
/// Compact payload: when every child has one, AllOf has one too and its
/// Sample operator is its payload operator on the two payloads: the
/// children's shared `Payload` type (e.g. `AllOf<AngularLinkage,
/// AngularLinkage>`, 16 bytes), or for different types a composed payload
/// of each distinct one (e.g. `AllOf<RangeAdaptiveLinkage, Gate>` with a
/// 4-byte gate payload: 32 bytes, 32-aligned) when it fits 32 bytes; each
/// child reads its own part. Otherwise (a child without a payload, or more
/// than 32 bytes together) it stays on the Sample path. No `link_many`.
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
class AllOf : public detail::CombinatorPayload<detail::CombinedPayload<Ls...>> {
  using combined = detail::CombinedPayload<Ls...>;
  using payload_type = typename combined::type;  // void: none
  static_assert((detail::check_linkage_capabilities<Ls>() && ...), "STREAMCLUST_LINKAGE_CAPABILITY_INVALID");

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

  /// True iff all children link the two payloads (each its part).
  /// Short-circuits. Only with a payload.
  template <class P, std::enable_if_t<std::is_same_v<P, payload_type>, int> = 0>
  bool operator()(const P& a, const P& b) const {
    return on_payloads(a, b, std::index_sequence_for<Ls...>{});
  }

  /// The I-th child linkage.
  template <std::size_t I>
  const auto& child() const {
    return std::get<I>(children_);
  }

 private:
  template <std::size_t... I>
  AllOf(const Params& params, std::index_sequence<I...>) : children_(Ls{std::get<I>(params)}...) {}

  /// Each child on its part of the two payloads, left to right, short-circuit.
  template <class P, std::size_t... I>
  bool on_payloads(const P& a, const P& b, std::index_sequence<I...>) const {
    return (true && ... &&
            static_cast<bool>(std::get<I>(children_)(combined::template part_of<Ls>(a),
                                                    combined::template part_of<Ls>(b))));
  }

  std::tuple<Ls...> children_;
};

/// Links a and b iff ANY child linkage does (short-circuit, left to right:
/// put the cheapest or most often true criterion first).
///
/// `Params` is `std::tuple<typename Ls::Params...>`, default- and
/// brace-constructible. Children held by value. Symmetric if every child is.
/// `AnyOf<>` links nothing.
///
/// Compact payload: as AllOf (shared, or composed up to 32 bytes).
/// `AngularOrEuclidean` composes the angular payload (direction + range, a
/// ray payload) and the Euclidean one (position): 32 bytes, and the engine
/// keeps 24-byte samples beside it.
///
/// Complexity: the sum of the children's, at most. Thread safety: as the children.
///
/// Usage:
/// \code
///   streamclust::AnyOf<streamclust::AngularLinkage, streamclust::EuclideanLinkage> link{{{10.0f, 0.0f}, {0.1f}}};
/// \endcode
template <class... Ls>
class AnyOf : public detail::CombinatorPayload<detail::CombinedPayload<Ls...>> {
  using combined = detail::CombinedPayload<Ls...>;
  using payload_type = typename combined::type;  // void: none
  static_assert((detail::check_linkage_capabilities<Ls>() && ...), "STREAMCLUST_LINKAGE_CAPABILITY_INVALID");

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

  /// True iff at least one child links the two payloads (each its part).
  /// Short-circuits. Only with a payload.
  template <class P, std::enable_if_t<std::is_same_v<P, payload_type>, int> = 0>
  bool operator()(const P& a, const P& b) const {
    return on_payloads(a, b, std::index_sequence_for<Ls...>{});
  }

  /// The I-th child linkage.
  template <std::size_t I>
  const auto& child() const {
    return std::get<I>(children_);
  }

 private:
  template <std::size_t... I>
  AnyOf(const Params& params, std::index_sequence<I...>) : children_(Ls{std::get<I>(params)}...) {}

  /// Each child on its part of the two payloads, left to right, short-circuit.
  template <class P, std::size_t... I>
  bool on_payloads(const P& a, const P& b, std::index_sequence<I...>) const {
    return (false || ... ||
            static_cast<bool>(std::get<I>(children_)(combined::template part_of<Ls>(a),
                                                    combined::template part_of<Ls>(b))));
  }

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
/// 10 cm). The angular child is evaluated first. A composed payload of 32
/// bytes (the angular and the Euclidean ones), which carries the ray.
using AngularOrEuclidean = AnyOf<AngularLinkage, EuclideanLinkage>;

}  // namespace streamclust

static_assert(streamclust::is_linkage_policy_v<streamclust::AngularOrEuclidean>,
              "STREAMCLUST_LINKAGE_POLICY_INVALID: AngularOrEuclidean");
static_assert(streamclust::is_linkage_policy_v<
                  streamclust::AllOf<streamclust::AngularLinkage, streamclust::EuclideanLinkage>>,
              "STREAMCLUST_LINKAGE_POLICY_INVALID: AllOf");
static_assert(streamclust::has_linkage_ray_payload_v<streamclust::AngularOrEuclidean> &&
                  sizeof(streamclust::linkage_payload_t<streamclust::AngularOrEuclidean>) == 32 &&
                  alignof(streamclust::linkage_payload_t<streamclust::AngularOrEuclidean>) == 32,
              "STREAMCLUST_LINKAGE_PAYLOAD_INVALID: AngularOrEuclidean composes a 32-byte payload");
static_assert(streamclust::has_linkage_payload_v<
                  streamclust::AllOf<streamclust::AngularLinkage, streamclust::AngularLinkage>>,
              "STREAMCLUST_LINKAGE_PAYLOAD_INVALID: AllOf of one payload type");
