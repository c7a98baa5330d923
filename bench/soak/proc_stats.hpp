// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The process's resident set and the machine's load, read from /proc with
/// a stack buffer: no heap allocation, so sampling them does not move what
/// they measure. Linux only; each read is one open/read/close, O(1).
/// Thread-safe (no shared state).

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

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

/// A fixed piece of CPU work, timed [us]: 2^20 steps of a dependent
/// multiply-xorshift chain (no memory traffic), about 1-2 ms. Its time moves
/// only with the host (clock frequency, another tenant on the core), so a
/// cycle latency that rises with it is the machine's. Thread-safe.
inline double host_probe_us() {
  const auto t0 = std::chrono::steady_clock::now();
  std::uint64_t x = 0x9E3779B97F4A7C15ull;
  for (int i = 0; i < (1 << 20); ++i) {
    x ^= x >> 29;
    x *= 0xBF58476D1CE4E5B9ull;
  }
  volatile std::uint64_t sink = x;  // keeps the chain, done before the clock is read again
  (void)sink;
  std::atomic_signal_fence(std::memory_order_seq_cst);
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
}

/// A fixed walk through memory, timed [us]: 2^15 dependent loads along one
/// random cycle over 16 MiB (a pointer chase: every load misses the caches
/// of a core and waits for the shared last-level cache or DRAM), about
/// 2-4 ms. Its time moves with the other tenants of the host's caches and
/// memory, which host_probe_us() does not see. The buffer is built at
/// construction (Sattolo's shuffle, fixed seed). Not thread-safe.
class MemoryProbe {
 public:
  MemoryProbe() : next_(std::size_t{1} << 22) {
    for (std::size_t i = 0; i < next_.size(); ++i) next_[i] = static_cast<std::uint32_t>(i);
    std::uint64_t x = 0x2545F4914F6CDD1Dull;
    for (std::size_t i = next_.size() - 1; i > 0; --i) {  // one cycle through every slot
      x ^= x << 13;
      x ^= x >> 7;
      x ^= x << 17;
      const std::size_t j = static_cast<std::size_t>(x % i);
      const std::uint32_t t = next_[i];
      next_[i] = next_[j];
      next_[j] = t;
    }
  }

  double run_us() {
    const auto t0 = std::chrono::steady_clock::now();
    std::uint32_t at = position_;
    for (int i = 0; i < (1 << 15); ++i) at = next_[at];
    volatile std::uint32_t end = at;  // the walk must be done before the clock is read again
    std::atomic_signal_fence(std::memory_order_seq_cst);
    position_ = end;  // the next run continues the walk: no warm lines
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  }

 private:
  std::vector<std::uint32_t> next_;
  std::uint32_t position_ = 0;
};

}  // namespace streamclust::bench
