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

#include <algorithm>
#include <cstddef>
#include <cstdint>
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

/// Candidates per call of a combinator's first child's `link_many`: their
/// parts are copied to a stack buffer of this many (1 KB of 16-byte parts).
inline constexpr std::size_t kCombinatorBlock = 64;

/// 0, 1, ..., kCombinatorBlock - 1: the slots of that buffer.
struct IdentitySlots {
  std::uint32_t slot[kCombinatorBlock];
  constexpr IdentitySlots() : slot{} {
    for (std::size_t k = 0; k < kCombinatorBlock; ++k) slot[k] = static_cast<std::uint32_t>(k);
  }
};
inline constexpr IdentitySlots kIdentitySlots{};

/// The optional `link_many` (concepts/linkage.hpp) of combinator `Derived`
/// with payload P, when its first child has one: the first child decides
/// every candidate at once on its parts (in blocks of kCombinatorBlock
/// candidates copied together, or on the ring itself when the payload is
/// the children's shared one), then the other children decide, one by one,
/// only the candidates the first left open (AllOf: those it linked; AnyOf:
/// those it did not). The pairwise operator's decisions bit for bit (the
/// first child's `link_many` gives its pairwise ones, the others are the
/// pairwise operator's remaining terms). Nothing when `Enabled` is false.
template <class Derived, class P, bool Enabled>
struct CombinatorLinkMany {};
template <class Derived, class P>
struct CombinatorLinkMany<Derived, P, true> {
  /// linked[k] = the combinator on (a, ring[slots[k]]), for k < count. O(count).
  void link_many(const P& a, const P* ring, const std::uint32_t* slots, std::size_t count,
                 std::uint8_t* linked) const {
    const Derived& self = static_cast<const Derived&>(*this);
    const auto& first = self.template child<0>();
    using First = std::remove_cv_t<std::remove_reference_t<decltype(first)>>;
    using Part = linkage_payload_t<First>;
    using Combined = typename Derived::combined;
    if constexpr (std::is_same_v<Part, P>) {
      first.link_many(a, ring, slots, count, linked);
    } else {
      Part parts[kCombinatorBlock];
      const Part& own = Combined::template part_of<First>(a);
      for (std::size_t done = 0; done < count; done += kCombinatorBlock) {
        const std::size_t n = std::min(kCombinatorBlock, count - done);
        for (std::size_t k = 0; k < n; ++k) parts[k] = Combined::template part_of<First>(ring[slots[done + k]]);
        first.link_many(own, parts, kIdentitySlots.slot, n, linked + done);
      }
    }
    for (std::size_t k = 0; k < count; ++k) {
      if ((linked[k] != 0) == Derived::kRestWhenFirstLinks) linked[k] = self.rest_decides(a, ring[slots[k]]) ? 1 : 0;
    }
  }
};

/// True when a combinator of Ls... with payload P gets `link_many`: it has a
/// payload and its first child has `link_many`.
template <class P, class... Ls>
struct combinator_links_many : std::false_type {};
template <class P, class L, class... Ls>
struct combinator_links_many<P, L, Ls...> : std::bool_constant<!std::is_void_v<P> && has_linkage_link_many_v<L>> {};
}  // namespace detail

namespace detail {
/// The body of AllOf (kAll true: a pair is linked when every child links it)
/// and AnyOf (kAll false: when any child does): the children, built from
/// their Params tuple, asked left to right with a short circuit, on Samples
/// or on their parts of the combined payload.
template <bool kAll, class... Ls>
class Junction : public CombinatorPayload<CombinedPayload<Ls...>>,
                 public CombinatorLinkMany<Junction<kAll, Ls...>, typename CombinedPayload<Ls...>::type,
                                           combinator_links_many<typename CombinedPayload<Ls...>::type, Ls...>::value> {
  using combined = CombinedPayload<Ls...>;
  using payload_type = typename combined::type;  // void: none
  template <class, class, bool>
  friend struct CombinatorLinkMany;
  /// link_many: the other children decide where the first linked (AllOf),
  /// or where it did not (AnyOf).
  static constexpr bool kRestWhenFirstLinks = kAll;
  static_assert((check_linkage_capabilities<Ls>() && ...), "STREAMCLUST_LINKAGE_CAPABILITY_INVALID");

 public:
  using Params = std::tuple<typename Ls::Params...>;

  explicit Junction(const Params& params) : Junction(params, std::index_sequence_for<Ls...>{}) {}

  /// The children's verdict on a and b. Short-circuits.
  bool operator()(const Sample& a, const Sample& b) const {
    if constexpr (!std::is_void_v<payload_type>) {
      return (*this)(this->make_payload(a), this->make_payload(b));
    } else {
      return std::apply([&](const auto&... l) { return join([&] { return static_cast<bool>(l(a, b)); }...); },
                        children_);
    }
  }

  /// The children's verdict on the two payloads (each its part).
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
  Junction(const Params& params, std::index_sequence<I...>) : children_(Ls{std::get<I>(params)}...) {}

  /// The fold of the junction: all (kAll) or any of the verdicts, each
  /// computed only when the ones before did not decide.
  template <class... Verdicts>
  static bool join(Verdicts&&... v) {
    if constexpr (kAll) {
      return (true && ... && v());
    } else {
      return (false || ... || v());
    }
  }

  /// Children `Offset + I...` on their parts of the two payloads, left to
  /// right, short-circuit.
  template <std::size_t Offset = 0, class P, std::size_t... I>
  bool on_payloads(const P& a, const P& b, std::index_sequence<I...>) const {
    return join([&] {
      using Child = std::tuple_element_t<Offset + I, std::tuple<Ls...>>;
      return static_cast<bool>(
          std::get<Offset + I>(children_)(combined::template part_of<Child>(a), combined::template part_of<Child>(b)));
    }...);
  }
  /// Every child but the first on the two payloads (for link_many).
  template <class P>
  bool rest_decides(const P& a, const P& b) const {
    return on_payloads<1>(a, b, std::make_index_sequence<sizeof...(Ls) - 1>{});
  }

  std::tuple<Ls...> children_;
};
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
/// than 32 bytes together) it stays on the Sample path. With a payload and a
/// first child with `link_many`, AllOf has `link_many` too: the first child
/// tests every candidate at once, the others only those it linked (put the
/// vectorised child first).
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
class AllOf : public detail::Junction<true, Ls...> {
 public:
  using detail::Junction<true, Ls...>::Junction;
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
class AnyOf : public detail::Junction<false, Ls...> {
 public:
  using detail::Junction<false, Ls...>::Junction;
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
