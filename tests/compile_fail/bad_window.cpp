// EXPECT: STREAMCLUST_WINDOW_POLICY_INVALID
// SPDX-License-Identifier: MIT
// A window without complete(oldest, newest, size) cannot end calibration and
// must be rejected where the engine starts.
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <cstddef>

struct NotAWindow {
  struct Params {
    double duration = 0.1;  ///< [s]
  };
  explicit NotAWindow(const Params& p) : params(p) {}
  bool expired(double oldest, double newest, std::size_t) const { return newest - oldest > params.duration; }
  // missing: bool complete(double, double, std::size_t) const
  Params params;
};

struct Cfg : streamclust::CArcConfig {
  using window = NotAWindow;
};

void instantiate() {
  streamclust::StreamClusterer<Cfg> c;
  (void)c;
}
