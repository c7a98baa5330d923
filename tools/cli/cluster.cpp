// SPDX-License-Identifier: MIT
// `streamclust cluster`: the choice of the translation unit compiled for the
// options' projection and linkage (the registry's dispatch).

#include "cli/cluster.hpp"
#include "cli/engine_config.hpp"
#include "cli/memory_context.hpp"
#include "cli/run_setup.hpp"

#include <streamclust/io/reader.hpp>

#include <memory>
#include <stdexcept>

namespace streamclust::cli {

namespace {

int run_cluster_setup(const ClusterOptions& options, std::ostream& out, std::ostream& err) {
  ClusterOptions o = options;
  // One time base for the first-window estimate, the run and the poses
  // (epoch times keep their nanoseconds: io/stream_time.hpp).
  if (!o.read.time_origin) o.read.time_origin = io::find_time_origin(o.input, o.read);
  if (o.mode == Mode::continuous && !o.setup) {
    try {
      o.setup = std::make_shared<const RunSetup>(make_run_setup(o, !o.report_path.empty(), err));
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  return with_projection_and_linkage(o, [&](auto projection, auto linkage) {
    return run_cluster_for<typename decltype(projection)::type, typename decltype(linkage)::type>(o, out, err);
  });
}

}  // namespace

int run_cluster(const ClusterOptions& o, std::ostream& out, std::ostream& err) {
  // The setup reads (the time origin, the first window); the driver names its own stages.
  return with_memory_context("cluster", o.input, [&](Stage&) { return run_cluster_setup(o, out, err); });
}

}  // namespace streamclust::cli
