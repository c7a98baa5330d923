// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// MemoryUsage: the heap footprint of a StreamClusterer, by part.

#include <cstddef>
#include <vector>

namespace streamclust {

/// Heap bytes held by an engine (`StreamClusterer::memory_usage()`), by part.
///
/// Every figure is a CAPACITY in bytes (`vector::capacity() x sizeof(element)`),
/// not a size: what the engine holds, including the slack of its rings
/// (rounded up to powers of two, never shrunk) and of reusable buffers. It
/// does not include the allocator's rounding and headers (malloc's usable
/// size exceeds the request by up to 16 bytes per block), the engine object
/// itself (`sizeof(StreamClusterer<Config>)`, a few hundred bytes) nor the
/// small heap of policies other than the spatial index (e.g. the adaptive
/// resolution's calibration trace).
struct MemoryUsage {
  std::size_t point_ring = 0;     ///< [bytes] the window rings: samples and point records
  std::size_t edge_storage = 0;   ///< [bytes] the edge ring(s) of the point graph; spanning forest: forest + new edges
  std::size_t spatial_index = 0;  ///< [bytes] the index's heap; 0 when unknown (see spatial_index_known)
  std::size_t clusters = 0;       ///< [bytes] cluster table, free/pending lists and bridge lists
  std::size_t scratch = 0;        ///< [bytes] buffers reused across insertions and retrievals
  std::size_t result = 0;         ///< [bytes] the last Clustering (labels + component summaries)
  std::size_t structure = 0;      ///< [bytes] the ground policy's model and the structure points' ring
  /// False when the spatial index does not report its heap (no `heap_bytes()`
  /// member, see is_spatial_index_heap_reporting_v): `spatial_index` is then 0.
  bool spatial_index_known = true;

  /// Sum of the parts [bytes]. O(1).
  std::size_t total() const { return point_ring + edge_storage + spatial_index + clusters + scratch + result + structure; }
};

/// Heap bytes reserved by a vector: capacity x element size (excluding the
/// allocator's overhead and any heap owned by the elements). O(1).
template <class T, class A>
std::size_t capacity_bytes(const std::vector<T, A>& v) {
  return v.capacity() * sizeof(T);
}

}  // namespace streamclust
