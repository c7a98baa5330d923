// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A counting global operator new / delete for the latency benchmark
/// (alloc_counter.cpp replaces them for the whole program). Only work done
/// inside an `AllocScope` is attributed: the benchmark opens one around every
/// call into the engine, so its counters are the engine's heap traffic and
/// live heap bytes, excluding the simulator, the peers and the bookkeeping.
///
/// Bytes are the allocator's usable sizes (malloc_usable_size), i.e. what
/// the heap really hands out, not the sizes asked for.
/// Thread safety: the counters are relaxed atomics; the scope flag is
/// thread-local, so allocations on other threads are never attributed.

#include <cstddef>
#include <cstdint>

namespace streamclust::bench {

/// Counters of the allocations made inside AllocScope (monotone).
struct AllocCounters {
  std::uint64_t allocations = 0;    ///< calls to operator new (any form) inside a scope
  std::uint64_t deallocations = 0;  ///< calls to operator delete inside a scope
  std::int64_t live_bytes = 0;      ///< usable bytes allocated minus freed inside scopes
};

/// Snapshot of the counters. O(1).
AllocCounters alloc_counters();

/// Allocation tracing (to find where steady-state allocations come from):
/// while enabled, every allocation attributed to a scope records its call
/// stack (glibc backtrace(), up to 32 frames) into a fixed table of distinct
/// stacks with a count each (no allocation while recording; at most 256
/// distinct stacks, the rest only counted). Not thread-safe: enable from the
/// benchmark's single thread only.
void set_alloc_tracing(bool enabled);
/// Writes the recorded stacks, most frequent first, to file descriptor `fd`
/// (backtrace_symbols_fd format: `binary(+offset)`, resolve with
/// `addr2line -Cfie <binary> <offset>` on a build with -g), then forgets
/// them. Returns the number of traced allocations.
std::uint64_t dump_alloc_traces(int fd);

/// While alive on this thread, allocations and frees are attributed.
class AllocScope {
 public:
  AllocScope();
  ~AllocScope();
  AllocScope(const AllocScope&) = delete;
  AllocScope& operator=(const AllocScope&) = delete;

 private:
  bool previous_;
};

}  // namespace streamclust::bench
