// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The vocabulary of the I/O module: the record every reader returns, the
/// formats, time units, read options and what a reader learnt about its input.

#include <streamclust/io/stream_time.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace streamclust::io {

/// One point as read from a file. It models the library's point concept
/// through the generic `point_traits` (members x, y, z, t, intensity), so a
/// `std::vector<Record>` can be fed to a clusterer directly.
///
/// Every record of the file is returned, including those with NaN or infinite
/// coordinates (the engine rejects and counts them), so that record indices
/// match point indices in the file.
struct Record {
  float x = 0;          ///< [m]
  float y = 0;          ///< [m]
  float z = 0;          ///< [m]
  float intensity = 0;  ///< intensity / reflectivity / reflectance; 0 when the file has none
  double t = 0;         ///< stream time [s] since the reader's time origin (`PointReader::time_origin`)
  /// Ground truth / label from a field named `label`, `gt`, `instance` or
  /// `object` (first found in this order); -1 when the file has none.
  std::int64_t label = -1;
};

/// The supported input formats: point files (csv, pcd, ply, kitti) and
/// recordings (ROS 1 bag, rosbag2 SQLite, MCAP, Livox LVX / LVX2).
enum class Format { csv, pcd, ply, kitti, ros1_bag, rosbag2_sqlite, mcap, lvx };

/// Units of a time field.
enum class TimeUnit { s, ms, us, ns };

/// How to read an input. All members are optional.
struct ReadOptions {
  /// Force a format instead of detecting it (see `detect_format`).
  std::optional<Format> format;
  /// Unit of the time field; default: see docs/io.md (`offset_time` -> ns, others -> s).
  std::optional<TimeUnit> time_unit;
  /// Points per second [Hz]: when the input has no time field, record i gets
  /// t = i / point_rate (i counts every record). Ignored when the input has a time field.
  std::optional<double> point_rate;
  /// The whole seconds times are counted from (stream_time.hpp); default:
  /// the first finite time's whole seconds (`PointReader::time_origin`).
  /// Give it to read several inputs, or one input twice, on one time base.
  std::optional<TimeOrigin> time_origin;
  /// Recordings: the stream to read -- a topic of a bag or MCAP file, or a
  /// LiDAR of an LVX file (its serial number or device index). Default: the
  /// only point-cloud stream; with several, the reader lists them in its error.
  std::optional<std::string> topic;
};

/// What a reader found in the header of its input.
struct InputInfo {
  Format format = Format::csv;
  /// "ascii", "binary", "binary_compressed", "binary_little_endian", or "" (CSV, KITTI).
  std::string encoding;
  /// Field / column / property names in file order, as written in the file.
  std::vector<std::string> fields;
  /// Number of points the header declares (PCD POINTS, PLY element vertex,
  /// KITTI file size / 16); empty for CSV.
  std::optional<std::uint64_t> declared_points;
  bool has_time = false;       ///< the input has a time field (else t comes from the point rate)
  bool has_intensity = false;  ///< the input has an intensity field
  bool has_label = false;      ///< the input has a label field
  std::string time_field;      ///< name of the time field as written in the file, "" if none
  TimeUnit time_unit = TimeUnit::s;  ///< unit the time field is read in
};

/// "csv", "pcd", "ply", "kitti", "bag", "db3", "mcap", "lvx".
inline const char* to_string(Format f) noexcept {
  switch (f) {
    case Format::csv: return "csv";
    case Format::pcd: return "pcd";
    case Format::ply: return "ply";
    case Format::kitti: return "kitti";
    case Format::ros1_bag: return "bag";
    case Format::rosbag2_sqlite: return "db3";
    case Format::mcap: return "mcap";
    case Format::lvx: return "lvx";
  }
  return "?";
}

/// "s", "ms", "us", "ns".
inline const char* to_string(TimeUnit u) noexcept {
  switch (u) {
    case TimeUnit::s: return "s";
    case TimeUnit::ms: return "ms";
    case TimeUnit::us: return "us";
    case TimeUnit::ns: return "ns";
  }
  return "?";
}

/// Seconds per unit: 1, 1e-3, 1e-6, 1e-9.
inline double seconds_per(TimeUnit u) noexcept {
  switch (u) {
    case TimeUnit::s: return 1.0;
    case TimeUnit::ms: return 1e-3;
    case TimeUnit::us: return 1e-6;
    case TimeUnit::ns: return 1e-9;
  }
  return 1.0;
}

/// Parses the names to_string gives (also "bin" for kitti, "lvx2" for lvx);
/// nullopt otherwise.
inline std::optional<Format> parse_format(std::string_view s) noexcept {
  if (s == "csv") return Format::csv;
  if (s == "pcd") return Format::pcd;
  if (s == "ply") return Format::ply;
  if (s == "kitti" || s == "bin") return Format::kitti;
  if (s == "bag") return Format::ros1_bag;
  if (s == "db3") return Format::rosbag2_sqlite;
  if (s == "mcap") return Format::mcap;
  if (s == "lvx" || s == "lvx2") return Format::lvx;
  return std::nullopt;
}

/// Parses "s", "ms", "us", "ns"; nullopt otherwise.
inline std::optional<TimeUnit> parse_time_unit(std::string_view s) noexcept {
  if (s == "s") return TimeUnit::s;
  if (s == "ms") return TimeUnit::ms;
  if (s == "us") return TimeUnit::us;
  if (s == "ns") return TimeUnit::ns;
  return std::nullopt;
}

}  // namespace streamclust::io
