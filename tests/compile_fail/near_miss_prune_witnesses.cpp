// EXPECT: STREAMCLUST_CONNECTIVITY_CAPABILITY_INVALID: `prune_witnesses` is not the optional
// SPDX-License-Identifier: MIT
// A connectivity whose `prune_witnesses` is not const would keep every edge
// without a word: the slot check names the expected signature.
#include <streamclust/connectivity/spanning_forest.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

struct MutablePruning : streamclust::SpanningForestConnectivity {
  using SpanningForestConnectivity::SpanningForestConnectivity;
  std::uint32_t prune_witnesses() { return 2; }  // not const: a near miss
};

struct Cfg : streamclust::CArcConfig {
  using connectivity = MutablePruning;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
