// SPDX-License-Identifier: MIT
#pragma once
// The message of the std::invalid_argument a callable throws.

#include <stdexcept>
#include <string>

namespace streamclust::test {

/// what() of the std::invalid_argument thrown by `f()`, or "" if none is thrown.
template <class F>
std::string invalid_argument_message(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace streamclust::test
