// SPDX-License-Identifier: MIT
// The Python module's engines for the spherical projection and the euclidean
// linkage (every index, window and connectivity; one file per pair keeps
// each translation unit small enough to build in parallel, as in the CLI).

#include "engine_clusterer.hpp"

namespace streamclust::python {

std::unique_ptr<ErasedClusterer> make_spherical_euclidean(const cli::ClusterOptions& o) {
  return make_for<SphericalProjection, EuclideanLinkage>(o);
}

}  // namespace streamclust::python
