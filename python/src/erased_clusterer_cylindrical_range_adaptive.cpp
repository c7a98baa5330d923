// SPDX-License-Identifier: MIT
// The Python module's engines for one projection and linkage (every index,
// window and connectivity; one file per pair keeps each translation unit
// small enough to build in parallel, as in the CLI).

#include "engine_clusterer.hpp"

STREAMCLUST_INSTANTIATE_PYTHON_ENGINE(streamclust::CylindricalProjection, streamclust::RangeAdaptiveLinkage);
