// SPDX-License-Identifier: MIT
// `streamclust evaluate --tracks`: the objects tracker, the same boxes into
// the centroid tracker, and the centroid peer on one simulated scenario,
// every retrieval scored against the scene's truth boxes.

#include "cli/evaluate_tracks.hpp"

#include "cli/euclidean_clusters.hpp"
#include "cli/evaluate_objects.hpp"
#include "cli/objects_engine.hpp"
#include "cli/objects_sensors.hpp"
#include "cli/stopwatch.hpp"
#include "cli/structure_planes.hpp"

#include <streamclust/motion/trajectory.hpp>
#include <streamclust/objects_presets.hpp>
#include <streamclust/percentiles.hpp>
#include <streamclust/retrieval_schedule.hpp>
#include <streamclust/tracking/centroid_tracker.hpp>
#include <streamclust/tracking/kalman_tracker.hpp>
#include <streamclust/tracking/tracks_csv.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace streamclust::cli {
namespace {

using Clock = std::chrono::steady_clock;

/// The reported tracks of a tracker (confirmed and coasting; tentative
/// ones are not objects yet) as metric inputs.
std::vector<eval::TrackReport> reports_of(const std::vector<tracking::Track>& tracks) {
  std::vector<eval::TrackReport> out;
  for (const tracking::Track& t : tracks) {
    if (t.state == tracking::TrackState::tentative) continue;
    out.push_back(eval::TrackReport{t.id, eval::Footprint{t.position.head<2>(), t.yaw, t.length, t.width},
                                    t.velocity.head<2>(), t.position.z() - 0.5f * t.height,
                                    t.position.z() + 0.5f * t.height});
  }
  return out;
}

/// One method being scored.
struct MethodRun {
  TracksMethodResult result;
  eval::TrackMetricsAccumulator metrics;
  MethodRun(std::string name, const eval::TrackMetricOptions& options) : metrics(options) { result.name = std::move(name); }
};

/// The peer's observations of one window: clusters of `labels` over
/// `points` (world frame) with at least `min_points` points and no longer
/// than `max_extent`, each as its centroid with its axis-aligned extent.
void centroid_observations(const std::vector<Eigen::Vector3f>& points, const std::vector<std::int64_t>& labels,
                           std::size_t min_points, float max_extent, double time,
                           std::vector<tracking::ObjectObservation>& out) {
  struct Cluster {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e30f), hi = Eigen::Vector3f::Constant(-1e30f);
    std::size_t n = 0;
  };
  std::unordered_map<std::int64_t, Cluster> clusters;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (labels[i] < 0) continue;
    Cluster& c = clusters[labels[i]];
    c.sum += points[i].cast<double>();
    c.lo = c.lo.cwiseMin(points[i]);
    c.hi = c.hi.cwiseMax(points[i]);
    ++c.n;
  }
  out.clear();
  std::vector<std::pair<std::int64_t, const Cluster*>> ordered;
  for (const auto& [label, c] : clusters) ordered.emplace_back(label, &c);
  std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [label, c] : ordered) {
    const Eigen::Vector3f extent = c->hi - c->lo;
    if (c->n < min_points || std::max(extent.x(), extent.y()) > max_extent) continue;
    tracking::ObjectObservation o;
    o.box.center = (c->sum / static_cast<double>(c->n)).cast<float>();
    o.box.length = std::max(extent.x(), extent.y());
    o.box.width = std::min(extent.x(), extent.y());
    o.box.yaw = extent.x() >= extent.y() ? 0.0f : 1.57079633f;
    o.box.height = extent.z();
    o.box.points = c->n;
    o.time = o.time_begin = time;
    out.push_back(o);
  }
}

float effective_height(const EvaluateTracksOptions& o) {
  if (o.height > 0.0f) return o.height;
  const double roll = std::remainder(o.scenario.mount_roll_deg, 360.0);
  return std::abs(roll) > 90.0 ? 2.5f : 1.0f;
}

}  // namespace

TracksEvaluation evaluate_tracks(const EvaluateTracksOptions& o) {
  const ObjectsSensor& sensor = objects_sensor(o.scenario.sensor);
  const SimulateOptions& s = o.scenario;
  TracksEvaluation e;
  e.height = effective_height(o);
  const SimulatedStream stream = simulate_objects_stream(s, e.height);
  const std::vector<io::Record>& records = stream.records;
  e.records = records.size();
  const sim::Scene scene = sim::make_scene(s.scene, s.seed);
  for (const sim::ObjectInfo& info : scene.objects()) e.moving_objects += info.moving ? 1u : 0u;

  // The objects engine with the vehicle's trajectory (the simulator's
  // sensor poses without the mount) and the mount: tracks in the world frame.
  const Pose mount = mount_from_roll_pitch_yaw_deg(s.mount_roll_deg, s.mount_pitch_deg, s.mount_yaw_deg);
  ObjectsSetup setup;
  setup.mount = mount;
  setup.sensor_height = e.height;
  setup.window_seconds = o.window_seconds;
  setup.trajectory = vehicle_trajectory(stream.trajectory, mount);
  std::unique_ptr<ObjectsEngine> objects;
  if (o.run_objects || o.run_objects_centroid) {
    try {
      objects = make_objects_engine(objects_preset_linkage(), objects_linkage_values(),
                                    objects_params(*sensor.facts, setup), false);
    } catch (const std::invalid_argument& ex) {
      throw UsageError(ex.what());
    }
  }
  KalmanTracker kalman;
  CentroidTracker objects_centroid, peer;
  std::vector<MethodRun> runs;
  if (o.run_objects) runs.emplace_back("objects", o.metrics);
  if (o.run_objects_centroid) runs.emplace_back("objects-centroid", o.metrics);
  if (o.run_centroid) runs.emplace_back("centroid", o.metrics);
  const auto run_of = [&](const char* name) -> MethodRun* {
    for (MethodRun& r : runs)
      if (r.result.name == name) return &r;
    return nullptr;
  };
  MethodRun* const r_objects = run_of("objects");
  MethodRun* const r_objects_centroid = run_of("objects-centroid");
  MethodRun* const r_centroid = run_of("centroid");

  // The peer: structure planes on the sensor-frame window (gravity from the
  // sensor's pose), the rest clustered in the world frame.
  EuclideanClustering clustering(o.peer_distance);
  StructurePlaneChecks plane_checks;
  plane_checks.sensor_height = e.height;
  const bool frame_ceiling = o.frame_ceiling == "on" || (o.frame_ceiling == "auto" && s.scene == "office");
  PoseTrajectory sensor_poses(stream.trajectory);  // at(): a cached lookup, not const
  std::vector<Eigen::Vector3f> world(records.size());
  for (std::size_t i = 0; i < records.size(); ++i) {
    const std::optional<Pose> pose = sensor_poses.at(records[i].t);
    const Eigen::Vector3d p(records[i].x, records[i].y, records[i].z);
    world[i] = (pose ? *pose * p : p).cast<float>();
  }

  std::ofstream tracks_file;
  std::string tracks_text;
  if (!o.tracks_path.empty()) {
    tracks_file.open(o.tracks_path, std::ios::binary | std::ios::trunc);
    if (!tracks_file) throw std::runtime_error(o.tracks_path + ": cannot open for writing (--tracks)");
    tracks_text = std::string(tracking::kTracksCsvHeader) + "\n";
  }

  std::vector<Eigen::Vector3f> sensor_points, rest;
  std::vector<std::int64_t> planes;
  std::vector<tracking::ObjectObservation> peer_objects;
  std::vector<eval::TruthObjectState> truth;
  std::unordered_map<std::int64_t, std::size_t> points_of;
  RetrievalSchedule schedule(o.rate_hz);
  const double first = records.front().t;
  std::size_t fed = 0, lo = 0, scored = 0;
  std::uint64_t cycle = 0;
  double first_scored = 0.0, last_scored = 0.0;

  const auto retrieve = [&](double time, std::size_t hi) {
    while (lo < hi && time - records[lo].t > o.window_seconds) ++lo;
    const bool score = time - first >= o.window_seconds - 1e-9;
    // Objects: boxes of the retrieval into both trackers.
    if (objects) {
      objects->feed(records, fed, hi);
      objects->retrieve(time);
      if (!objects->calibrating()) {
        const auto t0 = Clock::now();
        const std::vector<tracking::ObjectObservation>& boxes = objects->boxes();
        const double boxes_ms = ms_since(t0);
        if (r_objects) {
          const auto t1 = Clock::now();
          const std::vector<tracking::Track>& tracks = kalman.update(boxes, time);
          if (score) r_objects->result.cost_ms.push_back(boxes_ms + ms_since(t1));
          if (score && tracks_file.is_open()) tracking::append_track_rows(tracks_text, cycle, {}, time, tracks);
        }
        if (r_objects_centroid) {
          const auto t1 = Clock::now();
          objects_centroid.update(boxes, time);
          if (score) r_objects_centroid->result.cost_ms.push_back(boxes_ms + ms_since(t1));
        }
      }
    }
    fed = hi;
    if (r_centroid) {
      const std::size_t n = hi - lo;
      sensor_points.resize(n);
      for (std::size_t k = 0; k < n; ++k) {
        const io::Record& rec = records[lo + k];
        sensor_points[k] = Eigen::Vector3f(rec.x, rec.y, rec.z);
      }
      Eigen::Quaterniond attitude = mount.rotation;
      if (const std::optional<Pose> pose = sensor_poses.at(time)) attitude = pose->rotation;
      plane_checks.up = (attitude.conjugate() * Eigen::Vector3d::UnitZ()).cast<float>().normalized();
      classify_structure_planes(sensor_points, o.plane_distance, o.ransac_iterations, s.seed, plane_checks,
                                frame_ceiling, planes);
      rest.clear();
      for (std::size_t k = 0; k < n; ++k)
        if (planes[k] == -1) rest.push_back(world[lo + k]);
      const std::vector<std::int64_t>& labels = clustering.cluster(rest);
      const auto t0 = Clock::now();
      centroid_observations(rest, labels, 10, o.peer_max_extent, time, peer_objects);
      peer.update(peer_objects, time);
      if (score) r_centroid->result.cost_ms.push_back(ms_since(t0));
    }
    if (!score || (objects && objects->calibrating())) return;
    if (scored++ == 0) first_scored = time;
    last_scored = time;
    ++cycle;
    // The truth: every object with a point in the window, at the retrieval's time.
    points_of.clear();
    for (std::size_t k = lo; k < hi; ++k)
      if (records[k].label > 0) ++points_of[records[k].label];
    truth.clear();
    for (const auto& [id, count] : points_of) {
      const sim::ObjectState state = scene.object_state(static_cast<int>(id), time);
      eval::TruthObjectState t;
      t.id = id;
      t.box = eval::Footprint{state.box.center.head<2>(), state.box.yaw, state.box.length, state.box.width};
      t.velocity = state.velocity.head<2>();
      t.moving = state.moving;
      t.points = count;
      for (int k = 1; k <= 5 && t.moving; ++k) {  // steady: the same velocity over the window
        const double before = time - o.window_seconds * k / 5.0;
        const Eigen::Vector3f change = scene.object_state(static_cast<int>(id), before).velocity - state.velocity;
        t.steady = t.steady && change.head<2>().norm() <= 0.2f;
      }
      t.bottom = state.box.center.z() - 0.5f * state.box.height;
      t.top = state.box.center.z() + 0.5f * state.box.height;
      truth.push_back(t);
    }
    std::sort(truth.begin(), truth.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
    if (r_objects) r_objects->metrics.add_frame(truth, reports_of(kalman.tracks()));
    if (r_objects_centroid) r_objects_centroid->metrics.add_frame(truth, reports_of(objects_centroid.tracks()));
    if (r_centroid) r_centroid->metrics.add_frame(truth, reports_of(peer.tracks()));
  };
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (const auto due = schedule.on_record(records[i].t)) retrieve(*due, i);
  }
  if (scored == 0) throw UsageError("--duration: no retrieval after the first window");
  if (tracks_file.is_open()) {
    tracks_file << tracks_text;
    tracks_file.close();
    if (!tracks_file) throw std::runtime_error(o.tracks_path + ": write failed (disk full?)");
  }
  e.scored_seconds = last_scored - first_scored + 1.0 / o.rate_hz;
  for (MethodRun& r : runs) {
    TracksMethodResult& m = r.result;
    m.metrics = r.metrics.result();
    m.id_switches_per_object_4s =
        m.metrics.objects > 0 ? static_cast<double>(m.metrics.id_switches) / static_cast<double>(m.metrics.objects) *
                                    (4.0 / e.scored_seconds)
                              : 0.0;
    // The first scored retrieval holds the trackers' start: costs from the second.
    if (!m.cost_ms.empty()) m.cost_ms.erase(m.cost_ms.begin());
    m.cost_median_ms = percentile(m.cost_ms, 50.0);
    m.cost_p99_ms = percentile(m.cost_ms, 99.0);
    e.methods.push_back(std::move(m));
  }
  return e;
}

Json tracks_evaluation_json(const EvaluateTracksOptions& o, const TracksEvaluation& e) {
  const SimulateOptions& s = o.scenario;
  Json methods = Json::array();
  for (const TracksMethodResult& m : e.methods) {
    const eval::TrackMetrics& t = m.metrics;
    methods.push_back({{"method", m.name},
                       {"mota", t.mota},
                       {"motp_m", t.motp},
                       {"idf1", t.idf1},
                       {"id_switches", t.id_switches},
                       {"id_switches_per_object_4s", m.id_switches_per_object_4s},
                       {"recall", t.recall},
                       {"precision", t.precision},
                       {"mean_bev_iou", t.mean_iou},
                       {"velocity_rmse_mps", t.velocity_rmse},
                       {"velocity_samples", t.velocity_samples},
                       {"steady_velocity_rmse_mps", t.steady_velocity_rmse},
                       {"steady_velocity_samples", t.steady_velocity_samples},
                       {"still_share", t.still_share},
                       {"static_samples", t.static_samples},
                       {"objects", t.objects},
                       {"truth", t.truth},
                       {"tracks", t.tracks},
                       {"matches", t.matches},
                       {"misses", t.misses},
                       {"false_positives", t.false_positives},
                       {"frames", t.frames},
                       {"cost_median_ms", m.cost_median_ms},
                       {"cost_p99_ms", m.cost_p99_ms}});
  }
  return Json{{"sensor", s.sensor},
              {"scene", s.scene},
              {"seed", s.seed},
              {"duration_s", s.seconds},
              {"speed_mps", static_cast<double>(s.speed)},
              {"yaw_rate_radps", static_cast<double>(s.yaw_rate)},
              {"mount_deg", Json::array({s.mount_roll_deg, s.mount_pitch_deg, s.mount_yaw_deg})},
              {"height_m", static_cast<double>(e.height)},
              {"window_s", o.window_seconds},
              {"rate_hz", o.rate_hz},
              {"match_distance_m", static_cast<double>(o.metrics.match_distance)},
              {"min_points", o.metrics.min_points},
              {"still_speed_mps", static_cast<double>(o.metrics.still_speed)},
              {"peer_distance_m", static_cast<double>(o.peer_distance)},
              {"plane_distance_m", static_cast<double>(o.plane_distance)},
              {"peer_max_extent_m", static_cast<double>(o.peer_max_extent)},
              {"records", e.records},
              {"scored_seconds", e.scored_seconds},
              {"moving_objects", e.moving_objects},
              {"methods", methods}};
}

void print_tracks_evaluation(std::ostream& out, const EvaluateTracksOptions& o, const TracksEvaluation& e) {
  const SimulateOptions& s = o.scenario;
  char line[256];
  std::snprintf(line, sizeof line,
                "tracks: %s, %s, %.1f s, %.2f m/s, yaw rate %.2f rad/s, T_B %.2f s, %.0f Hz; %zu points, "
                "%zu moving objects in the scene\n",
                s.sensor.c_str(), s.scene.c_str(), s.seconds, static_cast<double>(s.speed),
                static_cast<double>(s.yaw_rate), o.window_seconds, o.rate_hz, e.records, e.moving_objects);
  out << line;
  std::snprintf(line, sizeof line,
                "rated: objects with >= %zu points in the window; a match: a track's centre within %.2f m of the "
                "object's footprint\n",
                o.metrics.min_points, static_cast<double>(o.metrics.match_distance));
  out << line;
  std::snprintf(line, sizeof line, "%-30s", "");
  out << line;
  for (const TracksMethodResult& m : e.methods) {
    std::snprintf(line, sizeof line, "%18s", m.name.c_str());
    out << line;
  }
  out << "\n";
  const auto row = [&](const char* label, auto value, const char* format) {
    std::snprintf(line, sizeof line, "%-30s", label);
    out << line;
    for (const TracksMethodResult& m : e.methods) {
      std::snprintf(line, sizeof line, format, value(m));
      out << line;
    }
    out << "\n";
  };
  using M = const TracksMethodResult&;
  row("MOTA", [](M m) { return m.metrics.mota; }, "%18.3f");
  row("MOTP [m]", [](M m) { return m.metrics.motp; }, "%18.3f");
  row("IDF1", [](M m) { return m.metrics.idf1; }, "%18.3f");
  row("id switches", [](M m) { return m.metrics.id_switches; }, "%18zu");
  row("id switches / object / 4 s", [](M m) { return m.id_switches_per_object_4s; }, "%18.3f");
  row("recall", [](M m) { return m.metrics.recall; }, "%18.3f");
  row("precision", [](M m) { return m.metrics.precision; }, "%18.3f");
  row("bird's-eye IoU", [](M m) { return m.metrics.mean_iou; }, "%18.3f");
  row("velocity RMSE, moving [m/s]", [](M m) { return m.metrics.velocity_rmse; }, "%18.3f");
  row("  (matches of moving objects)", [](M m) { return m.metrics.velocity_samples; }, "%18zu");
  row("  in steady motion [m/s]", [](M m) { return m.metrics.steady_velocity_rmse; }, "%18.3f");
  row("  (matches in steady motion)", [](M m) { return m.metrics.steady_velocity_samples; }, "%18zu");
  row("static reported still", [](M m) { return m.metrics.still_share; }, "%18.3f");
  row("  (matches of static objects)", [](M m) { return m.metrics.static_samples; }, "%18zu");
  row("objects rated", [](M m) { return m.metrics.objects; }, "%18zu");
  row("  misses", [](M m) { return m.metrics.misses; }, "%18zu");
  row("  false positives", [](M m) { return m.metrics.false_positives; }, "%18zu");
  row("tracking cost median [ms]", [](M m) { return m.cost_median_ms; }, "%18.3f");
  row("tracking cost P99 [ms]", [](M m) { return m.cost_p99_ms; }, "%18.3f");
}

int run_evaluate_tracks(const EvaluateTracksOptions& o, std::ostream& out) {
  const TracksEvaluation e = evaluate_tracks(o);
  if (!o.json_path.empty()) write_json_file("--json", o.json_path, tracks_evaluation_json(o, e));
  if (!o.quiet) print_tracks_evaluation(out, o, e);
  return kOk;
}

EvaluateTracksOptions parse_evaluate_tracks_options(const std::vector<std::string>& args) {
  EvaluateTracksOptions o;
  o.scenario.seconds = 4.0;
  const auto bounded = [](const std::string& option, const std::string& text, float limit) {
    const float v = parse_positive_float(option, text);
    if (v > limit) throw UsageError(option + ": expected (0, " + std::to_string(limit) + "], got " + text);
    return v;
  };
  for (ArgCursor c(args); !c.done(); c.next()) {
    const std::string& a = c.option();
    if (a == "--velocity") {
      o.scenario.speed = static_cast<float>(parse_number(a, c.value()));
      continue;
    }
    if (a == "--burst" || a == "--burst-speed" || a == "--burst-yaw-rate" || a == "--point-rate") {
      throw UsageError(a + ": not an option of evaluate --tracks (see streamclust evaluate --tracks --help)");
    }
    if (parse_simulation_option(c, o.scenario)) continue;
    if (a == "--height") {
      o.height = bounded(a, c.value(), 100.0f);
    } else if (a == "--method") {
      const std::string v = c.value();
      o.run_objects = o.run_objects_centroid = o.run_centroid = false;
      std::stringstream list(v);
      std::string item;
      bool any = false;
      while (std::getline(list, item, ',')) {
        any = true;
        if (item == "all") {
          o.run_objects = o.run_objects_centroid = o.run_centroid = true;
        } else if (item == "objects") {
          o.run_objects = true;
        } else if (item == "objects-centroid") {
          o.run_objects_centroid = true;
        } else if (item == "centroid") {
          o.run_centroid = true;
        } else {
          throw UsageError("--method: expected all|objects|objects-centroid|centroid (comma-separated), got '" + v +
                           "'");
        }
      }
      if (!any) throw UsageError("--method: expected all|objects|objects-centroid|centroid, got ''");
    } else if (a == "--window-time") {
      o.window_seconds = parse_positive(a, c.value());
      if (o.window_seconds > 60.0) throw UsageError("--window-time: expected (0, 60] s");
    } else if (a == "--rate") {
      o.rate_hz = parse_positive(a, c.value());
      if (o.rate_hz > 1000.0) throw UsageError("--rate: expected (0, 1000] Hz");
    } else if (a == "--min-points") {
      o.metrics.min_points = static_cast<std::size_t>(parse_count(a, c.value()));
      if (o.metrics.min_points < 1 || o.metrics.min_points > 1000000) {
        throw UsageError("--min-points: expected [1, 1000000]");
      }
    } else if (a == "--match-distance") {
      o.metrics.match_distance = bounded(a, c.value(), 100.0f);
    } else if (a == "--still-speed") {
      o.metrics.still_speed = bounded(a, c.value(), 100.0f);
    } else if (a == "--peer-distance") {
      o.peer_distance = bounded(a, c.value(), 100.0f);
    } else if (a == "--plane-distance") {
      o.plane_distance = bounded(a, c.value(), 10.0f);
    } else if (a == "--peer-max-extent") {
      o.peer_max_extent = bounded(a, c.value(), 1000.0f);
    } else if (a == "--frame-ceiling") {
      o.frame_ceiling = c.choice({"auto", "on", "off"});
    } else if (a == "--ransac-iterations") {
      o.ransac_iterations = static_cast<std::size_t>(parse_count(a, c.value()));
      if (o.ransac_iterations < 1 || o.ransac_iterations > 100000) {
        throw UsageError("--ransac-iterations: expected [1, 100000]");
      }
    } else if (a == "--tracks-out") {
      o.tracks_path = c.value();
    } else if (a == "--json") {
      o.json_path = c.value();
    } else if (a == "--quiet" || a == "-q") {
      o.quiet = true;
    } else {
      throw UsageError("unknown option '" + a + "' (see streamclust evaluate --tracks --help)");
    }
  }
  validate_objects_scenario(o.scenario, o.window_seconds, o.rate_hz);
  return o;
}

const char* evaluate_tracks_help() {
  return R"(usage: streamclust evaluate --tracks [scenario options] [method options] [--json FILE] [--tracks-out FILE]

Simulates one scenario with the objects' truth (their boxes and velocities over
time) and scores, at every retrieval of a --rate Hz schedule after the first
window, three trackers (docs/evaluation.md, section Tracks):
  objects           the objects preset with poses, its components' oriented boxes and
                    in-window velocities into the Kalman tracker (the `--tracks` of cluster)
  objects-centroid  the same boxes into the centroid tracker (ids and capture times unused)
  centroid          the peer: per window, RANSAC ground (indoors also ceiling) removal on the
                    sensor-frame points, Euclidean clustering of the rest moved to the world
                    frame by their poses, the centroids of clusters of >= 10 points no longer
                    than --peer-max-extent into a constant-velocity Kalman filter associated
                    by nearest neighbour
Confirmed and coasting tracks are scored. A truth object is rated with at least
--min-points points in the window (fewer: ignored, a track on it is neither right
nor wrong); a track matches an object when its centre lies within
--match-distance of the object's footprint. Prints CLEAR MOT (MOTA, MOTP = mean
centre distance of matches), IDF1, id switches (also per object and 4 s),
recall, precision, mean bird's-eye box IoU of matches, the velocity RMSE of
matched moving objects, the share of matched static objects reported slower
than --still-speed, and each method's tracking cost per retrieval (boxes or
centroids and tracker, median and P99).

scenario (tracks are in the world frame: the simulator's poses go to every method):
  --sensor mid360|avia|mid40|mid70              (default mid360)
  --scene office|forest|street|hills            (default office)
  --mount ROLL,PITCH,YAW  --height M            sensor mount [deg] and height (default 1.0; 2.5 upside down)
  --speed M/S | --velocity M/S  --yaw-rate RAD/S   ego-motion (default 0: at rest)
  --duration S | --seconds S (default 4)  --seed N (default 1)
  --noise M (default 0.02)  --dropout P (default 0)  --max-range M (default 40)
methods:
  --method all|objects|objects-centroid|centroid[,...]  (default all)
  --window-time T_B (default 0.5)  --rate HZ (default 20)
  --peer-distance M (default 0.6)   the peer's Euclidean radius
  --plane-distance M (default 0.1)  the peer's plane inlier tolerance
  --peer-max-extent M (default 10)  the peer drops longer clusters (walls, buildings)
  --frame-ceiling auto|on|off       the peer removes a ceiling plane (auto: the office)
  --ransac-iterations N (default 100)
scoring:
  --min-points N (default 50)  --match-distance M (default 1.0)  --still-speed M/S (default 0.2)
outputs:
  --json FILE  --tracks-out FILE (the objects method's tracks CSV)  --quiet, -q

examples:
  streamclust evaluate --tracks --sensor mid360 --scene office
  streamclust evaluate --tracks --sensor avia --scene street --speed 1.2 --json street.json
)";
}

}  // namespace streamclust::cli
