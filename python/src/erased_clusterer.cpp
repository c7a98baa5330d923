// SPDX-License-Identifier: MIT
// make_erased_clusterer: the translation unit compiled for the options'
// projection and linkage (the CLI's choice in tools/cli/cluster.cpp).

#include "erased_clusterer.hpp"

namespace streamclust::python {

std::unique_ptr<ErasedClusterer> make_erased_clusterer(const cli::ClusterOptions& o) {
  const bool spherical = o.projection == cli::ProjectionKind::spherical;
  switch (o.linkage) {
    case cli::LinkageKind::euclidean:
      return spherical ? make_spherical_euclidean(o) : make_cylindrical_euclidean(o);
    case cli::LinkageKind::range_adaptive:
      return spherical ? make_spherical_range_adaptive(o) : make_cylindrical_range_adaptive(o);
    case cli::LinkageKind::angular: break;
  }
  return spherical ? make_spherical_angular(o) : make_cylindrical_angular(o);
}

}  // namespace streamclust::python
