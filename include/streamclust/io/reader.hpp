// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Opening a point file or a recording of any supported format as a
/// streaming reader.
///
///     #include <streamclust/io/reader.hpp>
///     namespace io = streamclust::io;
///     auto reader = io::open_reader("frame.pcd", {});      // throws io::InputError
///     std::vector<io::Record> chunk;
///     while (chunk.clear(), reader->read(chunk, 4096) > 0) { /* ... */ }
///
/// See docs/io.md for formats, field names, time rules and error messages.

#include <streamclust/io/csv_reader.hpp>
#include <streamclust/io/error.hpp>
#include <streamclust/io/input_stream.hpp>
#include <streamclust/io/kitti_reader.hpp>
#include <streamclust/io/lvx_reader.hpp>
#include <streamclust/io/mcap_reader.hpp>
#include <streamclust/io/pcd_reader.hpp>
#include <streamclust/io/ply_reader.hpp>
#include <streamclust/io/point_reader.hpp>
#include <streamclust/io/record.hpp>
#include <streamclust/io/recording_reader.hpp>
#include <streamclust/io/ros1_bag_reader.hpp>
#include <streamclust/io/rosbag2_folder.hpp>
#include <streamclust/io/rosbag2_sqlite_reader.hpp>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace streamclust::io {

namespace detail {

/// The format a file's first bytes announce, if any (binary magics).
inline std::optional<Format> format_from_magic(std::string_view head) {
  if (head.rfind("#ROSBAG", 0) == 0) return Format::ros1_bag;
  if (head.size() >= 8 && std::equal(mcap::magic.begin(), mcap::magic.end(), head.begin(),
                                     [](std::uint8_t a, char b) { return a == static_cast<std::uint8_t>(b); }))
    return Format::mcap;
  if (head.rfind(std::string_view("SQLite format 3\0", 16), 0) == 0) return Format::rosbag2_sqlite;
  if (head.rfind("livox_tech", 0) == 0) return Format::lvx;
  return std::nullopt;
}

/// The storage of a rosbag2 folder as a Format.
inline Format folder_format(const std::string& folder, const Rosbag2Metadata& m) {
  if (m.storage_identifier == "sqlite3") return Format::rosbag2_sqlite;
  if (m.storage_identifier == "mcap") return Format::mcap;
  throw InputError(folder + "/metadata.yaml", "storage_identifier",
                   "storage \"" + printable(m.storage_identifier) + "\": expected sqlite3 or mcap");
}

/// The container of one recording file.
inline std::unique_ptr<RecordingSource> open_recording_file(const std::string& path, Format f) {
  switch (f) {
    case Format::ros1_bag: return std::make_unique<Ros1BagReader>(path);
    case Format::mcap: return std::make_unique<McapReader>(path);
    case Format::rosbag2_sqlite: return std::make_unique<Rosbag2SqliteReader>(path);
    default: throw InputError(path, "header", std::string("not a recording container: ") + to_string(f));
  }
}

/// The recording at `path`: a file, or a rosbag2 folder (all its files).
inline std::unique_ptr<RecordingSource> open_recording(const std::string& path, Format f) {
  if (!std::filesystem::is_directory(path)) return open_recording_file(path, f);
  const Rosbag2Metadata m = read_rosbag2_metadata(path);
  const Format storage = folder_format(path, m);
  if (m.files.size() == 1) return open_recording_file(m.files.front(), storage);
  std::vector<std::unique_ptr<RecordingSource>> parts;
  for (const std::string& file : m.files) parts.push_back(open_recording_file(file, storage));
  return std::make_unique<SplitRecording>(path, std::move(parts));
}

}  // namespace detail

/// The format of `path`: a rosbag2 folder (a directory with metadata.yaml)
/// by its storage; else by extension (.csv .txt -> csv, .pcd, .ply, .bin ->
/// kitti, .bag, .db3, .mcap, .lvx .lvx2; case-insensitive); else by content
/// (the magics of bags, MCAP, SQLite and LVX; first line "ply" -> ply;
/// "# .PCD", "VERSION" or "FIELDS" -> pcd; a text line with commas -> csv).
/// Throws InputError when the file cannot be opened, is empty or is none of these.
inline Format detect_format(const std::string& path) {
  if (std::filesystem::is_directory(path)) {
    if (!std::filesystem::exists(std::filesystem::path(path) / "metadata.yaml")) {
      throw InputError(path, "directory", "a directory is read as a rosbag2 bag folder: expected metadata.yaml in it");
    }
    return detail::folder_format(path, read_rosbag2_metadata(path));
  }
  const std::string ext = detail::lower(std::filesystem::path(path).extension().string());
  detail::ByteSource src(path);
  if (src.size() == 0) throw InputError(path, "byte 0", "empty file: expected point data");
  if (ext == ".csv" || ext == ".txt") return Format::csv;
  if (ext == ".pcd") return Format::pcd;
  if (ext == ".ply") return Format::ply;
  if (ext == ".bin") return Format::kitti;
  if (ext == ".bag") return Format::ros1_bag;
  if (ext == ".db3") return Format::rosbag2_sqlite;
  if (ext == ".mcap") return Format::mcap;
  if (ext == ".lvx" || ext == ".lvx2") return Format::lvx;
  const std::string head = src.peek(4096);
  if (head.empty()) throw InputError(path, "byte 0", "empty file: expected point data");
  if (const auto f = detail::format_from_magic(head)) return *f;
  const std::string first = head.substr(0, head.find('\n'));
  const std::string_view line = detail::trim(first);
  if (line == "ply") return Format::ply;
  const std::string low = detail::lower(line);
  if (low.rfind("# .pcd", 0) == 0 || low.rfind("version", 0) == 0 || low.rfind("fields", 0) == 0) return Format::pcd;
  bool text = true;
  for (const char c : first) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 32 && c != '\t' && c != '\r') text = false;
  }
  if (text && first.find(',') != std::string::npos) return Format::csv;
  throw InputError(path, "header",
                   "unknown format: expected extension .csv .txt .pcd .ply .bin .bag .db3 .mcap .lvx .lvx2, or content "
                   "starting with \"ply\", \"# .PCD\", VERSION or FIELDS, a bag, MCAP, SQLite or LVX magic, or "
                   "comma-separated text (or choose the format explicitly)");
}

/// Opens `path` for streaming (format from `options.format` or `detect_format`).
/// Reads and checks the header (a recording: its topics, and its first
/// message of the chosen topic); throws InputError (missing file "cannot
/// open", empty file, unknown format, malformed header, no time field and no
/// point rate, no or several point-cloud topics) and std::invalid_argument
/// (point rate not finite and > 0).
inline std::unique_ptr<PointReader> open_reader(const std::string& path, const ReadOptions& options = {}) {
  Format f{};
  if (options.format) {
    if (!std::filesystem::is_directory(path)) {
      detail::ByteSource src(path);  // "cannot open" / "empty file" before the reader's own checks
      if (src.size() == 0) throw InputError(path, "byte 0", "empty file: expected point data");
    }
    f = *options.format;
  } else {
    f = detect_format(path);
  }
  switch (f) {
    case Format::csv: return std::make_unique<CsvReader>(path, options);
    case Format::pcd: return std::make_unique<PcdReader>(path, options);
    case Format::ply: return std::make_unique<PlyReader>(path, options);
    case Format::kitti: return std::make_unique<KittiReader>(path, options);
    case Format::lvx: return std::make_unique<LvxReader>(path, options);
    case Format::ros1_bag:
    case Format::rosbag2_sqlite:
    case Format::mcap: return std::make_unique<RecordingReader>(detail::open_recording(path, f), f, options);
  }
  throw InputError(path, "header", "unknown format");
}

/// The time origin the reader of `path` finds (PointReader::time_origin):
/// reads records until the first with a finite time, so several readers of
/// one input, and its trajectory, can share it through
/// `ReadOptions::time_origin`. Zero for an input without such a record.
/// Throws as open_reader and PointReader::read do. O(records up to it).
inline TimeOrigin find_time_origin(const std::string& path, const ReadOptions& options = {}) {
  if (options.time_origin) return *options.time_origin;
  auto reader = open_reader(path, options);
  if (!reader->info().has_time) return TimeOrigin{};
  std::vector<Record> chunk;
  while (!reader->time_origin_found()) {
    chunk.clear();
    if (reader->read(chunk, 4096) == 0) break;
  }
  return reader->time_origin();
}

}  // namespace streamclust::io
