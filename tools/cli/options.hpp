// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Command-line options of the `streamclust` tool: parsing and validation
/// (the presets: cli/presets.hpp). Every bad option becomes a UsageError (exit code 2). The
/// policy choices and their options come from the tool's registry
/// (cli/tool_policies.hpp).

#include "cli/tool_policies.hpp"

#include <streamclust/io/input_stream.hpp>
#include <streamclust/io/point_reader.hpp>
#include <streamclust/io/record.hpp>

#include <nlohmann/json_fwd.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace streamclust::cli {

/// Exit codes, part of the tool's documented contract (docs/cli.md).
enum ExitCode : int { kOk = 0, kUsage = 2, kMismatch = 3, kInputError = 4, kOutOfMemory = 5 };

/// A usage error: bad option, value or combination. Exit code 2.
using registry::UsageError;
using registry::parse_count;
using registry::parse_number;
using registry::parse_positive;
using registry::parse_positive_float;
using registry::Slot;

enum class Mode { continuous, frame };

}  // namespace streamclust::cli

namespace streamclust {
class PoseTrajectory;  // motion/trajectory.hpp: poses given by a live source
}  // namespace streamclust

namespace streamclust::cli {

struct RunSetup;     // cli/run_setup.hpp: what the options resolve to before a run
struct CycleReport;  // cli/report.hpp: one retrieval cycle as reported
}  // namespace streamclust::cli
namespace streamclust::tracking {
struct Track;  // streamclust/tracking/track.hpp
}  // namespace streamclust::tracking
namespace streamclust::cli {

/// What a run's watcher (ClusterOptions::on_cycle) sees after each cycle.
/// Valid during the call only.
struct CycleView {
  const CycleReport& report;                   ///< the cycle, its stream time [s]
  const std::vector<io::Record>& points;       ///< with cycle_windows: the window's points; else empty
  const std::vector<std::int64_t>& labels;     ///< per point: component, -1 unlabelled, -2 ground, -3 ceiling
  const std::vector<tracking::Track>* tracks;  ///< with --tracks: the tracks after the cycle; else null
};

/// Everything `streamclust cluster` needs, after presets and overrides.
struct ClusterOptions {
  std::string input;
  io::ReadOptions read;
  // policies: the registered names (cli/tool_policies.hpp) and their Params
  std::string projection = "spherical";
  std::string index = "bucket";
  std::string linkage = "angular";
  /// How the engine keeps its components: the spanning forest (the fastest
  /// exact strategy, the default) or the paper's lazy BFS (same partition;
  /// see docs/policies.md).
  std::string connectivity = "forest";
  /// The parameters of every registered policy: params.get<AngularLinkage>().theta_deg.
  ToolRegistry::Values params;
  int mask = 5;
  bool window_is_count = false;
  double window_seconds = 0.1;
  std::size_t window_count = 20000;
  double rate_hz = 20.0;
  double max_time_jump = 60.0;  ///< [s] a point further ahead of the stream is a time_jump (acceptance.hpp)
  std::optional<std::pair<std::uint32_t, std::uint32_t>> grid;  ///< rows x cols; empty = auto
  float max_multiplicity = 2.0f;
  bool connectivity_given = false;  ///< --connectivity was on the command line
  Mode mode = Mode::continuous;
  // field of view (spherical: degrees; cylindrical: azimuth degrees, z metres)
  float azimuth_min = -180.0f, azimuth_max = 180.0f;
  float elevation_min = -90.0f, elevation_max = 90.0f;
  float z_min = -3.0f, z_max = 3.0f;
  float min_range = 0.1f;
  // sensor poses (motion compensation) and mount: tools/cli/poses.hpp loads them
  std::string poses_path;                         ///< --poses FILE: TUM trajectory or a recording's odometry; empty: none
  std::optional<std::string> poses_topic;         ///< --poses-topic NAME: the recording's odometry topic
  /// Poses given by the caller instead of --poses (a live source's odometry,
  /// growing as it arrives); null: none.
  std::shared_ptr<const PoseTrajectory> trajectory;
  std::optional<std::array<double, 3>> mount_deg;  ///< --mount ROLL,PITCH,YAW [deg]; empty: none given
  // structure removal (HeightMapGround)
  bool ground = false;                 ///< --ground: class ground, wall and ceiling points out of the clustering
  std::optional<float> sensor_height;  ///< --sensor-height [m]; empty: estimated from the first window
  float ground_tolerance = 0.03f;      ///< --ground-tolerance [m]
  float ground_cell = 0.5f;            ///< --ground-cell [m]
  float max_slope_deg = 15.0f;         ///< --max-slope [deg]
  bool ceiling = true;                 ///< false: --no-ceiling
  bool walls = true;                   ///< false: --no-walls
  /// Filled by make_run_setup before a run: the poses, the mount (given or
  /// estimated), the ground model's parameters and the projection bounds in
  /// world orientation. Null: none resolved (a level sensor, no ground).
  std::shared_ptr<const RunSetup> setup;
  // outputs
  std::string labels_path, report_path, ply_path, pcd_path;
  std::string mcap_path;  ///< every cycle for Foxglove (tools/cli/mcap_output.hpp)
  std::string tracks_path;  ///< tracked objects every cycle (CSV; streamclust/tracking/tracks_csv.hpp)
  std::string png_path;   ///< a bird's-eye picture of the last selected cycle
  std::uint64_t png_every = 0;  ///< > 0: a picture of every N-th cycle instead (FILE_<cycle>.png)
  bool all_cycles = false;
  std::vector<std::uint64_t> cycle_list;  ///< empty and !all_cycles: last cycle only
  bool verify = false;
  bool quiet = false;
  // A run that another command feeds and watches (`live`); all empty for `cluster`.
  /// Opens the input instead of io::open_reader(input, read), for the
  /// driver (a live source instead of a file).
  std::function<std::unique_ptr<io::PointReader>()> open_input;
  /// Called after every cycle (CycleView: the window's rows when
  /// `cycle_windows`, the tracks with --tracks).
  std::function<void(const CycleView&)> on_cycle;
  bool cycle_windows = false;
  /// > 0: the report keeps only the last this many cycles (fixed memory
  /// for a run of any length); 0: every cycle.
  std::size_t report_cycles_kept = 0;
  /// Adds its own members to the --report JSON document.
  std::function<void(nlohmann::ordered_json&)> report_extra;
};

struct InfoOptions {
  std::string input;
  io::ReadOptions read;
};

/// Applies a named preset to `o` (before the other options override it):
/// cli/presets.hpp, included at the end of this header.
inline void apply_preset(const std::string& name, ClusterOptions& o);

/// Walks an argument list: the current option, its value, a value from a
/// fixed set. Every problem is a UsageError naming the option.
class ArgCursor {
 public:
  explicit ArgCursor(const std::vector<std::string>& args) : args_(args) {}
  bool done() const { return i_ >= args_.size(); }
  /// The option under the cursor.
  const std::string& option() const { return args_[i_]; }
  /// Moves past the option (and its value, if one was taken).
  void next() { ++i_; }
  /// The option's value (the following argument); the cursor moves onto it.
  const std::string& value() {
    if (i_ + 1 >= args_.size()) throw UsageError(args_[i_] + ": missing value");
    return args_[++i_];
  }
  /// The option's value, which must be one of `allowed`.
  std::string choice(std::initializer_list<const char*> allowed) {
    const std::string& name = args_[i_];
    const std::string v = value();
    std::string list;
    for (const char* c : allowed) {
      if (v == c) return v;
      if (!list.empty()) list += '|';
      list += c;
    }
    throw UsageError(name + ": expected " + list + ", got '" + v + "'");
  }

 private:
  const std::vector<std::string>& args_;
  std::size_t i_ = 0;
};

/// Parses one clustering-policy option shared by `cluster` and `evaluate`
/// (window time, rate, linkage, index, connectivity, every registered
/// policy option such as --theta or --cap, mask, grid, T_M, FOV, min range)
/// into `o`. Returns false when the option under the cursor is not one of
/// them (nothing consumed).
inline bool parse_policy_option(ArgCursor& c, ClusterOptions& o) {
  const std::string& a = c.option();
  if (a == "--window-time") {
    o.window_seconds = parse_number(a, c.value());
    if (!(o.window_seconds >= 0.0) || o.window_seconds > 1e6) throw UsageError(a + ": expected seconds >= 0");
  } else if (a == "--rate") {
    o.rate_hz = parse_positive(a, c.value());
  } else if (a == "--max-time-jump") {
    o.max_time_jump = parse_positive(a, c.value());
  } else if (a == "--linkage") {
    o.linkage = ToolRegistry::choose(Slot::linkage, c.value());
  } else if (a == "--index") {
    o.index = ToolRegistry::choose(Slot::spatial_index, c.value());
  } else if (a == "--connectivity") {
    o.connectivity = ToolRegistry::choose(Slot::connectivity, c.value());
    o.connectivity_given = true;
  } else if (ToolRegistry::parse_option(a, [&] { return c.value(); }, o.params)) {
    // a registered policy's option (--theta, --distance, --cap, ...)
  } else if (a == "--mask") {
    o.mask = static_cast<int>(parse_count(a, c.value()));
  } else if (a == "--grid") {
    const std::string v = c.value();
    if (v == "auto") {
      o.grid.reset();
    } else {
      const auto x = v.find('x');
      if (x == std::string::npos) throw UsageError("--grid: expected auto or HxW (e.g. 64x1024), got '" + v + "'");
      o.grid = std::make_pair(static_cast<std::uint32_t>(parse_count("--grid", v.substr(0, x))),
                              static_cast<std::uint32_t>(parse_count("--grid", v.substr(x + 1))));
    }
  } else if (a == "--max-multiplicity" || a == "--multiplicity") {
    o.max_multiplicity = parse_positive_float(a, c.value());
  } else if (a == "--fov-azimuth" || a == "--fov-elevation" || a == "--fov-z") {
    const std::string v = c.value();
    const auto colon = v.find(':');
    if (colon == std::string::npos) throw UsageError(a + ": expected MIN:MAX, got '" + v + "'");
    const auto lo = static_cast<float>(parse_number(a, v.substr(0, colon)));
    const auto hi = static_cast<float>(parse_number(a, v.substr(colon + 1)));
    if (a == "--fov-azimuth") {
      o.azimuth_min = lo;
      o.azimuth_max = hi;
    } else if (a == "--fov-elevation") {
      o.elevation_min = lo;
      o.elevation_max = hi;
    } else {
      o.z_min = lo;
      o.z_max = hi;
    }
  } else if (a == "--min-range") {
    o.min_range = static_cast<float>(parse_number(a, c.value()));
  } else {
    return false;
  }
  return true;
}

/// The checks on policy values that no single option can make.
inline void validate_policy_options(const ClusterOptions& o) {
  // mask < 1: a count beyond INT_MAX wraps to a negative int.
  if (o.mask < 1 || o.mask % 2 == 0 || o.mask > 255) {
    throw UsageError("--mask: expected an odd number of cells from 1 to 255");
  }
}

/// Parses one input option shared by `cluster` and `info` (--format,
/// --topic, --time-unit, --point-rate, --time-origin) into `read`. --point-rate HZ is the stream's
/// point rate: the records of an input without a time field get
/// t = index / HZ (an input with a time field keeps its times). Returns
/// false when the option under the cursor is not one of them.
inline bool parse_input_option(ArgCursor& c, io::ReadOptions& read) {
  const std::string& a = c.option();
  if (a == "--format") {
    const std::string v = c.choice({"auto", "csv", "pcd", "ply", "kitti", "bag", "db3", "mcap", "lvx"});
    read.format = v == "auto" ? std::nullopt : io::parse_format(v);
  } else if (a == "--topic") {
    const std::string v = c.value();
    if (v.empty()) throw UsageError("--topic: expected a topic name (bags, MCAP) or a LiDAR (LVX: serial or index)");
    read.topic = v;
  } else if (a == "--time-unit") {
    read.time_unit = io::parse_time_unit(c.choice({"s", "ms", "us", "ns"}));
  } else if (a == "--point-rate") {
    read.point_rate = parse_positive(a, c.value());
  } else if (a == "--time-origin") {
    const std::string v = c.value();
    std::int64_t seconds = 0;
    if (!io::detail::parse_int64(v, seconds) || !(std::fabs(static_cast<double>(seconds)) <= io::max_time_origin_seconds))
      throw UsageError("--time-origin: expected whole seconds within +-9e9 (e.g. 1700000000), got '" + v + "'");
    read.time_origin = io::TimeOrigin{seconds};
  } else {
    return false;
  }
  return true;
}

/// Parses the value of `--mount`: three comma-separated angles in degrees
/// (roll, pitch, yaw; each finite, -360 to 360).
inline std::array<double, 3> parse_mount(const std::string& value) {
  const std::string expected =
      "--mount: expected ROLL,PITCH,YAW in degrees (e.g. 0,15,0 or 180,0,0), got '" + value + "'";
  std::array<double, 3> angles{};
  std::size_t start = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto comma = value.find(',', start);
    if ((k < 2) != (comma != std::string::npos)) throw UsageError(expected);
    const std::string item = value.substr(start, k < 2 ? comma - start : std::string::npos);
    try {
      angles[k] = parse_number("--mount", item);
    } catch (const UsageError&) {
      throw UsageError(expected);
    }
    if (!(std::abs(angles[k]) <= 360.0)) {
      throw UsageError("--mount: expected angles from -360 to 360 degrees, got '" + value + "'");
    }
    start = comma + 1;
  }
  return angles;
}

/// Parses `streamclust cluster` arguments (argv after the subcommand).
inline ClusterOptions parse_cluster_options(const std::vector<std::string>& args) {
  ClusterOptions o;
  // The preset applies first, wherever it stands on the command line.
  for (std::size_t i = 0; i + 1 < args.size(); ++i) {
    if (args[i] == "--preset") apply_preset(args[i + 1], o);
  }
  bool window_time_set = false, window_count_set = false;
  for (ArgCursor c(args); !c.done(); c.next()) {
    const std::string& a = c.option();
    if (a == "--window-time") window_time_set = true;
    if (parse_policy_option(c, o)) continue;
    if (parse_input_option(c, o.read)) continue;
    if (a == "--preset") {
      c.value();
    } else if (a == "--window-count") {
      o.window_count = parse_count(a, c.value());
      window_count_set = true;
    } else if (a == "--projection") {
      o.projection = ToolRegistry::choose(Slot::projection, c.value());
    } else if (a == "--mode") {
      o.mode = c.choice({"continuous", "frame"}) == "continuous" ? Mode::continuous : Mode::frame;
    } else if (a == "--poses") {
      o.poses_path = c.value();
    } else if (a == "--poses-topic") {
      o.poses_topic = c.value();
    } else if (a == "--mount") {
      o.mount_deg = parse_mount(c.value());
    } else if (a == "--ground") {
      o.ground = true;
    } else if (a == "--no-ground") {
      o.ground = false;
    } else if (a == "--sensor-height") {
      o.sensor_height = parse_positive_float(a, c.value());
      if (*o.sensor_height > 100.0f) throw UsageError("--sensor-height: expected metres in (0, 100]");
    } else if (a == "--ground-tolerance") {
      o.ground_tolerance = static_cast<float>(parse_number(a, c.value()));
      if (!(o.ground_tolerance >= 0.0f && o.ground_tolerance <= 2.0f)) {
        throw UsageError("--ground-tolerance: expected metres in [0, 2]");
      }
    } else if (a == "--ground-cell") {
      o.ground_cell = static_cast<float>(parse_positive(a, c.value()));
      if (!(o.ground_cell > 0.05f && o.ground_cell <= 10.0f)) throw UsageError("--ground-cell: expected metres in (0.05, 10]");
    } else if (a == "--max-slope") {
      o.max_slope_deg = static_cast<float>(parse_number(a, c.value()));
      if (!(o.max_slope_deg >= 0.0f && o.max_slope_deg <= 60.0f)) throw UsageError("--max-slope: expected degrees in [0, 60]");
    } else if (a == "--no-ceiling") {
      o.ceiling = false;
    } else if (a == "--no-walls") {
      o.walls = false;
    } else if (a == "--labels") {
      o.labels_path = c.value();
    } else if (a == "--report") {
      o.report_path = c.value();
    } else if (a == "--ply") {
      o.ply_path = c.value();
    } else if (a == "--pcd") {
      o.pcd_path = c.value();
    } else if (a == "--mcap") {
      o.mcap_path = c.value();
    } else if (a == "--tracks") {
      o.tracks_path = c.value();
    } else if (a == "--png") {
      o.png_path = c.value();
    } else if (a == "--png-every") {
      const std::string v = c.value();
      std::int64_t n = 0;
      if (!io::detail::parse_int64(v, n) || n < 1) throw UsageError("--png-every: expected a whole number of cycles >= 1, got '" + v + "'");
      o.png_every = static_cast<std::uint64_t>(n);
    } else if (a == "--cycles") {
      const std::string v = c.value();
      o.all_cycles = v == "all";
      o.cycle_list.clear();
      if (v != "all" && v != "last") {
        std::size_t start = 0;
        while (start <= v.size()) {
          const auto comma = v.find(',', start);
          const std::string item = v.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
          const double n = parse_number("--cycles", item);
          // The range first: converting a double beyond uint64 is undefined.
          if (!(n >= 0.0 && n <= 9e15) || n != static_cast<double>(static_cast<std::uint64_t>(n))) {
            throw UsageError("--cycles: expected all, last or a comma-separated list of cycle numbers >= 0, got '" +
                             v + "'");
          }
          o.cycle_list.push_back(static_cast<std::uint64_t>(n));
          if (comma == std::string::npos) break;
          start = comma + 1;
        }
      }
    } else if (a == "--verify") {
      o.verify = true;
    } else if (a == "--quiet" || a == "-q") {
      o.quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError("unknown option '" + a + "' (see streamclust cluster --help)");
    } else if (o.input.empty()) {
      o.input = a;
    } else {
      throw UsageError("more than one input file: '" + o.input + "' and '" + a + "'");
    }
  }
  if (o.input.empty()) throw UsageError("missing INPUT file (see streamclust cluster --help)");
  if (window_time_set && window_count_set) throw UsageError("--window-time and --window-count exclude each other");
  o.window_is_count = window_count_set;
  validate_policy_options(o);
  if (o.verify && o.mode == Mode::frame) throw UsageError("--verify compares the continuous engine: use --mode continuous");
  if (o.connectivity_given && o.mode == Mode::frame)
    throw UsageError("--connectivity chooses the continuous engine's strategy: use --mode continuous");
  if (o.poses_topic && o.poses_path.empty()) throw UsageError("--poses-topic: names the odometry topic of --poses FILE");
  if (!o.tracks_path.empty() && o.mode == Mode::frame) {
    throw UsageError("--tracks follows the continuous engine's components over cycles: use --mode continuous");
  }
  if (o.mode == Mode::frame && (o.ground || !o.poses_path.empty() || o.mount_deg)) {
    throw UsageError("--ground, --poses and --mount are stages of the continuous engine: use --mode continuous");
  }
  return o;
}

/// Parses `streamclust info` arguments with the input options of `cluster`.
inline InfoOptions parse_info_options(const std::vector<std::string>& args) {
  InfoOptions o;
  for (ArgCursor c(args); !c.done(); c.next()) {
    const std::string& a = c.option();
    if (parse_input_option(c, o.read)) continue;
    if (!a.empty() && a[0] == '-') {
      throw UsageError("unknown option '" + a + "' (see streamclust info --help)");
    } else if (o.input.empty()) {
      o.input = a;
    } else {
      throw UsageError("more than one input file: '" + o.input + "' and '" + a + "'");
    }
  }
  if (o.input.empty()) throw UsageError("missing INPUT file (see streamclust info --help)");
  return o;
}

}  // namespace streamclust::cli

#include "cli/presets.hpp"  // apply_preset, which needs ClusterOptions above
