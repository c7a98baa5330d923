// SPDX-License-Identifier: MIT
// `streamclust cluster`: the choice of the translation unit compiled for the
// options' projection and linkage.

#include "cli/cluster.hpp"

namespace streamclust::cli {

int run_cluster(const ClusterOptions& o, std::ostream& out, std::ostream& err) {
  const bool angular = o.linkage == LinkageKind::angular;
  if (o.projection == ProjectionKind::spherical) {
    return angular ? run_cluster_spherical_angular(o, out, err) : run_cluster_spherical_euclidean(o, out, err);
  }
  return angular ? run_cluster_cylindrical_angular(o, out, err) : run_cluster_cylindrical_euclidean(o, out, err);
}

}  // namespace streamclust::cli
