// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Streaming CSV reader.
///
/// - A header line names the columns (case-insensitive, trimmed, quotes
///   stripped), in any order; extra columns are ignored. Required: x, y, z.
///   Optional: intensity (or reflectivity, reflectance), time (t, time,
///   timestamp, offset_time: first found in this order), label (label, gt,
///   instance, object).
/// - Headerless files (first line numeric) are read as x,y,z[,intensity] in
///   column order; more columns are ignored; they have no time field.
/// - Separator: ',' if the first line has a comma, else blanks (space/tab).
///   A trailing separator (Livox exports end lines with a comma) is allowed.
/// - Every row must have as many fields as the first line; empty lines and
///   lines starting with '#' are skipped; lines over 1 MiB are an error.
/// - A UTF-8 byte-order mark before the first line is skipped. A column
///   name that plays a role (x, y, z, an intensity, time or label name)
///   given twice (case-insensitive) is an error naming the header line.
/// - Messages quote header names and values through detail::printable:
///   control and non-ASCII bytes appear as \xNN.
/// - Livox Viewer exports (a `Timestamp Type` column next to `Timestamp`):
///   `Timestamp` defaults to nanoseconds.

#include <streamclust/io/error.hpp>
#include <streamclust/io/field_names.hpp>
#include <streamclust/io/input_stream.hpp>
#include <streamclust/io/point_reader.hpp>
#include <streamclust/io/record.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace streamclust::io {

/// Reader of CSV / whitespace-separated text point files. See the file comment.
class CsvReader final : public PointReader {
 public:
  CsvReader(const std::string& path, const ReadOptions& options) : PointReader(path), src_(path) {
    info_.format = Format::csv;
    info_.encoding = "";
    if (!next_content_line()) throw InputError(path_, "byte 0", "empty file: expected a CSV header or data line");
    // Separator from the first line.
    comma_ = line_.find(',') != std::string::npos;
    split(line_);
    if (fields_.empty()) throw InputError(path_, detail::where_line(line_no_), "expected a CSV header, found no fields");
    float probe = 0;
    const bool headerless = detail::parse_real(detail::trim(fields_[0]), probe);
    n_fields_ = fields_.size();
    if (headerless) {
      if (n_fields_ < 3) {
        throw InputError(path_, detail::where_line(line_no_),
                         "expected a header naming the columns (x, y, z, ...) or at least 3 numeric columns "
                         "x,y,z[,intensity], found " + std::to_string(n_fields_) + " field(s)");
      }
      names_ = {"x", "y", "z", "intensity"};
      info_.fields.assign(names_.begin(), names_.begin() + static_cast<std::ptrdiff_t>(n_fields_ >= 4 ? 4 : 3));
      cx_ = 0, cy_ = 1, cz_ = 2;
      if (n_fields_ >= 4) ci_ = 3;
      pending_ = true;  // the first line is data
    } else {
      std::vector<std::string> lowered;
      for (auto f : fields_) {
        std::string_view name = detail::trim(f);
        if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = name.substr(1, name.size() - 2);
        names_.emplace_back(name);
        lowered.push_back(detail::lower(name));
      }
      info_.fields = names_;
      if (const auto d = detail::find_duplicate(lowered, detail::is_role_name)) {
        throw InputError(path_, detail::where_line(line_no_),
                         "column " + detail::quoted(names_[d->second]) + " appears twice (columns " +
                             std::to_string(d->first + 1) + " and " + std::to_string(d->second + 1) +
                             "): expected each of x, y, z and the intensity, time and label columns once");
      }
      const auto x = detail::find_field(lowered, {"x"});
      const auto y = detail::find_field(lowered, {"y"});
      const auto z = detail::find_field(lowered, {"z"});
      if (!x || !y || !z) {
        std::string found;
        for (const auto& n : names_) found += (found.empty() ? "" : ", ") + detail::quoted(n);
        throw InputError(path_, detail::where_line(line_no_),
                         "expected a header with columns named x, y and z (case-insensitive), found: " + found);
      }
      cx_ = *x, cy_ = *y, cz_ = *z;
      ci_ = detail::find_field(lowered, detail::intensity_names);
      ct_ = detail::find_field(lowered, detail::time_names);
      cl_ = detail::find_field(lowered, detail::label_names);
      if (ct_) {
        info_.has_time = true;
        info_.time_field = names_[*ct_];
        time_default_ = default_time_unit(lowered[*ct_]);
        if (lowered[*ct_] == "timestamp" && detail::find_field(lowered, {"timestamp type"})) time_default_ = TimeUnit::ns;
      }
    }
    info_.has_intensity = ci_.has_value();
    info_.has_label = cl_.has_value();
    setup_time(options, time_default_);
  }

  std::size_t read(std::vector<Record>& out, std::size_t max_records) override {
    std::size_t n = 0;
    while (n < max_records) {
      if (pending_) {
        pending_ = false;
      } else {
        if (!next_content_line()) break;
        split(line_);
      }
      if (fields_.size() != n_fields_) {
        throw InputError(path_, detail::where_line(line_no_),
                         "expected " + std::to_string(n_fields_) + " fields (as in the first line), found " +
                             std::to_string(fields_.size()));
      }
      Record r;
      r.x = real<float>(cx_);
      r.y = real<float>(cy_);
      r.z = real<float>(cz_);
      if (ci_) r.intensity = real<float>(*ci_);

      if (cl_) {
        const std::string_view s = detail::trim(fields_[*cl_]);
        std::int64_t v = 0;
        if (!detail::parse_int64(s, v)) {
          throw InputError(path_, detail::where_column(line_no_, *cl_ + 1, names_[*cl_]),
                           "expected an integer label, found " + detail::quoted(s));
        }
        r.label = v;
      }
      r.t = ct_ ? next_time_text(detail::trim(fields_[*ct_]), real<double>(*ct_)) : next_time();
      out.push_back(r);
      ++n;
    }
    return n;
  }

 private:
  template <class T>
  T real(std::size_t column) const {
    const std::string_view s = detail::trim(fields_[column]);
    T v{};
    if (!detail::parse_real(s, v)) {
      throw InputError(path_, detail::where_column(line_no_, column + 1, names_[column]),
                       "expected a number, found " + detail::quoted(s));
    }
    return v;
  }

  /// Next line that is neither blank nor a '#' comment; false at end of file.
  bool next_content_line() {
    for (;;) {
      const auto st = src_.read_line(line_, detail::max_line_bytes);
      if (st == detail::ByteSource::LineStatus::eof) return false;
      ++line_no_;
      if (line_no_ == 1 && line_.compare(0, 3, "\xEF\xBB\xBF") == 0) line_.erase(0, 3);  // UTF-8 byte-order mark
      if (st == detail::ByteSource::LineStatus::too_long) {
        throw InputError(path_, detail::where_line(line_no_),
                         "line longer than " + std::to_string(detail::max_line_bytes) +
                             " bytes: expected a CSV text line (is this a binary file?)");
      }
      const std::string_view t = detail::trim(line_);
      if (t.empty() || t.front() == '#') continue;
      return true;
    }
  }

  /// Splits line_ into fields_; a trailing empty field (line ends with the separator) is dropped.
  void split(std::string_view line) {
    line = detail::trim(line);
    if (!comma_) {
      detail::split_blanks(line, fields_);
      return;
    }
    fields_.clear();
    std::size_t b = 0;
    for (;;) {
      const std::size_t c = line.find(',', b);
      if (c == std::string_view::npos) {
        fields_.push_back(line.substr(b));
        break;
      }
      fields_.push_back(line.substr(b, c - b));
      b = c + 1;
    }
    if (fields_.size() > 1 && detail::trim(fields_.back()).empty()) fields_.pop_back();
  }

  detail::ByteSource src_;
  std::string line_;
  std::uint64_t line_no_ = 0;
  bool comma_ = true;
  bool pending_ = false;
  std::vector<std::string_view> fields_;
  std::vector<std::string> names_;
  std::size_t n_fields_ = 0;
  std::size_t cx_ = 0, cy_ = 1, cz_ = 2;
  std::optional<std::size_t> ci_, ct_, cl_;
  TimeUnit time_default_ = TimeUnit::s;
};

}  // namespace streamclust::io
