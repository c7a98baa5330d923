// SPDX-License-Identifier: MIT
// TUM trajectories: the reader (comments, blanks, tabs; every malformed line
// named), the round trip with write_tum at epoch-scale times, and the
// conversion to stamped poses.

#include <doctest/doctest.h>

#include <streamclust/io/error.hpp>
#include <streamclust/io/tum.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/motion/tum_poses.hpp>

#include "support/temp_dir.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace io = streamclust::io;
namespace sc = streamclust;

namespace {

/// The InputError's what() when reading `text`, or "" when it reads.
std::string error_of(const std::string& text) {
  std::istringstream in(text);
  try {
    io::read_tum(in, "odom.tum");
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("read_tum: blanks and tabs separate, comments and blank lines are skipped") {
  std::istringstream in(
      "# timestamp tx ty tz qx qy qz qw\n"
      "\n"
      "1.0 1 2 3 0 0 0 1\n"
      "   # an indented comment\n"
      "1.5\t4\t5\t6\t0\t0\t0.7071067811865476\t0.7071067811865476\r\n"
      "  2.25  -1e-3 +2 3.5e1   0 1 0 0  \n");
  const std::vector<io::TumRecord> r = io::read_tum(in, "odom.tum");
  REQUIRE(r.size() == 3);
  CHECK(r[0].t == 1.0);
  CHECK(r[0].tz == 3.0);
  CHECK(r[0].qw == 1.0);
  CHECK(r[1].t == 1.5);
  CHECK(r[1].qz == 0.7071067811865476);
  CHECK(r[2].tx == -1e-3);
  CHECK(r[2].ty == 2.0);
  CHECK(r[2].tz == 35.0);
  CHECK(r[2].qy == 1.0);
}

TEST_CASE("read_tum: every malformed line is an InputError naming the file, the line and what was expected") {
  const std::string ok = "# header\n0.0 0 0 0 0 0 0 1\n";
  std::string m = error_of(ok + "0.1 0 0 0 0 0 1\n");
  CHECK(m == "odom.tum: line 3: expected 8 numbers separated by blanks (t tx ty tz qx qy qz qw), found 7 fields: "
             "\"0.1 0 0 0 0 0 1\"");
  m = error_of(ok + "0.1,0,0,0,0,0,0,1\n");
  CHECK(m.find("odom.tum: line 3: expected 8 numbers") == 0);
  CHECK(m.find("found 1 field:") != std::string::npos);
  m = error_of(ok + "0.1 0 0 0 0 0 0 1 9\n");
  CHECK(m.find("line 3: expected 8 numbers") != std::string::npos);
  m = error_of(ok + "0.1 0 abc 0 0 0 0 1\n");
  CHECK(m == "odom.tum: line 3, column 3 (ty): expected a number, found \"abc\"");
  m = error_of(ok + "0.1 0 0 0 0 0 nan 1\n");
  CHECK(m == "odom.tum: line 3, column 7 (qz): expected a finite number, found \"nan\"");
  m = error_of(ok + "0.1 inf 0 0 0 0 0 1\n");
  CHECK(m.find("line 3, column 2 (tx): expected a finite number") != std::string::npos);
  m = error_of(ok + "0.1 0 0 0 0 0 0 0\n");
  CHECK(m.find("odom.tum: line 3: expected a rotation quaternion (qx qy qz qw) of norm near 1, found norm 0") == 0);
  m = error_of(ok + "\n0.0 0 0 0 0 0 0 1\n");
  CHECK(m == "odom.tum: line 4, column 1 (t): expected a time later than line 2's 0.000000000, found 0.000000000");
  m = error_of(ok + "-0.5 0 0 0 0 0 0 1\n");
  CHECK(m.find("line 3, column 1 (t): expected a time later than") != std::string::npos);
  m = error_of("# only a comment\n\n");
  CHECK(m == "odom.tum: line 3: expected at least one pose line (t tx ty tz qx qy qz qw), found end of file");
  CHECK(error_of(ok) == "");
}

TEST_CASE("read_tum: a missing file or a directory cannot be opened") {
  const streamclust::test::TempDir dir("io_tum", "open");
  try {
    io::read_tum(dir.path("absent.tum"));
    FAIL("no error");
  } catch (const io::InputError& e) {
    CHECK(e.file() == dir.path("absent.tum"));
    CHECK(e.what_expected().find("cannot open") != std::string::npos);
  }
  CHECK_THROWS_AS(io::read_tum(dir.dir.string()), io::InputError);
}

TEST_CASE("write_tum then read_tum: epoch-scale times come back exactly, other values within 0.5e-9") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> step(1e-3, 0.02);
  std::uniform_real_distribution<double> coordinate(-500.0, 500.0);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<io::TumRecord> records;
  double t = 1700000000.123456789;
  for (int i = 0; i < 500; ++i) {
    Eigen::Quaterniond q(unit(rng), unit(rng), unit(rng), unit(rng));
    q.normalize();
    records.push_back(io::TumRecord{t, coordinate(rng), coordinate(rng), coordinate(rng), q.x(), q.y(), q.z(), q.w()});
    t += step(rng);
  }
  const streamclust::test::TempDir dir("io_tum", "round_trip");
  {
    std::ofstream out(dir.path("odom.tum"));
    io::write_tum(out, records);
  }
  const std::vector<io::TumRecord> back = io::read_tum(dir.path("odom.tum"));
  REQUIRE(back.size() == records.size());
  for (std::size_t i = 0; i < records.size(); ++i) {
    CHECK(back[i].t == records[i].t);  // a double near 1.7e9 s resolves 2.4e-7 s: %.9f names it exactly
    CHECK(std::abs(back[i].tx - records[i].tx) <= 5e-10 * 1.01);
    CHECK(std::abs(back[i].qw - records[i].qw) <= 5e-10 * 1.01);
  }
  // Small times keep their nanoseconds.
  std::ostringstream out;
  io::write_tum(out, {io::TumRecord{0.000000001, 0, 0, 0, 0, 0, 0, 1},
                      io::TumRecord{12.345678912, 0, 0, 0, 0, 0, 0, 1}});
  std::istringstream in(out.str());
  const std::vector<io::TumRecord> small = io::read_tum(in, "small.tum");
  REQUIRE(small.size() == 2);
  CHECK(small[0].t == 1e-9);
  CHECK(small[1].t == 12.345678912);
}

TEST_CASE("to_stamped_poses: times, positions and normalised rotations, ready for PoseTrajectory") {
  const std::vector<io::TumRecord> records = {io::TumRecord{2.0, 1, 2, 3, 0, 0, 0, 2},
                                              io::TumRecord{3.0, 4, 5, 6, 0, 0, 0.6, 0.8}};
  const std::vector<sc::StampedPose> poses = sc::to_stamped_poses(records);
  REQUIRE(poses.size() == 2);
  CHECK(poses[0].time == 2.0);
  CHECK(poses[0].pose.translation == Eigen::Vector3d(1, 2, 3));
  CHECK(poses[0].pose.rotation.w() == 1.0);
  CHECK(poses[1].pose.rotation.z() == doctest::Approx(0.6));
  CHECK(poses[1].pose.rotation.w() == doctest::Approx(0.8));
  const sc::PoseTrajectory trajectory(poses);
  CHECK(trajectory.time_end() == 3.0);
  CHECK_THROWS_AS(sc::to_stamped_poses({io::TumRecord{0.0, 0, 0, 0, 0, 0, 0, 0}}), std::invalid_argument);
}
