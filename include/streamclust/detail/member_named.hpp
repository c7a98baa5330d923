// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Detects that a class has a member of a given NAME, whatever it is (a
/// member function of any signature, overloaded, a template, static or
/// not, public or not, a data member or a nested type): the half of a
/// near-miss diagnosis that the signature traits cannot give. The concept
/// headers compare it with their capability traits, so that a member named
/// like an optional capability but with another signature stops compilation
/// instead of being ignored.
///
/// `STREAMCLUST_DETAIL_MEMBER_NAME_TRAIT(NAME)`, in namespace
/// streamclust::detail, defines `template <class T> inline constexpr bool
/// names_NAME` (true when T has a member named NAME). How: a class deriving
/// from T and from a probe with an `int NAME` member; `&Mix::NAME` is
/// ambiguous exactly when T has a member of that name. A final class cannot
/// be derived from: for it only a non-overloaded member function or data
/// member is seen (`&T::NAME`). Compile time only.

#include <type_traits>

#define STREAMCLUST_DETAIL_MEMBER_NAME_TRAIT(NAME)                                                               \
  struct member_name_probe_##NAME {                                                                            \
    int NAME;                                                                                                  \
  };                                                                                                           \
  template <class T>                                                                                           \
  struct member_name_mix_##NAME : T, member_name_probe_##NAME {};                                              \
  template <class T, class = void>                                                                             \
  struct names_##NAME##_mixed : std::true_type {};                                                             \
  template <class T>                                                                                           \
  struct names_##NAME##_mixed<T, std::void_t<decltype(&member_name_mix_##NAME<T>::NAME)>> : std::false_type {}; \
  template <class T, class = void>                                                                             \
  struct names_##NAME##_direct : std::false_type {};                                                           \
  template <class T>                                                                                           \
  struct names_##NAME##_direct<T, std::void_t<decltype(&T::NAME)>> : std::true_type {};                        \
  template <class T>                                                                                           \
  inline constexpr bool names_##NAME = std::conditional_t<std::is_class_v<T> && !std::is_final_v<T>,            \
                                                          names_##NAME##_mixed<T>, names_##NAME##_direct<T>>::value
