// SPDX-License-Identifier: MIT
#pragma once
// Where the tests find the shared data (real sensor tables and frames) that
// a fresh clone does not have, and the doctest decorator that skips a test
// case when its data is absent. Tests needing the data live in files of
// their own, so that CTest reports such a file as skipped (doctest's
// summary then counts no test case run; tests/CMakeLists.txt maps that to a
// skip).
//
// Locations, first match wins:
//   Livox data: $STREAMCLUST_LIVOX_DATA, else <shared>/data/livox;
//   <shared>:   $STREAMCLUST_SHARED_DIR, else the folder `shared` beside the
//               source tree (<source>/../shared).

#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace streamclust::test {

/// The root of the shared data. O(1); reads the environment.
inline std::filesystem::path shared_data_dir() {
  if (const char* env = std::getenv("STREAMCLUST_SHARED_DIR")) return std::filesystem::path(env);
  // <source>/tests/support/shared_data.hpp -> <source>/../shared
  return std::filesystem::path(__FILE__).parent_path() / ".." / ".." / ".." / "shared";
}

/// The Livox data folder (tables in `patterns/`, recordings in `frames/`).
inline std::filesystem::path livox_data_dir() {
  if (const char* env = std::getenv("STREAMCLUST_LIVOX_DATA")) return std::filesystem::path(env);
  return shared_data_dir() / "data" / "livox";
}

/// True when `path` exists (a file or a folder).
inline bool data_present(const std::filesystem::path& path) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

/// Decorator of a test case that needs `livox_data_dir() / relative`:
/// `TEST_CASE("..." * needs_livox_data("patterns/mid360_u16le.bin"))`.
/// Evaluated once, when the test case is registered (static initialisation);
/// when the data is absent the case is skipped and counted as skipped.
inline doctest::skip needs_livox_data(const char* relative) {
  return doctest::skip(!data_present(livox_data_dir() / relative));
}

}  // namespace streamclust::test
