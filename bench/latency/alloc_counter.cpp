// SPDX-License-Identifier: MIT
// Replacement global operator new / delete counting allocations made inside
// an AllocScope (see alloc_counter.hpp). All forms forward to malloc/free.

#include "alloc_counter.hpp"

#include <execinfo.h>
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>

namespace streamclust::bench {
namespace {

std::atomic<std::uint64_t> g_allocations{0};
std::atomic<std::uint64_t> g_deallocations{0};
std::atomic<std::int64_t> g_live_bytes{0};
thread_local bool t_in_scope = false;

// Allocation tracing: a fixed table of distinct stacks (no heap use).
constexpr int kTraceFrames = 32;
constexpr std::size_t kMaxTraces = 256;
struct Trace {
  void* frames[kTraceFrames];
  int depth;
  std::uint64_t count;
};
Trace g_traces[kMaxTraces];
std::size_t g_trace_count = 0;
std::uint64_t g_traced = 0;
bool g_tracing = false;
bool g_in_trace = false;  // backtrace() itself may allocate once (loading libgcc)

void record_trace() {
  if (g_in_trace) return;
  g_in_trace = true;
  void* frames[kTraceFrames];
  const int depth = backtrace(frames, kTraceFrames);
  ++g_traced;
  for (std::size_t i = 0; i < g_trace_count; ++i) {
    Trace& t = g_traces[i];
    if (t.depth == depth && std::memcmp(t.frames, frames, sizeof(void*) * static_cast<std::size_t>(depth)) == 0) {
      ++t.count;
      g_in_trace = false;
      return;
    }
  }
  if (g_trace_count < kMaxTraces) {
    Trace& t = g_traces[g_trace_count++];
    std::memcpy(t.frames, frames, sizeof(void*) * static_cast<std::size_t>(depth));
    t.depth = depth;
    t.count = 1;
  }
  g_in_trace = false;
}

void* counted_alloc(std::size_t size, std::size_t alignment) {
  if (size == 0) size = 1;
  void* p = nullptr;
  if (alignment <= alignof(std::max_align_t)) {
    p = std::malloc(size);
  } else if (posix_memalign(&p, alignment, size) != 0) {
    p = nullptr;
  }
  if (p == nullptr) return nullptr;
  if (t_in_scope) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    g_live_bytes.fetch_add(static_cast<std::int64_t>(malloc_usable_size(p)), std::memory_order_relaxed);
    if (g_tracing) record_trace();
  }
  return p;
}

void* counted_alloc_or_throw(std::size_t size, std::size_t alignment) {
  void* p = counted_alloc(size, alignment);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

void counted_free(void* p) noexcept {
  if (p == nullptr) return;
  if (t_in_scope) {
    g_deallocations.fetch_add(1, std::memory_order_relaxed);
    g_live_bytes.fetch_sub(static_cast<std::int64_t>(malloc_usable_size(p)), std::memory_order_relaxed);
  }
  std::free(p);
}

}  // namespace

AllocCounters alloc_counters() {
  AllocCounters c;
  c.allocations = g_allocations.load(std::memory_order_relaxed);
  c.deallocations = g_deallocations.load(std::memory_order_relaxed);
  c.live_bytes = g_live_bytes.load(std::memory_order_relaxed);
  return c;
}

void set_alloc_tracing(bool enabled) { g_tracing = enabled; }

std::uint64_t dump_alloc_traces(int fd) {
  const bool was = g_tracing;
  g_tracing = false;
  std::sort(g_traces, g_traces + g_trace_count, [](const Trace& a, const Trace& b) { return a.count > b.count; });
  char line[128];
  for (std::size_t i = 0; i < g_trace_count; ++i) {
    const int n = std::snprintf(line, sizeof line, "--- %llu allocation(s) from:\n",
                                static_cast<unsigned long long>(g_traces[i].count));
    if (n > 0 && write(fd, line, static_cast<std::size_t>(n)) < 0) break;
    backtrace_symbols_fd(g_traces[i].frames, g_traces[i].depth, fd);
  }
  const std::uint64_t traced = g_traced;
  g_trace_count = 0;
  g_traced = 0;
  g_tracing = was;
  return traced;
}

AllocScope::AllocScope() : previous_(t_in_scope) { t_in_scope = true; }
AllocScope::~AllocScope() { t_in_scope = previous_; }

}  // namespace streamclust::bench

namespace scb = streamclust::bench;

void* operator new(std::size_t size) { return scb::counted_alloc_or_throw(size, 0); }
void* operator new[](std::size_t size) { return scb::counted_alloc_or_throw(size, 0); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return scb::counted_alloc(size, 0); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return scb::counted_alloc(size, 0); }
void* operator new(std::size_t size, std::align_val_t a) {
  return scb::counted_alloc_or_throw(size, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t size, std::align_val_t a) {
  return scb::counted_alloc_or_throw(size, static_cast<std::size_t>(a));
}
void* operator new(std::size_t size, std::align_val_t a, const std::nothrow_t&) noexcept {
  return scb::counted_alloc(size, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t size, std::align_val_t a, const std::nothrow_t&) noexcept {
  return scb::counted_alloc(size, static_cast<std::size_t>(a));
}

void operator delete(void* p) noexcept { scb::counted_free(p); }
void operator delete[](void* p) noexcept { scb::counted_free(p); }
void operator delete(void* p, std::size_t) noexcept { scb::counted_free(p); }
void operator delete[](void* p, std::size_t) noexcept { scb::counted_free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { scb::counted_free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { scb::counted_free(p); }
void operator delete(void* p, std::align_val_t) noexcept { scb::counted_free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { scb::counted_free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { scb::counted_free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { scb::counted_free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { scb::counted_free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { scb::counted_free(p); }
