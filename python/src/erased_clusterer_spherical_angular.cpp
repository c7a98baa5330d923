// SPDX-License-Identifier: MIT
// The Python module's engines for the spherical projection and the angular
// linkage (every index, window and connectivity; one file per pair keeps
// each translation unit small enough to build in parallel, as in the CLI).

#include "engine_clusterer.hpp"

namespace streamclust::python {

std::unique_ptr<ErasedClusterer> make_spherical_angular(const cli::ClusterOptions& o) {
  return make_for<SphericalProjection, AngularLinkage>(o);
}

}  // namespace streamclust::python
