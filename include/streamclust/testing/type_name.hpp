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

/// The demangled name of `T` with the `streamclust::` and
/// `streamclust::testing::` qualifications dropped (the mangled name where the
/// ABI offers no demangler). O(length of the name); allocates.
template <class T>
std::string type_name() {
  std::string name = typeid(T).name();
#if defined(__GNUG__) || defined(__clang__)
  int status = 0;
  const std::unique_ptr<char, void (*)(void*)> demangled(
      abi::__cxa_demangle(name.c_str(), nullptr, nullptr, &status), std::free);
  if (status == 0 && demangled) name = demangled.get();
#endif
  for (const std::string prefix : {"streamclust::testing::", "streamclust::test::", "streamclust::", "(anonymous namespace)::"}) {
    for (std::size_t at = name.find(prefix); at != std::string::npos; at = name.find(prefix, at))
      name.erase(at, prefix.size());
  }
  return name;
}

}  // namespace streamclust::testing
