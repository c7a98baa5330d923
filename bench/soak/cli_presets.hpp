// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The engines `streamclust cluster --preset NAME` runs, taken from the
/// tool's own headers (tools/cli) so that the soak cannot drift from them:
/// apply_preset, the compiled CliConfig, make_params and make_run_setup.
///
/// - `carc` (the tool's default): `CliConfig<SphericalProjection,
///   BucketGrid, AngularLinkage, TimeWindow>`, spanning forest; theta
///   10 deg, w 5, T_M 2, T_B 0.1 s, the full sphere.
/// - `objects-mid360`: `CliConfig<SphericalProjection, CappedGrid,
///   RangeAdaptiveLinkage, TimeWindow>`, spanning forest; K 4, w 5, T_M 4,
///   T_B 0.5 s, the Mid-360's field of view, the height-map ground; mount and
///   sensor height given (`--mount`, `--sensor-height`) or estimated from
///   the first window.
///
/// CliConfig's resolution, motion and ground slots are run-time forwarders
/// (RuntimeResolution, RuntimeMotion, RuntimeGround); the library's
/// equivalents are CArcFastConfig with `CArcParams{}` and ObjectsConfig with
/// `objects_mid360_params()`.

#include "cli/engine_config.hpp"
#include "cli/options.hpp"
#include "cli/run_setup.hpp"

#include <Eigen/Core>

#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace streamclust::bench {

/// `streamclust cluster --preset carc` (the tool's default).
using CarcCliConfig = cli::CliConfig<SphericalProjection, BucketGrid, AngularLinkage, TimeWindow>;
/// `streamclust cluster --preset objects-mid360`.
using ObjectsCliConfig = cli::CliConfig<SphericalProjection, CappedGrid, RangeAdaptiveLinkage, TimeWindow>;

/// The options the tool resolves for `--preset name` and nothing else
/// (UsageError for an unknown name). Quiet: the soak reports the setup.
inline cli::ClusterOptions cli_preset_options(const std::string& name) {
  cli::ClusterOptions o;
  o.quiet = true;
  cli::apply_preset(name, o);
  return o;
}

/// Throws std::logic_error unless the tool's dispatch (with_engine_config,
/// continuous mode) would run `Config` for `o`: the soak names its two
/// configurations instead of instantiating every combination.
template <class Config>
void require_cli_config(const cli::ClusterOptions& o) {
  using Index = typename Config::spatial_index;
  using Linkage = typename Config::linkage;
  using registry::PolicyDescriptor;
  const bool index_ok = o.index == PolicyDescriptor<Index>::name;
  const bool linkage_ok = o.linkage == PolicyDescriptor<Linkage>::name;
  const bool rest_ok = o.mode == cli::Mode::continuous && o.projection == "spherical" && !o.window_is_count &&
                       o.connectivity == "forest" && std::is_same_v<typename Config::window, TimeWindow> &&
                       std::is_same_v<typename Config::connectivity, SpanningForestConnectivity>;
  if (!(index_ok && linkage_ok && rest_ok)) {
    throw std::logic_error("the preset's options no longer map to the configuration the soak names (cli_presets.hpp)");
  }
}

/// Resolves the run as the tool does before clustering (make_run_setup):
/// with the preset's ground, the mount and sensor height are estimated from
/// `first_window` (sensor-frame points of the first T_B seconds). Stores
/// the setup in `o` and returns it. O(first window).
inline std::shared_ptr<const cli::RunSetup> resolve_cli_setup(cli::ClusterOptions& o,
                                                              const std::vector<Eigen::Vector3f>& first_window) {
  std::ostringstream quiet;  // o.quiet: nothing is written
  o.setup = std::make_shared<const cli::RunSetup>(cli::make_run_setup(o, false, quiet, &first_window));
  return o.setup;
}

}  // namespace streamclust::bench
