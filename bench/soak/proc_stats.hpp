// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The process's resident set and the machine's load, read from /proc with
/// a stack buffer: no heap allocation, so sampling them does not move what
/// they measure. Linux only; each read is one open/read/close, O(1).
/// Thread-safe (no shared state).

#include <fcntl.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace streamclust::bench {

namespace detail {

/// Reads up to size - 1 bytes of `path` into `buffer`, NUL-terminated.
/// False when the file cannot be read.
inline bool read_small_file(const char* path, char* buffer, std::size_t size) {
  const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const ssize_t n = ::read(fd, buffer, size - 1);
  ::close(fd);
  if (n <= 0) return false;
  buffer[n] = '\0';
  return true;
}

}  // namespace detail

/// Resident set of this process [KiB], whole and split: anonymous pages
/// (the heap, stacks) and file-backed pages (the program's and libraries'
/// code and data as they are first touched). Zero when /proc is unavailable.
struct ResidentSet {
  std::uint64_t total_kib = 0;  ///< VmRSS
  std::uint64_t anon_kib = 0;   ///< RssAnon
  std::uint64_t file_kib = 0;   ///< RssFile
};

/// Reads ResidentSet from /proc/self/status (one read of about 1.5 KB).
inline ResidentSet resident_set() {
  char buffer[4096];
  ResidentSet r;
  if (!detail::read_small_file("/proc/self/status", buffer, sizeof buffer)) return r;
  const auto field = [&](const char* name, std::uint64_t& out) {
    const char* at = std::strstr(buffer, name);
    if (at != nullptr) out = std::strtoull(at + std::strlen(name), nullptr, 10);  // "Name:   1234 kB"
  };
  field("VmRSS:", r.total_kib);
  field("RssAnon:", r.anon_kib);
  field("RssFile:", r.file_kib);
  return r;
}

/// The one-minute load average of the machine (/proc/loadavg); -1 when
/// unavailable. On a shared machine it tells a slow second of the host
/// from a slow second of the engine.
inline double load_average_1min() {
  char buffer[128];
  if (!detail::read_small_file("/proc/loadavg", buffer, sizeof buffer)) return -1.0;
  return std::strtod(buffer, nullptr);
}

}  // namespace streamclust::bench
