// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The CLI's option machinery used from Python: the package turns keywords
/// into CLI arguments (`window_time=0.1` -> `--window-time 0.1`), these
/// functions parse them with the CLI's own parser (presets, validation and
/// messages included) and resolve the run setup (poses, mount, ground) as
/// `streamclust cluster` does.

#include "point_buffers.hpp"

#include "cli/options.hpp"
#include "cli/poses.hpp"
#include "cli/run_setup.hpp"

#include <Eigen/Core>

#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::python {

/// Stands for the input file the CLI parser requires; never opened.
inline constexpr const char* kArrayInput = "<numpy arrays>";

/// ClusterOptions of CLI-style policy arguments. Throws cli::UsageError
/// with the CLI's message.
inline cli::ClusterOptions parse_python_options(std::vector<std::string> args) {
  args.emplace_back(kArrayInput);
  return cli::parse_cluster_options(args);
}

/// True when `o` asks the run setup to estimate the mount or the sensor
/// height from the first window (--ground without --mount/--poses or
/// without --sensor-height).
inline bool needs_ground_window(const cli::ClusterOptions& o) {
  return o.ground && (!cli::has_motion_options(o) || !o.sensor_height);
}

/// True when the run setup reads the first window: a ground estimate, or a
/// linkage fitted to the sensor (`--linkage scan-adaptive`, sensor_fit.hpp).
inline bool needs_first_window(const cli::ClusterOptions& o) {
  return needs_ground_window(o) || (o.mode == cli::Mode::continuous && cli::linkage_fits_sensor(o));
}

/// The first window of a stream given as arrays, as the CLI's
/// first_window_points reads it from a file: finite points of the first T_B
/// seconds (or the first window_count points), at most `max_points`; their
/// times [s] in `times` when given. O(window).
inline std::vector<Eigen::Vector3f> first_window_of(const cli::ClusterOptions& o, const PointBuffers& points,
                                                    std::vector<double>* times = nullptr,
                                                    std::size_t max_points = 400000) {
  std::vector<Eigen::Vector3f> window;
  bool started = false;
  double t0 = 0.0;
  std::size_t seen = 0;
  for (std::size_t i = 0; i < points.size && window.size() < max_points; ++i) {
    const Point p = points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.t)) continue;
    if (!started) {
      started = true;
      t0 = p.t;
    }
    if (o.window_is_count ? seen >= o.window_count : p.t - t0 >= o.window_seconds) break;
    ++seen;
    window.emplace_back(p.x, p.y, p.z);
    if (times) times->push_back(p.t);
  }
  return window;
}

/// Fills `o.setup` as `streamclust cluster` does in continuous mode (quietly), the ground
/// estimate made on `first_window` when given. Without one, options that
/// need an estimate are a UsageError naming what to give instead. Poses
/// files that cannot be read throw io::InputError.
inline void resolve_setup(cli::ClusterOptions& o, const std::vector<Eigen::Vector3f>* first_window,
                          const std::vector<double>* first_window_times = nullptr) {
  if (o.mode != cli::Mode::continuous) return;  // the CLI resolves a setup for the continuous engine only
  if (!first_window && needs_ground_window(o)) {
    throw cli::UsageError("--ground: the mount and sensor height are estimated from the stream's first window, "
                          "which a Clusterer does not have yet: give first_window=(xyz, t) (the stream's "
                          "beginning), or --mount (or --poses) and --sensor-height, or use cluster_stream");
  }
  if (!first_window && needs_first_window(o)) {
    throw cli::UsageError("--linkage " + o.linkage + ": the linkage is fitted to the stream's first window, which "
                          "a Clusterer does not have yet: give first_window=(xyz, t) (the stream's beginning), or "
                          "use cluster_stream");
  }
  o.quiet = true;
  std::ostringstream notes;  // the CLI's notes on stderr; not shown
  try {
    o.setup = std::make_shared<const cli::RunSetup>(cli::make_run_setup(o, false, notes, first_window, first_window_times));
  } catch (const std::invalid_argument& e) {
    throw cli::UsageError(e.what());
  }
}

}  // namespace streamclust::python
