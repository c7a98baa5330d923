// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The streaming reader interface every format implements.

#include <streamclust/io/error.hpp>
#include <streamclust/io/record.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace streamclust::io {

/// Default unit of a time field when `ReadOptions::time_unit` is not set:
/// `offset_time` (Livox) is in nanoseconds, `t`, `time` and `timestamp` in
/// seconds. (The CSV reader also treats the `Timestamp` column of a Livox
/// Viewer export as nanoseconds, see docs/io.md.)
inline TimeUnit default_time_unit(std::string_view lowered_field_name) noexcept {
  return lowered_field_name == "offset_time" ? TimeUnit::ns : TimeUnit::s;
}

/// A streaming point reader: `read` hands out records in file order, a chunk
/// at a time; memory is bounded by a fixed buffer (plus one text line), not by
/// the file -- except for PCD binary_compressed, which is one LZF block by
/// definition of the format and is decompressed once.
///
/// Usage:
///
///     auto reader = streamclust::io::open_reader("scan.pcd", {});
///     std::vector<streamclust::io::Record> chunk;
///     while (chunk.clear(), reader->read(chunk, 4096) > 0)
///       for (const auto& r : chunk) engine.insert(r);
///
/// Thread safety: a reader is a single-threaded object.
class PointReader {
 public:
  virtual ~PointReader() = default;
  PointReader(const PointReader&) = delete;
  PointReader& operator=(const PointReader&) = delete;

  /// What the header said: format, encoding, fields, declared point count, time field.
  const InputInfo& info() const noexcept { return info_; }
  /// The path the reader was opened with.
  const std::string& path() const noexcept { return path_; }
  /// Records returned so far (every record counts, NaN ones included).
  std::uint64_t records_read() const noexcept { return index_; }

  /// Appends up to `max_records` records to `out` in file order and returns
  /// how many; 0 means end of input (or max_records == 0).
  /// Throws InputError on malformed data, naming file and place.
  virtual std::size_t read(std::vector<Record>& out, std::size_t max_records) = 0;

 protected:
  explicit PointReader(std::string path) : path_(std::move(path)) {}

  /// Call once `info_.has_time` and `info_.time_field` are set: fixes the time
  /// unit (options, else `default_unit`), or, without a time field, requires a
  /// point rate. Throws InputError (no time and no rate) or
  /// std::invalid_argument (point rate not finite and > 0).
  void setup_time(const ReadOptions& options, TimeUnit default_unit) {
    if (info_.has_time) {
      info_.time_unit = options.time_unit.value_or(default_unit);
      scale_ = seconds_per(info_.time_unit);
      return;
    }
    if (!options.point_rate) {
      throw InputError(path_, "header",
                       "no time field (t, time, timestamp or offset_time); pass a point rate (--point-rate HZ) "
                       "to assign t = index / rate");
    }
    rate_ = *options.point_rate;
    if (!(std::isfinite(rate_) && rate_ > 0)) {
      throw std::invalid_argument("ReadOptions::point_rate = " + std::to_string(rate_) +
                                  ": must be finite and > 0 [Hz]");
    }
  }

  /// Stream time of the next record from its raw time value (ignored without
  /// a time field: then index / point rate); advances the record index.
  double next_time(double raw) noexcept {
    const double t = info_.has_time ? raw * scale_ : static_cast<double>(index_) / rate_;
    ++index_;
    return t;
  }

  InputInfo info_;
  std::string path_;

 private:
  double scale_ = 1.0;
  double rate_ = 1.0;
  std::uint64_t index_ = 0;
};

}  // namespace streamclust::io
