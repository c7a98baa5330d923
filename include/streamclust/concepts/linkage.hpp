// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Linkage policy concept: the single-linkage predicate between two points
/// found in the same w x w mask.
///
/// | expression             | type      | meaning                                          | complexity |
/// |------------------------|-----------|--------------------------------------------------|------------|
/// | `typename L::Params`   | aggregate | parameters with defaults                         |            |
/// | `L l{params}`          |           | construct; throws std::invalid_argument if bad   |            |
/// | `l(a, b)`              | bool      | a and b (const Sample&) are linked               | O(1)       |
///
/// Must be symmetric (`l(a, b) == l(b, a)`), deterministic, const and
/// thread-safe. It sees position, unit direction, range, intensity and time.
///
/// Optional capability: a compact geometric payload (detected, never
/// required; a linkage without it works unchanged, on the Sample path).
///
/// | expression               | type     | meaning                                                        | complexity |
/// |--------------------------|----------|----------------------------------------------------------------|------------|
/// | `typename L::Payload`    | struct   | what the predicate reads of a point; trivially copyable, <= 32 bytes | |
/// | `l.make_payload(s)`      | Payload  | the payload of Sample `s` (a pure function of `s` and the linkage's parameters) | O(1) |
/// | `l(pa, pb)`              | bool     | the predicate on two payloads (const Payload&)                 | O(1)       |
///
/// Contract: `l(a, b)` on Samples MUST be implemented as
/// `l(l.make_payload(a), l.make_payload(b))`, so that both decide the same
/// bit for bit by construction (the batch oracle calls the Sample version,
/// the engine the payload one). The engine then keeps a ring of payloads
/// beside its ring of Samples (sizeof(Payload) bytes per point, counted in
/// `MemoryUsage::point_ring`) and reads candidates from it: sizeof(Payload)
/// dense bytes per candidate (16 for the standard linkages) instead of a
/// 40-byte Sample, and with a 16-byte (or smaller
/// power-of-two) payload never a candidate straddling two cache lines.
/// The stride is sizeof(Payload), fixed at compile time: a payload of 17 to
/// 32 bytes (a combinator's composed payload, detail::CombinedPayload) should
/// be `alignas(32)` so that it too stays in one cache line. Over 32 bytes a
/// payload would rather be a Sample (40 bytes): the engine rejects it.
/// `has_linkage_payload_v<L>` detects the capability, `linkage_payload_t<L>`
/// names the payload (`detail::NoPayload` without it).
/// `make_payload` is usually static: the payload does not depend on the
/// parameters, so combinators can build theirs from their children's
/// (AllOf/AnyOf of children with static payloads have the capability too).
/// It may instead be a const member (a *bound* payload,
/// `has_linkage_bound_payload_v<L>`) when the payload holds something the
/// parameters decide once per point, e.g. a per-point radius read from a
/// table (ScanAdaptiveLinkage): the engine and the batch clusterer make it
/// with their own linkage object, and a combinator with such a child stays
/// on the Sample path.
///
/// Optional refinement: a payload that carries the ray (detected with
/// `has_linkage_ray_payload_v<L>`).
///
/// | expression               | type | meaning                                                               | complexity |
/// |--------------------------|------|-----------------------------------------------------------------------|------------|
/// | `L::restore_ray(p, s)`   | void | static: writes `s.direction` and `s.range` back from payload `p` (Sample&) | O(1) |
///
/// Contract: for every Sample `a`, `restore_ray(make_payload(a), s)` sets
/// `s.direction` and `s.range` bit for bit to `a`'s. The engine then keeps
/// only position, intensity and time (24 bytes) beside the payload and
/// rebuilds a Sample on demand (`StreamClusterer::sample` returns by value),
/// 16 bytes per windowed point less than a full Sample ring.
///
/// Optional refinement: a test of one payload against many (detected with
/// `has_linkage_link_many_v<L>`), for a vectorised neighbour search.
///
/// | expression                                   | type | meaning                                                        | complexity |
/// |----------------------------------------------|------|----------------------------------------------------------------|------------|
/// | `l.link_many(a, ring, slots, count, linked)` | void | `linked[k] = l(a, ring[slots[k]])` (0 or 1) for k < count      | O(count)   |
///
/// (`a`: const Payload&, `ring`: const Payload*, `slots`: const
/// std::uint32_t*, `linked`: std::uint8_t*.) Contract: the same decisions
/// as the pairwise operator, bit for bit. The engine's neighbour search and
/// the batch clusterer then call it once per point with all its candidates.
///
/// Optional, for the tools: `static Params fit_to_sensor(const Params&, const
/// SensorFit&)` (sensor_fit.hpp, `has_sensor_fit_v<L>`): the Params completed
/// from the sensor's first window and placement before an engine is built.
///
/// Near misses: a linkage with a member NAMED like one of these
/// (`Payload`, `make_payload`, `restore_ray`, `link_many`) that does not
/// have the signature above stops compilation where the engine starts
/// (`STREAMCLUST_LINKAGE_CAPABILITY_INVALID`, naming the expected signature)
/// instead of running on the slower path without a word.

#include <streamclust/detail/member_named.hpp>
#include <streamclust/types.hpp>

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

namespace streamclust {
namespace detail {
template <class L, class = void>
struct is_linkage_policy : std::false_type {};
template <class L>
struct is_linkage_policy<
    L, std::void_t<typename L::Params, decltype(L{std::declval<const typename L::Params&>()}),
                   decltype(std::declval<const L&>()(std::declval<const Sample&>(), std::declval<const Sample&>()))>>
    : std::is_convertible<decltype(std::declval<const L&>()(std::declval<const Sample&>(),
                                                              std::declval<const Sample&>())),
                          bool> {};

/// The payload of a linkage without the capability: empty, never stored.
struct NoPayload {};

template <class L, class = void>
struct has_linkage_payload : std::false_type {};
template <class L>
struct has_linkage_payload<
    L, std::void_t<typename L::Payload, decltype(std::declval<const L&>().make_payload(std::declval<const Sample&>())),
                   decltype(std::declval<const L&>()(std::declval<const typename L::Payload&>(),
                                                     std::declval<const typename L::Payload&>()))>>
    : std::bool_constant<
          std::is_same_v<decltype(std::declval<const L&>().make_payload(std::declval<const Sample&>())),
                         typename L::Payload> &&
          std::is_convertible_v<decltype(std::declval<const L&>()(std::declval<const typename L::Payload&>(),
                                                                  std::declval<const typename L::Payload&>())),
                                bool>> {};

template <class L, class = void>
struct has_linkage_static_payload : std::false_type {};
template <class L>
struct has_linkage_static_payload<L, std::void_t<decltype(L::make_payload(std::declval<const Sample&>()))>>
    : has_linkage_payload<L> {};

template <class L, class = void>
struct has_linkage_ray_payload : std::false_type {};
template <class L>
struct has_linkage_ray_payload<L, std::void_t<decltype(L::restore_ray(std::declval<const typename L::Payload&>(),
                                                                       std::declval<Sample&>()))>>
    : has_linkage_payload<L> {};

template <class L, class = void>
struct has_linkage_link_many : std::false_type {};
template <class L>
struct has_linkage_link_many<
    L, std::void_t<decltype(std::declval<const L&>().link_many(
           std::declval<const typename L::Payload&>(), std::declval<const typename L::Payload*>(),
           std::declval<const std::uint32_t*>(), std::declval<std::size_t>(), std::declval<std::uint8_t*>()))>>
    : has_linkage_payload<L> {};
template <class L, bool = has_linkage_payload<L>::value>
struct linkage_payload {
  using type = NoPayload;
};
template <class L>
struct linkage_payload<L, true> {
  using type = typename L::Payload;
};
}  // namespace detail

template <class L>
inline constexpr bool is_linkage_policy_v = detail::is_linkage_policy<L>::value;

/// True when linkage `L` declares the optional compact payload: `L::Payload`,
/// `Payload make_payload(const Sample&)` (static, or a const member) and
/// `bool operator()(const Payload&, const Payload&) const`.
template <class L>
inline constexpr bool has_linkage_payload_v = detail::has_linkage_payload<L>::value;

/// True when linkage `L` has the compact payload made by a static
/// `make_payload` (independent of the parameters: combinators compose it).
template <class L>
inline constexpr bool has_linkage_static_payload_v = detail::has_linkage_static_payload<L>::value;

/// True when linkage `L` has the compact payload made by a const member
/// `make_payload` (a bound payload: it depends on the parameters).
template <class L>
inline constexpr bool has_linkage_bound_payload_v =
    detail::has_linkage_payload<L>::value && !detail::has_linkage_static_payload<L>::value;

/// True when linkage `L` has the compact payload and its payload carries the
/// ray: `static void restore_ray(const Payload&, Sample&)`.
template <class L>
inline constexpr bool has_linkage_ray_payload_v = detail::has_linkage_ray_payload<L>::value;

/// True when linkage `L` has the compact payload and tests one payload
/// against many: `void link_many(const Payload&, const Payload* ring, const
/// std::uint32_t* slots, std::size_t count, std::uint8_t* linked) const`.
template <class L>
inline constexpr bool has_linkage_link_many_v = detail::has_linkage_link_many<L>::value;
/// `L::Payload` when `has_linkage_payload_v<L>`, else `detail::NoPayload`.
template <class L>
using linkage_payload_t = typename detail::linkage_payload<L>::type;

/// Largest payload the engine accepts [bytes]: a wider one would cost more
/// than the 40-byte Sample it stands for.
inline constexpr std::size_t kMaxLinkagePayloadBytes = 32;

/// True when `L` has no payload, or a payload the engine can store densely:
/// trivially copyable and at most kMaxLinkagePayloadBytes bytes.
template <class L>
inline constexpr bool is_linkage_payload_valid_v =
    !has_linkage_payload_v<L> || (std::is_trivially_copyable_v<linkage_payload_t<L>> &&
                                  sizeof(linkage_payload_t<L>) <= kMaxLinkagePayloadBytes);

namespace detail {
STREAMCLUST_DETAIL_MEMBER_NAME_TRAIT(Payload);
STREAMCLUST_DETAIL_MEMBER_NAME_TRAIT(make_payload);
STREAMCLUST_DETAIL_MEMBER_NAME_TRAIT(restore_ray);
STREAMCLUST_DETAIL_MEMBER_NAME_TRAIT(link_many);

/// The optional capabilities of linkage `L` are whole or absent: a member
/// named like one must have its signature (near misses stop here, each with
/// the signature it needs), and a payload must be storable. True, or a
/// failed static_assert. Compile time only; used by
/// STREAMCLUST_CHECK_LINKAGE_POLICY and by the combinators for their children.
template <class L>
constexpr bool check_linkage_capabilities() {
  if constexpr (is_linkage_policy_v<L>) {
    static_assert(!(names_Payload<L> || names_make_payload<L>) || has_linkage_payload_v<L>,
                  "STREAMCLUST_LINKAGE_CAPABILITY_INVALID: a linkage with a member named `Payload` or "
                  "`make_payload` declares the optional compact payload and needs all three of `struct Payload` "
                  "(trivially copyable, <= 32 bytes), `Payload make_payload(const Sample&)` (static, or a const "
                  "member; returning exactly Payload) and `bool operator()(const Payload&, const Payload&) const` "
                  "(see docs/policies.md, Linkage)");
    static_assert(is_linkage_payload_valid_v<L>,
                  "STREAMCLUST_LINKAGE_PAYLOAD_INVALID: a linkage's optional Payload must be trivially "
                  "copyable and at most 32 bytes (or drop Payload/make_payload to stay on the Sample path)");
    static_assert(!names_restore_ray<L> || has_linkage_ray_payload_v<L>,
                  "STREAMCLUST_LINKAGE_CAPABILITY_INVALID: `restore_ray` is not the optional ray payload: "
                  "expected `static void restore_ray(const Payload&, Sample&)` beside the compact payload "
                  "(see docs/policies.md, Linkage)");
    static_assert(!names_link_many<L> || has_linkage_link_many_v<L>,
                  "STREAMCLUST_LINKAGE_CAPABILITY_INVALID: `link_many` is not the optional one-against-many test: "
                  "expected `void link_many(const Payload& a, const Payload* ring, const std::uint32_t* slots, "
                  "std::size_t count, std::uint8_t* linked) const` beside the compact payload "
                  "(see docs/policies.md, Linkage)");
  }
  return true;
}
}  // namespace detail

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
template <class L>
concept LinkagePolicy = is_linkage_policy_v<L>;
#endif

}  // namespace streamclust

#define STREAMCLUST_CHECK_LINKAGE_POLICY(L)                                                                  \
  static_assert(::streamclust::is_linkage_policy_v<L>,                                                       \
                "STREAMCLUST_LINKAGE_POLICY_INVALID: the linkage slot needs a nested Params aggregate, a "     \
                "constructor from Params and `bool operator()(const Sample&, const Sample&) const` "           \
                "(see docs/policies.md)");                                                                   \
  static_assert(::streamclust::detail::check_linkage_capabilities<L>(), "STREAMCLUST_LINKAGE_CAPABILITY_INVALID")
