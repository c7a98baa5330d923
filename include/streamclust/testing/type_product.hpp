// SPDX-License-Identifier: MIT
#pragma once
// Type-level helpers over std::tuple lists of policies: the cartesian
// product of several lists, concatenation, filtering, and a compile-time
// loop calling a functor once per type.

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
