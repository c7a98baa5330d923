// EXPECT: STREAMCLUST_RESOLUTION_POLICY_INVALID
// SPDX-License-Identifier: MIT
// A resolution policy without calibrate(coords, fov_aspect) must be rejected
// where the engine starts.
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

struct NotAResolution {
  struct Params {
    streamclust::GridSize grid{64, 1024};
  };
  explicit NotAResolution(const Params& p) : params(p) {}
  bool needs_calibration() const { return false; }
  streamclust::GridSize grid() const { return params.grid; }
  // missing: GridSize calibrate(const std::vector<Projected>&, float)
  Params params;
};

struct Cfg : streamclust::CArcConfig {
  using resolution = NotAResolution;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
