// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// StructureRing: the window's points that the ground policy took out of
/// clustering (ground, ceiling), oldest first.

#include <streamclust/clustering.hpp>
#include <streamclust/detail/growth.hpp>
#include <streamclust/detail/ring_queue.hpp>
#include <streamclust/surface_class.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {

/// One structure point: what the result reports and what eviction needs
/// (its time for the window, its world position for the ground model).
struct StructureEntry {
  std::uint64_t stream_index = 0;
  double time = 0.0;                                ///< [s]
  Eigen::Vector3f world = Eigen::Vector3f::Zero();  ///< [m]
  SurfaceClass surface = SurfaceClass::ground;
};

/// FIFO of StructureEntry (32 bytes each) in a ring that grows to the peak
/// and never shrinks. push/pop O(1) amortised; `write` O(size). Thread
/// safety: none.
class StructureRing {
 public:
  bool empty() const { return queue_.empty(); }
  std::size_t size() const { return queue_.size(); }
  const StructureEntry& oldest() const { return queue_.front(); }
  void push(const StructureEntry& e) { queue_.push(e); }
  void pop() { queue_.pop(); }

  /// Writes every entry as a StructurePoint to `out` (replacing its
  /// contents), oldest first. O(size).
  void write(std::vector<StructurePoint>& out) const {
    out.clear();
    detail::reserve_geometric(out, queue_.size());
    queue_.for_each([&out](const StructureEntry& e) { out.push_back(StructurePoint{e.stream_index, e.surface}); });
  }

  /// Calls `f(const StructureEntry&)` for every entry, oldest first. O(size).
  template <class F>
  void for_each(F&& f) const {
    queue_.for_each(f);
  }

  std::size_t heap_bytes() const { return queue_.heap_bytes(); }

 private:
  detail::RingQueue<StructureEntry> queue_;
};

}  // namespace streamclust
