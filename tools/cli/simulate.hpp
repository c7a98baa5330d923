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
  double point_rate = 200000.0;  ///< synthetic sensor only; the models have their own rates
  float speed = 0.0f;            ///< ego-motion along +x [m/s]
  float yaw_rate = 0.0f;         ///< [rad/s]
  float noise = 0.02f;           ///< range noise [m]
  float dropout = 0.0f;          ///< probability
  float max_range = 40.0f;       ///< [m]
  std::uint64_t seed = 1;
  std::string out;
  bool quiet = false;
};

inline SimulateOptions parse_simulate_options(const std::vector<std::string>& args) {
  SimulateOptions o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw UsageError(a + ": missing value");
      return args[++i];
    };
    if (a == "--sensor") {
      o.sensor = value();
      if (o.sensor != "mid360" && o.sensor != "mid40" && o.sensor != "mid70" && o.sensor != "avia" &&
          o.sensor != "spinning32" && o.sensor != "synthetic") {
        throw UsageError("--sensor: expected mid360|mid40|mid70|avia|spinning32|synthetic, got '" + o.sensor + "'");
      }
    } else if (a == "--scene") {
      o.scene = value();
      if (o.scene != "office" && o.scene != "forest" && o.scene != "street" && o.scene != "room") {
        throw UsageError("--scene: expected office|forest|street (or room with --sensor synthetic), got '" + o.scene +
                         "'");
      }
    } else if (a == "--speed") {
      o.speed = static_cast<float>(parse_number(a, value()));
    } else if (a == "--yaw-rate") {
      o.yaw_rate = static_cast<float>(parse_number(a, value()));
    } else if (a == "--noise") {
      o.noise = static_cast<float>(parse_number(a, value()));
    } else if (a == "--dropout") {
      o.dropout = static_cast<float>(parse_number(a, value()));
    } else if (a == "--max-range") {
      o.max_range = static_cast<float>(parse_positive(a, value()));
    } else if (a == "--seconds") {
      o.seconds = parse_positive(a, value());
      if (o.seconds > 3600.0) throw UsageError("--seconds: at most 3600");
    } else if (a == "--point-rate") {
      o.point_rate = parse_positive(a, value());
    } else if (a == "--seed") {
      o.seed = parse_count(a, value());
    } else if (a == "--out") {
      o.out = value();
    } else if (a == "--quiet" || a == "-q") {
      o.quiet = true;
    } else {
      throw UsageError("unknown option '" + a + "' (see streamclust simulate --help)");
    }
  }
  if (o.out.empty()) throw UsageError("missing --out FILE (.csv or .pcd)");
  if ((o.sensor == "synthetic") != (o.scene == "room")) {
    throw UsageError("--sensor synthetic goes with --scene room, and only with it");
  }
  const auto ends_with = [&](const char* ext) {
    const std::string e(ext);
    return o.out.size() >= e.size() && o.out.compare(o.out.size() - e.size(), e.size(), e) == 0;
  };
  if (!ends_with(".csv") && !ends_with(".pcd")) throw UsageError("--out: expected a .csv or .pcd file name");
  return o;
}

template <class Sensor>
void simulate_into(Sensor sensor, const SimulateOptions& o, std::vector<io::Record>& records) {
  sim::Scene scene = o.scene == "forest"   ? sim::forest_scene(o.seed)
                     : o.scene == "street" ? sim::street_scene(o.seed)
                                           : sim::office_scene(o.seed);
  typename sim::Simulator<Sensor>::Params p;
  p.range_noise = o.noise;
  p.dropout = o.dropout;
  p.max_range = o.max_range;
  p.velocity = Eigen::Vector3f(o.speed, 0.0f, 0.0f);
  p.yaw_rate = o.yaw_rate;
  p.seed = o.seed;
  sim::Simulator<Sensor> simulator(std::move(sensor), std::move(scene), p);
  while (simulator.time() < o.seconds) {
    const sim::SimPoint s = simulator.next();
    records.push_back(io::Record{s.x, s.y, s.z, s.intensity, s.t, s.instance});
  }
}

inline int run_simulate(const SimulateOptions& o, std::ostream& out) {
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
