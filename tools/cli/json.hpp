// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The one JSON writer of the tool (`cluster --report`, `evaluate --json`):
/// documents are built as nlohmann::ordered_json (keys in insertion order,
/// strings escaped, NaN and infinities written as null) and laid out for
/// reading and for line tools: a container holding a list of records (an
/// array with an object in it, at any depth) is written one member or
/// element per line; every other container on one line. So each record of
/// a list (a retrieval cycle, an adaptive step) is exactly one line.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::cli {

using Json = nlohmann::ordered_json;

/// The binary subtype that marks a number held as its decimal text.
inline constexpr std::uint8_t kNumberTextSubtype = 0x74;

/// A number written verbatim as `text` (a valid JSON number): a stream time
/// with nanoseconds (io::format_time), which a double cannot hold at epoch
/// scale. Held as a binary value of subtype kNumberTextSubtype; only this
/// writer knows it.
inline Json number_text(const std::string& text) {
  return Json::binary(std::vector<std::uint8_t>(text.begin(), text.end()), kNumberTextSubtype);
}

namespace detail {

/// True when `j` holds an array with an object in it, at any depth. O(size).
inline bool holds_record_list(const Json& j) {
  if (j.is_array()) {
    for (const Json& e : j) {
      if (e.is_object() || holds_record_list(e)) return true;
    }
  } else if (j.is_object()) {
    for (const auto& kv : j.items()) {
      if (holds_record_list(kv.value())) return true;
    }
  }
  return false;
}

inline void write_inline(std::ostream& out, const Json& j) {
  if (j.is_object()) {
    out << '{';
    bool first = true;
    for (const auto& kv : j.items()) {
      out << (first ? "" : ", ") << Json(kv.key()).dump() << ": ";
      write_inline(out, kv.value());
      first = false;
    }
    out << '}';
  } else if (j.is_array()) {
    out << '[';
    bool first = true;
    for (const Json& e : j) {
      out << (first ? "" : ", ");
      write_inline(out, e);
      first = false;
    }
    out << ']';
  } else if (j.is_binary() && j.get_binary().has_subtype() && j.get_binary().subtype() == kNumberTextSubtype) {
    const auto& bytes = j.get_binary();
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  } else {
    out << j.dump();
  }
}

inline void write_laid_out(std::ostream& out, const Json& j, int indent) {
  if (!j.is_structured() || !holds_record_list(j)) {
    write_inline(out, j);
    return;
  }
  const std::string pad(static_cast<std::size_t>(indent + 2), ' ');
  const bool object = j.is_object();
  out << (object ? "{\n" : "[\n");
  bool first = true;
  for (const auto& kv : j.items()) {
    out << (first ? "" : ",\n") << pad;
    if (object) out << Json(kv.key()).dump() << ": ";
    write_laid_out(out, kv.value(), indent + 2);
    first = false;
  }
  out << '\n' << std::string(static_cast<std::size_t>(indent), ' ') << (object ? '}' : ']');
}

}  // namespace detail

/// Writes `j` laid out as the file comment says, with a final newline.
inline void write_json(std::ostream& out, const Json& j) {
  detail::write_laid_out(out, j, 0);
  out << '\n';
}

/// Writes `j` to the file `path`; a file that cannot be written is a
/// std::runtime_error naming `option` (exit code 4).
inline void write_json_file(const std::string& option, const std::string& path, const Json& j) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error(option + ": cannot write '" + path + "'");
  write_json(f, j);
  f.flush();
  if (!f) throw std::runtime_error(option + ": writing '" + path + "' failed");
}

}  // namespace streamclust::cli
