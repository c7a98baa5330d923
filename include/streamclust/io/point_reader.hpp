// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The streaming reader interface every format implements.

#include <streamclust/io/error.hpp>
#include <streamclust/io/input_stream.hpp>
#include <streamclust/io/record.hpp>
#include <streamclust/io/time_decoder.hpp>

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
  /// The whole seconds the records' times count from (stream_time.hpp):
  /// `ReadOptions::time_origin` when given, else the first finite time's
  /// whole seconds once a record with one is read (zero before, and for a
  /// stream of times below 1 s or without a time field). Absolute time =
  /// origin + Record::t.
  TimeOrigin time_origin() const noexcept { return time_.origin(); }
  /// True when the origin was given or found (false until a record with a
  /// finite time is read).
  bool time_origin_found() const noexcept { return time_.origin_found(); }

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
      time_ = TimeDecoder(info_.time_unit, options.time_origin);
      return;
    }
    if (options.time_origin) time_ = TimeDecoder(TimeUnit::s, options.time_origin);
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

  /// Stream time of the next record from its time value written as decimal
  /// text, `parsed` its value (both ignored without a time field: then
  /// index / point rate); advances the record index.
  double next_time_text(std::string_view text, double parsed) {
    const double t = info_.has_time ? time_.from_text(text, parsed) : time_from_rate();
    ++index_;
    return t;
  }

  /// The same for a time value stored as the binary scalar at `p`.
  double next_time_scalar(detail::Scalar scalar, const unsigned char* p) noexcept {
    double t = 0.0;
    if (!info_.has_time) {
      t = time_from_rate();
    } else if (scalar == detail::Scalar::u64) {
      t = time_.from_unsigned(detail::load_le<std::uint64_t>(p));
    } else if (scalar == detail::Scalar::i64) {
      t = time_.from_integer(detail::load_le<std::int64_t>(p));
    } else if (detail::scalar_is_float(scalar)) {
      t = time_.from_real(detail::scalar_to_double(scalar, p));
    } else {
      t = time_.from_integer(static_cast<std::int64_t>(detail::scalar_to_double(scalar, p)));  // exact below 64 bits
    }
    ++index_;
    return t;
  }

  /// The same for an unsigned integer time in the field's unit (recordings:
  /// nanoseconds composed from a message's base time and a point's offset).
  double next_time_unsigned(std::uint64_t raw) noexcept {
    const double t = info_.has_time ? time_.from_unsigned(raw) : time_from_rate();
    ++index_;
    return t;
  }

  /// The same for a record without a time value (no time field).
  double next_time() noexcept {
    const double t = time_from_rate();
    ++index_;
    return t;
  }

  InputInfo info_;
  std::string path_;

 private:
  double time_from_rate() const noexcept { return static_cast<double>(index_) / rate_; }

  TimeDecoder time_;
  double rate_ = 1.0;
  std::uint64_t index_ = 0;
};

}  // namespace streamclust::io
