// SPDX-License-Identifier: MIT
// `streamclust evaluate --objects`: the objects preset and its three peers
// on one simulated scenario, every retrieval scored with eval::object_metrics.

#include "cli/evaluate_objects.hpp"

#include "cli/euclidean_clusters.hpp"
#include "cli/objects_engine.hpp"
#include "cli/objects_sensors.hpp"
#include "cli/stopwatch.hpp"
#include "cli/structure_planes.hpp"

#include <streamclust/eval/object_metrics.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/objects_presets.hpp>
#include <streamclust/percentiles.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/retrieval_schedule.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

namespace streamclust::cli {
namespace {

/// Fills `stream` like simulate_stream, with the sensor `height` above the
/// ground at the start (the simulator keeps it over a terrain).
template <class Sensor>
void simulate_at_height(Sensor sensor, const SimulateOptions& o, float height, SimulatedStream& stream) {
  typename sim::Simulator<Sensor>::Params params = simulator_params<Sensor>(o);
  params.start_position = Eigen::Vector3f(0.0f, 0.0f, height);
  sim::Simulator<Sensor> simulator(std::move(sensor), sim::make_scene(o.scene, o.seed), params);
  while (simulator.time() < o.seconds) {
    const sim::SimPoint s = simulator.next();
    stream.records.push_back(io::Record{s.x, s.y, s.z, s.intensity, s.t, s.instance});
    stream.classes.push_back(s.surface);
  }
  if (stream.records.empty()) throw UsageError("the scenario returned no point (--duration)");
  stream.trajectory = simulator.trajectory(stream.records.front().t, stream.records.back().t, kTrajectoryRateHz);
}

}  // namespace

SimulatedStream simulate_objects_stream(const SimulateOptions& s, float height) {
  SimulatedStream stream;
  try {
    if (s.sensor == "mid360") {
      simulate_at_height(sim::Mid360Model(sim::Mid360Model::Params{}), s, height, stream);
    } else if (s.sensor == "avia") {
      simulate_at_height(sim::AviaModel(sim::AviaModel::Params{}), s, height, stream);
    } else if (s.sensor == "mid40") {
      simulate_at_height(sim::RisleyPairModel::mid40(), s, height, stream);
    } else {
      simulate_at_height(sim::RisleyPairModel::mid70(), s, height, stream);
    }
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return stream;
}

namespace {

using Clock = std::chrono::steady_clock;

/// A continuous engine of the evaluation, fed in stretches between
/// retrievals; its labels written over the scored window [lo, hi).
template <class Config>
struct EngineRun {
  StreamClusterer<Config> engine;
  double pending_ms = 0.0;  ///< work since the last retrieval

  explicit EngineRun(const ClustererParams<Config>& params) : engine(params) {}

  void feed(const std::vector<io::Record>& records, std::size_t first, std::size_t last) {
    const auto t0 = Clock::now();
    for (std::size_t i = first; i < last; ++i) engine.insert(records[i], records[i].t);
    pending_ms += ms_since(t0);
  }
  const Clustering& retrieve(double time) {
    const auto t0 = Clock::now();
    engine.advance_to(time);
    const Clustering& result = engine.retrieve();
    pending_ms += ms_since(t0);
    return result;
  }
  /// The work since the previous call [ms].
  double take_cost() {
    const double c = pending_ms;
    pending_ms = 0.0;
    return c;
  }
};

/// Predicted labels of the window [lo, lo + n) from an engine's result:
/// cluster ids, -2 / -3 / -4 for ground / ceiling / wall, -1 for points the
/// engine does not hold. Returns the result's points outside the window.
std::size_t labels_from(const Clustering& result, std::size_t lo, std::vector<std::int64_t>& predicted) {
  std::size_t outside = 0;
  const std::size_t n = predicted.size();
  const auto put = [&](std::uint64_t index, std::int64_t label) {
    if (index < lo || index - lo >= n) {
      ++outside;
      return;
    }
    predicted[static_cast<std::size_t>(index - lo)] = label;
  };
  for (const PointLabel& p : result.points) put(p.stream_index, static_cast<std::int64_t>(p.label));
  for (const StructurePoint& s : result.structure) {
    put(s.stream_index, s.surface == SurfaceClass::ceiling ? eval::kClassedCeiling
                        : s.surface == SurfaceClass::wall  ? eval::kClassedWall
                                                           : eval::kClassedGround);
  }
  return outside;
}

/// The name of a swept peer: "euclidean@0.3", "frame@0.2/0.3"; the plain
/// name when its settings are not swept.
std::string peer_name(const char* method, bool swept, float plane_distance, float distance) {
  if (!swept) return method;
  char name[64];
  if (plane_distance > 0.0f) {
    std::snprintf(name, sizeof name, "%s@%g/%g", method, static_cast<double>(plane_distance), static_cast<double>(distance));
  } else {
    std::snprintf(name, sizeof name, "%s@%g", method, static_cast<double>(distance));
  }
  return name;
}

void summarize_objects_method(ObjectsMethodResult& m) {
  m.cost_median_ms = percentile(m.cost_ms, 50.0);
  m.cost_p99_ms = percentile(m.cost_ms, 99.0);
}

}  // namespace

ObjectsEvaluation evaluate_objects(const EvaluateObjectsOptions& o) {
  const ObjectsSensor& sensor = objects_sensor(o.scenario.sensor);
  ObjectsEvaluation e;
  e.height = effective_height(o);
  const SimulatedStream stream = simulate_objects_stream(o.scenario, e.height);
  const std::vector<io::Record>& records = stream.records;
  e.records = records.size();
  for (const SurfaceClass c : stream.classes) {
    e.scene_has_ceiling = e.scene_has_ceiling || c == SurfaceClass::ceiling;
    e.scene_has_wall = e.scene_has_wall || c == SurfaceClass::wall;
  }

  const SimulateOptions& s = o.scenario;
  const Pose mount = mount_from_roll_pitch_yaw_deg(s.mount_roll_deg, s.mount_pitch_deg, s.mount_yaw_deg);

  // The objects engine: the vehicle's trajectory (the simulator's sensor
  // poses without the mount) and the mount, or the mount alone.
  ObjectsSetup setup;
  setup.mount = mount;
  setup.sensor_height = e.height;
  setup.window_seconds = o.window_seconds;
  if (o.poses) setup.trajectory = vehicle_trajectory(stream.trajectory, mount);
  // Its linkage slot is the chosen linkage (the preset's by default).
  std::unique_ptr<ObjectsEngine> objects;
  // The paper's preset, sensor frame.
  std::optional<EngineRun<CArcFastConfig>> carc;
  try {
    ClustererParams<ObjectsConfig> objects_parameters = objects_params(*sensor.facts, setup);
    objects_parameters.ground.detect_walls = o.walls;
    if (o.run_objects) objects = make_objects_engine(o.linkage, o.linkage_params, objects_parameters, o.verify);
    CArcParams paper;
    paper.theta_deg = sensor.carc_theta_deg;
    paper.field_of_view = field_of_view_of(*sensor.facts);
    paper.window_seconds = o.window_seconds;
    if (o.run_carc) carc.emplace(to_clusterer_params<CArcFastConfig>(paper));
  } catch (const std::invalid_argument& ex) {
    throw UsageError(ex.what());
  }
  // The peers: one Euclidean clustering per radius; the frame pipeline's
  // structure stage per plane distance, its clustering per radius.
  std::vector<EuclideanClustering> euclidean, frame_clustering;
  std::vector<ObjectsMethodResult> r_euclidean, r_frame;  // r_frame: plane distance major
  const bool euclidean_swept = o.euclidean_distances.size() > 1;
  const bool frame_swept = o.frame_distances.size() > 1 || o.plane_distances.size() > 1;
  if (o.run_euclidean) {
    for (const float d : o.euclidean_distances) {
      euclidean.emplace_back(d);
      r_euclidean.push_back(ObjectsMethodResult{peer_name("euclidean", euclidean_swept, 0.0f, d), d, 0.0f, {}, {}, {}, 0.0, 0.0});
    }
  }
  if (o.run_frame) {
    for (const float d : o.frame_distances) frame_clustering.emplace_back(d);
    for (const float plane : o.plane_distances) {
      for (const float d : o.frame_distances) {
        r_frame.push_back(ObjectsMethodResult{peer_name("frame", frame_swept, plane, d), d, plane, {}, {}, {}, 0.0, 0.0});
      }
    }
  }
  const bool frame_ceiling = o.frame_ceiling == "on" || (o.frame_ceiling == "auto" && s.scene == "office");
  StructurePlaneChecks plane_checks;
  plane_checks.sensor_height = e.height;
  plane_checks.max_tilt_deg = o.frame_max_tilt_deg;
  plane_checks.height_tolerance = o.frame_height_tolerance;
  // Gravity in the sensor frame: from the simulator's sensor poses (the
  // vehicle's attitude and the mount) with poses, else the mount alone.
  PoseTrajectory gravity_poses(stream.trajectory);
  const auto up_at = [&](double time) -> Eigen::Vector3f {
    Eigen::Quaterniond attitude = mount.rotation;
    if (o.poses) {
      if (const std::optional<Pose> pose = gravity_poses.at(time)) attitude = pose->rotation;
    }
    return (attitude.conjugate() * Eigen::Vector3d::UnitZ()).cast<float>().normalized();
  };

  ObjectsMethodResult r_objects{"objects", 0.0f, 0.0f, {}, {}, {}, 0.0, 0.0},
      r_carc{"carc", 0.0f, 0.0f, {}, {}, {}, 0.0, 0.0};
  eval::MetricOptions metric_options;
  metric_options.min_points = o.min_points;

  // Heights above the scene's ground of the object points (diagnostics):
  // world position from the simulator's sensor poses.
  std::vector<float> heights(records.size(), 0.0f);
  if (o.run_objects) {
    const sim::Scene scene = sim::make_scene(s.scene, s.seed);
    PoseTrajectory sensor_poses(stream.trajectory);
    for (std::size_t i = 0; i < records.size(); ++i) {
      if (records[i].label <= 0) continue;
      const std::optional<Pose> pose = sensor_poses.at(records[i].t);
      if (!pose) continue;
      const Eigen::Vector3d w = *pose * Eigen::Vector3d(records[i].x, records[i].y, records[i].z);
      const std::optional<float> ground =
          scene.ground_height(static_cast<float>(w.x()), static_cast<float>(w.y()));
      heights[i] = static_cast<float>(w.z()) - ground.value_or(0.0f);
    }
  }

  std::vector<std::int64_t> truth, predicted, planes;
  std::vector<SurfaceClass> classes;
  std::vector<Eigen::Vector3f> points, rest;
  std::vector<float> ranges;
  std::vector<std::size_t> rest_index;
  RetrievalSchedule schedule(o.rate_hz);
  const double first = records.front().t;
  std::size_t fed = 0, lo = 0;
  double window_points = 0.0;
  bool first_evaluated = true;

  const auto retrieve = [&](double time, std::size_t hi) {
    if (objects) objects->feed(records, fed, hi);
    if (carc) carc->feed(records, fed, hi);
    fed = hi;
    const Clustering* objects_result = objects ? &objects->retrieve(time) : nullptr;
    const Clustering* carc_result = carc ? &carc->retrieve(time) : nullptr;
    const double objects_cost = objects ? objects->take_cost() : 0.0;
    const double carc_cost = carc ? carc->take_cost() : 0.0;
    // The window at `time`: the points no more than T_B older (TimeWindow's rule).
    while (lo < hi && time - records[lo].t > o.window_seconds) ++lo;
    // Scored from the first retrieval at which the first window is full and
    // no engine still buffers its first window (the objects engine's starts
    // at its first object point).
    if (time - first < o.window_seconds - 1e-9) return;
    if ((objects && objects->calibrating()) || (carc && carc->engine.calibrating())) return;
    const std::size_t n = hi - lo;
    truth.resize(n);
    classes.resize(n);
    points.resize(n);
    ranges.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const io::Record& rec = records[lo + k];
      truth[k] = rec.label;
      classes[k] = stream.classes[lo + k];
      points[k] = Eigen::Vector3f(rec.x, rec.y, rec.z);
      ranges[k] = points[k].norm();
    }
    ++e.retrievals;
    window_points += static_cast<double>(n);
    // Cycle costs skip the first scored retrieval: it holds the grid's calibration.
    const bool timed = !first_evaluated;
    first_evaluated = false;
    const auto score = [&](ObjectsMethodResult& m, double cost_ms) {
      m.average.add(eval::object_metrics(truth, classes, predicted, metric_options));
      m.range_coverage.add(truth, predicted, ranges);
      if (timed) m.cost_ms.push_back(cost_ms);
    };
    if (objects) {
      predicted.assign(n, eval::kUnlabelled);
      const std::size_t outside = labels_from(*objects_result, lo, predicted);
      score(r_objects, objects_cost);
      StructureDiagnostics& d = e.structure;
      for (std::size_t k = 0; k < n; ++k) {
        const bool lost = eval::is_classed_structure(predicted[k]);
        if (truth[k] > 0) {
          const std::size_t bin = StructureDiagnostics::bin_of(heights[lo + k]);
          ++d.object_points[bin];
          d.object_points_lost[bin] += lost ? 1u : 0u;
        }
        const auto c = static_cast<std::size_t>(classes[k]);
        if (predicted[k] == eval::kClassedGround) ++d.classed_ground[c];
        if (predicted[k] == eval::kClassedCeiling) ++d.classed_ceiling[c];
        if (predicted[k] == eval::kClassedWall) ++d.classed_wall[c];
      }
      if (o.verify) {
        ++e.verified;
        const std::string mismatch = objects->verify(records, outside);
        if (!mismatch.empty()) {
          char at[48];
          std::snprintf(at, sizeof at, "retrieval at %.3f s: ", time);
          e.mismatches.push_back(at + mismatch);
        }
      }
    }
    if (carc) {
      predicted.assign(n, eval::kUnlabelled);
      labels_from(*carc_result, lo, predicted);
      score(r_carc, carc_cost);
    }
    for (std::size_t m = 0; m < euclidean.size(); ++m) {
      const auto t0 = Clock::now();
      predicted = euclidean[m].cluster(points);
      score(r_euclidean[m], ms_since(t0));
    }
    if (o.run_frame) {
      plane_checks.up = up_at(time);
      for (std::size_t p = 0; p < o.plane_distances.size(); ++p) {
        const auto t0 = Clock::now();
        classify_structure_planes(points, o.plane_distances[p], o.ransac_iterations, o.scenario.seed, plane_checks,
                                  frame_ceiling, planes);
        rest.clear();
        rest_index.clear();
        for (std::size_t k = 0; k < n; ++k) {
          if (planes[k] != -1) continue;
          rest.push_back(points[k]);
          rest_index.push_back(k);
        }
        const double structure_cost = ms_since(t0);
        for (std::size_t d = 0; d < frame_clustering.size(); ++d) {
          const auto t1 = Clock::now();
          const std::vector<std::int64_t>& labels = frame_clustering[d].cluster(rest);
          predicted = planes;
          for (std::size_t k = 0; k < rest.size(); ++k) predicted[rest_index[k]] = labels[k];
          score(r_frame[p * frame_clustering.size() + d], structure_cost + ms_since(t1));
        }
      }
    }
  };
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (const auto due = schedule.on_record(records[i].t)) retrieve(*due, i);
  }
  if (e.retrievals == 0) throw UsageError("--duration: no retrieval after the first window");
  e.window_points = window_points / static_cast<double>(e.retrievals);
  std::vector<ObjectsMethodResult*> all{&r_objects, &r_carc};
  for (ObjectsMethodResult& m : r_euclidean) all.push_back(&m);
  for (ObjectsMethodResult& m : r_frame) all.push_back(&m);
  for (ObjectsMethodResult* m : all) {
    if (m->average.frames() == 0) continue;
    summarize_objects_method(*m);
    e.methods.push_back(std::move(*m));
  }
  return e;
}

namespace {

Json mean_json(const ObjectsMethodResult& m) {
  const eval::MeanObjectMetrics a = m.average.mean();
  const eval::StrictObjectRates pooled = m.average.pooled_objects();
  return Json{{"ari", a.ari},
              {"correct", a.correct},
              {"over_segmented", a.over_segmented},
              {"under_segmented", a.under_segmented},
              {"missed", a.missed},
              {"objects", a.objects},
              {"object_point_coverage", a.object_point_coverage},
              {"ground_precision", a.ground_precision},
              {"ground_recall", a.ground_recall},
              {"ground_f1", a.ground_f1},
              {"ceiling_precision", a.ceiling_precision},
              {"ceiling_recall", a.ceiling_recall},
              {"ceiling_f1", a.ceiling_f1},
              {"wall_precision", a.wall_precision},
              {"wall_recall", a.wall_recall},
              {"wall_f1", a.wall_f1},
              {"pooled_correct", pooled.correct},
              {"pooled_ground_f1", m.average.pooled_ground().f1},
              {"pooled_ceiling_f1", m.average.pooled_ceiling().f1},
              {"pooled_wall_f1", m.average.pooled_wall().f1},
              {"pooled_object_point_coverage", m.average.pooled_object_point_coverage()}};
}

/// Object-point coverage per range band, pooled over the retrievals:
/// [{"from_m": 0, "to_m": 10, "object_points": N, "kept": K, "coverage": K / N}, ...].
Json range_coverage_json(const eval::RangeCoverage& r) {
  Json bands = Json::array();
  for (std::size_t b = 0; b < eval::RangeCoverage::kBands; ++b) {
    bands.push_back({{"from_m", eval::RangeCoverage::kLowerEdges[b]},
                     {"to_m", b + 1 < eval::RangeCoverage::kBands ? Json(eval::RangeCoverage::kLowerEdges[b + 1])
                                                                  : Json(nullptr)},
                     {"object_points", r.object_points(b)},
                     {"kept", r.kept(b)},
                     {"coverage", r.coverage(b)}});
  }
  return bands;
}

/// A list of floats as a JSON array.
Json floats_json(const std::vector<float>& values) {
  Json list = Json::array();
  for (const float v : values) list.push_back(static_cast<double>(v));
  return list;
}

/// The options of the objects engine's linkage by their JSON key
/// ({"min_distance": 0.2, "range_factor": 0.01}).
Json linkage_parameters_json(const EvaluateObjectsOptions& o) {
  Json parameters = Json::object();
  ToolRegistry::with_policy<Slot::linkage>(o.linkage, [&](auto tag) {
    using Linkage = typename decltype(tag)::type;
    for (const auto& option : registry::PolicyDescriptor<Linkage>::options()) {
      const double v = option.value(o.linkage_params.template get<Linkage>());
      parameters[option.key] = option.integral ? Json(static_cast<std::int64_t>(v)) : Json(v);
    }
  });
  return parameters;
}

}  // namespace

Json objects_evaluation_json(const EvaluateObjectsOptions& o, const ObjectsEvaluation& e) {
  const SimulateOptions& s = o.scenario;
  Json doc;
  doc["scenario"] = {{"sensor", s.sensor},
                     {"scene", s.scene},
                     {"mount", Json::array({s.mount_roll_deg, s.mount_pitch_deg, s.mount_yaw_deg})},
                     {"height", e.height},
                     {"speed", s.speed},
                     {"yaw_rate", s.yaw_rate},
                     {"poses", o.poses},
                     {"seconds", s.seconds},
                     {"seed", s.seed},
                     {"noise", s.noise},
                     {"dropout", s.dropout},
                     {"max_range", s.max_range}};
  doc["settings"] = {{"window_time", o.window_seconds},
                     {"rate", o.rate_hz},
                     {"euclidean_distances", floats_json(o.euclidean_distances)},
                     {"frame_distances", floats_json(o.frame_distances)},
                     {"plane_distances", floats_json(o.plane_distances)},
                     {"frame_ceiling", o.frame_ceiling},
                     {"frame_max_tilt", o.frame_max_tilt_deg},
                     {"frame_height_tolerance", o.frame_height_tolerance},
                     {"ransac_iterations", o.ransac_iterations},
                     {"min_points", o.min_points},
                     {"linkage", o.linkage},
                     {"linkage_parameters", linkage_parameters_json(o)}};
  doc["records"] = e.records;
  doc["retrievals"] = e.retrievals;
  doc["window_points"] = e.window_points;
  doc["scene_has_ceiling"] = e.scene_has_ceiling;
  doc["scene_has_wall"] = e.scene_has_wall;
  if (o.run_objects) {
    const StructureDiagnostics& d = e.structure;
    Json bins = Json::array();
    for (std::size_t b = 0; b < StructureDiagnostics::kHeightBins; ++b) {
      bins.push_back({{"below_m", b + 1 < StructureDiagnostics::kHeightBins ? Json(StructureDiagnostics::kHeightEdges[b])
                                                                           : Json(nullptr)},
                      {"object_points", d.object_points[b]},
                      {"classed_structure", d.object_points_lost[b]}});
    }
    Json ground = Json::object(), ceiling = Json::object(), wall = Json::object();
    for (std::size_t c = 0; c < static_cast<std::size_t>(kSurfaceClassCount); ++c) {
      ground[to_string(static_cast<SurfaceClass>(c))] = d.classed_ground[c];
      ceiling[to_string(static_cast<SurfaceClass>(c))] = d.classed_ceiling[c];
      wall[to_string(static_cast<SurfaceClass>(c))] = d.classed_wall[c];
    }
    doc["objects_structure"] = {{"object_points_by_height", std::move(bins)},
                                {"classed_ground_by_truth", std::move(ground)},
                                {"classed_ceiling_by_truth", std::move(ceiling)},
                                {"classed_wall_by_truth", std::move(wall)}};
  }
  doc["verify"] = o.verify ? Json{{"retrievals", e.verified}, {"mismatches", e.mismatches}} : Json(nullptr);
  Json methods = Json::array();
  for (const ObjectsMethodResult& m : e.methods) {
    Json settings = Json::object();
    if (m.distance > 0.0f) settings["distance"] = static_cast<double>(m.distance);
    if (m.plane_distance > 0.0f) settings["plane_distance"] = static_cast<double>(m.plane_distance);
    methods.push_back({{"name", m.name},
                       {"settings", std::move(settings)},
                       {"retrievals", m.average.frames()},
                       {"object_point_coverage_by_range", range_coverage_json(m.range_coverage)},
                       {"cost_median_ms", m.cost_median_ms},
                       {"cost_p99_ms", m.cost_p99_ms},
                       {"mean", mean_json(m)}});
  }
  doc["methods"] = std::move(methods);
  return doc;
}

void print_objects_evaluation(std::ostream& out, const EvaluateObjectsOptions& o, const ObjectsEvaluation& e) {
  const SimulateOptions& s = o.scenario;
  char line[200];
  std::snprintf(line, sizeof line,
                "streamclust evaluate --objects: sensor %s, scene %s, mount %g,%g,%g deg, height %.2f m, %.3g s, "
                "seed %llu, %zu points",
                s.sensor.c_str(), s.scene.c_str(), s.mount_roll_deg, s.mount_pitch_deg, s.mount_yaw_deg,
                static_cast<double>(e.height), s.seconds, static_cast<unsigned long long>(s.seed), e.records);
  out << line << "\n";
  if (s.speed != 0.0f || s.yaw_rate != 0.0f) {
    std::snprintf(line, sizeof line, "moving %.3g m/s, yaw rate %.3g rad/s; objects engine %s", static_cast<double>(s.speed),
                  static_cast<double>(s.yaw_rate), o.poses ? "with the vehicle's poses" : "with the mount only");
  } else {
    std::snprintf(line, sizeof line, "at rest; objects engine %s", o.poses ? "with the vehicle's poses" : "with the mount only");
  }
  out << line;
  if (o.run_objects) out << ", linkage " << ToolRegistry::describe(Slot::linkage, o.linkage, o.linkage_params);
  out << "\n";
  std::snprintf(line, sizeof line, "T_B %.3g s, retrievals %.3g Hz: %zu scored, %.0f points per window", o.window_seconds,
                o.rate_hz, e.retrievals, e.window_points);
  out << line << "\n\n";
  // A column per method, 11 characters or its name's length + 1.
  const auto column = [](const ObjectsMethodResult& m) { return static_cast<int>(std::max<std::size_t>(11, m.name.size() + 1)); };
  std::snprintf(line, sizeof line, "%-30s", "mean over retrievals");
  out << line;
  for (const ObjectsMethodResult& m : e.methods) {
    std::snprintf(line, sizeof line, "%*s", column(m), m.name.c_str());
    out << line;
  }
  out << "\n";
  struct Row {
    const char* label;
    double eval::MeanObjectMetrics::*field;
  };
  std::vector<Row> rows = {{"ARI (object points)", &eval::MeanObjectMetrics::ari},
                           {"objects correct (strict)", &eval::MeanObjectMetrics::correct},
                           {"objects over-segmented", &eval::MeanObjectMetrics::over_segmented},
                           {"objects under-segmented", &eval::MeanObjectMetrics::under_segmented},
                           {"objects missed", &eval::MeanObjectMetrics::missed},
                           {"object-point coverage", &eval::MeanObjectMetrics::object_point_coverage},
                           {"ground F1", &eval::MeanObjectMetrics::ground_f1}};
  if (e.scene_has_wall) {
    rows.push_back({"wall precision", &eval::MeanObjectMetrics::wall_precision});
    rows.push_back({"wall recall", &eval::MeanObjectMetrics::wall_recall});
  }
  if (e.scene_has_ceiling) rows.push_back({"ceiling F1", &eval::MeanObjectMetrics::ceiling_f1});
  rows.push_back({"objects rated per window", &eval::MeanObjectMetrics::objects});
  for (const Row& r : rows) {
    std::snprintf(line, sizeof line, "%-30s", r.label);
    out << line;
    for (const ObjectsMethodResult& m : e.methods) {
      std::snprintf(line, sizeof line, "%*.3f", column(m), m.average.mean().*(r.field));
      out << line;
    }
    out << "\n";
  }
  for (std::size_t b = 0; b < eval::RangeCoverage::kBands; ++b) {
    if (b + 1 < eval::RangeCoverage::kBands) {
      std::snprintf(line, sizeof line, "coverage %g-%g m (pooled)", eval::RangeCoverage::kLowerEdges[b],
                    eval::RangeCoverage::kLowerEdges[b + 1]);
    } else {
      std::snprintf(line, sizeof line, "coverage >= %g m (pooled)", eval::RangeCoverage::kLowerEdges[b]);
    }
    char label[40];
    std::snprintf(label, sizeof label, "%-30s", line);
    out << label;
    for (const ObjectsMethodResult& m : e.methods) {
      std::snprintf(line, sizeof line, "%*.3f", column(m), m.range_coverage.coverage(b));
      out << line;
    }
    out << "\n";
  }
  for (const bool p99 : {false, true}) {
    std::snprintf(line, sizeof line, "%-30s", p99 ? "cycle cost P99 [ms]" : "cycle cost median [ms]");
    out << line;
    for (const ObjectsMethodResult& m : e.methods) {
      std::snprintf(line, sizeof line, "%*.2f", column(m), p99 ? m.cost_p99_ms : m.cost_median_ms);
      out << line;
    }
    out << "\n";
  }
  if (o.run_objects) {
    const StructureDiagnostics& d = e.structure;
    out << "\nobjects: object points classed structure, by height above the ground:";
    double lower = -1e9;
    const char* separator = " ";
    for (std::size_t b = 0; b < StructureDiagnostics::kHeightBins; ++b) {
      if (d.object_points[b] > 0) {
        out << separator;
        separator = ", ";
        const double rate = static_cast<double>(d.object_points_lost[b]) / static_cast<double>(d.object_points[b]);
        if (b == 0) {
          std::snprintf(line, sizeof line, "<0 m %.3f", rate);
        } else if (b + 1 == StructureDiagnostics::kHeightBins) {
          std::snprintf(line, sizeof line, ">=%g m %.3f", lower, rate);
        } else {
          std::snprintf(line, sizeof line, "%g-%g m %.3f", lower, StructureDiagnostics::kHeightEdges[b], rate);
        }
        out << line;
      }
      if (b < StructureDiagnostics::kHeightBins - 1) lower = StructureDiagnostics::kHeightEdges[b];
    }
    out << "\nobjects: points classed ground / ceiling / wall by truth class (object, ground, wall, ceiling):";
    for (const auto* counts : {&d.classed_ground, &d.classed_ceiling, &d.classed_wall}) {
      out << (counts == &d.classed_ground ? " ground" : counts == &d.classed_ceiling ? "; ceiling" : "; wall");
      for (const std::uint64_t v : *counts) out << ' ' << v;
    }
    out << "\n";
  }
  if (o.verify) {
    if (e.mismatches.empty()) {
      out << "verify: the objects partition equals the batch partition of its object points at all " << e.verified
          << " retrievals\n";
    } else {
      out << "verify: " << e.mismatches.size() << " of " << e.verified << " retrievals differ from the batch\n";
    }
  }
}

int run_evaluate_objects(const EvaluateObjectsOptions& o, std::ostream& out, std::ostream& err) {
  const ObjectsEvaluation e = evaluate_objects(o);
  if (!o.json_path.empty()) write_json_file("--json", o.json_path, objects_evaluation_json(o, e));
  if (!o.quiet) print_objects_evaluation(out, o, e);
  if (!e.mismatches.empty()) {
    for (const std::string& m : e.mismatches) err << "streamclust: verify: " << m << "\n";
    return kMismatch;
  }
  return kOk;
}

}  // namespace streamclust::cli
