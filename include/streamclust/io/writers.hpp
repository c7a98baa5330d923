// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Writers: CSV points/labels, PCD (ascii, binary, binary_compressed) with a
/// label field, PLY (ascii, binary little-endian) with a label and a colour
/// per label, KITTI .bin and SemanticKITTI .label. All throw
/// std::runtime_error naming the file when it cannot be written, and
/// std::invalid_argument when `labels` is neither empty nor one per record.
/// Floats are written in the shortest form that reads back to the same value
/// (NaN as "nan"), so every text round trip is exact.

#include <streamclust/io/lzf.hpp>
#include <streamclust/io/record.hpp>
#include <streamclust/io/stream_time.hpp>

#include <array>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace streamclust::io {

namespace detail {

/// Buffered output file; `close()` reports any failure with the file name.
class OutFile {
 public:
  explicit OutFile(const std::string& path) : path_(path) {
    out_.open(path, std::ios::binary | std::ios::trunc);
    if (!out_) throw std::runtime_error(path + ": cannot open for writing");
  }
  void write(const void* p, std::size_t n) {
    out_.write(static_cast<const char*>(p), static_cast<std::streamsize>(n));
    if (!out_) throw std::runtime_error(path_ + ": write failed");
  }
  void write(std::string_view s) { write(s.data(), s.size()); }
  template <class T>
  void write_le(T v) {
    write(&v, sizeof v);
  }
  void close() {
    out_.flush();
    out_.close();
    if (!out_) throw std::runtime_error(path_ + ": write failed (disk full?)");
  }

 private:
  std::string path_;
  std::ofstream out_;
};

template <class T>
void append_number(std::string& s, T v);

/// Appends "x<sep>y<sep>z<sep>intensity<sep>t<sep>" of a record (text
/// formats), t as the absolute time origin + r.t.
template <class Record>
void append_point_fields(std::string& s, const Record& r, char sep, TimeOrigin origin) {
  append_number(s, r.x);
  s += sep;
  append_number(s, r.y);
  s += sep;
  append_number(s, r.z);
  s += sep;
  append_number(s, r.intensity);
  s += sep;
  append_time(s, origin, r.t);
  s += sep;
}

/// Appends the shortest round-trip text of v ("nan", "inf", "-inf" for non-finite values).
template <class T>
void append_number(std::string& s, T v) {
  if (v != v) {
    s += "nan";
    return;
  }
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}

inline void check_labels(const std::string& path, const std::vector<Record>& records,
                         const std::vector<std::int64_t>& labels) {
  if (!labels.empty() && labels.size() != records.size()) {
    throw std::invalid_argument(path + ": " + std::to_string(labels.size()) + " labels for " +
                                std::to_string(records.size()) + " records: expected one label per record (or none)");
  }
}

inline std::int64_t label_of(const std::vector<Record>& records, const std::vector<std::int64_t>& labels,
                             std::size_t i) {
  return labels.empty() ? records[i].label : labels[i];
}

inline std::int32_t label32(const std::string& path, std::int64_t l) {
  if (l < std::numeric_limits<std::int32_t>::min() || l > std::numeric_limits<std::int32_t>::max())
    throw std::invalid_argument(path + ": label " + std::to_string(l) + " does not fit the int32 label field");
  return static_cast<std::int32_t>(l);
}

}  // namespace detail

/// The colour of a label: grey (128, 128, 128) for -1 (and any negative
/// label), else a bright colour derived deterministically from the label
/// (a 64-bit mix of it; the same label always gets the same colour).
inline std::array<std::uint8_t, 3> label_color(std::int64_t label) noexcept {
  if (label < 0) return {128, 128, 128};
  std::uint64_t z = static_cast<std::uint64_t>(label) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  // Hue from the hash, full saturation-ish, bright value: never grey.
  const unsigned hue = static_cast<unsigned>(z % 1536u);  // 6 sectors of 256
  const auto f = static_cast<std::uint8_t>(hue & 255u);
  const auto rising = static_cast<std::uint8_t>(40u + (f * 215u) / 255u);
  const auto falling = static_cast<std::uint8_t>(255u - (f * 215u) / 255u);
  switch (hue >> 8) {
    case 0: return {255, rising, 40};
    case 1: return {falling, 255, 40};
    case 2: return {40, 255, rising};
    case 3: return {40, falling, 255};
    case 4: return {rising, 40, 255};
    default: return {255, 40, falling};
  }
}

/// CSV with the header `x,y,z,intensity,t,label` (t in seconds: origin +
/// the record's t, as the shortest text that reads back to it). `labels`:
/// one per record, or empty (the default) to write each record's own label.
inline void write_csv_points(const std::string& path, const std::vector<Record>& records,
                             const std::vector<std::int64_t>& labels, TimeOrigin origin = {}) {
  detail::check_labels(path, records, labels);
  detail::OutFile out(path);
  std::string s = "x,y,z,intensity,t,label\n";
  for (std::size_t i = 0; i < records.size(); ++i) {
    const Record& r = records[i];
    detail::append_point_fields(s, r, ',', origin);
    s += std::to_string(detail::label_of(records, labels, i));
    s += '\n';
    if (s.size() > (1u << 16)) {
      out.write(s);
      s.clear();
    }
  }
  out.write(s);
  out.close();
}

/// CSV with the header `x,y,z,intensity,t,label`, labels from the records.
inline void write_csv_points(const std::string& path, const std::vector<Record>& records) {
  write_csv_points(path, records, {});
}

/// PCD v0.7 with fields `x y z intensity t label` (F4 F4 F4 F4 F8 I4), WIDTH
/// = POINTS = records.size(), HEIGHT 1. `encoding`: "ascii", "binary" or
/// "binary_compressed". `labels`: one per record, or empty to write each
/// record's own label. Labels must fit int32 (std::invalid_argument otherwise).
/// t is the absolute time origin + the record's t (ascii: exact text;
/// binary: a double, 0.24 us at epoch scale).
inline void write_pcd(const std::string& path, const std::vector<Record>& records,
                      const std::vector<std::int64_t>& labels, std::string_view encoding, TimeOrigin origin = {}) {
  detail::check_labels(path, records, labels);
  if (encoding != "ascii" && encoding != "binary" && encoding != "binary_compressed")
    throw std::invalid_argument(path + ": PCD encoding \"" + std::string(encoding) +
                                "\": expected ascii, binary or binary_compressed");
  const std::size_t n = records.size();
  detail::OutFile out(path);
  std::string s = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity t label\n"
                  "SIZE 4 4 4 4 8 4\nTYPE F F F F F I\nCOUNT 1 1 1 1 1 1\nWIDTH " +
                  std::to_string(n) + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(n) + "\nDATA " +
                  std::string(encoding) + "\n";
  out.write(s);
  s.clear();
  constexpr std::size_t point_size = 28;
  if (encoding == "ascii") {
    for (std::size_t i = 0; i < n; ++i) {
      const Record& r = records[i];
      detail::append_point_fields(s, r, ' ', origin);
      s += std::to_string(detail::label32(path, detail::label_of(records, labels, i)));
      s += '\n';
      if (s.size() > (1u << 16)) {
        out.write(s);
        s.clear();
      }
    }
    out.write(s);
  } else if (encoding == "binary") {
    std::vector<unsigned char> buf;
    buf.reserve(4096 * point_size);
    auto put = [&buf](const void* p, std::size_t k) {
      const auto* b = static_cast<const unsigned char*>(p);
      buf.insert(buf.end(), b, b + k);
    };
    for (std::size_t i = 0; i < n; ++i) {
      const Record& r = records[i];
      const std::int32_t l = detail::label32(path, detail::label_of(records, labels, i));
      put(&r.x, 4);
      put(&r.y, 4);
      put(&r.z, 4);
      put(&r.intensity, 4);
      const double t = absolute_seconds(origin, r.t);
      put(&t, 8);
      put(&l, 4);
      if (buf.size() >= 4096 * point_size) {
        out.write(buf.data(), buf.size());
        buf.clear();
      }
    }
    out.write(buf.data(), buf.size());
  } else {
    if (static_cast<std::uint64_t>(n) * point_size > 0xffffffffull)
      throw std::invalid_argument(path + ": " + std::to_string(n) +
                                  " points exceed the 4 GiB limit of a binary_compressed block");
    // Structure of arrays: all x, then all y, ...
    std::vector<unsigned char> soa(n * point_size);
    unsigned char* p = soa.data();
    for (const Record& r : records) std::memcpy(p, &r.x, 4), p += 4;
    for (const Record& r : records) std::memcpy(p, &r.y, 4), p += 4;
    for (const Record& r : records) std::memcpy(p, &r.z, 4), p += 4;
    for (const Record& r : records) std::memcpy(p, &r.intensity, 4), p += 4;
    for (const Record& r : records) {
      const double t = absolute_seconds(origin, r.t);
      std::memcpy(p, &t, 8);
      p += 8;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::int32_t l = detail::label32(path, detail::label_of(records, labels, i));
      std::memcpy(p, &l, 4);
      p += 4;
    }
    const std::vector<unsigned char> comp = lzf_compress(soa.data(), soa.size());
    out.write_le(static_cast<std::uint32_t>(comp.size()));
    out.write_le(static_cast<std::uint32_t>(soa.size()));
    out.write(comp.data(), comp.size());
  }
  out.close();
}

/// PLY (ascii, or binary_little_endian when `binary`) with vertex properties
/// `float x y z intensity`, `double t`, `int label`, `uchar red green blue`
/// (colour from `label_color`). `labels`: one per record, or empty to use
/// the records' labels. Labels must fit int32. t as in write_pcd.
inline void write_ply(const std::string& path, const std::vector<Record>& records,
                      const std::vector<std::int64_t>& labels, bool binary, TimeOrigin origin = {}) {
  detail::check_labels(path, records, labels);
  detail::OutFile out(path);
  const std::size_t n = records.size();
  std::string s = std::string("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") +
                  " 1.0\ncomment written by streamclust\nelement vertex " + std::to_string(n) +
                  "\nproperty float x\nproperty float y\nproperty float z\nproperty float intensity\n"
                  "property double t\nproperty int label\nproperty uchar red\nproperty uchar green\n"
                  "property uchar blue\nend_header\n";
  for (std::size_t i = 0; i < n; ++i) {
    const Record& r = records[i];
    const std::int32_t l = detail::label32(path, detail::label_of(records, labels, i));
    const auto c = label_color(l);
    if (binary) {
      auto put = [&s](const void* p, std::size_t k) { s.append(static_cast<const char*>(p), k); };
      put(&r.x, 4);
      put(&r.y, 4);
      put(&r.z, 4);
      put(&r.intensity, 4);
      const double t = absolute_seconds(origin, r.t);
      put(&t, 8);
      put(&l, 4);
      put(c.data(), 3);
    } else {
      detail::append_point_fields(s, r, ' ', origin);
      s += std::to_string(l) + ' ' + std::to_string(c[0]) + ' ' + std::to_string(c[1]) + ' ' + std::to_string(c[2]) +
           '\n';
    }
    if (s.size() > (1u << 16)) {
      out.write(s);
      s.clear();
    }
  }
  out.write(s);
  out.close();
}

/// KITTI .bin: float32 x, y, z, intensity (as reflectance) per record; no time, no label.
inline void write_kitti_bin(const std::string& path, const std::vector<Record>& records) {
  detail::OutFile out(path);
  std::vector<float> buf;
  buf.reserve(4 * 4096);
  for (const Record& r : records) {
    buf.insert(buf.end(), {r.x, r.y, r.z, r.intensity});
    if (buf.size() >= 4 * 4096) {
      out.write(buf.data(), buf.size() * sizeof(float));
      buf.clear();
    }
  }
  out.write(buf.data(), buf.size() * sizeof(float));
  out.close();
}

/// The SemanticKITTI encoding of a label: `instance << 16 | semantic` with
/// semantic 0 (unlabelled) and instance 0 for labels < 0, else semantic 1
/// (labelled) and instance = min(label + 1, 65535).
inline std::uint32_t semantickitti_encode(std::int64_t label) noexcept {
  if (label < 0) return 0;
  const std::uint32_t instance = label >= 65534 ? 65535u : static_cast<std::uint32_t>(label + 1);
  return (instance << 16) | 1u;
}

/// Inverse of `semantickitti_encode`: -1 for semantic 0, else instance - 1.
inline std::int64_t semantickitti_decode(std::uint32_t v) noexcept {
  if ((v & 0xffffu) == 0) return -1;
  return static_cast<std::int64_t>(v >> 16) - 1;
}

/// SemanticKITTI .label: one little-endian uint32 per point, `semantickitti_encode(label)`.
inline void write_semantickitti_labels(const std::string& path, const std::vector<std::int64_t>& labels) {
  detail::OutFile out(path);
  std::vector<std::uint32_t> buf;
  buf.reserve(labels.size());
  for (const std::int64_t l : labels) buf.push_back(semantickitti_encode(l));
  out.write(buf.data(), buf.size() * sizeof(std::uint32_t));
  out.close();
}

/// Reads a SemanticKITTI .label file back into labels (`semantickitti_decode`).
/// Throws std::runtime_error naming the file when it cannot be read or its
/// size is not a multiple of 4.
inline std::vector<std::int64_t> read_semantickitti_labels(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::vector<std::int64_t> labels;
  unsigned char b[4];
  std::uint64_t offset = 0;
  for (;;) {
    in.read(reinterpret_cast<char*>(b), 4);
    const auto got = in.gcount();
    if (got == 0) break;
    if (got != 4)
      throw std::runtime_error(path + ": byte " + std::to_string(offset) +
                               ": partial label: expected 4 bytes (uint32), file ends after " + std::to_string(got));
    std::uint32_t v;
    std::memcpy(&v, b, 4);
    labels.push_back(semantickitti_decode(v));
    offset += 4;
  }
  return labels;
}

}  // namespace streamclust::io
