// SPDX-License-Identifier: MIT
// Fuzz target: the db3 reader (io::open_reader on a .db3 file), driven as the
// CLI drives it (support/reader_driver.hpp: read in chunks, the time origin,
// `streamclust info` with its topic list, detection by content). Covers
// rosbag2 SQLite (.db3: topics, messages, message definitions, through libsqlite3).

#include "support/reader_driver.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static streamclust::fuzz::TempInput file("input.db3");
  static streamclust::fuzz::TempInput bare("input");
  streamclust::fuzz::drive_reader(data, size, file, bare);
  return 0;
}
