// SPDX-License-Identifier: MIT
// Replacement global operator new / delete counting allocations made inside
// an AllocScope (see alloc_counter.hpp). All forms forward to malloc/free.

#include "alloc_counter.hpp"

#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace streamclust::bench {
namespace {

std::atomic<std::uint64_t> g_allocations{0};
std::atomic<std::uint64_t> g_deallocations{0};
std::atomic<std::int64_t> g_live_bytes{0};
thread_local bool t_in_scope = false;

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
