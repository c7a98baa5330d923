// SPDX-License-Identifier: MIT
// `streamclust cluster` compiled for the spherical projection and the
// range-adaptive linkage (every index, window and connectivity; one file per
// pair keeps each translation unit small enough to build in parallel).

#include "cli/cluster.hpp"
#include "cli/cluster_driver.hpp"

namespace streamclust::cli {

int run_cluster_spherical_range_adaptive(const ClusterOptions& o, std::ostream& out, std::ostream& err) {
  return run_cluster_for<SphericalProjection, RangeAdaptiveLinkage>(o, out, err);
}

}  // namespace streamclust::cli
