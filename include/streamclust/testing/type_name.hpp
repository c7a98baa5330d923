// SPDX-License-Identifier: MIT
#pragma once
// Readable names of types, for the messages of generated tests and the
// names of generated benchmarks.

#include <cstdlib>
#include <memory>
#include <string>
#include <typeinfo>

#if defined(__GNUG__) || defined(__clang__)
#include <cxxabi.h>
#endif

namespace streamclust::testing {

namespace internal {

/// The demangled form of a `std::type_info::name()` with the
/// `streamclust::`, `streamclust::testing::` and anonymous-namespace
/// qualifications dropped. One copy for every type (compile time).
inline std::string readable_type_name(const char* mangled) {
  std::string name = mangled;
#if defined(__GNUG__) || defined(__clang__)
  int status = 0;
  const std::unique_ptr<char, void (*)(void*)> demangled(abi::__cxa_demangle(mangled, nullptr, nullptr, &status),
                                                         std::free);
  if (status == 0 && demangled) name = demangled.get();
#endif
  for (const std::string prefix : {"streamclust::testing::", "streamclust::test::", "streamclust::",
                                   "(anonymous namespace)::"}) {
    for (std::size_t at = name.find(prefix); at != std::string::npos; at = name.find(prefix, at))
      name.erase(at, prefix.size());
  }
  return name;
}

}  // namespace internal

/// The demangled name of `T` with the `streamclust::` and
/// `streamclust::testing::` qualifications dropped (the mangled name where
/// the ABI offers no demangler). O(length of the name); allocates.
template <class T>
std::string type_name() {
  return internal::readable_type_name(typeid(T).name());
}

}  // namespace streamclust::testing
