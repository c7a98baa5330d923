// SPDX-License-Identifier: MIT
// `streamclust cluster` with structure removal and poses, in-process: the
// objects presets (the same labels as the library's presets), --ground with
// the labels -2/-3 and the report's ground fields, --poses/--mount with
// --verify, the mount and sensor height estimated from the first window (the
// office floor under a level Mid-360; ambiguous planes named as such; the
// ceiling alone, the floor out of view: the mount from it, no height), and
// the usage and input errors.

#include <doctest/doctest.h>

#include "cli/main.hpp"
#include "cli/options.hpp"
#include "cli/run_setup.hpp"

#include <streamclust/io/reader.hpp>
#include <streamclust/io/tum.hpp>
#include <streamclust/objects_presets.hpp>
#include <streamclust/retrieval_schedule.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/simulator.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using streamclust::test::run_cli;
using streamclust::test::slurp;

/// label -> rows of the labels file's last cycle.
std::map<long long, std::size_t> label_histogram(const fs::path& path) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  REQUIRE(line == "cycle,time,index,label");
  std::map<long long, std::size_t> counts;
  while (std::getline(f, line)) {
    std::istringstream s(line);
    std::string cycle, time, index, label;
    std::getline(s, cycle, ',');
    std::getline(s, time, ',');
    std::getline(s, index, ',');
    std::getline(s, label, ',');
    ++counts[std::stoll(label) < 0 ? std::stoll(label) : 0];
  }
  return counts;
}

/// cycle -> stream index -> label of the rows of a labels file written with
/// --cycles all (rejected rows, -1, left out).
using CycleLabels = std::map<std::uint64_t, std::map<std::uint64_t, long long>>;
CycleLabels labels_by_cycle(const fs::path& path) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  REQUIRE(line == "cycle,time,index,label");
  CycleLabels rows;
  while (std::getline(f, line)) {
    std::istringstream s(line);
    std::string cycle, time, index, label;
    std::getline(s, cycle, ',');
    std::getline(s, time, ',');
    std::getline(s, index, ',');
    std::getline(s, label, ',');
    if (std::stoll(label) != -1) rows[std::stoull(cycle)][std::stoull(index)] = std::stoll(label);
  }
  return rows;
}

/// The same rows from the library's objects engine on the records of
/// `input`, retrieved at 20 Hz of stream time as the tool retrieves (its
/// final cycle after the last record left out): objects by component,
/// ground -2, ceiling -3.
CycleLabels library_labels(const fs::path& input, const streamclust::ClustererParams<streamclust::ObjectsConfig>& params) {
  namespace sc = streamclust;
  sc::StreamClusterer<sc::ObjectsConfig> engine(params);
  sc::RetrievalSchedule schedule(20.0);
  auto reader = sc::io::open_reader(input.string());
  std::vector<sc::io::Record> chunk;
  CycleLabels rows;
  std::uint64_t cycle = 0;
  while (reader->read(chunk, 65536) > 0) {
    for (const sc::io::Record& r : chunk) {
      if (const auto due = schedule.on_record(r.t)) {
        engine.advance_to(*due);
        if (!engine.calibrating()) {
          auto& row = rows[cycle++];
          for (const sc::PointLabel& p : engine.retrieve().points) row[p.stream_index] = static_cast<long long>(p.label);
          engine.for_each_structure_point([&](const sc::StructureEntry& e) {
            row[e.stream_index] = e.surface == sc::SurfaceClass::ceiling ? -3 : e.surface == sc::SurfaceClass::wall ? -4 : -2;
          });
        }
      }
      engine.insert(r);
    }
    chunk.clear();
  }
  return rows;
}

/// Simulates `seconds` of a scene into dir/name.csv (and its .tum); a
/// Mid-360 unless `extra` names another sensor.
fs::path simulate(const fs::path& dir, const std::string& name, const std::vector<std::string>& extra, double seconds) {
  std::vector<std::string> args{"simulate", "--sensor", "mid360", "--duration", std::to_string(seconds), "--out",
                                (dir / (name + ".csv")).string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = run_cli(args);
  INFO(r.err);
  REQUIRE(r.code == 0);
  return dir / (name + ".csv");
}

}  // namespace

TEST_CASE("cluster --preset objects-mid360: ground rows -2, ceiling rows -3, verified, ground fields in the report") {
  const streamclust::test::TempDir tmp("cli", "objects");
  const fs::path input = simulate(tmp.dir, "office", {"--scene", "office"}, 0.8);
  const auto r = run_cli({"cluster", input.string(), "--preset", "objects-mid360", "--sensor-height", "1",
                          "--verify", "--labels", (tmp.dir / "labels.csv").string(), "--report",
                          (tmp.dir / "report.json").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto counts = label_histogram(tmp.dir / "labels.csv");
  CHECK(counts.count(-2) == 1);  // ground
  CHECK(counts.count(-3) == 1);  // the office ceiling, seen by the Mid-360
  CHECK(counts.at(0) > 1000);    // object points (labels >= 0)
  const auto doc = nlohmann::json::parse(slurp(tmp.dir / "report.json"));
  CHECK(doc.at("ground").at("sensor_height").get<double>() == doctest::Approx(1.0));
  CHECK_FALSE(doc.at("ground").at("sensor_height_estimated").get<bool>());
  const auto& last = doc.at("cycles").back();
  CHECK(last.at("structure_size").get<std::size_t>() > 1000);
  CHECK(last.at("latency_us").at("ground").get<double>() > 0.0);
  CHECK(last.at("latency_us").at("ground").get<double>() < last.at("latency_us").at("total").get<double>());
}

TEST_CASE("cluster --preset objects*: with a mount and a height, the labels of the library's preset" *
          doctest::test_suite("slow")) {
  namespace sc = streamclust;
  struct Case {
    const char* preset;
    std::vector<std::string> scenario;  // simulate's options
    std::array<double, 3> mount_deg;    // roll, pitch, yaw
    sc::SphericalProjection::Params sensor_fov;
  };
  const std::vector<Case> cases{
      {"objects-mid360", {"--scene", "office"}, {0.0, 0.0, 0.0}, sc::field_of_view_of(sc::livox_mid360)},
      {"objects-mid360", {"--scene", "street", "--mount", "0,15,0"}, {0.0, 15.0, 0.0}, sc::field_of_view_of(sc::livox_mid360)},
      {"objects", {"--scene", "office"}, {0.0, 0.0, 0.0}, sc::SphericalProjection::Params{}},
      {"objects-avia", {"--sensor", "avia", "--scene", "office", "--mount", "0,10,0"}, {0.0, 10.0, 0.0},
       sc::field_of_view_of(sc::livox_avia)},
  };
  const streamclust::test::TempDir tmp("cli", "preset_labels");
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    CAPTURE(c.preset);
    CAPTURE(k);
    const fs::path input = simulate(tmp.dir, "scene" + std::to_string(k), c.scenario, 0.8);
    const std::string mount = std::to_string(c.mount_deg[0]) + "," + std::to_string(c.mount_deg[1]) + "," +
                              std::to_string(c.mount_deg[2]);
    const fs::path labels = tmp.dir / ("labels" + std::to_string(k) + ".csv");
    const auto r = run_cli({"cluster", input.string(), "--preset", c.preset, "--mount", mount, "--sensor-height", "1",
                            "--cycles", "all", "--labels", labels.string(), "--quiet"});
    INFO(r.err);
    REQUIRE(r.code == 0);
    const CycleLabels tool = labels_by_cycle(labels);

    sc::ObjectsSetup setup;
    setup.mount = sc::mount_from_roll_pitch_yaw_deg(c.mount_deg[0], c.mount_deg[1], c.mount_deg[2]);
    setup.sensor_height = 1.0f;
    const CycleLabels library = library_labels(input, sc::objects_params(c.sensor_fov, setup));
    REQUIRE(library.size() >= 5);
    std::size_t ground = 0;
    for (const auto& entry : library) {  // not a structured binding: CAPTURE takes it into a lambda
      const auto cycle = entry.first;
      CAPTURE(cycle);
      REQUIRE(tool.count(cycle) == 1);
      CHECK(tool.at(cycle) == entry.second);
      for (const auto& row : entry.second) ground += row.second == -2 ? 1 : 0;
    }
    CHECK(ground > 1000);  // the structure removal ran
  }
}

TEST_CASE("cluster --ground without a mount or height estimates both from the first window") {
  const streamclust::test::TempDir tmp("cli", "estimate");
  const fs::path input = simulate(tmp.dir, "pitched", {"--scene", "street", "--mount", "0,20,0"}, 0.7);
  const auto r = run_cli({"cluster", input.string(), "--preset", "objects-mid360", "--verify", "--report",
                          (tmp.dir / "report.json").string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("ground of the first window") != std::string::npos);
  const auto doc = nlohmann::json::parse(slurp(tmp.dir / "report.json"));
  const auto& g = doc.at("ground");
  CHECK(g.at("sensor_height_estimated").get<bool>());
  CHECK(g.at("sensor_height").get<double>() == doctest::Approx(1.0).epsilon(0.1));
  CHECK(g.at("estimated_mount").at("pitch_deg").get<double>() == doctest::Approx(20.0).epsilon(0.1));
}

TEST_CASE("cluster --preset objects-mid360, a level Mid-360 1 m up in the office: the floor, not the ceiling") {
  const streamclust::test::TempDir tmp("cli", "office_estimate");
  const fs::path input = simulate(tmp.dir, "office", {"--scene", "office"}, 0.7);
  const auto r = run_cli({"cluster", input.string(), "--preset", "objects-mid360", "--report",
                          (tmp.dir / "report.json").string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("ground of the first window: roll") != std::string::npos);
  const auto doc = nlohmann::json::parse(slurp(tmp.dir / "report.json"));
  const auto& g = doc.at("ground");
  CHECK(g.at("sensor_height_estimated").get<bool>());
  CHECK(g.at("sensor_height").get<double>() == doctest::Approx(1.0).epsilon(0.01));  // was 2.0: the ceiling
  CHECK(std::abs(g.at("estimated_mount").at("roll_deg").get<double>()) < 0.5);       // was 180
  CHECK(std::abs(g.at("estimated_mount").at("pitch_deg").get<double>()) < 0.5);
}

TEST_CASE("cluster --ground, two parallel planes with nothing on them: ambiguous, the tool asks for the mount") {
  const streamclust::test::TempDir tmp("cli", "ambiguous");
  const fs::path input = tmp.dir / "planes.csv";
  {
    // 0.6 s at 20 kHz: a floor 1 m below and a ceiling 2 m above the sensor, discs 2-15 m out, nothing else.
    std::ofstream f(input);
    f << "x,y,z,intensity,t\n";
    for (int i = 0; i < 12000; ++i) {
      const double r = 2.0 + 13.0 * std::fmod(i * 0.6180339887, 1.0), a = i * 2.399963;
      f << r * std::cos(a) << ',' << r * std::sin(a) << ',' << (i % 2 == 0 ? -1.0 : 2.0) << ",50," << i / 20000.0
        << '\n';
    }
  }
  const auto r = run_cli({"cluster", input.string(), "--preset", "objects-mid360", "--report",
                          (tmp.dir / "report.json").string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("the ground of the first window is ambiguous") != std::string::npos);
  CHECK(r.err.find("give --mount and --sensor-height") != std::string::npos);
  CHECK(r.err.find("ground of the first window: roll") == std::string::npos);
  const auto doc = nlohmann::json::parse(slurp(tmp.dir / "report.json"));
  CHECK_FALSE(doc.at("ground").at("sensor_height_estimated").get<bool>());
  CHECK_FALSE(doc.at("ground").contains("estimated_mount"));
}

TEST_CASE("cluster --ground, a level Mid-360 1.5 m up in the office: the ceiling alone, the mount from it, no height") {
  namespace sc = streamclust;
  namespace sim = streamclust::sim;
  // The first 0.5 s: the lowest ray (-7 deg) meets the floor 12 m out, beyond the walls.
  sim::Simulator<sim::Mid360Model>::Params params;
  params.start_position = Eigen::Vector3f(0.0f, 0.0f, 1.5f);
  sim::Simulator<sim::Mid360Model> simulator(sim::Mid360Model{}, sim::make_scene("office", 1), params);
  std::vector<Eigen::Vector3f> window;
  while (simulator.time() < 0.5) {
    const sim::SimPoint p = simulator.next();
    window.emplace_back(p.x, p.y, p.z);
  }
  std::ostringstream err;
  const auto setup = [&](std::vector<std::string> args) {
    args.insert(args.begin(), {"in.csv", "--preset", "objects-mid360"});
    err.str("");
    return sc::cli::make_run_setup(sc::cli::parse_cluster_options(args), false, err, &window);
  };
  const sc::cli::RunSetup estimated = setup({});
  INFO(err.str());
  CHECK(err.str().find("the first window shows a ceiling 1.50 m above the sensor and no floor: level from the "
                       "ceiling (roll ") != std::string::npos);
  CHECK(err.str().find("height unknown (give --sensor-height)") != std::string::npos);
  REQUIRE(estimated.estimate.has_value());
  CHECK(estimated.estimate->status == sc::GroundStatus::floor_out_of_view);
  CHECK(std::abs(estimated.estimate->roll_deg) < 0.5);
  CHECK(std::abs(estimated.estimate->pitch_deg) < 0.5);
  CHECK(estimated.motion.enabled);
  CHECK(estimated.estimated_mount);
  CHECK(estimated.motion.posed.mount.rotation.coeffs() == estimated.estimate->mount.rotation.coeffs());
  CHECK_FALSE(estimated.estimated_height);
  CHECK(estimated.ground.height_map.sensor_height == 0.0f);  // unknown, as without a ground plane
  // A height given is used with the mount from the ceiling; a mount given is used, the height still unknown.
  const sc::cli::RunSetup with_height = setup({"--sensor-height", "1.5"});
  CHECK(err.str().find("and no floor: level from the ceiling") != std::string::npos);
  CHECK(err.str().find("the height given is used") != std::string::npos);
  CHECK(with_height.estimated_mount);
  CHECK(with_height.ground.height_map.sensor_height == 1.5f);
  const sc::cli::RunSetup with_mount = setup({"--mount", "0,0,0"});
  CHECK(err.str().find("and no floor: the mount given is used, height unknown") != std::string::npos);
  CHECK_FALSE(with_mount.estimated_mount);
  CHECK(with_mount.ground.height_map.sensor_height == 0.0f);
}

TEST_CASE("cluster --ground with the orientation known: planes nothing else tells apart, the height from gravity") {
  namespace sc = streamclust;
  // A floor 1.2 m below the sensor and a ceiling 1.8 m above, nothing
  // standing on either: the sensor frame alone cannot tell them apart.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> across(-10.0f, 10.0f);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  std::vector<Eigen::Vector3f> window;
  std::vector<double> times;
  for (int i = 0; i < 20000; ++i) {
    window.emplace_back(across(rng), across(rng), -1.2f + noise(rng));
    window.emplace_back(across(rng), across(rng), 1.8f + noise(rng));
    times.push_back(0.5 * i / 20000.0);
    times.push_back(0.5 * i / 20000.0);
  }
  std::ostringstream err;
  const auto setup = [&](std::vector<std::string> args, const std::vector<Eigen::Vector3f>& points) {
    args.insert(args.begin(), {"in.csv", "--preset", "objects-mid360"});
    err.str("");
    return sc::cli::make_run_setup(sc::cli::parse_cluster_options(args), false, err, &points, &times);
  };
  // No orientation: ambiguous, the height unknown.
  const sc::cli::RunSetup unknown = setup({}, window);
  CHECK(err.str().find("the ground of the first window is ambiguous") != std::string::npos);
  CHECK(unknown.ground.height_map.sensor_height == 0.0f);
  // Level: the plane below is the ground. Upside down: the other one.
  const sc::cli::RunSetup level = setup({"--mount", "0,0,0"}, window);
  INFO(err.str());
  CHECK(err.str().find("ground below the sensor in the first window: 1.20 m (no ground plane in the sensor frame; "
                       "orientation from the mount") != std::string::npos);
  CHECK(level.estimated_height);
  CHECK(level.ground.height_map.sensor_height == doctest::Approx(1.2f).epsilon(0.02));
  const sc::cli::RunSetup flipped = setup({"--mount", "180,0,0"}, window);
  CHECK(flipped.ground.height_map.sensor_height == doctest::Approx(1.8f).epsilon(0.02));
  // Poses that turn the vehicle upside down (the mount level): the same.
  const streamclust::test::TempDir tmp("cli", "ground_from_poses");
  const fs::path tum = tmp.dir / "upside_down.tum";
  {
    std::ofstream out(tum);
    std::vector<sc::io::TumRecord> poses;
    for (double t = -0.1; t <= 0.6; t += 0.1) {
      sc::io::TumRecord r;
      r.t = t;
      r.qx = 1.0;  // roll 180 deg
      r.qw = 0.0;
      poses.push_back(r);
    }
    sc::io::write_tum(out, poses);
  }
  const sc::cli::RunSetup posed = setup({"--poses", tum.string()}, window);
  CHECK(err.str().find("orientation from the poses") != std::string::npos);
  CHECK(posed.ground.height_map.sensor_height == doctest::Approx(1.8f).epsilon(0.02));
  // Too little below the sensor for a layer: said, the height unknown. (The
  // plane search in the sensor frame takes the ceiling's points for a floor
  // under an upside-down sensor; the mount given says otherwise.)
  std::vector<Eigen::Vector3f> above;
  for (const Eigen::Vector3f& p : window) {
    if (p.z() > 0.0f) above.push_back(p);
  }
  std::vector<Eigen::Vector3f> sparse(above.begin(), above.begin() + 40);
  times.resize(sparse.size());
  const sc::cli::RunSetup lost = setup({"--mount", "0,0,0"}, sparse);
  CHECK(err.str().find("no ground in the first window, neither a plane nor a dense layer below the sensor within "
                       "12 m (orientation from the mount): its height unknown (give --sensor-height)") !=
        std::string::npos);
  CHECK(lost.ground.height_map.sensor_height == 0.0f);
  CHECK_FALSE(lost.estimated_height);
}

TEST_CASE("cluster --poses with a moving, turning sensor: verified; points outside the poses' span are no_pose") {
  const streamclust::test::TempDir tmp("cli", "poses");
  const fs::path input =
      simulate(tmp.dir, "moving", {"--scene", "street", "--speed", "1.5", "--yaw-rate", "0.5"}, 0.8);
  const fs::path tum = tmp.dir / "moving.tum";
  REQUIRE(fs::exists(tum));
  const auto r = run_cli({"cluster", input.string(), "--preset", "objects-mid360", "--sensor-height", "1", "--poses",
                          tum.string(), "--verify", "--report", (tmp.dir / "report.json").string(), "--quiet"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  // The same stream with the poses cut to their first half.
  std::ifstream in(tum);
  std::ofstream cut(tmp.dir / "half.tum");
  std::string line;
  std::size_t kept = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || std::stod(line) <= 0.4) {
      cut << line << '\n';
      kept += line.empty() || line[0] == '#' ? 0 : 1;
    }
  }
  cut.close();
  REQUIRE(kept > 10);
  const auto half = run_cli({"cluster", input.string(), "--preset", "objects-mid360", "--sensor-height", "1",
                             "--poses", (tmp.dir / "half.tum").string(), "--verify", "--report",
                             (tmp.dir / "half.json").string(), "--quiet"});
  INFO(half.err);
  REQUIRE(half.code == 0);
  const auto doc = nlohmann::json::parse(slurp(tmp.dir / "half.json"));
  CHECK(doc.at("totals").at("rejected").at("no_pose").get<std::uint64_t>() > 1000);
}

TEST_CASE("cluster: structure options are usage errors in frame mode or out of range; a bad poses file names its line") {
  const streamclust::test::TempDir tmp("cli", "errors");
  const fs::path input = simulate(tmp.dir, "office", {"--scene", "office"}, 0.2);
  CHECK(run_cli({"cluster", input.string(), "--ground", "--mode", "frame"}).code == 2);
  CHECK(run_cli({"cluster", input.string(), "--ground", "--sensor-height", "-1"}).code == 2);
  CHECK(run_cli({"cluster", input.string(), "--ground", "--max-slope", "80"}).code == 2);
  CHECK(run_cli({"cluster", input.string(), "--preset", "objects-lidar"}).code == 2);
  {
    std::ofstream bad(tmp.dir / "bad.tum");
    bad << "# t tx ty tz qx qy qz qw\n0.0 0 0 0 0 0 0 1\n0.1 0 0 zero 0 0 0 1\n";
  }
  const auto r = run_cli({"cluster", input.string(), "--poses", (tmp.dir / "bad.tum").string()});
  CHECK(r.code == 4);
  CHECK(r.err.find("line 3") != std::string::npos);
}
