// SPDX-License-Identifier: MIT
// make_erased_clusterer: the translation unit compiled for the options'
// projection and linkage (the registry's dispatch, as in tools/cli/cluster.cpp).

#include "erased_clusterer.hpp"

#include "cli/engine_config.hpp"

namespace streamclust::python {

std::unique_ptr<ErasedClusterer> make_erased_clusterer(const cli::ClusterOptions& o) {
  return cli::with_projection_and_linkage(o, [&](auto projection, auto linkage) {
    return make_for<typename decltype(projection)::type, typename decltype(linkage)::type>(o);
  });
}

}  // namespace streamclust::python
