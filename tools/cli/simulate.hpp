// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust simulate`: writes a simulated stream with its ground truth
/// (the `label` column/field is the id of the object hit: 0 for structure).
/// Sensors: the Livox models of streamclust::sim (mid360, mid40, mid70, avia)
/// and a 32-beam spinning sensor; scenes: office, forest, street. The older
/// stand-in (`--sensor synthetic --scene room`) stays available.

#include "cli/options.hpp"

#include <streamclust/io/writers.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/avia_model.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/sensors/risley_pair_model.hpp>
#include <streamclust/sim/sensors/spinning_model.hpp>
#include <streamclust/sim/simulator.hpp>
#include <streamclust/sim/synthetic_stream.hpp>

#include <ostream>
#include <stdexcept>
#include <utility>
#include <string>
#include <vector>

namespace streamclust::cli {

struct SimulateOptions {
  std::string sensor = "mid360";
  std::string scene = "office";
  double seconds = 1.0;
  double point_rate = 200000.0;  ///< synthetic sensor only (t = index / rate); the models have their own rates
  bool point_rate_given = false;  ///< --point-rate was on the command line
  float speed = 0.0f;            ///< ego-motion along +x [m/s]
  float yaw_rate = 0.0f;         ///< [rad/s]
  float noise = 0.02f;           ///< range noise [m]
  float dropout = 0.0f;          ///< probability
  float max_range = 40.0f;       ///< [m]
  std::uint64_t seed = 1;
  // An ego-motion burst: from burst_start for burst_length seconds the sensor
  // moves with burst_speed (+x) and burst_yaw_rate, then with speed/yaw_rate again.
  double burst_start = 0.0;     ///< [s]
  double burst_length = 0.0;    ///< [s]; 0 = no burst
  float burst_speed = 0.0f;     ///< [m/s]
  float burst_yaw_rate = 0.0f;  ///< [rad/s]
  std::string out;
  bool quiet = false;
};

/// Parses one option of the simulated scenario (sensor, scene, duration,
/// seed, ego-motion, burst, noise, dropout, max range), shared by `simulate`
/// and `evaluate`. Returns false when the option under the cursor is not one
/// of them (nothing consumed).
inline bool parse_simulation_option(ArgCursor& c, SimulateOptions& o) {
  const std::string& a = c.option();
  if (a == "--sensor") {
    o.sensor = c.choice({"mid360", "mid40", "mid70", "avia", "spinning32", "synthetic"});
  } else if (a == "--scene") {
    o.scene = c.value();
    if (o.scene != "office" && o.scene != "forest" && o.scene != "street" && o.scene != "room") {
      throw UsageError("--scene: expected office|forest|street (or room with --sensor synthetic), got '" + o.scene +
                       "'");
    }
  } else if (a == "--speed") {
    o.speed = static_cast<float>(parse_number(a, c.value()));
  } else if (a == "--yaw-rate") {
    o.yaw_rate = static_cast<float>(parse_number(a, c.value()));
  } else if (a == "--burst") {
    const std::string v = c.value();
    const auto colon = v.find(':');
    if (colon == std::string::npos) throw UsageError("--burst: expected START:LENGTH in seconds, got '" + v + "'");
    o.burst_start = parse_number(a, v.substr(0, colon));
    o.burst_length = parse_positive(a, v.substr(colon + 1));
    if (!(o.burst_start >= 0.0) || o.burst_start > 3600.0) throw UsageError("--burst: START must be in [0, 3600] s");
  } else if (a == "--burst-speed") {
    o.burst_speed = static_cast<float>(parse_number(a, c.value()));
  } else if (a == "--burst-yaw-rate") {
    o.burst_yaw_rate = static_cast<float>(parse_number(a, c.value()));
  } else if (a == "--noise") {
    o.noise = static_cast<float>(parse_number(a, c.value()));
  } else if (a == "--dropout") {
    o.dropout = static_cast<float>(parse_number(a, c.value()));
  } else if (a == "--max-range") {
    o.max_range = static_cast<float>(parse_positive(a, c.value()));
  } else if (a == "--seconds" || a == "--duration") {
    o.seconds = parse_positive(a, c.value());
    if (o.seconds > 3600.0) throw UsageError(a + ": at most 3600");
  } else if (a == "--point-rate") {
    o.point_rate = parse_positive(a, c.value());
    o.point_rate_given = true;
  } else if (a == "--seed") {
    o.seed = parse_count(a, c.value());
  } else {
    return false;
  }
  return true;
}

/// The checks on a scenario that no single option can make.
inline void validate_simulation_options(const SimulateOptions& o) {
  if ((o.sensor == "synthetic") != (o.scene == "room")) {
    throw UsageError("--sensor synthetic goes with --scene room, and only with it");
  }
  if (o.point_rate_given && o.sensor != "synthetic") {
    throw UsageError("--point-rate: the " + o.sensor +
                     " model fires at its own rate; --point-rate times a stream without its own timing"
                     " (--sensor synthetic)");
  }
  if (o.sensor == "synthetic" && o.burst_length > 0.0) {
    throw UsageError("--burst needs a simulated sensor (not --sensor synthetic)");
  }
}

inline SimulateOptions parse_simulate_options(const std::vector<std::string>& args) {
  SimulateOptions o;
  for (ArgCursor c(args); !c.done(); c.next()) {
    const std::string& a = c.option();
    if (parse_simulation_option(c, o)) continue;
    if (a == "--out") {
      o.out = c.value();
    } else if (a == "--quiet" || a == "-q") {
      o.quiet = true;
    } else {
      throw UsageError("unknown option '" + a + "' (see streamclust simulate --help)");
    }
  }
  if (o.out.empty()) throw UsageError("missing --out FILE (.csv or .pcd)");
  validate_simulation_options(o);
  const auto ends_with = [&](const char* ext) {
    const std::string e(ext);
    return o.out.size() >= e.size() && o.out.compare(o.out.size() - e.size(), e.size(), e) == 0;
  };
  if (!ends_with(".csv") && !ends_with(".pcd")) throw UsageError("--out: expected a .csv or .pcd file name");
  return o;
}

/// The simulator parameters of a scenario (noise, dropout, range, ego-motion
/// with its optional burst, seed).
template <class Sensor>
typename sim::Simulator<Sensor>::Params simulator_params(const SimulateOptions& o) {
  typename sim::Simulator<Sensor>::Params p;
  p.range_noise = o.noise;
  p.dropout = o.dropout;
  p.max_range = o.max_range;
  p.velocity = Eigen::Vector3f(o.speed, 0.0f, 0.0f);
  p.yaw_rate = o.yaw_rate;
  p.seed = o.seed;
  if (o.burst_length > 0.0) {
    p.motion_profile.push_back(
        sim::MotionSegment{o.burst_start, Eigen::Vector3f(o.burst_speed, 0.0f, 0.0f), o.burst_yaw_rate});
    p.motion_profile.push_back(
        sim::MotionSegment{o.burst_start + o.burst_length, Eigen::Vector3f(o.speed, 0.0f, 0.0f), o.yaw_rate});
  }
  return p;
}

template <class Sensor>
void simulate_into(Sensor sensor, const SimulateOptions& o, std::vector<io::Record>& records) {
  sim::Scene scene = o.scene == "forest"   ? sim::forest_scene(o.seed)
                     : o.scene == "street" ? sim::street_scene(o.seed)
                                           : sim::office_scene(o.seed);
  sim::Simulator<Sensor> simulator(std::move(sensor), std::move(scene), simulator_params<Sensor>(o));
  while (simulator.time() < o.seconds) {
    const sim::SimPoint s = simulator.next();
    records.push_back(io::Record{s.x, s.y, s.z, s.intensity, s.t, s.instance});
  }
}

/// The whole simulated stream of a scenario, in firing order, with the
/// ground-truth instance id in `label`. Bad simulator parameters become a
/// UsageError.
inline std::vector<io::Record> simulate_records(const SimulateOptions& o) {
  std::vector<io::Record> records;
  try {
    if (o.sensor == "synthetic") {
      SyntheticStream::Params p;
      p.point_rate = o.point_rate;
      p.seed = o.seed;
      SyntheticStream stream(p);
      while (stream.time() < o.seconds) {
        const SyntheticPoint s = stream.next();
        records.push_back(io::Record{s.x, s.y, s.z, s.intensity, s.t, s.object});
      }
    } else if (o.sensor == "mid360") {
      simulate_into(sim::Mid360Model(sim::Mid360Model::Params{}), o, records);
    } else if (o.sensor == "mid40") {
      simulate_into(sim::RisleyPairModel::mid40(), o, records);
    } else if (o.sensor == "mid70") {
      simulate_into(sim::RisleyPairModel::mid70(), o, records);
    } else if (o.sensor == "avia") {
      simulate_into(sim::AviaModel(sim::AviaModel::Params{}), o, records);
    } else {
      simulate_into(sim::SpinningModel(sim::SpinningModel::Params{}), o, records);
    }
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return records;
}

inline int run_simulate(const SimulateOptions& o, std::ostream& out) {
  const std::vector<io::Record> records = simulate_records(o);
  const bool pcd = o.out.size() >= 4 && o.out.compare(o.out.size() - 4, 4, ".pcd") == 0;
  if (pcd) {
    io::write_pcd(o.out, records, {}, "binary");
  } else {
    io::write_csv_points(o.out, records);
  }
  if (!o.quiet) {
    out << "streamclust: simulated " << records.size() << " points (" << o.seconds << " s, sensor " << o.sensor
        << ", scene " << o.scene << ", seed " << o.seed << ") -> " << o.out << "\n";
  }
  return kOk;
}

}  // namespace streamclust::cli
