// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust simulate`: writes a simulated stream with its ground truth
/// (the `label` column/field is the id of the object hit: 0 for structure;
/// optionally a `class` column with the SurfaceClass number) and, beside it,
/// the sensor trajectory it used as a TUM file (200 Hz) and every object's
/// box and velocity over time (objects CSV, 20 Hz: the trackers' truth).
/// Sensors: the Livox models of streamclust::sim (mid360, mid40, mid70, avia)
/// and a 32-beam spinning sensor, on a tilted or upside-down mount if asked;
/// scenes: office, forest, street, hills. The older stand-in (`--sensor
/// synthetic --scene room`) stays available.

#include "cli/options.hpp"

#include <streamclust/io/tum.hpp>
#include <streamclust/io/writers.hpp>
#include <streamclust/motion/pose.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/avia_model.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/sensors/risley_pair_model.hpp>
#include <streamclust/sim/sensors/spinning_model.hpp>
#include <streamclust/sim/simulator.hpp>
#include <streamclust/sim/synthetic_stream.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>
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
  // The sensor's mount on the vehicle (--mount ROLL,PITCH,YAW in degrees).
  double mount_roll_deg = 0.0;   ///< 180: upside down
  double mount_pitch_deg = 0.0;  ///< > 0: forward axis tilted down
  double mount_yaw_deg = 0.0;
  bool mount_given = false;      ///< --mount was on the command line
  std::string out;
  std::string trajectory;        ///< TUM output; "" = `out` without its extension + ".tum"
  std::string objects;           ///< objects truth CSV; "" = `out` without its extension + ".objects.csv"
  double objects_rate = 20.0;    ///< [Hz] rows per object per second in `objects`
  bool class_column = false;     ///< CSV: a `class` column (SurfaceClass number)
  /// --start-time S: whole seconds added to every written time (a recording's
  /// epoch times); the stream itself is simulated from 0.
  io::TimeOrigin start_time;
  bool quiet = false;
};

/// Trajectory poses per second written beside a simulated stream.
inline constexpr double kTrajectoryRateHz = 200.0;

/// The header of the objects truth CSV written beside a simulated stream.
inline constexpr const char* kObjectTruthCsvHeader =
    "time,instance,label,moving,x,y,z,vx,vy,vz,length,width,height,yaw";

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
    bool known = o.scene == "room";
    for (const char* name : sim::kSceneNames) known = known || o.scene == name;
    if (!known) {
      throw UsageError("--scene: expected office|forest|street|hills (or room with --sensor synthetic), got '" +
                       o.scene + "'");
    }
  } else if (a == "--mount") {
    const std::string v = c.value();
    const auto c1 = v.find(',');
    const auto c2 = c1 == std::string::npos ? std::string::npos : v.find(',', c1 + 1);
    if (c2 == std::string::npos || v.find(',', c2 + 1) != std::string::npos) {
      throw UsageError("--mount: expected ROLL,PITCH,YAW in degrees, got '" + v + "'");
    }
    o.mount_roll_deg = parse_number(a, v.substr(0, c1));
    o.mount_pitch_deg = parse_number(a, v.substr(c1 + 1, c2 - c1 - 1));
    o.mount_yaw_deg = parse_number(a, v.substr(c2 + 1));
    for (const double deg : {o.mount_roll_deg, o.mount_pitch_deg, o.mount_yaw_deg}) {
      if (!(deg >= -360.0 && deg <= 360.0)) throw UsageError("--mount: angles must be in [-360, 360] degrees");
    }
    o.mount_given = true;
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
    o.max_range = parse_positive_float(a, c.value());
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
  if (o.sensor == "synthetic" && o.mount_given) {
    throw UsageError("--mount needs a simulated sensor (not --sensor synthetic)");
  }
}

inline SimulateOptions parse_simulate_options(const std::vector<std::string>& args) {
  SimulateOptions o;
  for (ArgCursor c(args); !c.done(); c.next()) {
    const std::string& a = c.option();
    if (parse_simulation_option(c, o)) continue;
    if (a == "--out") {
      o.out = c.value();
    } else if (a == "--trajectory") {
      o.trajectory = c.value();
    } else if (a == "--objects") {
      o.objects = c.value();
    } else if (a == "--objects-rate") {
      o.objects_rate = parse_positive(a, c.value());
      if (o.objects_rate > 1000.0) throw UsageError("--objects-rate: at most 1000 Hz");
    } else if (a == "--class-column") {
      o.class_column = true;
    } else if (a == "--start-time") {
      const std::string v = c.value();
      std::int64_t seconds = 0;
      if (!io::detail::parse_int64(v, seconds) || seconds < 0 || seconds > 4000000000)
        throw UsageError("--start-time: expected whole seconds in [0, 4e9] (Unix time), got '" + v + "'");
      o.start_time = io::TimeOrigin{seconds};
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
  if (o.class_column && !ends_with(".csv")) {
    throw UsageError("--class-column: only the CSV output has it (the PCD writer has a fixed set of fields)");
  }
  if (o.class_column && o.sensor == "synthetic") {
    throw UsageError("--class-column needs a simulated sensor (the synthetic stand-in has no surface classes)");
  }
  if (o.trajectory.empty()) o.trajectory = o.out.substr(0, o.out.size() - 4) + ".tum";
  if (o.trajectory == o.out) throw UsageError("--trajectory: must differ from --out");
  if (o.sensor == "synthetic" && !o.objects.empty()) {
    throw UsageError("--objects needs a simulated scene (the synthetic stand-in has no object trajectories)");
  }
  if (o.objects.empty() && o.sensor != "synthetic") o.objects = o.out.substr(0, o.out.size() - 4) + ".objects.csv";
  if (o.objects == o.out || o.objects == o.trajectory) throw UsageError("--objects: must differ from --out and --trajectory");
  return o;
}

/// The simulator parameters of a scenario (noise, dropout, range, ego-motion
/// with its optional burst, mount, seed).
template <class Sensor>
typename sim::Simulator<Sensor>::Params simulator_params(const SimulateOptions& o) {
  typename sim::Simulator<Sensor>::Params p;
  p.range_noise = o.noise;
  p.dropout = o.dropout;
  p.max_range = o.max_range;
  p.velocity = Eigen::Vector3f(o.speed, 0.0f, 0.0f);
  p.yaw_rate = o.yaw_rate;
  p.seed = o.seed;
  p.mount = mount_from_roll_pitch_yaw_deg(o.mount_roll_deg, o.mount_pitch_deg, o.mount_yaw_deg);
  if (o.burst_length > 0.0) {
    p.motion_profile.push_back(
        sim::MotionSegment{o.burst_start, Eigen::Vector3f(o.burst_speed, 0.0f, 0.0f), o.burst_yaw_rate});
    p.motion_profile.push_back(
        sim::MotionSegment{o.burst_start + o.burst_length, Eigen::Vector3f(o.speed, 0.0f, 0.0f), o.yaw_rate});
  }
  return p;
}

/// A simulated stream: the points (ground-truth instance id in `label`),
/// their surface classes (one per record; `object` throughout for the
/// synthetic stand-in, which has none) and the sensor trajectory over the
/// stream's span (first to last point time, both included, at
/// kTrajectoryRateHz; world from sensor).
struct SimulatedStream {
  std::vector<io::Record> records;
  std::vector<SurfaceClass> classes;
  std::vector<StampedPose> trajectory;
};

template <class Sensor>
void simulate_into(Sensor sensor, const SimulateOptions& o, SimulatedStream& stream) {
  sim::Simulator<Sensor> simulator(std::move(sensor), sim::make_scene(o.scene, o.seed), simulator_params<Sensor>(o));
  while (simulator.time() < o.seconds) {
    const sim::SimPoint s = simulator.next();
    stream.records.push_back(io::Record{s.x, s.y, s.z, s.intensity, s.t, s.instance});
    stream.classes.push_back(s.surface);
  }
  const double t0 = stream.records.empty() ? 0.0 : stream.records.front().t;
  const double t1 = stream.records.empty() ? 0.0 : stream.records.back().t;
  stream.trajectory = simulator.trajectory(t0, t1, kTrajectoryRateHz);
}

/// The whole simulated stream of a scenario, in firing order, with its
/// classes and trajectory. Bad simulator parameters become a UsageError.
inline SimulatedStream simulate_stream(const SimulateOptions& o) {
  SimulatedStream stream;
  try {
    if (o.sensor == "synthetic") {
      SyntheticStream::Params p;
      p.point_rate = o.point_rate;
      p.seed = o.seed;
      SyntheticStream synthetic(p);
      while (synthetic.time() < o.seconds) {
        const SyntheticPoint s = synthetic.next();
        stream.records.push_back(io::Record{s.x, s.y, s.z, s.intensity, s.t, s.object});
      }
      stream.classes.assign(stream.records.size(), SurfaceClass::object);
      // A sensor at rest, sensor_height above the floor.
      const Pose fixed{Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.0, 0.0, static_cast<double>(p.sensor_height))};
      const double t1 = stream.records.empty() ? 0.0 : stream.records.back().t;
      for (std::uint64_t k = 0;; ++k) {
        const double t = static_cast<double>(k) / kTrajectoryRateHz;
        if (!(t < t1 - 1e-9)) break;
        stream.trajectory.push_back(StampedPose{t, fixed});
      }
      stream.trajectory.push_back(StampedPose{t1, fixed});
    } else if (o.sensor == "mid360") {
      simulate_into(sim::Mid360Model(sim::Mid360Model::Params{}), o, stream);
    } else if (o.sensor == "mid40") {
      simulate_into(sim::RisleyPairModel::mid40(), o, stream);
    } else if (o.sensor == "mid70") {
      simulate_into(sim::RisleyPairModel::mid70(), o, stream);
    } else if (o.sensor == "avia") {
      simulate_into(sim::AviaModel(sim::AviaModel::Params{}), o, stream);
    } else {
      simulate_into(sim::SpinningModel(sim::SpinningModel::Params{}), o, stream);
    }
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return stream;
}

/// The points of simulate_stream alone (ground-truth instance id in `label`).
inline std::vector<io::Record> simulate_records(const SimulateOptions& o) { return simulate_stream(o).records; }

/// CSV `x,y,z,intensity,t,label,class`: the io writer's columns and number
/// format plus the SurfaceClass number of each record.
inline void write_csv_with_classes(const std::string& path, const std::vector<io::Record>& records,
                                   const std::vector<SurfaceClass>& classes, io::TimeOrigin origin) {
  if (classes.size() != records.size()) throw std::invalid_argument(path + ": one class per record expected");
  io::detail::OutFile file(path);
  std::string s = "x,y,z,intensity,t,label,class\n";
  for (std::size_t i = 0; i < records.size(); ++i) {
    io::detail::append_point_fields(s, records[i], ',', origin);
    s += std::to_string(records[i].label);
    s += ',';
    s += std::to_string(static_cast<int>(classes[i]));
    s += '\n';
    if (s.size() > (1u << 16)) {
      file.write(s);
      s.clear();
    }
  }
  file.write(s);
  file.close();
}

/// Writes `poses` as a TUM trajectory file, times from `origin` (throws
/// std::runtime_error naming the file when it cannot be written).
inline void write_trajectory(const std::string& path, const std::vector<StampedPose>& poses, io::TimeOrigin origin) {
  std::vector<io::TumRecord> rows;
  rows.reserve(poses.size());
  for (const StampedPose& p : poses) {
    const Eigen::Quaterniond& q = p.pose.rotation;
    const Eigen::Vector3d& x = p.pose.translation;
    rows.push_back(io::TumRecord{p.time, x.x(), x.y(), x.z(), q.x(), q.y(), q.z(), q.w()});
  }
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) throw std::runtime_error(path + ": cannot open for writing");
  io::write_tum(file, rows, origin);
  file.close();
  if (!file) throw std::runtime_error(path + ": write failed (disk full?)");
}

/// Writes every object of `scene` at times t0, t0 + 1 / rate, ... up to t1
/// (included) as kObjectTruthCsvHeader rows, world frame (the trajectory's),
/// times from `origin`: box centre [m], velocity [m/s], length, width,
/// height [m], yaw [rad], moving 0/1. Throws std::runtime_error naming the
/// file when it cannot be written. O(samples x objects).
inline void write_object_truth(const std::string& path, const sim::Scene& scene, double t0, double t1, double rate,
                               io::TimeOrigin origin) {
  io::detail::OutFile file(path);
  std::string s = kObjectTruthCsvHeader;
  s += '\n';
  const auto number = [&s](float v) {
    io::detail::append_number(s, v);
    s += ',';
  };
  for (std::uint64_t k = 0;; ++k) {
    double t = t0 + static_cast<double>(k) / rate;
    if (t > t1 + 1e-9) break;
    t = std::min(t, t1);
    for (const sim::ObjectInfo& info : scene.objects()) {
      const sim::ObjectState state = scene.object_state(info.instance, t);
      io::append_time(s, origin, t);
      s += ',';
      s += std::to_string(info.instance);
      s += ',';
      s += info.label;
      s += state.moving ? ",1," : ",0,";
      for (int i = 0; i < 3; ++i) number(state.box.center[i]);
      for (int i = 0; i < 3; ++i) number(state.velocity[i]);
      number(state.box.length);
      number(state.box.width);
      number(state.box.height);
      io::detail::append_number(s, state.box.yaw);
      s += '\n';
    }
    if (s.size() > (1u << 16)) {
      file.write(s);
      s.clear();
    }
  }
  file.write(s);
  file.close();
}

inline int run_simulate(const SimulateOptions& o, std::ostream& out) {
  const SimulatedStream stream = simulate_stream(o);
  const bool pcd = o.out.size() >= 4 && o.out.compare(o.out.size() - 4, 4, ".pcd") == 0;
  if (pcd) {
    io::write_pcd(o.out, stream.records, {}, "binary", o.start_time);
  } else if (o.class_column) {
    write_csv_with_classes(o.out, stream.records, stream.classes, o.start_time);
  } else {
    io::write_csv_points(o.out, stream.records, {}, o.start_time);
  }
  write_trajectory(o.trajectory, stream.trajectory, o.start_time);
  if (!o.objects.empty()) {
    const double t0 = stream.trajectory.empty() ? 0.0 : stream.trajectory.front().time;
    const double t1 = stream.trajectory.empty() ? 0.0 : stream.trajectory.back().time;
    write_object_truth(o.objects, sim::make_scene(o.scene, o.seed), t0, t1, o.objects_rate, o.start_time);
  }
  if (!o.quiet) {
    out << "streamclust: simulated " << stream.records.size() << " points (" << o.seconds << " s, sensor "
        << o.sensor << ", scene " << o.scene << ", seed " << o.seed << ") -> " << o.out << ", trajectory -> "
        << o.trajectory;
    if (!o.objects.empty()) out << ", objects -> " << o.objects;
    out << "\n";
  }
  return kOk;
}

}  // namespace streamclust::cli
