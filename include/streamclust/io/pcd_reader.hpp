// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Streaming PCD v0.7 reader: DATA ascii, binary and binary_compressed (LZF).
///
/// - Header keywords VERSION FIELDS SIZE TYPE COUNT WIDTH HEIGHT VIEWPOINT
///   POINTS DATA ('#' lines are comments). Types F (size 4, 8), I and U
///   (1, 2, 4, 8). Fields read: x y z (required, COUNT 1), intensity
///   (reflectivity, reflectance), time (t, time, timestamp, offset_time),
///   label (label, gt, instance, object); others (and any COUNT > 1 field)
///   are skipped. A field name given twice (case-insensitive; `_` padding
///   may repeat) and a keyword given twice are errors.
/// - POINTS is authoritative. WIDTH 0 HEIGHT 0 with a correct POINTS (a
///   real-world quirk) is accepted; WIDTH x HEIGHT != POINTS with neither 0 is an error.
/// - binary: read block by block. binary_compressed: u32 compressed size, u32
///   uncompressed size, one LZF block holding the fields one after the other
///   (structure of arrays). It is decompressed once, after checking the sizes
///   against the file size, POINTS x point size and the LZF expansion limit.
/// - Absurd POINTS values are rejected against the file size before any allocation.
/// - After the POINTS records: blank lines (ascii) or nothing (binary, and
///   after the LZF block); anything else is an error (data_end.hpp).
/// - Header errors name their line: a keyword's own line, or the DATA line
///   for what is missing when the header ends.

#include <streamclust/io/data_end.hpp>
#include <streamclust/io/error.hpp>
#include <streamclust/io/field_names.hpp>
#include <streamclust/io/input_stream.hpp>
#include <streamclust/io/lzf.hpp>
#include <streamclust/io/point_reader.hpp>
#include <streamclust/io/record.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace streamclust::io {

/// Reader of PCD v0.7 files. See the file comment.
class PcdReader final : public PointReader {
 public:
  PcdReader(const std::string& path, const ReadOptions& options) : PointReader(path), src_(path) {
    info_.format = Format::pcd;
    parse_header();
    setup_time(options, time_default_);
    prepare_data();
  }

  std::size_t read(std::vector<Record>& out, std::size_t max_records) override {
    std::size_t n = 0;
    if (encoding_ == Encoding::ascii) {
      while (n < max_records && done_ < points_) {
        read_ascii_record(out);
        ++n;
      }
    } else if (encoding_ == Encoding::binary) {
      while (n < max_records && done_ < points_) {
        const std::uint64_t want = std::min<std::uint64_t>({points_ - done_, max_records - n, block_records_});
        const std::size_t bytes = static_cast<std::size_t>(want) * point_size_;
        const std::size_t got = src_.read(reinterpret_cast<char*>(block_.data()), bytes);
        const std::size_t whole = got / point_size_;
        for (std::size_t k = 0; k < whole; ++k) out.push_back(decode_aos(block_.data() + k * point_size_));
        done_ += whole;
        n += whole;
        if (got < bytes) throw_truncated_binary(done_);
      }
    } else {
      while (n < max_records && done_ < points_) {
        out.push_back(decode_soa(static_cast<std::size_t>(done_)));
        ++done_;
        ++n;
      }
      if (done_ == points_) std::vector<unsigned char>().swap(soa_);  // release the block
    }
    if (done_ == points_ && !ended_) {
      ended_ = true;
      if (encoding_ == Encoding::ascii)
        detail::expect_text_end(src_, line_, line_no_, "the " + std::to_string(points_) + " points POINTS declares");
      else if (encoding_ == Encoding::binary)
        detail::expect_binary_end(src_, declared_binary());
    }
    return n;
  }

 private:
  enum class Encoding { ascii, binary, binary_compressed };
  struct Field {
    std::string name;
    char type = 'F';
    std::size_t size = 4;
    std::size_t count = 1;
    detail::Scalar scalar = detail::Scalar::f32;
    std::size_t offset = 0;       // byte offset in a binary record
    std::size_t first_value = 0;  // index of its first value in an ascii line
    std::uint64_t soa_base = 0;   // byte offset of its array in the binary_compressed block
  };

  [[noreturn]] void header_error(std::uint64_t line, const std::string& what) const {
    throw InputError(path_, detail::where_line(line), what);
  }
  [[noreturn]] void line_error(const std::string& what) const {
    throw InputError(path_, detail::where_line(line_no_), what);
  }

  static std::string join(const std::vector<std::string_view>& v, std::size_t from) {
    std::string r;
    for (std::size_t i = from; i < v.size(); ++i) {
      if (i > from) r += ' ';
      r.append(v[i].data(), v[i].size());
    }
    return r;
  }

  void parse_header() {
    std::vector<std::string_view> tok;
    std::vector<std::string> sizes, types, counts;  // copies: line_ is reused
    bool have_data = false;
    std::optional<std::uint64_t> width, height, points;
    std::map<std::string, std::uint64_t> keyword_lines;  // keyword (lower case) -> its line
    bool first = true;
    for (std::size_t lines = 0; !have_data; ++lines) {
      const auto st = src_.read_line(line_, detail::max_header_line_bytes);
      if (st == detail::ByteSource::LineStatus::eof) {
        if (line_no_ == 0) throw InputError(path_, "byte 0", "empty file: expected a PCD header");
        throw InputError(path_, detail::where_line(line_no_ + 1),
                         "file ends inside the header: expected a DATA line (ascii, binary or binary_compressed)");
      }
      ++line_no_;
      if (st == detail::ByteSource::LineStatus::too_long || lines >= detail::max_header_lines) {
        line_error(first ? "expected a PCD header (\"# .PCD v0.7\", VERSION or FIELDS), found a line longer than " +
                               std::to_string(detail::max_header_line_bytes) + " bytes"
                         : "header line longer than " + std::to_string(detail::max_header_line_bytes) +
                               " bytes or too many header lines: expected a DATA line");
      }
      const std::string_view t = detail::trim(line_);
      if (t.empty()) continue;
      if (t.front() == '#') {
        if (first && detail::lower(t).find(".pcd") == std::string::npos)
          line_error("expected a PCD header (\"# .PCD v0.7\", VERSION or FIELDS), found " + detail::quoted(t));
        first = false;
        continue;
      }
      detail::split_blanks(t, tok);
      const std::string key = detail::lower(tok[0]);
      if (first && key != "version" && key != "fields")
        line_error("expected a PCD header (\"# .PCD v0.7\", VERSION or FIELDS), found " + detail::quoted(t));
      first = false;
      const std::string canonical = key == "columns" ? "fields" : key;
      if (canonical != "fields" && canonical != "size" && canonical != "type" && canonical != "count" &&
          canonical != "width" && canonical != "height" && canonical != "points" && canonical != "data" &&
          canonical != "version" && canonical != "viewpoint")
        line_error("unknown PCD header keyword " + detail::quoted(tok[0]) +
                   ": expected VERSION, FIELDS, SIZE, TYPE, COUNT, WIDTH, HEIGHT, VIEWPOINT, POINTS or DATA");
      std::uint64_t& keyword_line = keyword_lines[canonical];
      if (keyword_line != 0)
        line_error("second " + std::string(tok[0]) + " line (the first is line " + std::to_string(keyword_line) +
                   "): expected each header keyword once");
      keyword_line = line_no_;
      if (key == "version" || key == "viewpoint") {
        continue;
      } else if (key == "fields" || key == "columns") {
        for (std::size_t i = 1; i < tok.size(); ++i) {
          Field f;
          f.name = std::string(tok[i]);
          fields_.push_back(f);
          info_.fields.push_back(f.name);
        }
        check_distinct_fields();
      } else if (key == "size") {
        sizes.assign(tok.begin() + 1, tok.end());
      } else if (key == "type") {
        types.assign(tok.begin() + 1, tok.end());
      } else if (key == "count") {
        counts.assign(tok.begin() + 1, tok.end());
      } else if (key == "width" || key == "height" || key == "points") {
        std::uint64_t v = 0;
        if (tok.size() != 2 || !detail::parse_uint64(tok[1], v))
          line_error("expected " + std::string(tok[0]) + " followed by one non-negative integer, found " +
                     detail::quoted(join(tok, 1)));
        (key == "width" ? width : key == "height" ? height : points) = v;
      } else if (key == "data") {
        const std::string enc = tok.size() == 2 ? detail::lower(tok[1]) : std::string();
        if (enc == "ascii") {
          encoding_ = Encoding::ascii;
        } else if (enc == "binary") {
          encoding_ = Encoding::binary;
        } else if (enc == "binary_compressed") {
          encoding_ = Encoding::binary_compressed;
        } else {
          line_error("expected DATA ascii, binary or binary_compressed, found " + detail::quoted(join(tok, 1)));
        }
        info_.encoding = enc;
        have_data = true;
      }
    }
    const std::uint64_t data_line = line_no_;
    const std::uint64_t fields_line = keyword_lines["fields"], size_line = keyword_lines["size"],
                        type_line = keyword_lines["type"], count_line = keyword_lines["count"],
                        points_line = keyword_lines["points"];
    const bool have_count = count_line != 0;

    // Fields, sizes, types, counts.
    if (fields_line == 0)
      header_error(data_line, "the header ends without FIELDS: expected a FIELDS line naming x, y, z");
    if (fields_.empty()) header_error(fields_line, "FIELDS names no field: expected x, y, z and others");
    if (size_line == 0) header_error(data_line, "the header ends without SIZE: expected one size per field");
    if (type_line == 0) header_error(data_line, "the header ends without TYPE: expected one type (F, I or U) per field");
    const std::size_t nf = fields_.size();
    auto check_len = [&](const char* kw, std::uint64_t line, std::size_t n) {
      if (n != nf)
        header_error(line, std::string(kw) + " has " + std::to_string(n) + " entries, expected " + std::to_string(nf) +
                               " (one per field in FIELDS, line " + std::to_string(fields_line) + ")");
    };
    check_len("SIZE", size_line, sizes.size());
    check_len("TYPE", type_line, types.size());
    if (have_count) check_len("COUNT", count_line, counts.size());
    std::size_t offset = 0, value = 0;
    std::vector<std::string> lowered;
    for (std::size_t i = 0; i < nf; ++i) {
      Field& f = fields_[i];
      std::uint64_t size = 0, count = 1;
      if (!detail::parse_uint64(sizes[i], size) || (size != 1 && size != 2 && size != 4 && size != 8))
        header_error(size_line, "SIZE of field " + detail::printable(f.name) + " is " + detail::quoted(sizes[i]) +
                                    ", expected 1, 2, 4 or 8");
      if (have_count && (!detail::parse_uint64(counts[i], count) || count == 0 || count > (1u << 20)))
        header_error(count_line, "COUNT of field " + detail::printable(f.name) + " is " + detail::quoted(counts[i]) +
                                     ", expected an integer in [1, 1048576]");
      const std::string type(types[i]);
      f.size = static_cast<std::size_t>(size);
      f.count = static_cast<std::size_t>(count);
      if (type == "F" && size == 4) {
        f.scalar = detail::Scalar::f32;
      } else if (type == "F" && size == 8) {
        f.scalar = detail::Scalar::f64;
      } else if (type == "I" || type == "U") {
        const bool u = type == "U";
        f.scalar = size == 1   ? (u ? detail::Scalar::u8 : detail::Scalar::i8)
                   : size == 2 ? (u ? detail::Scalar::u16 : detail::Scalar::i16)
                   : size == 4 ? (u ? detail::Scalar::u32 : detail::Scalar::i32)
                               : (u ? detail::Scalar::u64 : detail::Scalar::i64);
      } else {
        header_error(type_line, "field " + detail::printable(f.name) + " has TYPE " + detail::quoted(type) + " and SIZE " +
                                    std::to_string(size) +
                                    ", expected F with SIZE 4 or 8, or I / U with SIZE 1, 2, 4 or 8");
      }
      f.type = type[0];
      f.offset = offset;
      f.first_value = value;
      offset += f.size * f.count;
      value += f.count;
      // Only single-valued fields can play a role.
      lowered.push_back(f.count == 1 ? detail::lower(f.name) : std::string());
    }
    point_size_ = offset;
    values_per_point_ = value;
    if (point_size_ > (std::size_t{1} << 24))
      header_error(size_line, "point size " + std::to_string(point_size_) + " bytes is absurd: expected at most 16 MiB");

    const auto x = detail::find_field(lowered, {"x"});
    const auto y = detail::find_field(lowered, {"y"});
    const auto z = detail::find_field(lowered, {"z"});
    if (!x || !y || !z) {
      std::string found;
      for (const auto& f : fields_) found += (found.empty() ? "" : " ") + detail::printable(f.name);
      header_error(fields_line, "expected fields x, y and z with COUNT 1, found FIELDS " + found);
    }
    ix_ = *x, iy_ = *y, iz_ = *z;
    ii_ = detail::find_field(lowered, detail::intensity_names);
    it_ = detail::find_field(lowered, detail::time_names);
    il_ = detail::find_field(lowered, detail::label_names);
    info_.has_intensity = ii_.has_value();
    info_.has_label = il_.has_value();
    if (it_) {
      info_.has_time = true;
      info_.time_field = fields_[*it_].name;
      time_default_ = default_time_unit(lowered[*it_]);
    }

    // Point count.
    if (width && height && *width != 0 && *height != 0) {
      const std::uint64_t wh_line = std::max(keyword_lines["width"], keyword_lines["height"]);
      if (*width > std::numeric_limits<std::uint64_t>::max() / *height)
        header_error(wh_line, "WIDTH x HEIGHT overflows");
      if (points && *points != *width * *height)
        header_error(points_line, "WIDTH " + std::to_string(*width) + " x HEIGHT " + std::to_string(*height) + " = " +
                                      std::to_string(*width * *height) + " does not match POINTS " +
                                      std::to_string(*points));
      if (!points) points = *width * *height;
      if (!points_line) points_line_ = wh_line;
    }
    if (!points)
      header_error(data_line, "the header ends without POINTS (and without WIDTH x HEIGHT): expected the number of points");
    if (points_line) points_line_ = points_line;
    points_ = *points;
    info_.declared_points = points_;
  }

  /// A field name given twice (case-insensitive) is an error on the FIELDS
  /// line; `_` (padding) may repeat.
  void check_distinct_fields() const {
    std::vector<std::string> lowered;
    for (const auto& f : fields_) lowered.push_back(detail::lower(f.name));
    const auto d = detail::find_duplicate(lowered, [](const std::string& n) { return n != "_"; });
    if (d)
      line_error("field " + detail::quoted(fields_[d->second].name) + " appears twice in FIELDS (fields " +
                 std::to_string(d->first + 1) + " and " + std::to_string(d->second + 1) + "): expected each name once");
  }

  std::string declared_binary() const {
    return "the declared data (POINTS " + std::to_string(points_) + " x " + std::to_string(point_size_) + " bytes)";
  }

  void throw_truncated_binary(std::uint64_t whole_points) const {
    throw InputError(path_, detail::where_byte(data_offset_ + whole_points * point_size_),
                     "truncated binary data: expected " + std::to_string(points_) + " points of " +
                         std::to_string(point_size_) + " bytes, file ends after " + std::to_string(whole_points) +
                         " points");
  }

  void prepare_data() {
    data_offset_ = src_.offset();
    const std::uint64_t remaining = src_.remaining();
    const std::uint64_t max64 = std::numeric_limits<std::uint64_t>::max();
    if (encoding_ == Encoding::binary) {
      if (points_ > max64 / point_size_ || points_ * point_size_ > remaining) throw_truncated_binary(remaining / point_size_);
      if (src_.size() != max64 && points_ * point_size_ < remaining) {
        detail::throw_trailing_bytes(path_, data_offset_ + points_ * point_size_, src_.size(), declared_binary());
      }
      block_records_ = std::max<std::size_t>(1, std::min<std::size_t>(4096, (std::size_t{1} << 20) / point_size_));
      block_.resize(block_records_ * point_size_);
    } else if (encoding_ == Encoding::ascii) {
      // No allocation depends on POINTS here; reject only what cannot fit even
      // at 2 bytes per point, and let streaming report smaller truncations by line.
      if (points_ > 0 && points_ - 1 > remaining / 2) {
        header_error(points_line_, "POINTS " + std::to_string(points_) + " cannot fit in the " +
                                       std::to_string(remaining) +
                                       " bytes of ascii data after the header (every point needs at least 2 bytes)");
      }
    } else {
      load_compressed(remaining);
    }
  }

  void load_compressed(std::uint64_t remaining) {
    unsigned char sizes[8];
    if (src_.read(reinterpret_cast<char*>(sizes), 8) != 8) {
      throw InputError(path_, detail::where_byte(data_offset_),
                       "truncated binary_compressed data: expected 8 bytes (compressed and uncompressed sizes), "
                       "file has " + std::to_string(remaining));
    }
    const std::uint32_t csize = detail::load_le<std::uint32_t>(sizes);
    const std::uint32_t usize = detail::load_le<std::uint32_t>(sizes + 4);
    const std::uint64_t expected = points_ * static_cast<std::uint64_t>(point_size_);
    if (points_ > (std::uint64_t{1} << 32) || expected > 0xffffffffu) {
      header_error(points_line_, "POINTS " + std::to_string(points_) + " x " + std::to_string(point_size_) +
                                     " bytes exceeds the 4 GiB limit of a binary_compressed block");
    }
    if (usize != expected) {
      throw InputError(path_, detail::where_byte(data_offset_ + 4),
                       "binary_compressed uncompressed size is " + std::to_string(usize) + " bytes, expected POINTS " +
                           std::to_string(points_) + " x " + std::to_string(point_size_) + " bytes = " +
                           std::to_string(expected));
    }
    if (csize > remaining - 8) {
      throw InputError(path_, detail::where_byte(data_offset_ + 8),
                       "truncated binary_compressed data: expected " + std::to_string(csize) +
                           " bytes of LZF data, file has " + std::to_string(remaining - 8));
    }
    // One back reference (3 bytes) produces at most 264 bytes.
    if (static_cast<std::uint64_t>(usize) > static_cast<std::uint64_t>(csize) * 88 + 88) {
      throw InputError(path_, detail::where_byte(data_offset_),
                       "binary_compressed sizes are inconsistent: " + std::to_string(csize) +
                           " bytes of LZF data cannot expand to " + std::to_string(usize) + " bytes");
    }
    // Read the compressed block in chunks, so a lying size cannot allocate more than the file holds.
    std::vector<unsigned char> comp;
    while (comp.size() < csize) {
      const std::size_t old = comp.size();
      const std::size_t want = std::min<std::size_t>(csize - old, std::size_t{1} << 24);
      comp.resize(old + want);
      const std::size_t got = src_.read(reinterpret_cast<char*>(comp.data() + old), want);
      if (got < want) {
        throw InputError(path_, detail::where_byte(data_offset_ + 8 + old + got),
                         "truncated binary_compressed data: expected " + std::to_string(csize) +
                             " bytes of LZF data, file ends after " + std::to_string(old + got));
      }
    }
    detail::expect_binary_end(src_, "the LZF block of " + std::to_string(csize) + " bytes (its size at byte " +
                                        std::to_string(data_offset_) + ")");
    soa_.resize(usize);
    const std::string err = lzf_decompress(comp.data(), comp.size(), soa_.data(), soa_.size());
    if (!err.empty()) throw InputError(path_, detail::where_byte(data_offset_ + 8), "corrupt binary_compressed data: " + err);
    std::uint64_t base = 0;
    for (auto& f : fields_) {
      f.soa_base = base;
      base += points_ * f.size * f.count;
    }
  }

  Record decode_aos(const unsigned char* p) {
    Record r;
    r.x = detail::scalar_to_float(fields_[ix_].scalar, p + fields_[ix_].offset);
    r.y = detail::scalar_to_float(fields_[iy_].scalar, p + fields_[iy_].offset);
    r.z = detail::scalar_to_float(fields_[iz_].scalar, p + fields_[iz_].offset);
    if (ii_) r.intensity = detail::scalar_to_float(fields_[*ii_].scalar, p + fields_[*ii_].offset);
    if (il_) r.label = detail::scalar_to_label(fields_[*il_].scalar, p + fields_[*il_].offset);
    r.t = it_ ? next_time_scalar(fields_[*it_].scalar, p + fields_[*it_].offset) : next_time();
    return r;
  }

  const unsigned char* soa_at(std::size_t field, std::size_t i) const {
    const Field& f = fields_[field];
    return soa_.data() + f.soa_base + static_cast<std::uint64_t>(i) * f.size;
  }

  Record decode_soa(std::size_t i) {
    Record r;
    r.x = detail::scalar_to_float(fields_[ix_].scalar, soa_at(ix_, i));
    r.y = detail::scalar_to_float(fields_[iy_].scalar, soa_at(iy_, i));
    r.z = detail::scalar_to_float(fields_[iz_].scalar, soa_at(iz_, i));
    if (ii_) r.intensity = detail::scalar_to_float(fields_[*ii_].scalar, soa_at(*ii_, i));
    if (il_) r.label = detail::scalar_to_label(fields_[*il_].scalar, soa_at(*il_, i));
    r.t = it_ ? next_time_scalar(fields_[*it_].scalar, soa_at(*it_, i)) : next_time();
    return r;
  }

  template <class T>
  T ascii_value(std::size_t field) const {
    const Field& f = fields_[field];
    const std::string_view s = tok_[f.first_value];
    T v{};
    if (!detail::parse_real(s, v)) {
      throw InputError(path_, detail::where_column(line_no_, f.first_value + 1, f.name),
                       "expected a number, found " + detail::quoted(s));
    }
    return v;
  }

  void read_ascii_record(std::vector<Record>& out) {
    for (;;) {
      const auto st = src_.read_line(line_, detail::max_line_bytes);
      if (st == detail::ByteSource::LineStatus::eof) {
        throw InputError(path_, detail::where_line(line_no_ + 1),
                         "truncated ascii data: expected " + std::to_string(points_) +
                             " points, file ends after " + std::to_string(done_) + " points");
      }
      ++line_no_;
      if (st == detail::ByteSource::LineStatus::too_long)
        line_error("line longer than " + std::to_string(detail::max_line_bytes) + " bytes: expected " +
                   std::to_string(values_per_point_) + " values");
      detail::split_blanks(line_, tok_);
      if (!tok_.empty()) break;
    }
    if (tok_.size() != values_per_point_) {
      std::string names;
      for (const auto& f : fields_) names += (names.empty() ? "" : " ") + f.name;
      line_error("expected " + std::to_string(values_per_point_) + " values (" + names + "), found " +
                 std::to_string(tok_.size()));
    }
    Record r;
    r.x = ascii_value<float>(ix_);
    r.y = ascii_value<float>(iy_);
    r.z = ascii_value<float>(iz_);
    if (ii_) r.intensity = ascii_value<float>(*ii_);
    if (il_) {
      const Field& f = fields_[*il_];
      std::int64_t v = 0;
      if (!detail::parse_int64(tok_[f.first_value], v))
        throw InputError(path_, detail::where_column(line_no_, f.first_value + 1, f.name),
                         "expected an integer label, found " + detail::quoted(tok_[f.first_value]));
      r.label = v;
    }
    r.t = it_ ? next_time_text(tok_[fields_[*it_].first_value], ascii_value<double>(*it_)) : next_time();
    out.push_back(r);
    ++done_;
  }

  detail::ByteSource src_;
  std::string line_;
  std::uint64_t line_no_ = 0;
  std::uint64_t points_line_ = 0;  ///< the line that gave the point count
  bool ended_ = false;             ///< what follows the data was checked
  std::vector<std::string_view> tok_;
  std::vector<Field> fields_;
  std::size_t point_size_ = 0;
  std::size_t values_per_point_ = 0;
  std::size_t ix_ = 0, iy_ = 0, iz_ = 0;
  std::optional<std::size_t> ii_, it_, il_;
  TimeUnit time_default_ = TimeUnit::s;
  Encoding encoding_ = Encoding::ascii;
  std::uint64_t points_ = 0;
  std::uint64_t done_ = 0;
  std::uint64_t data_offset_ = 0;
  std::size_t block_records_ = 1;
  std::vector<unsigned char> block_;
  std::vector<unsigned char> soa_;
};

}  // namespace streamclust::io
