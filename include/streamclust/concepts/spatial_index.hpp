// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The SpatialIndex policy concept: per-cell storage of point handles.
///
/// | expression                 | type        | meaning                                                              | complexity |
/// |----------------------------|-------------|----------------------------------------------------------------------|------------|
/// | `typename I::Params`       | aggregate   | parameters with defaults                                             |            |
/// | `I i{params}`              |             | construct (empty, no cells until reset)                              |            |
/// | `i.reset(shape)`           | void        | allocate `shape.cell_count()` empty cells                            | O(cells)   |
/// | `i.clear()`                | void        | empty every cell, keep the allocation                                | O(cells)   |
/// | `i.insert(cell, h)`        | PointHandle | store h; returns the handle it displaced from the index, or kNoPoint | O(1) amort.|
/// | `i.remove(cell, h)`        | void        | forget h if still stored (no-op if displaced earlier)                | O(k)       |
/// | `i.for_each(cell, f)`      | void        | call `f(PointHandle)` for every handle stored in the cell            | O(k)       |
/// | `i.size()`                 | std::size_t | handles currently stored                                             | O(1)       |
///
/// Optional capabilities (detected, never required; an index without them
/// works unchanged):
///
/// | expression                 | type        | meaning                                                              | complexity |
/// |----------------------------|-------------|----------------------------------------------------------------------|------------|
/// | `ci.prefetch(cell)`        | any         | hint that `for_each(cell, f)` follows soon (e.g. prefetch the cell's memory); must not change the contents | O(1) |
/// | `ci.heap_bytes()`          | std::size_t | heap bytes held (capacities, not sizes), for `StreamClusterer::memory_usage()`; without it the index's memory is reported as unknown | any |
/// | `ci.max_cell_size()`       | std::size_t | the most handles one cell can ever hold (a bounded index); the engine then sizes its neighbour-search scratch once (w^2 x this) instead of growing it with the densest mask seen so far | O(1) |
/// | `ci.gather(cell, out, room)` | std::size_t | return n, the cell's handle count; when n <= room, `out[0, n)` holds its handles in `for_each` order. `out[0, room)` may be overwritten with anything, nothing past it. The engine passes room >= `max_cell_size()` (bounded cells), grows its buffer and asks again when n > room. Lets it gather a mask without a branch on each cell's occupancy | O(k) |
/// | `ci.youngest(cell)`        | PointHandle | the handle stored last in the cell (the cell is not empty)           | O(1)       |
/// | `ci.gather_older(cell, bound, out, room)` | std::size_t | return n, the count of the cell's handles stored before handle `bound` (older: `std::int32_t(h - bound) < 0`); when n <= room, `out[0, n)` holds them. Nothing past `out + room` is written | O(n + 1) |
///
/// The engine calls `prefetch` for every cell of the mask before it visits
/// them, so the cells' cache misses overlap (`has_spatial_index_prefetch_v`);
/// `is_spatial_index_heap_reporting_v` detects `heap_bytes`,
/// `has_spatial_index_cell_bound_v` detects `max_cell_size`,
/// `has_spatial_index_gather_v` detects `gather`; `has_spatial_index_chain_v`
/// detects `youngest` with `gather_older`, with which the engine reads a
/// crowded cell in O(1) when the new point links its youngest point
/// (engine/cell_chains.hpp).
///
/// `cell` is a CellIndex below the last `reset` shape's cell count; k is the
/// cell's occupancy. A displaced point stays in the window and keeps its edges;
/// it can only no longer be found by later points. The engine removes points
/// in insertion order (oldest first), which indexes may exploit.
/// Not thread-safe: one writer, no concurrent readers.
///
/// Near misses: an index with a member NAMED like an optional capability
/// (`prefetch`, `heap_bytes`, `max_cell_size`, `gather`, `youngest`,
/// `gather_older`) without the signature above stops compilation where the
/// engine starts (`STREAMCLUST_SPATIAL_INDEX_CAPABILITY_INVALID`, naming the
/// expected signature) instead of being ignored. `youngest` and
/// `gather_older` come together.

#include <streamclust/detail/member_named.hpp>
#include <streamclust/types.hpp>

#include <cstddef>
#include <type_traits>
#include <utility>

namespace streamclust {
namespace detail {
struct HandleSink {
  void operator()(PointHandle) const {}
};
template <class I, class = void>
struct is_spatial_index_policy : std::false_type {};
template <class I>
struct is_spatial_index_policy<
    I, std::void_t<typename I::Params, decltype(I{std::declval<const typename I::Params&>()}),
                   decltype(std::declval<I&>().reset(std::declval<const GridShape&>())),
                   decltype(std::declval<I&>().clear()),
                   decltype(std::declval<I&>().insert(CellIndex{}, PointHandle{})),
                   decltype(std::declval<I&>().remove(CellIndex{}, PointHandle{})),
                   decltype(std::declval<const I&>().for_each(CellIndex{}, HandleSink{})),
                   decltype(std::declval<const I&>().size())>>
    : std::bool_constant<
          std::is_convertible_v<decltype(std::declval<I&>().insert(CellIndex{}, PointHandle{})), PointHandle> &&
          std::is_convertible_v<decltype(std::declval<const I&>().size()), std::size_t>> {};

template <class I, class = void>
struct has_spatial_index_prefetch : std::false_type {};
template <class I>
struct has_spatial_index_prefetch<I, std::void_t<decltype(std::declval<const I&>().prefetch(CellIndex{}))>>
    : std::true_type {};
}  // namespace detail

template <class I>
inline constexpr bool is_spatial_index_policy_v = detail::is_spatial_index_policy<I>::value;

namespace detail {
template <class I, class = void>
struct is_spatial_index_heap_reporting : std::false_type {};
template <class I>
struct is_spatial_index_heap_reporting<I, std::void_t<decltype(std::declval<const I&>().heap_bytes())>>
    : std::is_convertible<decltype(std::declval<const I&>().heap_bytes()), std::size_t> {};
}  // namespace detail

/// True when index `I` has the optional `std::size_t heap_bytes() const`.
template <class I>
inline constexpr bool is_spatial_index_heap_reporting_v = detail::is_spatial_index_heap_reporting<I>::value;

namespace detail {
template <class I, class = void>
struct has_spatial_index_cell_bound : std::false_type {};
template <class I>
struct has_spatial_index_cell_bound<I, std::void_t<decltype(std::declval<const I&>().max_cell_size())>>
    : std::is_convertible<decltype(std::declval<const I&>().max_cell_size()), std::size_t> {};
}  // namespace detail

/// True when index `I` has the optional `std::size_t max_cell_size() const`
/// (its cells are bounded).
template <class I>
inline constexpr bool has_spatial_index_cell_bound_v = detail::has_spatial_index_cell_bound<I>::value;

namespace detail {
template <class I, class = void>
struct has_spatial_index_gather : std::false_type {};
template <class I>
struct has_spatial_index_gather<I, std::void_t<decltype(std::declval<const I&>().gather(
                                       CellIndex{}, std::declval<PointHandle*>(), std::size_t{}))>>
    : std::is_convertible<decltype(std::declval<const I&>().gather(CellIndex{}, std::declval<PointHandle*>(),
                                                                   std::size_t{})),
                          std::size_t> {};
}  // namespace detail

/// True when index `I` has the optional
/// `std::size_t gather(CellIndex, PointHandle* out, std::size_t room) const`.
template <class I>
inline constexpr bool has_spatial_index_gather_v = detail::has_spatial_index_gather<I>::value;

namespace detail {
template <class I, class = void>
struct has_spatial_index_chain : std::false_type {};
template <class I>
struct has_spatial_index_chain<
    I, std::void_t<decltype(std::declval<const I&>().youngest(CellIndex{})),
                   decltype(std::declval<const I&>().gather_older(CellIndex{}, PointHandle{},
                                                                  std::declval<PointHandle*>(), std::size_t{}))>>
    : std::bool_constant<std::is_convertible_v<decltype(std::declval<const I&>().youngest(CellIndex{})), PointHandle> &&
                         std::is_convertible_v<decltype(std::declval<const I&>().gather_older(
                                                   CellIndex{}, PointHandle{}, std::declval<PointHandle*>(),
                                                   std::size_t{})),
                                               std::size_t>> {};
}  // namespace detail

/// True when index `I` has the optional `PointHandle youngest(CellIndex) const`
/// and `std::size_t gather_older(CellIndex, PointHandle bound, PointHandle* out,
/// std::size_t room) const` (the crowded-cell reads of engine/cell_chains.hpp).
template <class I>
inline constexpr bool has_spatial_index_chain_v = detail::has_spatial_index_chain<I>::value;

/// True when spatial index `I` offers the optional `prefetch(CellIndex) const`.
template <class I>
inline constexpr bool has_spatial_index_prefetch_v = detail::has_spatial_index_prefetch<I>::value;

namespace detail {
STREAMCLUST_DETAIL_MEMBER_NAME_TRAIT(prefetch);
STREAMCLUST_DETAIL_MEMBER_NAME_TRAIT(heap_bytes);
STREAMCLUST_DETAIL_MEMBER_NAME_TRAIT(max_cell_size);
STREAMCLUST_DETAIL_MEMBER_NAME_TRAIT(gather);
STREAMCLUST_DETAIL_MEMBER_NAME_TRAIT(youngest);
STREAMCLUST_DETAIL_MEMBER_NAME_TRAIT(gather_older);

/// A member of index `I` named like an optional capability has its
/// signature (near misses stop here, each with the signature it needs).
/// True, or a failed static_assert. Used by STREAMCLUST_CHECK_SPATIAL_INDEX_POLICY.
template <class I>
constexpr bool check_spatial_index_capabilities() {
  if constexpr (is_spatial_index_policy_v<I>) {
    static_assert(!names_prefetch<I> || has_spatial_index_prefetch_v<I>,
                  "STREAMCLUST_SPATIAL_INDEX_CAPABILITY_INVALID: `prefetch` is not the optional prefetch hint: "
                  "expected `void prefetch(CellIndex) const` (see docs/policies.md, SpatialIndex)");
    static_assert(!names_heap_bytes<I> || is_spatial_index_heap_reporting_v<I>,
                  "STREAMCLUST_SPATIAL_INDEX_CAPABILITY_INVALID: `heap_bytes` is not the optional memory report: "
                  "expected `std::size_t heap_bytes() const` (see docs/policies.md, SpatialIndex)");
    static_assert(!names_max_cell_size<I> || has_spatial_index_cell_bound_v<I>,
                  "STREAMCLUST_SPATIAL_INDEX_CAPABILITY_INVALID: `max_cell_size` is not the optional cell bound: "
                  "expected `std::size_t max_cell_size() const` (see docs/policies.md, SpatialIndex)");
    static_assert(!names_gather<I> || has_spatial_index_gather_v<I>,
                  "STREAMCLUST_SPATIAL_INDEX_CAPABILITY_INVALID: `gather` is not the optional branch-free read: "
                  "expected `std::size_t gather(CellIndex cell, PointHandle* out, std::size_t room) const` "
                  "(see docs/policies.md, SpatialIndex)");
    static_assert(!(names_youngest<I> || names_gather_older<I>) || has_spatial_index_chain_v<I>,
                  "STREAMCLUST_SPATIAL_INDEX_CAPABILITY_INVALID: `youngest` / `gather_older` are not the optional "
                  "crowded-cell chain: expected both `PointHandle youngest(CellIndex) const` and `std::size_t "
                  "gather_older(CellIndex cell, PointHandle bound, PointHandle* out, std::size_t room) const` "
                  "(see docs/policies.md, SpatialIndex)");
  }
  return true;
}
}  // namespace detail

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
template <class I>
concept SpatialIndexPolicy = is_spatial_index_policy_v<I>;
#endif

}  // namespace streamclust

#define STREAMCLUST_CHECK_SPATIAL_INDEX_POLICY(I)                                                               \
  static_assert(::streamclust::is_spatial_index_policy_v<I>,                                                    \
                "STREAMCLUST_SPATIAL_INDEX_POLICY_INVALID: the spatial_index slot needs a nested Params "       \
                "aggregate, a constructor from Params, reset(GridShape), clear(), "                              \
                "`PointHandle insert(CellIndex, PointHandle)`, remove(CellIndex, PointHandle), "                 \
                "`for_each(CellIndex, F) const` and `size() const` (see docs/policies.md)");                   \
  static_assert(::streamclust::detail::check_spatial_index_capabilities<I>(),                                   \
                "STREAMCLUST_SPATIAL_INDEX_CAPABILITY_INVALID")
