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
///   the vertex are skipped. Elements before the vertex element are skipped
///   (ascii: one line per item; binary: only when they have no list
///   property); elements after it are ignored.
/// - binary_big_endian: a clear "unsupported" error.

#include <streamclust/io/error.hpp>
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
    return n;
  }

 private:
  struct Property {
    std::string name;
    detail::Scalar scalar = detail::Scalar::f32;
    bool is_list = false;
    detail::Scalar count_scalar = detail::Scalar::u8;
  };
  struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> props;
  };

  [[noreturn]] void header_error(const std::string& what) const { throw InputError(path_, "header", what); }
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
        elements_.back().props.push_back(p);
      } else {
        line_error("unknown PLY header keyword " + detail::quoted(key) +
                   ": expected format, element, property, comment or end_header");
      }
    }
    if (!have_format) header_error("missing format line: expected \"format ascii 1.0\" or \"format binary_little_endian 1.0\"");
    const auto v = std::find_if(elements_.begin(), elements_.end(), [](const Element& e) { return e.name == "vertex"; });
    if (v == elements_.end()) header_error("no \"element vertex N\": expected the points in a vertex element");
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
      for (const auto& p : v->props) found += (found.empty() ? "" : " ") + p.name;
      header_error("expected vertex properties x, y and z, found: " + found);
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

  static std::uint64_t element_fixed_size(const Element& e, bool& has_list) {
    std::uint64_t s = 0;
    has_list = false;
    for (const auto& p : e.props) {
      if (p.is_list) has_list = true;
      s += detail::scalar_size(p.scalar);
    }
    return s;
  }

  void prepare_data() {
    const std::uint64_t max64 = std::numeric_limits<std::uint64_t>::max();
    // Skip the elements before the vertex element.
    for (std::size_t e = 0; e < vertex_; ++e) {
      const Element& el = elements_[e];
      if (binary_) {
        bool list = false;
        const std::uint64_t s = element_fixed_size(el, list);
        if (list)
          header_error("element " + el.name + " before the vertex element has a list property: unsupported in binary PLY");
        if (s != 0 && (el.count > max64 / s || el.count * s > src_.remaining()))
          throw InputError(path_, detail::where_byte(src_.offset()),
                           "truncated binary data: element " + el.name + " needs " + std::to_string(el.count) + " x " +
                               std::to_string(s) + " bytes");
        src_.skip(el.count * s);
      } else {
        for (std::uint64_t i = 0; i < el.count; ++i) {
          const auto st = src_.read_line(line_, detail::max_line_bytes);
          if (st == detail::ByteSource::LineStatus::eof)
            throw InputError(path_, detail::where_line(line_no_ + 1),
                             "truncated ascii data: element " + el.name + " expects " + std::to_string(el.count) +
                                 " lines, file ends after " + std::to_string(i));
          ++line_no_;
          if (st == detail::ByteSource::LineStatus::too_long) line_error("line longer than 1 MiB");
        }
      }
    }
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
      record_.resize(fixed_size_ + 8);
    } else {
      // No allocation depends on the count here; reject only what cannot fit
      // even at 2 bytes per vertex, and let streaming report smaller truncations by line.
      if (vertices_ > 0 && vertices_ - 1 > remaining / 2) {
        header_error("element vertex " + std::to_string(vertices_) + " cannot fit in the " + std::to_string(remaining) +
                     " bytes of ascii data after the header (every vertex needs at least 2 bytes)");
      }
    }
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

  Record read_ascii_record() {
    for (;;) {
      const auto st = src_.read_line(line_, detail::max_line_bytes);
      if (st == detail::ByteSource::LineStatus::eof)
        throw InputError(path_, detail::where_line(line_no_ + 1),
                         "truncated ascii data: expected " + std::to_string(vertices_) + " vertices, file ends after " +
                             std::to_string(done_) + " vertices");
      ++line_no_;
      if (st == detail::ByteSource::LineStatus::too_long) line_error("line longer than 1 MiB: expected a vertex");
      detail::split_blanks(line_, tok_);
      if (!tok_.empty()) break;
    }
    std::size_t k = 0;  // token index
    for (std::size_t i = 0; i < props_.size(); ++i) {
      const Property& p = props_[i];
      if (k >= tok_.size()) count_error(k);
      if (p.is_list) {
        std::int64_t count = 0;
        if (!detail::parse_int64(tok_[k], count) || count < 0)
          throw InputError(path_, detail::where_column(line_no_, k + 1, p.name),
                           "expected a list length, found " + detail::quoted(tok_[k]));
        ++k;
        if (static_cast<std::uint64_t>(count) > tok_.size() - k) count_error(tok_.size() + 1);
        k += static_cast<std::size_t>(count);
        continue;
      }
      double v = 0;
      if (!detail::parse_real(tok_[k], v))
        throw InputError(path_, detail::where_column(line_no_, k + 1, p.name),
                         "expected a number, found " + detail::quoted(tok_[k]));
      values_[i] = v;
      if (it_ && i == *it_) time_text_ = tok_[k];
      if (il_ && i == *il_) {
        std::int64_t l = 0;
        if (!detail::parse_int64(tok_[k], l))
          throw InputError(path_, detail::where_column(line_no_, k + 1, p.name),
                           "expected an integer label, found " + detail::quoted(tok_[k]));
        label_value_ = l;
      }
      ++k;
    }
    if (k != tok_.size()) count_error(k);
    return make_record();
  }

  [[noreturn]] void count_error(std::size_t) const {
    std::string names;
    for (const auto& p : props_) names += (names.empty() ? "" : " ") + p.name;
    line_error("expected " + std::to_string(props_.size()) + " vertex properties (" + names + "), found " +
               std::to_string(tok_.size()) + " values");
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
  std::vector<unsigned char> record_;
  std::vector<double> values_;
  std::int64_t label_value_ = -1;
  std::array<unsigned char, 8> time_bytes_{};  ///< the time property's bytes (binary)
  std::string_view time_text_;                 ///< the time property's token (ascii)
};

}  // namespace streamclust::io
