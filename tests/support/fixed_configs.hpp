// SPDX-License-Identifier: MIT
#pragma once
// CArcFixedConfig with the rebuilding connectivity strategies.

#include <streamclust/connectivity/spanning_forest.hpp>
#include <streamclust/connectivity/union_find_rebuild.hpp>
#include <streamclust/presets.hpp>

namespace streamclust::test {

/// CArcFixedConfig with the union-find rebuild.
struct RebuildConfig : CArcFixedConfig {
  using connectivity = UnionFindRebuildConnectivity;
};

/// CArcFixedConfig with the spanning forest.
struct ForestConfig : CArcFixedConfig {
  using connectivity = SpanningForestConnectivity;
};

}  // namespace streamclust::test
