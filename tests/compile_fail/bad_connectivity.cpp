// EXPECT: STREAMCLUST_CONNECTIVITY_POLICY_INVALID
// SPDX-License-Identifier: MIT
// A connectivity policy without `static constexpr ConnectivityStrategy
// strategy` names no algorithm and must be rejected where the engine starts.
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

struct NotAConnectivity {
  struct Params {};
  explicit NotAConnectivity(const Params&) {}
  // missing: static constexpr streamclust::ConnectivityStrategy strategy = ...;
};

struct Cfg : streamclust::CArcConfig {
  using connectivity = NotAConnectivity;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
