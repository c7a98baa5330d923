// SPDX-License-Identifier: MIT
// Fuzz target: the mcap reader (io::open_reader on a .mcap file), driven as the
// CLI drives it (support/reader_driver.hpp: read in chunks, the time origin,
// `streamclust info` with its topic list, detection by content). Covers
// MCAP (records, chunks ""/lz4/zstd, CRCs, summary, schemas and channels; the CDR decoders behind them).

#include "support/reader_driver.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static streamclust::fuzz::TempInput file("input.mcap");
  static streamclust::fuzz::TempInput bare("input");
  streamclust::fuzz::drive_reader(data, size, file, bare);
  return 0;
}
