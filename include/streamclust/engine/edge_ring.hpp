// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// EdgeRing: the point-level edges of the window, for the connectivity
/// strategies that store them, in the FIFO order they die in.

#include <streamclust/types.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace streamclust {

/// Handle of a point-graph edge (a 32-bit sequence number that wraps).
using EdgeHandle = std::uint32_t;
inline constexpr EdgeHandle kNoEdge = std::numeric_limits<EdgeHandle>::max();

/// The edges of the window's point graph. A new point's edges to its older
/// neighbours are appended together, so the edges are grouped by newer
/// endpoint in insertion order; each is also threaded into its older
/// endpoint's forward list (newest first). An edge is dropped when its NEWER
/// endpoint leaves (`release_before`): points leave in insertion order, so
/// the live edges are one contiguous run of handles [oldest(), next()). Edges
/// whose older endpoint left stay in the run until then (callers test the
/// older endpoint's liveness).
///
/// Memory: 12 bytes per edge (the older endpoint in its own array, so that a
/// pass over the older endpoints streams 4 bytes per edge); capacity a power
/// of two, doubled when full, never shrunk.
/// Thread safety: none (one engine, one thread).
class EdgeRing {
 public:
  /// Newer endpoint and forward-list link of an edge.
  struct Record {
    PointHandle newer = kNoPoint;
    EdgeHandle next_forward = kNoEdge;  ///< next edge in the older endpoint's forward list
  };

  EdgeHandle oldest() const { return oldest_; }
  EdgeHandle next() const { return next_; }
  PointHandle older(EdgeHandle e) const { return older_[e & mask_]; }
  PointHandle newer(EdgeHandle e) const { return records_[e & mask_].newer; }
  EdgeHandle next_forward(EdgeHandle e) const { return records_[e & mask_].next_forward; }

  /// Room for `extra` more edges. O(1) when they fit, else O(capacity).
  void reserve(std::size_t extra) {
    const std::size_t needed = static_cast<std::uint32_t>(next_ - oldest_) + extra;
    if (needed <= records_.size()) return;
    std::size_t capacity = std::max<std::size_t>(records_.size() * 2, kMinCapacity);
    while (capacity < needed) capacity *= 2;
    std::vector<Record> records(capacity);
    std::vector<PointHandle> older(capacity);
    const auto mask = static_cast<std::uint32_t>(capacity - 1);
    for (EdgeHandle e = oldest_; e != next_; ++e) {
      records[e & mask] = records_[e & mask_];
      older[e & mask] = older_[e & mask_];
    }
    records_.swap(records);
    older_.swap(older);
    mask_ = mask;
  }

  /// Appends edge (older, newer) whose older endpoint's forward list starts
  /// at `forward_head`; returns its handle, the list's new head. Requires
  /// room (`reserve`). O(1).
  EdgeHandle push(PointHandle older, PointHandle newer, EdgeHandle forward_head) {
    const EdgeHandle e = next_++;
    older_[e & mask_] = older;
    records_[e & mask_] = Record{newer, forward_head};
    return e;
  }

  /// Calls `f(older, newer)` for every edge still in the ring, oldest first
  /// (grouped by newer endpoint; the older one may have left the window).
  /// O(edges), a sequential read of both arrays.
  template <class F>
  void for_each(F&& f) const {
    const PointHandle* const older = older_.data();  // hoisted: f's stores could alias the members
    const Record* const records = records_.data();
    const std::uint32_t mask = mask_;
    const EdgeHandle end = next_;
    for (EdgeHandle e = oldest_; e != end; ++e) f(older[e & mask], records[e & mask].newer);
  }

  /// Drops the edges before `first` (those of points that left). O(1).
  void release_before(EdgeHandle first) { oldest_ = first; }

  std::size_t heap_bytes() const {
    return records_.capacity() * sizeof(Record) + older_.capacity() * sizeof(PointHandle);
  }

 private:
  static constexpr std::size_t kMinCapacity = 4096;
  std::vector<Record> records_;
  std::vector<PointHandle> older_;
  std::uint32_t mask_ = 0;
  EdgeHandle oldest_ = 0;
  EdgeHandle next_ = 0;
};

}  // namespace streamclust
