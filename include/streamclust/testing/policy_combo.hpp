// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A configuration of five policies on a FixedResolution grid: what the
/// generated exactness checks run (the product of the policy lists, the
/// connectivity law's probes). The grid comes from the resolution's Params
/// (random_params draws it per seed).

#include <streamclust/resolution/fixed.hpp>

namespace streamclust::testing {

template <class Projection, class Index, class Linkage, class Window, class Connectivity>
struct PolicyCombo {
  using projection = Projection;
  using spatial_index = Index;
  using linkage = Linkage;
  using window = Window;
  using resolution = FixedResolution;
  using connectivity = Connectivity;
};

}  // namespace streamclust::testing
