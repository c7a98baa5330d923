// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Streaming PLY reader: `format ascii 1.0` and `format binary_little_endian 1.0`.
///
/// - Header: `ply`, `format ...`, `comment` / `obj_info` lines, `element NAME N`,
///   `property TYPE NAME` (char uchar short ushort int uint float double and the
///   int8 .. float64 aliases), `property list CTYPE ITYPE NAME`, `end_header`.
/// - Points come from `element vertex`: x y z (required), intensity
///   (reflectivity, reflectance, scalar_intensity), time (t, time, timestamp,
///   offset_time), label (label, gt, instance, object). List properties of
///   the vertex are skipped. The other elements (faces, edges, ...), before
///   and after the vertex element, are read and checked, not kept: every item
///   complete (ascii: one line of numbers, lists as long as their count says;
///   binary: up to its last byte), then the end of the file (data_end.hpp):
///   blank lines (ascii) or nothing (binary). Binary sizes are checked against
///   the file size at open where no list makes them variable.
/// - An element name twice, or a property name twice in one element
///   (case-insensitive), is an error naming the header line; so are header
///   consistency errors (no format: the end_header line; no x, y, z: the
///   `element vertex` line).
/// - binary_big_endian: a clear "unsupported" error.

#include <streamclust/io/data_end.hpp>
#include <streamclust/io/error.hpp>
#include <streamclust/io/field_names.hpp>
#include <streamclust/io/input_stream.hpp>
#include <streamclust/io/point_reader.hpp>
#include <streamclust/io/record.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace streamclust::io {

/// Reader of PLY files. See the file comment.
class PlyReader final : public PointReader {
 public:
  PlyReader(const std::string& path, const ReadOptions& options) : PointReader(path), src_(path) {
    info_.format = Format::ply;
    parse_header();
    setup_time(options, time_default_);
    prepare_data();
  }

  std::size_t read(std::vector<Record>& out, std::size_t max_records) override {
    std::size_t n = 0;
    while (n < max_records && done_ < vertices_) {
      out.push_back(binary_ ? read_binary_record() : read_ascii_record());
      ++done_;
      ++n;
    }
    if (done_ == vertices_ && !ended_) {
      ended_ = true;
      for (std::size_t e = vertex_ + 1; e < elements_.size(); ++e) skip_element(elements_[e]);
      const std::string declared = "the last element (" + detail::printable(elements_.back().name) + ", " +
                                   std::to_string(elements_.back().count) + " items)";
      if (binary_) detail::expect_binary_end(src_, declared);
      else detail::expect_text_end(src_, line_, line_no_, declared);
    }
    return n;
  }

 private:
  struct Property {
    std::string name;
    detail::Scalar scalar = detail::Scalar::f32;
    bool is_list = false;
    detail::Scalar count_scalar = detail::Scalar::u8;
    std::uint64_t line = 0;  ///< header line
  };
  struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> props;
    std::uint64_t line = 0;  ///< header line
  };

  [[noreturn]] void header_error(std::uint64_t line, const std::string& what) const {
    throw InputError(path_, detail::where_line(line), what);
  }
  [[noreturn]] void line_error(const std::string& what) const {
    throw InputError(path_, detail::where_line(line_no_), what);
  }

  static std::optional<detail::Scalar> scalar_of(std::string_view t) {
    using detail::Scalar;
    if (t == "char" || t == "int8") return Scalar::i8;
    if (t == "uchar" || t == "uint8") return Scalar::u8;
    if (t == "short" || t == "int16") return Scalar::i16;
    if (t == "ushort" || t == "uint16") return Scalar::u16;
    if (t == "int" || t == "int32") return Scalar::i32;
    if (t == "uint" || t == "uint32") return Scalar::u32;
    if (t == "float" || t == "float32") return Scalar::f32;
    if (t == "double" || t == "float64") return Scalar::f64;
    if (t == "int64") return Scalar::i64;
    if (t == "uint64") return Scalar::u64;
    return std::nullopt;
  }

  void parse_header() {
    std::vector<std::string_view> tok;
    bool have_format = false;
    for (std::size_t lines = 0;; ++lines) {
      const auto st = src_.read_line(line_, detail::max_header_line_bytes);
      if (st == detail::ByteSource::LineStatus::eof) {
        if (line_no_ == 0) throw InputError(path_, "byte 0", "empty file: expected a PLY header");
        throw InputError(path_, detail::where_line(line_no_ + 1), "file ends inside the header: expected end_header");
      }
      ++line_no_;
      if (line_no_ == 1) {
        if (st != detail::ByteSource::LineStatus::ok || detail::trim(line_) != "ply")
          line_error("expected the PLY magic line \"ply\", found " +
                     detail::quoted(st == detail::ByteSource::LineStatus::ok ? std::string_view(line_)
                                                                             : std::string_view("(a very long line)")));
        continue;
      }
      if (st == detail::ByteSource::LineStatus::too_long || lines >= detail::max_header_lines)
        line_error("header line too long or too many header lines: expected end_header");
      detail::split_blanks(line_, tok);
      if (tok.empty()) continue;
      const std::string_view key = tok[0];
      if (key == "comment" || key == "obj_info") continue;
      if (key == "end_header") break;
      if (key == "format") {
        if (tok.size() != 3) line_error("expected \"format ascii 1.0\" or \"format binary_little_endian 1.0\"");
        if (tok[1] == "ascii") {
          binary_ = false;
        } else if (tok[1] == "binary_little_endian") {
          binary_ = true;
        } else if (tok[1] == "binary_big_endian") {
          line_error("unsupported PLY format binary_big_endian: expected ascii or binary_little_endian");
        } else {
          line_error("expected format ascii or binary_little_endian, found " + detail::quoted(tok[1]));
        }
        info_.encoding = std::string(tok[1]);
        have_format = true;
      } else if (key == "element") {
        Element e;
        if (tok.size() != 3 || !detail::parse_uint64(tok[2], e.count))
          line_error("expected \"element NAME COUNT\" with a non-negative integer COUNT, found " + detail::quoted(line_));
        e.name = std::string(tok[1]);
        e.line = line_no_;
        for (const Element& other : elements_)
          if (detail::lower(other.name) == detail::lower(e.name))
            line_error("element " + detail::quoted(e.name) + " declared twice (the first on line " +
                       std::to_string(other.line) + "): expected each element once");
        elements_.push_back(e);
      } else if (key == "property") {
        if (elements_.empty()) line_error("property before any element");
        Property p;
        if (tok.size() == 5 && tok[1] == "list") {
          const auto c = scalar_of(tok[2]);
          const auto s = scalar_of(tok[3]);
          if (!c || !s || detail::scalar_is_float(*c))
            line_error("expected \"property list COUNT_TYPE ITEM_TYPE NAME\" with an integer COUNT_TYPE, found " +
                       detail::quoted(line_));
          p.is_list = true;
          p.count_scalar = *c;
          p.scalar = *s;
          p.name = std::string(tok[4]);
        } else if (tok.size() == 3) {
          const auto s = scalar_of(tok[1]);
          if (!s)
            line_error("unknown property type " + detail::quoted(tok[1]) +
                       ": expected char uchar short ushort int uint float double (or int8 .. float64)");
          p.scalar = *s;
          p.name = std::string(tok[2]);
        } else {
          line_error("expected \"property TYPE NAME\" or \"property list COUNT_TYPE ITEM_TYPE NAME\", found " +
                     detail::quoted(line_));
        }
        p.line = line_no_;
        for (const Property& other : elements_.back().props)
          if (detail::lower(other.name) == detail::lower(p.name))
            line_error("property " + detail::quoted(p.name) + " appears twice in element " +
                       detail::quoted(elements_.back().name) + " (the first on line " + std::to_string(other.line) +
                       "): expected each name once");
        elements_.back().props.push_back(p);
      } else {
        line_error("unknown PLY header keyword " + detail::quoted(key) +
                   ": expected format, element, property, comment or end_header");
      }
    }
    const std::uint64_t end_line = line_no_;
    if (!have_format)
      header_error(end_line, "the header ends without a format line: expected \"format ascii 1.0\" or "
                             "\"format binary_little_endian 1.0\"");
    const auto v = std::find_if(elements_.begin(), elements_.end(), [](const Element& e) { return e.name == "vertex"; });
    if (v == elements_.end())
      header_error(end_line, "the header ends without \"element vertex N\": expected the points in a vertex element");
    vertex_ = static_cast<std::size_t>(v - elements_.begin());
    vertices_ = v->count;
    info_.declared_points = vertices_;
    std::vector<std::string> lowered;
    for (const auto& p : v->props) {
      info_.fields.push_back(p.name);
      lowered.push_back(p.is_list ? std::string() : detail::lower(p.name));
    }
    const auto x = detail::find_field(lowered, {"x"});
    const auto y = detail::find_field(lowered, {"y"});
    const auto z = detail::find_field(lowered, {"z"});
    if (!x || !y || !z) {
      std::string found;
      for (const auto& p : v->props) found += (found.empty() ? "" : " ") + detail::printable(p.name);
      header_error(v->line, "expected vertex properties x, y and z, found: " + found);
    }
    ix_ = *x, iy_ = *y, iz_ = *z;
    ii_ = detail::find_field(lowered, {"intensity", "reflectivity", "reflectance", "scalar_intensity"});
    it_ = detail::find_field(lowered, detail::time_names);
    il_ = detail::find_field(lowered, detail::label_names);
    info_.has_intensity = ii_.has_value();
    info_.has_label = il_.has_value();
    if (it_) {
      info_.has_time = true;
      info_.time_field = v->props[*it_].name;
      time_default_ = default_time_unit(lowered[*it_]);
    }
    props_ = v->props;
    fixed_size_ = 0;
    for (const auto& p : props_) {
      if (p.is_list) has_list_ = true;
      else fixed_size_ += detail::scalar_size(p.scalar);
    }
    values_.assign(props_.size(), 0.0);
    label_value_ = -1;
  }

  /// Bytes of one item of `e`, a list counting only its length field;
  /// `has_list` tells whether items can be longer. O(properties).
  static std::uint64_t element_min_size(const Element& e, bool& has_list) {
    std::uint64_t s = 0;
    has_list = false;
    for (const auto& p : e.props) {
      has_list = has_list || p.is_list;
      s += detail::scalar_size(p.is_list ? p.count_scalar : p.scalar);
    }
    return s;
  }

  void prepare_data() {
    const std::uint64_t max64 = std::numeric_limits<std::uint64_t>::max();
    for (std::size_t e = 0; e < vertex_; ++e) skip_element(elements_[e]);
    data_offset_ = src_.offset();
    const std::uint64_t remaining = src_.remaining();
    if (binary_) {
      // x, y, z make fixed_size_ >= 3; list properties only add to it.
      if (vertices_ > max64 / fixed_size_ || vertices_ * fixed_size_ > remaining) {
        throw InputError(path_, detail::where_byte(data_offset_ + (remaining / fixed_size_) * fixed_size_),
                         "truncated binary data: expected " + std::to_string(vertices_) + " vertices of " +
                             std::to_string(fixed_size_) + (has_list_ ? " or more" : "") + " bytes, file ends after " +
                             std::to_string(remaining / fixed_size_) + " vertices");
      }
      if (src_.size() != max64 && !has_list_) check_binary_sizes(remaining - vertices_ * fixed_size_);
      record_.resize(fixed_size_ + 8);
    } else {
      // No allocation depends on the count here; reject only what cannot fit
      // even at 2 bytes per vertex, and let streaming report smaller truncations by line.
      if (vertices_ > 0 && vertices_ - 1 > remaining / 2) {
        header_error(elements_[vertex_].line,
                     "element vertex " + std::to_string(vertices_) + " cannot fit in the " + std::to_string(remaining) +
                         " bytes of ascii data after the header (every vertex needs at least 2 bytes)");
      }
    }
  }

  /// Binary, at open: the elements after the vertex element against the
  /// `rest` of the file after the vertices, while no list makes their size
  /// variable (then the reading checks). O(elements).
  void check_binary_sizes(std::uint64_t rest) const {
    const std::uint64_t max64 = std::numeric_limits<std::uint64_t>::max();
    const std::uint64_t start = data_offset_ + vertices_ * fixed_size_;
    std::uint64_t used = 0;
    for (std::size_t i = vertex_ + 1; i < elements_.size(); ++i) {
      const Element& e = elements_[i];
      bool list = false;
      const std::uint64_t size = element_min_size(e, list);
      if (list) return;
      if (size == 0) continue;
      if (e.count > max64 / size || e.count * size > rest - used) {
        const std::uint64_t whole = (rest - used) / size;
        throw_truncated_element(e, start + used + whole * size, whole, size);
      }
      used += e.count * size;
    }
    if (used < rest)
      detail::throw_trailing_bytes(path_, start + used, src_.size(),
                                   "the last element (" + detail::printable(elements_.back().name) + ", " +
                                       std::to_string(elements_.back().count) + " items)");
  }

  [[noreturn]] void throw_truncated_element(const Element& e, std::uint64_t at, std::uint64_t whole,
                                            std::uint64_t item_size) const {
    throw InputError(path_, detail::where_byte(at),
                     "truncated binary data: element " + detail::quoted(e.name) + " expects " + std::to_string(e.count) +
                         " items" + (item_size ? " of " + std::to_string(item_size) + " bytes" : std::string()) +
                         ", file ends after " + std::to_string(whole) + " items");
  }

  /// Reads past the items of an element that holds no points, checking each
  /// (see the file comment). O(bytes of the element).
  void skip_element(const Element& e) {
    if (e.props.empty()) return;  // items without bytes (ascii: empty lines, skipped as blank)
    if (!binary_) {
      for (std::uint64_t i = 0; i < e.count; ++i) {
        if (!next_data_line())
          throw InputError(path_, detail::where_line(line_no_ + 1),
                           "truncated ascii data: element " + detail::quoted(e.name) + " expects " +
                               std::to_string(e.count) + " items, file ends after " + std::to_string(i) + " items");
        parse_ascii_item(e, false);
      }
      return;
    }
    bool list = false;
    const std::uint64_t size = element_min_size(e, list);
    const std::uint64_t start = src_.offset();
    if (!list) {
      const std::uint64_t max64 = std::numeric_limits<std::uint64_t>::max();
      const std::uint64_t want = e.count > max64 / size ? max64 : e.count * size;
      const std::uint64_t got = want > src_.remaining() ? 0 : src_.skip(want);
      if (got < want) {
        const std::uint64_t whole = (want > src_.remaining() ? src_.remaining() : got) / size;
        throw_truncated_element(e, start + whole * size, whole, size);
      }
      return;
    }
    for (std::uint64_t i = 0; i < e.count; ++i) {
      if (!skip_binary_item(e)) throw_truncated_element(e, src_.offset(), i, 0);
    }
  }

  /// Binary: reads past one item of `e`; false when the file ends inside it.
  bool skip_binary_item(const Element& e) {
    unsigned char b[8];
    for (const Property& p : e.props) {
      if (!p.is_list) {
        const std::size_t s = detail::scalar_size(p.scalar);
        if (src_.skip(s) != s) return false;
        continue;
      }
      const std::size_t s = detail::scalar_size(p.count_scalar);
      if (src_.read(reinterpret_cast<char*>(b), s) != s) return false;
      const std::int64_t count = detail::scalar_to_label(p.count_scalar, b);
      if (count < 0)
        throw InputError(path_, detail::where_byte(src_.offset() - s),
                         "negative list length " + std::to_string(count) + " in property " + detail::quoted(p.name));
      const std::uint64_t bytes = static_cast<std::uint64_t>(count) * detail::scalar_size(p.scalar);
      if (src_.skip(bytes) != bytes) return false;
    }
    return true;
  }

  [[noreturn]] void throw_truncated(std::uint64_t whole) const {
    throw InputError(path_, detail::where_byte(has_list_ ? src_.offset() : data_offset_ + whole * fixed_size_),
                     "truncated binary data: expected " + std::to_string(vertices_) + " vertices" +
                         (has_list_ ? std::string() : " of " + std::to_string(fixed_size_) + " bytes") +
                         ", file ends after " + std::to_string(whole) + " vertices");
  }

  Record make_record() {
    Record r;
    r.x = detail::to_float(values_[ix_]);
    r.y = detail::to_float(values_[iy_]);
    r.z = detail::to_float(values_[iz_]);
    if (ii_) r.intensity = detail::to_float(values_[*ii_]);
    if (il_) r.label = label_value_;
    if (!it_) {
      r.t = next_time();
    } else if (binary_) {
      r.t = next_time_scalar(props_[*it_].scalar, time_bytes_.data());
    } else {
      r.t = next_time_text(time_text_, values_[*it_]);
    }
    return r;
  }

  Record read_binary_record() {
    if (!has_list_) {
      if (src_.read(reinterpret_cast<char*>(record_.data()), fixed_size_) != fixed_size_) throw_truncated(done_);
      std::size_t off = 0;
      for (std::size_t i = 0; i < props_.size(); ++i) {
        store(i, record_.data() + off);
        off += detail::scalar_size(props_[i].scalar);
      }
      return make_record();
    }
    for (std::size_t i = 0; i < props_.size(); ++i) {
      const Property& p = props_[i];
      if (!p.is_list) {
        const std::size_t s = detail::scalar_size(p.scalar);
        if (src_.read(reinterpret_cast<char*>(record_.data()), s) != s) throw_truncated(done_);
        store(i, record_.data());
      } else {
        const std::size_t s = detail::scalar_size(p.count_scalar);
        if (src_.read(reinterpret_cast<char*>(record_.data()), s) != s) throw_truncated(done_);
        const std::int64_t count = detail::scalar_to_label(p.count_scalar, record_.data());
        if (count < 0)
          throw InputError(path_, detail::where_byte(src_.offset() - s),
                           "negative list length " + std::to_string(count) + " in property " + p.name);
        const std::uint64_t bytes = static_cast<std::uint64_t>(count) * detail::scalar_size(p.scalar);
        if (src_.skip(bytes) != bytes) throw_truncated(done_);
      }
    }
    return make_record();
  }

  void store(std::size_t i, const unsigned char* p) {
    const Property& prop = props_[i];
    values_[i] = detail::scalar_to_double(prop.scalar, p);
    if (il_ && i == *il_) label_value_ = detail::scalar_to_label(prop.scalar, p);
    if (it_ && i == *it_) std::memcpy(time_bytes_.data(), p, detail::scalar_size(prop.scalar));
  }

  /// Ascii: the next non-blank line into tok_; false at end of file.
  bool next_data_line() {
    for (;;) {
      const auto st = src_.read_line(line_, detail::max_line_bytes);
      if (st == detail::ByteSource::LineStatus::eof) return false;
      ++line_no_;
      if (st == detail::ByteSource::LineStatus::too_long)
        line_error("line longer than " + std::to_string(detail::max_line_bytes) + " bytes: expected an item");
      detail::split_blanks(line_, tok_);
      if (!tok_.empty()) return true;
    }
  }

  Record read_ascii_record() {
    if (!next_data_line())
      throw InputError(path_, detail::where_line(line_no_ + 1),
                       "truncated ascii data: expected " + std::to_string(vertices_) + " vertices, file ends after " +
                           std::to_string(done_) + " vertices");
    parse_ascii_item(elements_[vertex_], true);
    return make_record();
  }

  /// Checks the tokens of one ascii item of `e` (tok_, line line_no_): a
  /// number per property, a list as long as its length says, nothing more.
  /// `vertex`: keeps the values make_record needs. O(tokens).
  void parse_ascii_item(const Element& e, bool vertex) {
    std::size_t k = 0;  // token index
    for (std::size_t i = 0; i < e.props.size(); ++i) {
      const Property& p = e.props[i];
      if (k >= tok_.size()) count_error(e, k);
      if (p.is_list) {
        std::int64_t count = 0;
        if (!detail::parse_int64(tok_[k], count) || count < 0)
          throw InputError(path_, detail::where_column(line_no_, k + 1, p.name),
                           "expected a list length, found " + detail::quoted(tok_[k]));
        ++k;
        if (static_cast<std::uint64_t>(count) > tok_.size() - k)
          throw InputError(path_, detail::where_column(line_no_, k, p.name),
                           "list of " + std::to_string(count) + " items cut short: the line ends after " +
                               std::to_string(tok_.size() - k));
        for (const std::size_t end = k + static_cast<std::size_t>(count); k < end; ++k) {
          double v = 0;
          if (!detail::parse_real(tok_[k], v))
            throw InputError(path_, detail::where_column(line_no_, k + 1, p.name),
                             "expected a number in the list, found " + detail::quoted(tok_[k]));
        }
        continue;
      }
      double v = 0;
      if (!detail::parse_real(tok_[k], v))
        throw InputError(path_, detail::where_column(line_no_, k + 1, p.name),
                         "expected a number, found " + detail::quoted(tok_[k]));
      if (vertex) {
        values_[i] = v;
        if (it_ && i == *it_) time_text_ = tok_[k];
        if (il_ && i == *il_) {
          std::int64_t l = 0;
          if (!detail::parse_int64(tok_[k], l))
            throw InputError(path_, detail::where_column(line_no_, k + 1, p.name),
                             "expected an integer label, found " + detail::quoted(tok_[k]));
          label_value_ = l;
        }
      }
      ++k;
    }
    if (k != tok_.size()) count_error(e, k);
  }

  /// An item with too few or too many values; `expected`: the values read
  /// when the line had too many.
  [[noreturn]] void count_error(const Element& e, std::size_t expected) const {
    std::string names;
    bool list = false;
    for (const auto& p : e.props) {
      if (!names.empty()) names += ' ';
      names += detail::printable(p.name);  // not `"" + string&&`: g++ 12 -Wrestrict false positive in C++20
      list = list || p.is_list;
    }
    if (!list)
      line_error("expected " + std::to_string(e.props.size()) + " " + detail::printable(e.name) + " properties (" +
                 names + "), found " + std::to_string(tok_.size()) + " values");
    line_error("expected " + (expected < tok_.size() ? std::to_string(expected) : std::string("more")) +
               " values for the " + detail::printable(e.name) + " properties (" + names + "; lists as long as their "
               "lengths say), found " + std::to_string(tok_.size()));
  }

  detail::ByteSource src_;
  std::string line_;
  std::uint64_t line_no_ = 0;
  std::vector<std::string_view> tok_;
  std::vector<Element> elements_;
  std::vector<Property> props_;
  std::size_t vertex_ = 0;
  bool binary_ = false;
  bool has_list_ = false;
  std::size_t fixed_size_ = 0;
  std::uint64_t vertices_ = 0;
  std::uint64_t done_ = 0;
  std::uint64_t data_offset_ = 0;
  std::size_t ix_ = 0, iy_ = 0, iz_ = 0;
  std::optional<std::size_t> ii_, it_, il_;
  TimeUnit time_default_ = TimeUnit::s;
  bool ended_ = false;  ///< the elements after the vertices and the end were checked
  std::vector<unsigned char> record_;
  std::vector<double> values_;
  std::int64_t label_value_ = -1;
  std::array<unsigned char, 8> time_bytes_{};  ///< the time property's bytes (binary)
  std::string_view time_text_;                 ///< the time property's token (ascii)
};

}  // namespace streamclust::io
