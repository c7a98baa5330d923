// EXPECT: STREAMCLUST_CONNECTIVITY_POLICY_INVALID
// SPDX-License-Identifier: MIT
// A connectivity policy without its per-point state, its
// `stores_point_edges` and its State template carries no algorithm and must
// be rejected where the engine starts.
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

struct NotAConnectivity {
  struct Params {};
  explicit NotAConnectivity(const Params&) {}
  // missing: PointState, stores_point_edges, template <class Ring> class State
};

struct Cfg : streamclust::CArcConfig {
  using connectivity = NotAConnectivity;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
