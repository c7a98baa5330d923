// SPDX-License-Identifier: MIT
// `streamclust simulate`'s scenario and output options, run in-process through
// cli/simulate.hpp alone (no engine configurations compiled): --mount, the
// hills scene, the trajectory written beside the stream (TUM), --trajectory
// and --class-column. The CSV points mapped by the TUM poses land on the
// surfaces their class names.

#include <doctest/doctest.h>

#include "cli/simulate.hpp"

#include <streamclust/io/reader.hpp>

#include "support/temp_dir.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstddef>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace sc = streamclust;
namespace cli = streamclust::cli;

/// parse_simulate_options, with a UsageError turned into its message ("" when none).
std::string simulate_usage_error(const std::vector<std::string>& args) {
  try {
    (void)cli::parse_simulate_options(args);
  } catch (const cli::UsageError& e) {
    return e.what();
  }
  return "";
}

/// The rows of a TUM file (comment lines skipped).
std::vector<sc::StampedPose> read_tum(const std::string& path) {
  std::ifstream f(path);
  std::vector<sc::StampedPose> poses;
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    double t, x, y, z, qx, qy, qz, qw;
    s >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
    REQUIRE(!s.fail());
    poses.push_back(sc::StampedPose{t, sc::Pose{Eigen::Quaterniond(qw, qx, qy, qz), Eigen::Vector3d(x, y, z)}});
  }
  return poses;
}

/// The pose at time t, interpolated between the samples around it.
sc::Pose pose_at(const std::vector<sc::StampedPose>& poses, double t) {
  std::size_t k = 1;
  while (k + 1 < poses.size() && poses[k].time < t) ++k;
  const sc::StampedPose& a = poses[k - 1];
  const sc::StampedPose& b = poses[k];
  const double f = b.time > a.time ? (t - a.time) / (b.time - a.time) : 0.0;
  return sc::interpolate(a.pose, b.pose, f);
}

struct ClassRow {
  Eigen::Vector3d p;
  double t;
  long label;
  int surface;
};

/// The rows of a CSV written with --class-column.
std::vector<ClassRow> read_class_csv(const std::string& path) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  REQUIRE(line == "x,y,z,intensity,t,label,class");
  std::vector<ClassRow> rows;
  while (std::getline(f, line)) {
    std::istringstream s(line);
    ClassRow r{};
    double intensity;
    char c;
    s >> r.p.x() >> c >> r.p.y() >> c >> r.p.z() >> c >> intensity >> c >> r.t >> c >> r.label >> c >> r.surface;
    REQUIRE(!s.fail());
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

TEST_CASE("simulate options: --mount, --scene hills, --trajectory, --class-column") {
  cli::SimulateOptions o =
      cli::parse_simulate_options({"--scene", "hills", "--mount", "180,-15.5,30", "--out", "/tmp/x/run.csv"});
  CHECK(o.scene == "hills");
  CHECK(o.mount_given);
  CHECK(o.mount_roll_deg == 180.0);
  CHECK(o.mount_pitch_deg == -15.5);
  CHECK(o.mount_yaw_deg == 30.0);
  CHECK(o.trajectory == "/tmp/x/run.tum");  // beside the output by default
  CHECK_FALSE(o.class_column);
  o = cli::parse_simulate_options({"--out", "a.pcd", "--trajectory", "poses.txt"});
  CHECK(o.trajectory == "poses.txt");
  CHECK_FALSE(o.mount_given);
  CHECK(cli::parse_simulate_options({"--out", "a.csv", "--class-column"}).class_column);

  // The mount reaches the simulator's parameters.
  o = cli::parse_simulate_options({"--mount", "0,30,0", "--out", "a.csv"});
  const auto params = cli::simulator_params<sc::sim::Mid360Model>(o);
  CHECK(params.mount.rotation.angularDistance(sc::mount_from_roll_pitch_yaw_deg(0.0, 30.0, 0.0).rotation) < 1e-12);

  CHECK(simulate_usage_error({"--mount", "1,2", "--out", "a.csv"}).find("ROLL,PITCH,YAW") != std::string::npos);
  CHECK(simulate_usage_error({"--mount", "1,2,3,4", "--out", "a.csv"}).find("ROLL,PITCH,YAW") != std::string::npos);
  CHECK(simulate_usage_error({"--mount", "a,0,0", "--out", "a.csv"}).find("--mount") != std::string::npos);
  CHECK(simulate_usage_error({"--mount", "0,400,0", "--out", "a.csv"}).find("[-360, 360]") != std::string::npos);
  CHECK(simulate_usage_error({"--mount", "--out", "a.csv"}).find("--mount") != std::string::npos);
  CHECK(simulate_usage_error({"--sensor", "synthetic", "--scene", "room", "--mount", "0,0,0", "--out", "a.csv"})
            .find("--mount needs a simulated sensor") != std::string::npos);
  CHECK(simulate_usage_error({"--class-column", "--out", "a.pcd"}).find("--class-column") != std::string::npos);
  CHECK(simulate_usage_error({"--sensor", "synthetic", "--scene", "room", "--class-column", "--out", "a.csv"})
            .find("--class-column") != std::string::npos);
  CHECK(simulate_usage_error({"--scene", "moon", "--out", "a.csv"}).find("office|forest|street|hills") != std::string::npos);
  CHECK(simulate_usage_error({"--out", "a.csv", "--trajectory", "a.csv"}).find("--trajectory") != std::string::npos);
  CHECK(simulate_usage_error({"--scene", "hills", "--out", "a.csv"}).empty());

  // The scenario options are the ones `evaluate` parses too.
  const std::vector<std::string> args = {"--mount", "0,10,0"};
  cli::ArgCursor cursor(args);
  cli::SimulateOptions shared;
  CHECK(cli::parse_simulation_option(cursor, shared));
  CHECK(shared.mount_pitch_deg == 10.0);
}

TEST_CASE("simulate: the trajectory beside the stream maps its points onto the surfaces of their class") {
  const sc::test::TempDir tmp("sim_cli", "trajectory");
  const std::string csv = tmp.path("office.csv");
  cli::SimulateOptions o = cli::parse_simulate_options({"--sensor", "mid360", "--scene", "office", "--seconds", "0.2",
                                                        "--speed", "1.2", "--yaw-rate", "0.6", "--noise", "0",
                                                        "--mount", "0,20,0", "--class-column", "--out", csv, "-q"});
  std::ostringstream out;
  REQUIRE(cli::run_simulate(o, out) == cli::kOk);
  CHECK(out.str().empty());

  const std::vector<ClassRow> rows = read_class_csv(csv);
  const std::vector<sc::StampedPose> poses = read_tum(tmp.path("office.tum"));
  REQUIRE(rows.size() > 10000);
  REQUIRE(poses.size() >= 2);
  // 200 Hz over the stream's span, both ends included.
  CHECK(poses.front().time == doctest::Approx(rows.front().t).epsilon(1e-9));
  CHECK(poses.back().time == doctest::Approx(rows.back().t).epsilon(1e-9));
  CHECK(poses[1].time - poses[0].time == doctest::Approx(0.005));
  CHECK(poses.size() == static_cast<std::size_t>(std::ceil((rows.back().t - rows.front().t) * 200.0 - 1e-6)) + 1);
  // At t = 0: at the start position, pitched 20 deg down.
  CHECK(poses.front().pose.translation.isApprox(Eigen::Vector3d(0.0, 0.0, 1.0), 1e-6));
  CHECK(poses.front().pose.rotation.angularDistance(sc::mount_from_roll_pitch_yaw_deg(0, 20, 0).rotation) < 1e-6);

  // The CLI's reader sees the usual label column; the extra class column is ignored.
  auto reader = sc::io::open_reader(csv, {});
  std::vector<sc::io::Record> records;
  while (reader->read(records, 4096) > 0) {
  }
  REQUIRE(records.size() == rows.size());
  CHECK(reader->info().has_label);

  std::map<int, int> classes;
  int wrong = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ClassRow& r = rows[i];
    CHECK(records[i].label == r.label);
    ++classes[r.surface];
    if ((r.label > 0) != (r.surface == 0)) ++wrong;
    const Eigen::Vector3d w = pose_at(poses, r.t) * r.p;
    // Poses every 5 ms at 1.2 m/s and 0.6 rad/s: interpolation is exact up to float text rounding.
    const double tol = 5e-3;
    if (r.surface == 1) wrong += std::abs(w.z()) > tol;
    if (r.surface == 3) wrong += std::abs(w.z() - 3.0) > tol;
    if (r.surface == 2) wrong += std::abs(std::abs(w.x()) - 10.0) > tol && std::abs(std::abs(w.y()) - 6.0) > tol;
  }
  CHECK(wrong == 0);
  CHECK(classes[0] > 1000);  // object
  CHECK(classes[1] > 1000);  // ground
  CHECK(classes[2] > 1000);  // wall
  CHECK(classes[3] > 100);   // ceiling
  CHECK(classes.size() == 4);
}

TEST_CASE("simulate: the hills scene, the sensor on the terrain, --trajectory, PCD output") {
  const sc::test::TempDir tmp("sim_cli", "hills");
  const std::string pcd = tmp.path("hills.pcd");
  const std::string tum = tmp.path("poses.txt");
  cli::SimulateOptions o = cli::parse_simulate_options({"--scene", "hills", "--seconds", "0.1", "--speed", "5",
                                                        "--seed", "3", "--out", pcd, "--trajectory", tum});
  std::ostringstream out;
  REQUIRE(cli::run_simulate(o, out) == cli::kOk);
  CHECK(out.str().find("trajectory -> " + tum) != std::string::npos);
  const std::vector<sc::StampedPose> poses = read_tum(tum);
  REQUIRE(poses.size() > 10);
  const sc::sim::Scene scene = sc::sim::hills_scene(3);
  for (const sc::StampedPose& p : poses) {
    const Eigen::Vector3d& x = p.pose.translation;
    CHECK(x.z() == doctest::Approx(*scene.ground_height(static_cast<float>(x.x()), static_cast<float>(x.y())) + 1.0)
                       .epsilon(1e-5));
  }
  CHECK(poses.back().pose.translation.x() == doctest::Approx(5.0 * poses.back().time).epsilon(1e-5));

  auto reader = sc::io::open_reader(pcd, {});
  std::vector<sc::io::Record> records;
  while (reader->read(records, 4096) > 0) {
  }
  std::size_t objects = 0;
  for (const sc::io::Record& r : records) objects += r.label > 0;
  CHECK(records.size() > 1500);  // a level Mid-360 (-7 .. 52 deg) in open terrain: most rays see the sky
  CHECK(objects > 100);

  // The same scenario twice: the same stream and trajectory, bit for bit.
  const cli::SimulatedStream a = cli::simulate_stream(o);
  const cli::SimulatedStream b = cli::simulate_stream(o);
  REQUIRE(a.records.size() == b.records.size());
  REQUIRE(a.classes.size() == a.records.size());
  for (std::size_t i = 0; i < a.records.size(); ++i) {
    REQUIRE(a.records[i].x == b.records[i].x);
    REQUIRE(a.records[i].z == b.records[i].z);
    REQUIRE(a.classes[i] == b.classes[i]);
    REQUIRE(a.classes[i] != sc::SurfaceClass::wall);
    REQUIRE(a.classes[i] != sc::SurfaceClass::ceiling);
  }
  REQUIRE(a.trajectory.size() == poses.size());
  CHECK(a.trajectory.back().pose.translation == b.trajectory.back().pose.translation);

  // The stand-in sensor gets a trajectory too: at rest, 1 m above its floor.
  o = cli::parse_simulate_options(
      {"--sensor", "synthetic", "--scene", "room", "--seconds", "0.02", "--out", tmp.path("s.csv"), "-q"});
  REQUIRE(cli::run_simulate(o, out) == cli::kOk);
  const std::vector<sc::StampedPose> rest = read_tum(tmp.path("s.tum"));
  REQUIRE(rest.size() >= 4);
  CHECK(rest.back().pose.translation.isApprox(Eigen::Vector3d(0.0, 0.0, 1.0)));
}
