// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// TUM trajectory files: one pose per line, `t tx ty tz qx qy qz qw`
/// (time [s], position [m], unit quaternion of world from sensor), separated
/// by spaces or tabs; lines starting with `#` and blank lines are ignored.
/// Standard library only: the records are plain numbers
/// (motion/tum_poses.hpp makes poses of them).
///
/// \code
/// const auto records = streamclust::io::read_tum("odom.tum");  // std::vector<TumRecord>; throws io::InputError
/// \endcode
///
/// Thread safety: free functions without shared state.

#include <streamclust/io/error.hpp>
#include <streamclust/io/input_stream.hpp>
#include <streamclust/io/stream_time.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <istream>
#include <ostream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace streamclust::io {

/// One line of a TUM trajectory.
struct TumRecord {
  double t = 0.0;                     ///< [s] since the time origin the file was read or written with
  double tx = 0.0, ty = 0.0, tz = 0.0;  ///< position [m]
  double qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;  ///< rotation, unit quaternion (x, y, z, w)
};

/// Writes `records` as a TUM trajectory with a `#` header line: times as
/// origin + t with nanosecond resolution (`format_time`, exact at any
/// origin), positions and quaternions with 9 decimals. O(records).
inline void write_tum(std::ostream& out, const std::vector<TumRecord>& records, TimeOrigin origin = {}) {
  out << "# t tx ty tz qx qy qz qw\n";
  char line[256];
  for (const TumRecord& r : records) {
    std::snprintf(line, sizeof line, "%s %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n", format_time(origin, r.t).c_str(), r.tx,
                  r.ty, r.tz, r.qx, r.qy, r.qz, r.qw);
    out << line;
  }
}

/// Quaternions shorter than this are rejected by read_tum as zero.
inline constexpr double tum_min_quaternion_norm = 1e-6;

/// Reads a TUM trajectory from `in`; `name` (the file's path) names it in
/// errors. Every line that is neither blank nor a `#` comment holds exactly
/// 8 numbers separated by spaces or tabs; each is finite, the times strictly
/// increase, the quaternion's norm is >= 1e-6 and finite (components of
/// 1e155 and more overflow it; not normalised here); at least one pose.
/// Otherwise io::InputError "NAME: line N[, column K (name)]:
/// expected ..., found ...". Times are returned as seconds since `origin`
/// (the stream's time origin, stream_time.hpp), shifted exactly as the
/// point readers shift theirs; numbers are parsed correctly rounded, so a
/// file written by write_tum with the same origin reads back within 0.5 ns.
/// O(lines); memory: the records.
inline std::vector<TumRecord> read_tum(std::istream& in, const std::string& name, TimeOrigin origin = {}) {
  static constexpr const char* columns[8] = {"t", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};
  std::vector<TumRecord> out;
  std::string line;
  std::vector<std::string_view> fields;
  std::uint64_t line_no = 0;
  std::uint64_t previous_line = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string_view text = detail::trim(line);
    if (text.empty() || text.front() == '#') continue;
    detail::split_blanks(text, fields);
    if (fields.size() != 8) {
      throw InputError(name, detail::where_line(line_no),
                       "expected 8 numbers separated by blanks (t tx ty tz qx qy qz qw), found " +
                           std::to_string(fields.size()) + " field" + (fields.size() == 1 ? "" : "s") + ": " +
                           detail::quoted(text));
    }
    double v[8] = {};
    for (std::size_t k = 0; k < 8; ++k) {
      if (!detail::parse_real(fields[k], v[k])) {
        throw InputError(name, detail::where_column(line_no, k + 1, columns[k]),
                         "expected a number, found " + detail::quoted(fields[k]));
      }
      if (!std::isfinite(v[k])) {
        throw InputError(name, detail::where_column(line_no, k + 1, columns[k]),
                         "expected a finite number, found " + detail::quoted(fields[k]));
      }
    }
    const double t = relative_seconds_of_text(fields[0], v[0], 1.0, 1, origin);
    const TumRecord r{t, v[1], v[2], v[3], v[4], v[5], v[6], v[7]};
    const double norm = std::sqrt(r.qx * r.qx + r.qy * r.qy + r.qz * r.qz + r.qw * r.qw);
    if (!(norm >= tum_min_quaternion_norm) || !std::isfinite(norm)) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.3g", norm);
      throw InputError(name, detail::where_line(line_no),
                       std::string("expected a rotation quaternion (qx qy qz qw) of norm near 1, found norm ") + buf);
    }
    if (!out.empty() && !(r.t > out.back().t)) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "expected a time later than line %llu's %s, found %s",
                    static_cast<unsigned long long>(previous_line), format_time(origin, out.back().t).c_str(),
                    format_time(origin, r.t).c_str());
      throw InputError(name, detail::where_column(line_no, 1, "t"), buf);
    }
    out.push_back(r);
    previous_line = line_no;
  }
  if (in.bad()) throw InputError(name, detail::where_line(line_no + 1), "read error");
  if (out.empty()) {
    throw InputError(name, detail::where_line(line_no + 1),
                     "expected at least one pose line (t tx ty tz qx qy qz qw), found end of file");
  }
  return out;
}

/// Reads the TUM trajectory file at `path` (see the stream overload);
/// io::InputError "cannot open" when it cannot be opened.
inline std::vector<TumRecord> read_tum(const std::string& path, TimeOrigin origin = {}) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "byte 0", "cannot open: is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "byte 0", "cannot open: no such file or not readable");
  return read_tum(in, path, origin);
}

}  // namespace streamclust::io
