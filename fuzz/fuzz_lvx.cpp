// SPDX-License-Identifier: MIT
// Fuzz target: the Livox LVX / LVX2 reader (io::LvxReader, constructed
// directly: format detection by extension is the tool's business) and
// summarize_lvx, on the same bytes. Covers LVX 1.0, 1.1 and LVX2: headers,
// device lists, frame chains, packages of every data type, timestamps.
//
// A bug, besides a crash, undefined behaviour, a leak or unbounded memory or
// time: an exception other than io::InputError; a clean read that breaks the
// reader's promises (chunks no longer than asked, records_read counting every
// record, nothing after the end, reflectivity 0-255, finite times); a reader
// and a summary that disagree (a clean read with a failing summary, or
// another record count than the summary gives its device; a failing read
// with a clean summary, unless the read failed on choosing the device or on
// its device type, which the summary does not need).

#include "support/expect.hpp"
#include "support/temp_input.hpp"

#include <streamclust/io/error.hpp>
#include <streamclust/io/lvx_reader.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace {

namespace io = streamclust::io;
using streamclust::fuzz::fail;
using streamclust::fuzz::require;

/// Read options varied by `variant` (from the input's size, so that an input
/// always reads the same way): no topic, index 0, index 1 or index 3; time
/// origin unset, 0 or 1.7e9 s.
io::ReadOptions lvx_options(std::size_t variant) {
  io::ReadOptions o;
  constexpr const char* topics[] = {nullptr, "0", "1", "3"};
  if (const char* topic = topics[variant % 4]) o.topic = topic;
  if ((variant / 4) % 3 == 1) o.time_origin = io::TimeOrigin{0};
  if ((variant / 4) % 3 == 2) o.time_origin = io::TimeOrigin{1700000000};
  return o;
}

/// Reads every record of `path` in chunks of `chunk`; returns the count and
/// the device read. Throws what the reader throws.
std::uint64_t read_all(const std::string& path, const io::ReadOptions& options, std::size_t chunk,
                       std::size_t& device) {
  io::LvxReader reader(path, options);
  require(reader.info().format == io::Format::lvx && reader.info().has_time &&
              reader.info().time_unit == io::TimeUnit::ns,
          "an LVX reader reports format lvx and a time field in ns");
  device = 0;
  while (&reader.devices()[device] != &reader.device()) ++device;
  std::vector<io::Record> records;
  std::uint64_t count = 0;
  for (;;) {
    records.clear();
    const std::size_t got = reader.read(records, chunk);
    require(got == records.size(), "read() returns the number of records appended");
    require(got <= chunk, "read() appends at most max_records");
    if (got == 0) break;
    for (const io::Record& r : records) {
      require(r.intensity >= 0 && r.intensity <= 255 && r.intensity == std::floor(r.intensity),
              "intensity is a reflectivity byte");
      require(std::isfinite(r.t), "times are finite");
      require(r.label == -1, "LVX records have no label");
    }
    count += got;
    require(reader.records_read() == count, "records_read() counts every record returned");
  }
  records.clear();
  require(reader.read(records, chunk) == 0 && records.empty(), "read() after the end returns nothing");
  return count;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static streamclust::fuzz::TempInput file("input.lvx");
  const std::string& path = file.write(data, size);
  constexpr std::size_t chunks[] = {1, 3, 4096};

  std::optional<io::InputError> read_error;
  std::uint64_t count = 0;
  std::size_t device = 0;
  try {
    count = read_all(path, lvx_options(size), chunks[size % 3], device);
  } catch (const io::InputError& e) {
    read_error = e;
  } catch (const std::exception& e) {
    fail(std::string("unexpected exception from LvxReader: ") + e.what());
  }

  std::optional<io::LvxSummary> summary;
  try {
    summary = io::summarize_lvx(path);
  } catch (const io::InputError&) {
  } catch (const std::exception& e) {
    fail(std::string("unexpected exception from summarize_lvx: ") + e.what());
  }

  if (!read_error) {
    require(summary.has_value(), "a file the reader reads cleanly summarizes cleanly");
    require(summary->devices[device].points == count, "the summary counts the records the reader returns");
  } else if (summary) {
    require(read_error->where() == "header" ||
                read_error->what_expected().rfind("unknown device type", 0) == 0,
            "a file that summarizes cleanly reads cleanly, unless the device cannot be chosen or timed");
  }
  return 0;
}
