// EXPECT: STREAMCLUST_NO_POINT_EDGES
// SPDX-License-Identifier: MIT
// The spanning-forest connectivity stores no point-level edges: the
// Boost.Graph point view (and for_each_neighbor, the edge accessors) must be
// rejected with a message saying why, not fail somewhere inside Boost.
#include <streamclust/graph/point_graph.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

struct Cfg : streamclust::CArcConfig {
  using connectivity = streamclust::SpanningForestConnectivity;
};

std::size_t instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  const auto g = streamclust::point_graph(c);
  return out_degree(0, g);
}
