// SPDX-License-Identifier: MIT
// `streamclust cluster` compiled for the cylindrical projection and the
// range-adaptive linkage (every index, window and connectivity; one file per
// pair keeps each translation unit small enough to build in parallel).

#include "cli/cluster.hpp"
#include "cli/cluster_driver.hpp"

namespace streamclust::cli {

int run_cluster_cylindrical_range_adaptive(const ClusterOptions& o, std::ostream& out, std::ostream& err) {
  return run_cluster_for<CylindricalProjection, RangeAdaptiveLinkage>(o, out, err);
}

}  // namespace streamclust::cli
