// EXPECT: STREAMCLUST_VISITOR_POLICY_INVALID
// SPDX-License-Identifier: MIT
// A visitor written from scratch that forgets most hooks (instead of deriving
// from streamclust::NullVisitor) must be rejected where the engine starts.
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

struct NotAVisitor {
  void cluster_created(streamclust::ClusterId) {}
  // missing: clusters_merged, cluster_split, cluster_evicted
};

struct Cfg : streamclust::CArcConfig {
  using visitor = NotAVisitor;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
