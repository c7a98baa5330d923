// EXPECT: the linkage slot's Params type differs
// SPDX-License-Identifier: MIT
// Carrying a preset's parameters to a configuration with another linkage
// needs the new linkage's Params: rebind_params names the slot.
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/objects_presets.hpp>
#include <streamclust/rebind_params.hpp>

struct Cfg : streamclust::ObjectsConfig {
  using linkage = streamclust::EuclideanLinkage;
};

void instantiate() {
  const auto params = streamclust::rebind_params<Cfg>(streamclust::objects_mid360_params());
  (void)params;
}
