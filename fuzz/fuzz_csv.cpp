// SPDX-License-Identifier: MIT
// Fuzz target: the CSV reader (io::open_reader on a .csv file), driven as the
// CLI drives it (support/reader_driver.hpp). Covers CSV: headers, headerless
// rows, separators, quotes, byte-order mark, long lines.

#include "support/reader_driver.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static streamclust::fuzz::TempInput file("input.csv");
  static streamclust::fuzz::TempInput bare("input");
  streamclust::fuzz::drive_reader(data, size, file, bare);
  return 0;
}
