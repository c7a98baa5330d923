// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// RingQueue: a first-in first-out queue in one power-of-two ring.

#include <streamclust/detail/hints.hpp>

#include <cstddef>
#include <vector>

namespace streamclust::detail {

/// FIFO queue of trivially copyable values in a ring of power-of-two
/// capacity that doubles when full and never shrinks: a queue whose
/// occupancy stays bounded allocates nothing once it reached its largest
/// occupancy, however many values pass through. push/pop/front O(1)
/// (push amortised). Not thread-safe.
template <class T>
class RingQueue {
 public:
  bool empty() const { return count_ == 0; }
  std::size_t size() const { return count_; }
  const T& front() const { return ring_[head_]; }

  STREAMCLUST_ALWAYS_INLINE void push(const T& v) {
    if (count_ == ring_.size()) grow();
    ring_[(head_ + count_) & (ring_.size() - 1)] = v;
    ++count_;
  }
  void pop() {
    head_ = (head_ + 1) & (ring_.size() - 1);
    --count_;
  }
  void clear() {
    head_ = 0;
    count_ = 0;
  }
  /// Calls `f(const T&)` for every queued value, oldest first. O(size).
  template <class F>
  void for_each(F&& f) const {
    for (std::size_t k = 0; k < count_; ++k) f(ring_[(head_ + k) & (ring_.size() - 1)]);
  }
  /// Heap bytes held (capacity). O(1).
  std::size_t heap_bytes() const { return ring_.capacity() * sizeof(T); }

 private:
  /// Doubles the ring (at least 64 slots), the queue moved to its front. O(size).
  STREAMCLUST_NOINLINE void grow() {
    std::vector<T> bigger(ring_.empty() ? 64 : 2 * ring_.size());
    for (std::size_t k = 0; k < count_; ++k) bigger[k] = ring_[(head_ + k) & (ring_.size() - 1)];
    ring_.swap(bigger);
    head_ = 0;
  }

  std::vector<T> ring_;
  std::size_t head_ = 0;
  std::size_t count_ = 0;
};

}  // namespace streamclust::detail
