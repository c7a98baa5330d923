// EXPECT: STREAMCLUST_SPATIAL_INDEX_CAPABILITY_INVALID: `gather` is not the optional branch-free read
// SPDX-License-Identifier: MIT
// An index whose `gather` takes a vector instead of (out, room) is not the
// branch-free mask read: the slot check names the expected signature
// instead of the engine visiting the cells one by one without a word.
#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <vector>

struct VectorGatherGrid : streamclust::BucketGrid {
  using BucketGrid::BucketGrid;
  std::size_t gather(streamclust::CellIndex cell, std::vector<streamclust::PointHandle>& out) const {
    for_each(cell, [&](streamclust::PointHandle h) { out.push_back(h); });
    return out.size();
  }
};

struct Cfg : streamclust::CArcConfig {
  using spatial_index = VectorGatherGrid;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
