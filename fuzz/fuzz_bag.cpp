// SPDX-License-Identifier: MIT
// Fuzz target: the bag reader (io::open_reader on a .bag file), driven as the
// CLI drives it (support/reader_driver.hpp: read in chunks, the time origin,
// `streamclust info` with its topic list, detection by content). Covers
// ROS 1 bags (v2.0: chunks none/bz2/lz4, connections, message definitions; the CustomMsg and PointCloud2 decoders behind them).

#include "support/reader_driver.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static streamclust::fuzz::TempInput file("input.bag");
  static streamclust::fuzz::TempInput bare("input");
  streamclust::fuzz::drive_reader(data, size, file, bare);
  return 0;
}
