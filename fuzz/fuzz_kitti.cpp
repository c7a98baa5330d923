// SPDX-License-Identifier: MIT
// Fuzz target: the KITTI reader (io::open_reader on a .bin file), driven as
// the CLI drives it (support/reader_driver.hpp). Covers KITTI .bin: float32 x
// y z reflectance records.

#include "support/reader_driver.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static streamclust::fuzz::TempInput file("input.bin");
  static streamclust::fuzz::TempInput bare("input");
  streamclust::fuzz::drive_reader(data, size, file, bare);
  return 0;
}
