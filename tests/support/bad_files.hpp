// SPDX-License-Identifier: MIT
#pragma once
// Helpers of the reader error tests: bytes of files, sample records, and the
// check that reading a file fails with an InputError at the expected place.

#include <streamclust/io/reader.hpp>

#include <doctest/doctest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace streamclust::test {

/// Read options with a point rate (files without a time field open too).
inline io::ReadOptions with_rate() {
  io::ReadOptions o;
  o.point_rate = 1000.0;
  return o;
}

/// Opens and reads all of `path`; requires an InputError naming `path`, at
/// `where`, whose message contains `expected`.
inline void expect_error(const std::string& path, const std::string& where, const std::string& expected,
                         const io::ReadOptions& options = with_rate()) {
  INFO("file " << path);
  try {
    auto r = io::open_reader(path, options);
    std::vector<io::Record> out;
    while (r->read(out, 100) > 0) {
    }
    FAIL("expected an InputError, read " << out.size() << " records");
  } catch (const io::InputError& e) {
    INFO("message: " << e.what());
    CHECK(e.file() == path);
    CHECK(e.where() == where);
    CHECK(e.what_expected().find(expected) != std::string::npos);
    CHECK(std::string(e.what()) == path + ": " + where + ": " + e.what_expected());
  }
}

/// Appends the bytes of `v` (host order: little-endian on the supported targets).
template <class T>
void append_bytes(std::string& s, T v) {
  char b[sizeof v];
  std::memcpy(b, &v, sizeof v);
  s.append(b, sizeof v);
}

/// The whole content of `path`.
inline std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// `n` records at x = i, y = 1, z = 2, t = i ms.
inline std::vector<io::Record> some_records(std::size_t n) {
  std::vector<io::Record> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    v[i].x = static_cast<float>(i);
    v[i].y = 1;
    v[i].z = 2;
    v[i].t = static_cast<double>(i) * 0.001;
  }
  return v;
}

}  // namespace streamclust::test
