// EXPECT: STREAMCLUST_SPATIAL_INDEX_POLICY_INVALID
// SPDX-License-Identifier: MIT
// A spatial index without remove(cell, handle) cannot follow the sliding
// window and must be rejected where the engine starts.
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <cstddef>

struct NotASpatialIndex {
  struct Params {};
  explicit NotASpatialIndex(const Params&) {}
  void reset(const streamclust::GridShape&) {}
  void clear() {}
  streamclust::PointHandle insert(streamclust::CellIndex, streamclust::PointHandle) { return streamclust::kNoPoint; }
  // missing: void remove(CellIndex, PointHandle)
  template <class F>
  void for_each(streamclust::CellIndex, F&&) const {}
  std::size_t size() const { return 0; }
};

struct Cfg : streamclust::CArcConfig {
  using spatial_index = NotASpatialIndex;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
