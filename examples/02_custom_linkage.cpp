// SPDX-License-Identifier: MIT
// Example 2: a custom linkage metric in about ten lines, combined with a
// standard one, plugged into a C-ARC configuration that keeps the Mid-360
// preset's parameters (rebind_params).

#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/streamclust.hpp>

#include <cstdio>

// Euclidean distance that grows with range: links when |a - b| <= k * min range.
struct RangeScaledLinkage {
  struct Params {
    float factor = 0.03f;  ///< allowed distance per metre of range
  };
  explicit RangeScaledLinkage(const Params& p) : factor_(p.factor) {}
  bool operator()(const streamclust::Sample& a, const streamclust::Sample& b) const {
    const float limit = factor_ * std::min(a.range, b.range);
    return (a.position - b.position).squaredNorm() <= limit * limit;
  }
  float factor_;
};

// Angular criterion AND the custom metric, on C-ARC's other policies.
struct MyConfig : streamclust::CArcFixedConfig {
  using linkage = streamclust::AllOf<streamclust::AngularLinkage, RangeScaledLinkage>;
};

int main() {
  // The paper's Mid-360 preset (theta 30 deg, its field of view, T_B 0.1 s,
  // w 5) carried to MyConfig: every slot and engine parameter kept, the
  // linkage given (the preset's angular Params and the custom metric's).
  const auto preset = streamclust::to_clusterer_params<streamclust::CArcFixedConfig>(streamclust::carc_mid360_params());
  auto params = streamclust::rebind_params<MyConfig>(preset, MyConfig::linkage::Params{preset.linkage, {0.05f}});
  params.resolution = {48, 720};  // the fixed grid [rows, cols]
  streamclust::StreamClusterer<MyConfig> engine(params);

  streamclust::SyntheticStream stream;
  while (stream.time() < 0.3) engine.insert(stream.next());
  const auto& result = engine.retrieve();
  std::printf("custom linkage: %zu points, %zu components\n", result.points.size(), result.components.size());
  return result.points.empty() ? 1 : 0;
}
