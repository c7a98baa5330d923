// SPDX-License-Identifier: MIT
// The reader targets' shared body (reader_driver.hpp), compiled once.

#include "support/reader_driver.hpp"

#include "support/expect.hpp"

#include "cli/info.hpp"
#include "cli/options.hpp"

#include <streamclust/io/reader.hpp>

#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace streamclust::fuzz {
namespace {

/// Read options varied by `variant` (a number taken from the input's size,
/// so that a given input always reads the same way): time unit, time origin;
/// always a point rate, so inputs without a time field are read too.
io::ReadOptions read_options(std::size_t variant) {
  io::ReadOptions o;
  o.point_rate = 1000.0;  // [Hz]
  constexpr io::TimeUnit units[] = {io::TimeUnit::s, io::TimeUnit::ms, io::TimeUnit::us, io::TimeUnit::ns};
  if (variant % 5 != 4) {
    if (variant % 5 != 0) o.time_unit = units[variant % 5 - 1];
  }
  if ((variant / 5) % 3 == 1) o.time_origin = io::TimeOrigin{0};
  if ((variant / 5) % 3 == 2) o.time_origin = io::TimeOrigin{1700000000};
  return o;
}

/// Opens `path` and reads every record in chunks of `chunk` records, as the
/// CLI does, checking what a clean read promises: chunks never longer than
/// asked, `records_read` counting every record, the count equal to the
/// declared count, times index / rate without a time field.
void read_all(const std::string& path, const io::ReadOptions& options, std::size_t chunk) {
  auto reader = io::open_reader(path, options);
  const io::InputInfo info = reader->info();
  std::vector<io::Record> records;
  std::uint64_t count = 0;
  for (;;) {
    records.clear();
    const std::size_t got = reader->read(records, chunk);
    require(got == records.size(), "read() returns the number of records appended");
    require(got <= chunk, "read() appends at most max_records");
    if (got == 0) break;
    for (const io::Record& r : records) {
      if (!info.has_time) {
        require(r.t == static_cast<double>(count) / *options.point_rate, "t = index / point rate without a time field");
      }
      ++count;
    }
    require(reader->records_read() == count, "records_read() counts every record returned");
  }
  records.clear();
  require(reader->read(records, chunk) == 0 && records.empty(), "read() after the end returns nothing");
  if (info.declared_points) require(count == *info.declared_points, "a clean read returns the declared point count");
}

}  // namespace

void drive_reader(const std::uint8_t* data, std::size_t size, TempInput& file, TempInput& bare) {
  const std::string& path = file.write(data, size);
  const io::ReadOptions options = read_options(size);
  constexpr std::size_t chunks[] = {1, 3, 4096, 65536};
  only_throws<io::InputError>([&] { read_all(path, options, chunks[size % 4]); });
  only_throws<io::InputError>([&] { io::find_time_origin(path, options); });
  only_throws<io::InputError>([&] {
    cli::InfoOptions info;
    info.input = path;
    if (size % 2 == 0) info.read.point_rate = 1000.0;  // else as `info` without --point-rate
    std::ostringstream out;
    cli::run_info_reading(info, out);
  });
  const std::string& bare_path = bare.write(data, size);
  only_throws<io::InputError>([&] {
    const io::Format f = io::detect_format(bare_path);
    io::ReadOptions forced = options;
    forced.format = f;
    read_all(bare_path, forced, 4096);
  });
}

}  // namespace streamclust::fuzz
