// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust cluster`: streams a recorded input through the continuous
/// engine (or the frame clusterer in frame mode), retrieves at a fixed rate
/// of stream time and writes labels, a JSON report and point clouds. The
/// driver is cli/cluster_driver.hpp, compiled once per configuration in
/// the tool's library (tools/cli/cluster_*.cpp).

#include "cli/options.hpp"

#include <ostream>

namespace streamclust::cli {

/// Runs `streamclust cluster` with the compiled configuration the options
/// name. Returns the exit code; throws io::InputError (exit 4) and
/// UsageError (exit 2).
int run_cluster(const ClusterOptions& o, std::ostream& out, std::ostream& err);

/// The same for one projection and linkage: defined in cli/cluster_driver.hpp,
/// explicitly instantiated in one translation unit per pair
/// (STREAMCLUST_INSTANTIATE_CLUSTER).
template <class Projection, class Linkage>
int run_cluster_for(const ClusterOptions& o, std::ostream& out, std::ostream& err);

}  // namespace streamclust::cli
