// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Opening a point file of any supported format as a streaming reader.
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
#include <streamclust/io/pcd_reader.hpp>
#include <streamclust/io/ply_reader.hpp>
#include <streamclust/io/point_reader.hpp>
#include <streamclust/io/record.hpp>

#include <filesystem>
#include <memory>
#include <string>

namespace streamclust::io {

/// The format of `path`: by extension (.csv .txt -> csv, .pcd, .ply, .bin ->
/// kitti; case-insensitive), else by content (first line "ply" -> ply;
/// "# .PCD", "VERSION" or "FIELDS" -> pcd; a text line with commas -> csv).
/// Throws InputError when the file cannot be opened, is empty or is none of these.
inline Format detect_format(const std::string& path) {
  const std::string ext = detail::lower(std::filesystem::path(path).extension().string());
  detail::ByteSource src(path);
  if (src.size() == 0) throw InputError(path, "byte 0", "empty file: expected point data");
  if (ext == ".csv" || ext == ".txt") return Format::csv;
  if (ext == ".pcd") return Format::pcd;
  if (ext == ".ply") return Format::ply;
  if (ext == ".bin") return Format::kitti;
  const std::string head = src.peek(4096);
  if (head.empty()) throw InputError(path, "byte 0", "empty file: expected point data");
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
                   "unknown format: expected extension .csv .txt .pcd .ply .bin, or content starting with \"ply\", "
                   "\"# .PCD\", VERSION or FIELDS, or comma-separated text (or choose the format explicitly)");
}

/// Opens `path` for streaming (format from `options.format` or `detect_format`).
/// Reads and checks the header; throws InputError (missing file "cannot open",
/// empty file, unknown format, malformed header, no time field and no point
/// rate) and std::invalid_argument (point rate not finite and > 0).
inline std::unique_ptr<PointReader> open_reader(const std::string& path, const ReadOptions& options = {}) {
  Format f{};
  if (options.format) {
    detail::ByteSource src(path);  // "cannot open" / "empty file" before the reader's own checks
    if (src.size() == 0) throw InputError(path, "byte 0", "empty file: expected point data");
    f = *options.format;
  } else {
    f = detect_format(path);
  }
  switch (f) {
    case Format::csv: return std::make_unique<CsvReader>(path, options);
    case Format::pcd: return std::make_unique<PcdReader>(path, options);
    case Format::ply: return std::make_unique<PlyReader>(path, options);
    case Format::kitti: return std::make_unique<KittiReader>(path, options);
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
