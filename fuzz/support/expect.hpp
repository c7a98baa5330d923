// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// What a fuzz target calls a bug: an exception of a type the API does not
/// document for bad input, or a broken invariant. Both abort with a message,
/// so libFuzzer saves the input as a crash.

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>

namespace streamclust::fuzz {

/// Prints `what` and aborts.
[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

/// Aborts with `what` unless `condition`.
inline void require(bool condition, const char* what) {
  if (!condition) fail(std::string("invariant broken: ") + what);
}

/// Runs `f`. An `Expected` exception (the documented error for bad input)
/// is swallowed and makes the result false; any other exception aborts,
/// naming its type. Returns true when `f` returned normally.
template <class Expected, class F>
bool only_throws(F&& f) {
  try {
    f();
    return true;
  } catch (const Expected&) {
    return false;
  } catch (const std::exception& e) {
    fail(std::string("unexpected exception ") + typeid(e).name() + ": " + e.what());
  } catch (...) {
    fail("unexpected exception of a non-standard type");
  }
}

/// Runs `f`; any exception aborts, naming its type.
template <class F>
void never_throws(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    fail(std::string("unexpected exception ") + typeid(e).name() + ": " + e.what());
  } catch (...) {
    fail("unexpected exception of a non-standard type");
  }
}

}  // namespace streamclust::fuzz
