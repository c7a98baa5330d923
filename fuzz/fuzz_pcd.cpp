// SPDX-License-Identifier: MIT
// Fuzz target: the PCD reader (io::open_reader on a .pcd file), driven as the
// CLI drives it (support/reader_driver.hpp). Covers PCD v0.7: every header
// keyword, DATA ascii, binary and binary_compressed (LZF).

#include "support/reader_driver.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static streamclust::fuzz::TempInput file("input.pcd");
  static streamclust::fuzz::TempInput bare("input");
  streamclust::fuzz::drive_reader(data, size, file, bare);
  return 0;
}
