// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The compact payload of a linkage combinator (AllOf, AnyOf) from its
/// children's payloads (concepts/linkage.hpp):
///
/// - every child has the same Payload type: that type (shared);
/// - the children have payloads of different types: a ComposedPayload, the
///   distinct payload types one after another, aligned to its size rounded
///   up to a power of two (so a candidate never straddles two cache lines);
///   used when it fits kMaxLinkagePayloadBytes (32);
/// - a child without a payload or with a bound one (made by a const member,
///   concepts/linkage.hpp), no child, or a composed payload over 32 bytes:
///   none (the combinator stays on the Sample path).
///
/// The payload carries the ray when one of its parts does (the first such
/// child's `restore_ray`). Compile time only; a payload is built by the
/// children's own `make_payload` and each child reads only its part, so the
/// combinator decides bit for bit as its children on Samples.

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/types.hpp>

#include <cstddef>
#include <type_traits>

namespace streamclust {
namespace detail {

/// Distinct payload types in first-seen order, each with the first linkage
/// that has it: `PayloadEntries<PayloadEntry<P1, L1>, PayloadEntry<P2, L2>, ...>`.
template <class P, class L>
struct PayloadEntry {
  using payload = P;
  using linkage = L;
};
template <class... Entries>
struct PayloadEntries {};

template <class List, class L>
struct add_payload_entry;
template <class... Es, class L>
struct add_payload_entry<PayloadEntries<Es...>, L> {
  static constexpr bool seen = (std::is_same_v<typename Es::payload, linkage_payload_t<L>> || ...);
  using type = std::conditional_t<seen, PayloadEntries<Es...>,
                                  PayloadEntries<Es..., PayloadEntry<linkage_payload_t<L>, L>>>;
};
template <class List, class... Ls>
struct distinct_payloads {
  using type = List;
};
template <class List, class L, class... Ls>
struct distinct_payloads<List, L, Ls...>
    : distinct_payloads<typename add_payload_entry<List, L>::type, Ls...> {};

/// Index of payload type P in PayloadEntries.
template <class P, class List>
struct payload_index;
template <class P, class E, class... Es>
struct payload_index<P, PayloadEntries<E, Es...>>
    : std::integral_constant<std::size_t,
                             std::is_same_v<P, typename E::payload> ? 0 : 1 + payload_index<P, PayloadEntries<Es...>>::value> {};
template <class P>
struct payload_index<P, PayloadEntries<>> : std::integral_constant<std::size_t, 0> {};

/// The parts, one member per distinct payload (a plain aggregate: trivially
/// copyable when every part is).
template <class... Ps>
struct PayloadParts;
template <class P>
struct PayloadParts<P> {
  P head;
};
template <class P, class Q, class... Ps>
struct PayloadParts<P, Q, Ps...> {
  P head;
  PayloadParts<Q, Ps...> tail;
};

/// The I-th part. O(1).
template <std::size_t I, class Parts>
constexpr const auto& payload_part(const Parts& parts) {
  if constexpr (I == 0) {
    return parts.head;
  } else {
    return payload_part<I - 1>(parts.tail);
  }
}

/// The smallest power of two >= n (n >= 1).
constexpr std::size_t power_of_two_at_least(std::size_t n) {
  std::size_t p = 1;
  while (p < n) p *= 2;
  return p;
}

template <class Entries>
struct ComposedPayloadOf;
/// The composed payload of distinct payload types Es::payload: their parts,
/// aligned (and so sized) to a power of two: 32 bytes for a 16-byte payload
/// with a 4-byte one.
template <class... Es>
struct ComposedPayloadOf<PayloadEntries<Es...>> {
  using Parts = PayloadParts<typename Es::payload...>;
  struct alignas(power_of_two_at_least(sizeof(Parts))) type {
    Parts parts;
  };
};

/// No distinct payload: nothing to compose (named, never stored).
template <>
struct ComposedPayloadOf<PayloadEntries<>> {
  using type = NoPayload;
};

/// The first linkage among Ls with the ray refinement, void for none.
template <class... Ls>
struct first_ray_linkage {
  using type = void;
};
template <class L, class... Ls>
struct first_ray_linkage<L, Ls...> {
  using type = std::conditional_t<has_linkage_ray_payload_v<L>, L, typename first_ray_linkage<Ls...>::type>;
};

/// How a combinator of linkages Ls... stores what its children read.
/// `type`: the payload (void: none); `make(s)`: the payload of Sample s;
/// `part<I>(p)`: what child I reads of payload p; `ray_linkage`: the child
/// whose `restore_ray` rebuilds the ray from `part_of<ray_linkage>(p)`
/// (void: the payload does not carry the ray).
template <class... Ls>
struct CombinedPayload {  // no child: no payload
  using type = void;
  using ray_linkage = void;
};

template <class... Es>
constexpr std::size_t count_entries(PayloadEntries<Es...>) {
  return sizeof...(Es);
}

/// The children's payloads, shared or composed (see the file comment).
template <class L0, class... Ls>
struct CombinedPayload<L0, Ls...> {
  static constexpr bool all_have_one = (has_linkage_static_payload_v<L0> && ... && has_linkage_static_payload_v<Ls>);
  using entries = typename distinct_payloads<PayloadEntries<>, L0, Ls...>::type;
  static constexpr bool shared = all_have_one && count_entries(entries{}) == 1;
  using composed = typename ComposedPayloadOf<std::conditional_t<all_have_one, entries, PayloadEntries<>>>::type;
  static constexpr bool composable =
      all_have_one && !shared && sizeof(composed) <= kMaxLinkagePayloadBytes;
  using type = std::conditional_t<shared, linkage_payload_t<L0>, std::conditional_t<composable, composed, void>>;
  using ray_linkage = std::conditional_t<std::is_void_v<type>, void, typename first_ray_linkage<L0, Ls...>::type>;

  /// What linkage L reads of payload p (a `type`): p itself when shared,
  /// else its part. O(1).
  template <class L, class P>
  static const linkage_payload_t<L>& part_of(const P& p) {
    if constexpr (shared) {
      return p;
    } else {
      return payload_part<payload_index<linkage_payload_t<L>, entries>::value>(p.parts);
    }
  }

  /// The payload of `s`, each part made by its first linkage (only when
  /// `type` is not void). O(1).
  template <class T = type>
  static T make(const Sample& s) {
    if constexpr (shared) {
      return L0::make_payload(s);
    } else {
      return make_composed(s, entries{});
    }
  }

 private:
  template <class... Es>
  static composed make_composed(const Sample& s, PayloadEntries<Es...>) {
    return composed{make_parts<Es...>(s)};
  }
  template <class E, class... Es>
  static PayloadParts<typename E::payload, typename Es::payload...> make_parts(const Sample& s) {
    if constexpr (sizeof...(Es) == 0) {
      return {E::linkage::make_payload(s)};
    } else {
      return {E::linkage::make_payload(s), make_parts<Es...>(s)};
    }
  }
};

}  // namespace detail
}  // namespace streamclust
