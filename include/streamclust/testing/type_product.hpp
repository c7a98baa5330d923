// SPDX-License-Identifier: MIT
#pragma once
// Type-level helpers over std::tuple lists of policies: the cartesian
// product of several lists and a pairwise cover of it, concatenation,
// filtering, and a compile-time loop calling a functor once per type.

#include <array>
#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

namespace streamclust::testing {

/// The tuple of every type of tuple `A` followed by every type of tuple `B`.
template <class A, class B>
struct tuple_concat;
template <class... As, class... Bs>
struct tuple_concat<std::tuple<As...>, std::tuple<Bs...>> {
  using type = std::tuple<As..., Bs...>;
};
template <class A, class B>
using tuple_concat_t = typename tuple_concat<A, B>::type;

namespace internal {
/// Prepends `Head` to every tuple of the tuple of tuples `Tails`.
template <class Head, class Tails>
struct prepend_each;
template <class Head, class... Tails>
struct prepend_each<Head, std::tuple<Tails...>> {
  template <class Tail>
  struct one;
  template <class... Ts>
  struct one<std::tuple<Ts...>> {
    using type = std::tuple<Head, Ts...>;
  };
  using type = std::tuple<typename one<Tails>::type...>;
};

template <class Heads, class Tails>
struct prepend_all;
template <class Tails>
struct prepend_all<std::tuple<>, Tails> {
  using type = std::tuple<>;
};
template <class H, class... Hs, class Tails>
struct prepend_all<std::tuple<H, Hs...>, Tails> {
  using type = tuple_concat_t<typename prepend_each<H, Tails>::type,
                              typename prepend_all<std::tuple<Hs...>, Tails>::type>;
};
}  // namespace internal

/// The cartesian product of the tuples `Lists...`: a tuple of tuples, one per
/// combination, the LAST list varying fastest. The product of no list is
/// one empty combination. O(product) instantiations, compile time only.
template <class... Lists>
struct tuple_product;
template <>
struct tuple_product<> {
  using type = std::tuple<std::tuple<>>;
};
template <class First, class... Rest>
struct tuple_product<First, Rest...> {
  using type = typename internal::prepend_all<First, typename tuple_product<Rest...>::type>::type;
};
template <class... Lists>
using tuple_product_t = typename tuple_product<Lists...>::type;

namespace internal {
/// The combinations (indices into the product, ascending) that a greedy
/// cover of every pair of values of two lists picks: each step takes the
/// first combination that covers the most pairs not yet covered.
/// O(cover x product x lists^2) constexpr steps.
template <std::size_t... Sizes>
struct pairwise_rows {
  static constexpr std::size_t kLists = sizeof...(Sizes);
  static constexpr std::array<std::size_t, kLists> kSizes{Sizes...};
  static constexpr std::size_t kProduct = (std::size_t{1} * ... * Sizes);

  static constexpr std::size_t pair_count() {
    std::size_t total = 0;
    for (std::size_t a = 0; a < kLists; ++a)
      for (std::size_t b = a + 1; b < kLists; ++b) total += kSizes[a] * kSizes[b];
    return total;
  }
  static constexpr std::size_t kPairs = pair_count();

  struct Rows {
    std::array<std::size_t, kProduct> index{};
    std::size_t count = 0;
  };

  static constexpr std::size_t kPairsPerRow = kLists * (kLists - (kLists > 0 ? 1 : 0)) / 2;

  static constexpr Rows compute() {
    Rows rows;
    if (kLists < 2 || kProduct == 0) {  // nothing to pair: every combination (or none)
      for (std::size_t row = 0; row < kProduct; ++row) rows.index[rows.count++] = row;
      return rows;
    }
    // Pairs (list a, value i) x (list b, value j), a < b, are numbered list
    // pair by list pair; row_pairs holds the numbers of each combination's pairs.
    std::array<std::size_t, kProduct * kPairsPerRow> row_pairs{};
    for (std::size_t row = 0; row < kProduct; ++row) {
      std::array<std::size_t, kLists> digit{};
      for (std::size_t list = kLists, rest = row; list-- > 0; rest /= kSizes[list]) digit[list] = rest % kSizes[list];
      std::size_t k = row * kPairsPerRow;
      std::size_t first = 0;
      for (std::size_t a = 0; a < kLists; ++a)
        for (std::size_t b = a + 1; b < kLists; ++b) {
          row_pairs[k++] = first + digit[a] * kSizes[b] + digit[b];
          first += kSizes[a] * kSizes[b];
        }
    }
    std::array<bool, kPairs> covered{};
    std::array<bool, kProduct> taken{};
    for (std::size_t uncovered = kPairs; uncovered > 0;) {
      std::size_t best = 0;
      std::size_t best_gain = 0;
      for (std::size_t row = 0; row < kProduct; ++row) {
        if (taken[row]) continue;
        std::size_t gain = 0;
        for (std::size_t k = row * kPairsPerRow; k < (row + 1) * kPairsPerRow; ++k) {
          if (!covered[row_pairs[k]]) ++gain;
        }
        if (gain > best_gain) {
          best_gain = gain;
          best = row;
        }
      }
      taken[best] = true;
      for (std::size_t k = best * kPairsPerRow; k < (best + 1) * kPairsPerRow; ++k) {
        if (!covered[row_pairs[k]]) --uncovered;
        covered[row_pairs[k]] = true;
      }
    }
    for (std::size_t row = 0; row < kProduct; ++row)
      if (taken[row]) rows.index[rows.count++] = row;
    return rows;
  }
  static constexpr Rows kRows = compute();
};

template <class Product, class Rows, class Seq>
struct pick_rows;
template <class Product, class Rows, std::size_t... I>
struct pick_rows<Product, Rows, std::index_sequence<I...>> {
  using type = std::tuple<std::tuple_element_t<Rows::kRows.index[I], Product>...>;
};
}  // namespace internal

/// A pairwise cover of the product of the tuples `Lists...`: combinations of
/// tuple_product_t (in its order) such that every two values of two
/// different lists appear together in at least one, so every value appears
/// at least once. Far fewer than the product (2 x 3 x 6 x 2 x 3 lists: 19
/// of 216); the whole product when there are fewer than two lists. For
/// checks whose faults come from one policy or the meeting of two (a
/// sanitizer run); a full check keeps the product. Compile time only,
/// O(cover x product x lists^2) constexpr steps: products of a few thousand.
template <class... Lists>
struct tuple_pairwise {
  using rows = internal::pairwise_rows<std::tuple_size_v<Lists>...>;
  using type = typename internal::pick_rows<tuple_product_t<Lists...>, rows,
                                            std::make_index_sequence<rows::kRows.count>>::type;
};
template <class... Lists>
using tuple_pairwise_t = typename tuple_pairwise<Lists...>::type;

/// Applies template `F` to every combination of tuple of tuples `Combos`:
/// `std::tuple<F<A1, B1, ...>, F<A1, B2, ...>, ...>`.
template <template <class...> class F, class Combos>
struct apply_each;
template <template <class...> class F, class... Combos>
struct apply_each<F, std::tuple<Combos...>> {
  template <class Combo>
  struct one;
  template <class... Ts>
  struct one<std::tuple<Ts...>> {
    using type = F<Ts...>;
  };
  using type = std::tuple<typename one<Combos>::type...>;
};
template <template <class...> class F, class Combos>
using apply_each_t = typename apply_each<F, Combos>::type;

/// The types `T` of tuple `List` for which `Pred<T>::value` is true, in order.
template <template <class> class Pred, class List>
struct tuple_filter;
template <template <class> class Pred>
struct tuple_filter<Pred, std::tuple<>> {
  using type = std::tuple<>;
};
template <template <class> class Pred, class T, class... Ts>
struct tuple_filter<Pred, std::tuple<T, Ts...>> {
  using rest = typename tuple_filter<Pred, std::tuple<Ts...>>::type;
  using type = std::conditional_t<Pred<T>::value, tuple_concat_t<std::tuple<T>, rest>, rest>;
};
template <template <class> class Pred, class List>
using tuple_filter_t = typename tuple_filter<Pred, List>::type;

/// Every `Step`-th type of tuple `List`, starting with the one at index
/// `First` (First < Step): `tuple_stride_t<L, 0, 3>`, `<L, 1, 3>` and
/// `<L, 2, 3>` partition L into three interleaved slices.
template <class List, std::size_t First, std::size_t Step, class = std::make_index_sequence<
                                                                   (std::tuple_size_v<List> + Step - 1 - First) / Step>>
struct tuple_stride;
template <class List, std::size_t First, std::size_t Step, std::size_t... I>
struct tuple_stride<List, First, Step, std::index_sequence<I...>> {
  static_assert(First < Step);
  using type = std::tuple<std::tuple_element_t<First + I * Step, List>...>;
};
template <class List, std::size_t First, std::size_t Step>
using tuple_stride_t = typename tuple_stride<List, First, Step>::type;

/// True when `T` is one of the types of tuple `List`.
template <class T, class List>
struct tuple_contains;
template <class T, class... Ts>
struct tuple_contains<T, std::tuple<Ts...>> : std::bool_constant<(std::is_same_v<T, Ts> || ...)> {};
template <class T, class List>
inline constexpr bool tuple_contains_v = tuple_contains<T, List>::value;

/// An empty value standing for type `T` (passed to the functor of for_each_type).
template <class T>
struct type_tag {
  using type = T;
};

namespace internal {
template <class List>
struct for_each_type_impl;
template <class... Ts>
struct for_each_type_impl<std::tuple<Ts...>> {
  template <class F>
  static void run(F& f) {
    (f(type_tag<Ts>{}), ...);
  }
};
}  // namespace internal

/// Calls `f(type_tag<T>{})` once per type `T` of tuple `List`, in order: a
/// compile-time loop (e.g. to register one benchmark per policy).
template <class List, class F>
void for_each_type(F&& f) {
  internal::for_each_type_impl<List>::run(f);
}

}  // namespace streamclust::testing
