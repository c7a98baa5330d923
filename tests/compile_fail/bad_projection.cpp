// EXPECT: STREAMCLUST_PROJECTION_POLICY_INVALID
// SPDX-License-Identifier: MIT
// A projection that forgets fov_aspect() (needed by the resolution policy) must
// be rejected where the engine starts, with the grep-able identifier.
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <Eigen/Core>

struct NotAProjection {
  struct Params {
    float min_range = 0.5f;
  };
  explicit NotAProjection(const Params& p) : params(p) {}
  streamclust::Projected project(const Eigen::Vector3f&) const { return {}; }
  bool wraps_horizontally() const { return true; }
  // missing: float fov_aspect() const
  Params params;
};

struct Cfg : streamclust::CArcConfig {
  using projection = NotAProjection;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
