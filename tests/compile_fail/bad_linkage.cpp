// EXPECT: STREAMCLUST_LINKAGE_POLICY_INVALID
// SPDX-License-Identifier: MIT
// A linkage whose predicate has the wrong name (linked(a, b) instead of the
// call operator) must be rejected where the engine starts.
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

struct NotALinkage {
  struct Params {
    float max_distance = 0.5f;  ///< [m]
  };
  explicit NotALinkage(const Params& p) : params(p) {}
  // wrong: the concept needs bool operator()(const Sample&, const Sample&) const
  bool linked(const streamclust::Sample&, const streamclust::Sample&) const { return true; }
  Params params;
};

struct Cfg : streamclust::CArcConfig {
  using linkage = NotALinkage;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
