// SPDX-License-Identifier: MIT
// The options of `streamclust evaluate --objects`, in their own translation
// unit: the option parser's fuzz target (fuzz/fuzz_cli_options.cpp) compiles
// it without the tool's engines.

#include "cli/evaluate_objects.hpp"

#include "cli/objects_sensors.hpp"

#include <sstream>
#include <string>
#include <vector>

namespace streamclust::cli {
namespace {

/// True when `option` is an option of a registered linkage.
bool is_linkage_option(const std::string& option) {
  for (const registry::OptionInfo& info : ToolRegistry::options()) {
    if (info.slot == Slot::linkage && info.name == option) return true;
  }
  return false;
}

/// A comma-separated list of radii or tolerances in (0, limit] m.
std::vector<float> parse_distances(const std::string& option, const std::string& text, float limit) {
  std::vector<float> values;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    const float v = parse_positive_float(option, item);
    if (v > limit) throw UsageError(option + ": expected values in (0, " + std::to_string(limit) + "] m, got " + item);
    values.push_back(v);
  }
  if (values.empty()) throw UsageError(option + ": expected one or more values, got '" + text + "'");
  return values;
}

}  // namespace

EvaluateObjectsOptions parse_evaluate_objects_options(const std::vector<std::string>& args) {
  EvaluateObjectsOptions o;
  o.scenario.seconds = 3.0;
  for (ArgCursor c(args); !c.done(); c.next()) {
    const std::string& a = c.option();
    if (a == "--velocity") {
      o.scenario.speed = static_cast<float>(parse_number(a, c.value()));
      continue;
    }
    if (a == "--burst" || a == "--burst-speed" || a == "--burst-yaw-rate" || a == "--point-rate") {
      throw UsageError(a + ": not an option of evaluate --objects (see streamclust evaluate --objects --help)");
    }
    if (parse_simulation_option(c, o.scenario)) continue;
    if (a == "--height") {
      o.height = parse_positive_float(a, c.value());
      if (o.height > 100.0f) throw UsageError("--height: expected (0, 100] m");
    } else if (a == "--poses") {
      o.poses = c.choice({"on", "off"}) == "on";
    } else if (a == "--method") {
      const std::string v = c.value();
      o.run_objects = o.run_carc = o.run_euclidean = o.run_frame = false;
      std::stringstream list(v);
      std::string item;
      bool any = false;
      while (std::getline(list, item, ',')) {
        any = true;
        if (item == "all") {
          o.run_objects = o.run_carc = o.run_euclidean = o.run_frame = true;
        } else if (item == "objects") {
          o.run_objects = true;
        } else if (item == "carc") {
          o.run_carc = true;
        } else if (item == "euclidean") {
          o.run_euclidean = true;
        } else if (item == "frame") {
          o.run_frame = true;
        } else {
          throw UsageError("--method: expected all|objects|carc|euclidean|frame (comma-separated), got '" + v + "'");
        }
      }
      if (!any) throw UsageError("--method: expected all|objects|carc|euclidean|frame, got ''");
    } else if (a == "--window-time") {
      o.window_seconds = parse_positive(a, c.value());
      if (o.window_seconds > 60.0) throw UsageError("--window-time: expected (0, 60] s");
    } else if (a == "--rate") {
      o.rate_hz = parse_positive(a, c.value());
      if (o.rate_hz > 10000.0) throw UsageError("--rate: expected (0, 10000] Hz");
    } else if (a == "--linkage") {
      o.linkage = ToolRegistry::choose(Slot::linkage, c.value());
    } else if (a == "--distance") {
      // The peers' radius, and that of every linkage with a --distance option.
      const std::string text = c.value();
      const float distance = parse_positive_float(a, text);
      if (distance > 100.0f) throw UsageError("--distance: expected (0, 100] m");
      o.euclidean_distances = o.frame_distances = {distance};
      ToolRegistry::parse_option(a, [&] { return text; }, o.linkage_params);
    } else if (a == "--euclidean-distances") {
      o.euclidean_distances = parse_distances(a, c.value(), 100.0f);
    } else if (a == "--frame-distances") {
      o.frame_distances = parse_distances(a, c.value(), 100.0f);
    } else if (a == "--frame-max-tilt") {
      o.frame_max_tilt_deg = parse_positive_float(a, c.value());
      if (o.frame_max_tilt_deg >= 90.0f) throw UsageError("--frame-max-tilt: expected (0, 90) deg");
    } else if (a == "--frame-height-tolerance") {
      o.frame_height_tolerance = parse_positive_float(a, c.value());
      if (o.frame_height_tolerance > 10.0f) throw UsageError("--frame-height-tolerance: expected (0, 10] m");
    } else if (a == "--frame-ceiling") {
      o.frame_ceiling = c.choice({"auto", "on", "off"});
    } else if (is_linkage_option(a)) {
      ToolRegistry::parse_option(a, [&] { return c.value(); }, o.linkage_params);
    } else if (a == "--plane-distance") {
      o.plane_distances = parse_distances(a, c.value(), 10.0f);
    } else if (a == "--ransac-iterations") {
      o.ransac_iterations = static_cast<std::size_t>(parse_count(a, c.value()));
      if (o.ransac_iterations > 100000) throw UsageError("--ransac-iterations: expected [1, 100000]");
    } else if (a == "--min-points") {
      o.min_points = static_cast<std::size_t>(parse_count(a, c.value()));
    } else if (a == "--verify") {
      o.verify = true;
    } else if (a == "--no-walls") {
      o.walls = false;
    } else if (a == "--json") {
      o.json_path = c.value();
    } else if (a == "--quiet" || a == "-q") {
      o.quiet = true;
    } else {
      throw UsageError("unknown option '" + a + "' (see streamclust evaluate --objects --help)");
    }
  }
  validate_objects_scenario(o.scenario, o.window_seconds, o.rate_hz);
  if (o.verify && !o.run_objects) throw UsageError("--verify checks the objects method: add it to --method");
  return o;
}

void validate_objects_scenario(const SimulateOptions& scenario, double window_seconds, double rate_hz) {
  validate_simulation_options(scenario);
  objects_sensor(scenario.sensor);  // throws for the others
  if (!(scenario.speed >= -10.0f && scenario.speed <= 10.0f)) throw UsageError("--speed: expected [-10, 10] m/s");
  if (!(scenario.yaw_rate >= -5.0f && scenario.yaw_rate <= 5.0f)) {
    throw UsageError("--yaw-rate: expected [-5, 5] rad/s");
  }
  const double period = 1.0 / rate_hz;
  if (scenario.seconds < window_seconds + period) {
    throw UsageError("--duration: at least one retrieval after the first window is needed: expected >= T_B + 1/rate = " +
                     std::to_string(window_seconds + period) + " s, got " + std::to_string(scenario.seconds) + " s");
  }
}

}  // namespace streamclust::cli
