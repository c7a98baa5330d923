// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust simulate`: writes a simulated stream with its ground truth
/// (the `label` column/field is the id of the object hit: 0 for structure).
/// Sensors and scenes: the built-in synthetic Mid-360-like pattern in a room
/// (`--sensor synthetic --scene room`) until the scan simulator adds more.

#include "cli/options.hpp"

#include <streamclust/io/writers.hpp>
#include <streamclust/sim/synthetic_stream.hpp>

#include <ostream>
#include <string>
#include <vector>

namespace streamclust::cli {

struct SimulateOptions {
  std::string sensor = "synthetic";
  std::string scene = "room";
  double seconds = 1.0;
  double point_rate = 200000.0;
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
      if (o.sensor != "synthetic") throw UsageError("--sensor: expected synthetic, got '" + o.sensor + "'");
    } else if (a == "--scene") {
      o.scene = value();
      if (o.scene != "room") throw UsageError("--scene: expected room, got '" + o.scene + "'");
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
  const auto ends_with = [&](const char* ext) {
    const std::string e(ext);
    return o.out.size() >= e.size() && o.out.compare(o.out.size() - e.size(), e.size(), e) == 0;
  };
  if (!ends_with(".csv") && !ends_with(".pcd")) throw UsageError("--out: expected a .csv or .pcd file name");
  return o;
}

inline int run_simulate(const SimulateOptions& o, std::ostream& out) {
  SyntheticStream::Params p;
  p.point_rate = o.point_rate;
  p.seed = o.seed;
  SyntheticStream stream(p);
  std::vector<io::Record> records;
  while (stream.time() < o.seconds) {
    const SyntheticPoint s = stream.next();
    records.push_back(io::Record{s.x, s.y, s.z, s.intensity, s.t, s.object});
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
