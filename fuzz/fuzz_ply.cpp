// SPDX-License-Identifier: MIT
// Fuzz target: the PLY reader (io::open_reader on a .ply file), driven as the
// CLI drives it (support/reader_driver.hpp). Covers PLY: ascii and
// binary_little_endian, vertex and other elements, list properties.

#include "support/reader_driver.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static streamclust::fuzz::TempInput file("input.ply");
  static streamclust::fuzz::TempInput bare("input");
  streamclust::fuzz::drive_reader(data, size, file, bare);
  return 0;
}
