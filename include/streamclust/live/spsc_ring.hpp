// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A bounded, lock-free, single-producer single-consumer ring of slots that
/// are filled and read in place: the hand-off from a receiver thread to an
/// engine thread. The producer never waits: when the ring is full, `try_push`
/// returns false and the caller counts the item as dropped. Memory is the
/// capacity's slots, allocated once.
///
/// Thread safety: exactly one producer thread calls `try_push`, exactly one
/// consumer thread calls `front`/`pop`; `size` and `capacity` may be called
/// from either (size is then a snapshot). Wait-free, O(1) per operation.

#include <atomic>
#include <cstddef>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>

namespace streamclust::live {

template <class T>
class SpscRing {
 public:
  /// A ring of `capacity` slots (at least 2; rounded up to a power of two).
  /// Throws std::invalid_argument for 0, 1 or more than 2^30 slots.
  explicit SpscRing(std::size_t capacity) {
    if (capacity < 2 || capacity > (std::size_t{1} << 30))
      throw std::invalid_argument("SpscRing capacity " + std::to_string(capacity) + ": expected 2 .. 2^30 slots");
    std::size_t n = 2;
    while (n < capacity) n <<= 1;
    mask_ = n - 1;
    slots_ = std::make_unique<T[]>(n);
  }

  std::size_t capacity() const noexcept { return mask_ + 1; }

  /// Items in the ring now (a snapshot when called across threads).
  std::size_t size() const noexcept {
    return tail_.load(std::memory_order_acquire) - head_.load(std::memory_order_acquire);
  }

  /// Producer: `fill(T&)` writes the next slot in place and returns true to
  /// publish it (false abandons it). Returns false, without calling `fill`,
  /// when the ring is full.
  template <class Fill>
  bool try_push(Fill&& fill) {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail - head_cache_ > mask_) {
      head_cache_ = head_.load(std::memory_order_acquire);
      if (tail - head_cache_ > mask_) return false;
    }
    if (!fill(slots_[tail & mask_])) return false;
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  /// Consumer: the oldest item, or nullptr when the ring is empty. Valid
  /// until `pop`.
  T* front() noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head == tail_cache_) {
      tail_cache_ = tail_.load(std::memory_order_acquire);
      if (head == tail_cache_) return nullptr;
    }
    return &slots_[head & mask_];
  }

  /// Consumer: releases the item `front` returned.
  void pop() noexcept { head_.store(head_.load(std::memory_order_relaxed) + 1, std::memory_order_release); }

 private:
  // Producer and consumer indices on their own cache lines (64 B on x86-64
  // and most ARM cores) so the two threads do not share one.
  static constexpr std::size_t kLine = 64;
  alignas(kLine) std::atomic<std::size_t> tail_{0};  // written by the producer
  std::size_t head_cache_ = 0;                       // producer's last view of head_
  alignas(kLine) std::atomic<std::size_t> head_{0};  // written by the consumer
  std::size_t tail_cache_ = 0;                       // consumer's last view of tail_
  alignas(kLine) std::size_t mask_ = 0;
  std::unique_ptr<T[]> slots_;
};

}  // namespace streamclust::live
