// SPDX-License-Identifier: MIT
// The command line's --poses and --mount: parsing, usage errors, and the
// loader that turns them into PosedMotion parameters (a malformed poses file
// names its line).

#include <doctest/doctest.h>

#include "cli/options.hpp"
#include "cli/poses.hpp"

#include <streamclust/io/error.hpp>
#include <streamclust/io/tum.hpp>
#include <streamclust/motion/pose.hpp>

#include "support/temp_dir.hpp"

#include <fstream>
#include <string>
#include <vector>

namespace sc = streamclust;
namespace cli = streamclust::cli;

namespace {

std::string usage_error(const std::vector<std::string>& args) {
  try {
    cli::parse_cluster_options(args);
  } catch (const cli::UsageError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("cluster --poses FILE --mount ROLL,PITCH,YAW are parsed; without them none is given") {
  const cli::ClusterOptions plain = cli::parse_cluster_options({"in.csv"});
  CHECK(plain.poses_path.empty());
  CHECK_FALSE(plain.mount_deg.has_value());
  CHECK_FALSE(cli::has_motion_options(plain));

  const cli::ClusterOptions o = cli::parse_cluster_options({"in.csv", "--poses", "odom.tum", "--mount", "180,-7.5,90"});
  CHECK(o.poses_path == "odom.tum");
  REQUIRE(o.mount_deg.has_value());
  CHECK((*o.mount_deg)[0] == 180.0);
  CHECK((*o.mount_deg)[1] == -7.5);
  CHECK((*o.mount_deg)[2] == 90.0);
  CHECK(cli::has_motion_options(o));
  CHECK(o.input == "in.csv");
}

TEST_CASE("cluster --mount and --poses: malformed values are usage errors naming the option") {
  const std::string expected = "--mount: expected ROLL,PITCH,YAW in degrees (e.g. 0,15,0 or 180,0,0), got '";
  CHECK(usage_error({"in.csv", "--mount", "0,15"}) == expected + "0,15'");
  CHECK(usage_error({"in.csv", "--mount", "0,15,0,1"}) == expected + "0,15,0,1'");
  CHECK(usage_error({"in.csv", "--mount", "0,x,0"}) == expected + "0,x,0'");
  CHECK(usage_error({"in.csv", "--mount", "0,15,"}) == expected + "0,15,'");
  CHECK(usage_error({"in.csv", "--mount", "0,400,0"}) ==
        "--mount: expected angles from -360 to 360 degrees, got '0,400,0'");
  CHECK(usage_error({"in.csv", "--mount", "nan,0,0"}) ==
        "--mount: expected angles from -360 to 360 degrees, got 'nan,0,0'");
  CHECK(usage_error({"in.csv", "--mount"}) == "--mount: missing value");
  CHECK(usage_error({"in.csv", "--poses"}) == "--poses: missing value");
}

TEST_CASE("load_motion_params: the mount from --mount, the trajectory from the --poses file") {
  const sc::test::TempDir dir("motion_cli", "load");
  const std::string path = dir.path("odom.tum");
  {
    std::ofstream out(path);
    sc::io::write_tum(out, {sc::io::TumRecord{1700000000.0, 0, 0, 0, 0, 0, 0, 1},
                            sc::io::TumRecord{1700000000.01, 0.1, 0, 0, 0, 0, 0.0499792, 0.9987503},
                            sc::io::TumRecord{1700000000.02, 0.2, 0, 0, 0, 0, 0.0998334, 0.9950042}});
  }
  cli::ClusterOptions o = cli::parse_cluster_options({"in.csv", "--poses", path, "--mount", "0,30,0"});
  const sc::PosedMotion::Params params = cli::load_motion_params(o);
  REQUIRE(params.trajectory != nullptr);
  CHECK(params.trajectory->size() == 3);
  CHECK(params.trajectory->time_begin() == 1700000000.0);
  CHECK(params.trajectory->time_end() == 1700000000.02);
  const sc::Pose expected = sc::mount_from_roll_pitch_yaw_deg(0.0, 30.0, 0.0);
  CHECK(params.mount.rotation.angularDistance(expected.rotation) < 1e-12);

  // The parameters make a working policy: the sensor pitched 30 degrees down on the vehicle's first pose.
  sc::PosedMotion motion(params);
  sc::PlacedPoint placed;
  REQUIRE(motion.place(Eigen::Vector3f(2.0f, 0.0f, 0.0f), 1700000000.0, placed) == sc::RejectReason::accepted);
  CHECK(placed.world.z() == doctest::Approx(-1.0).epsilon(1e-5));
  CHECK(motion.place(Eigen::Vector3f(2.0f, 0.0f, 0.0f), 1700000000.03, placed) == sc::RejectReason::no_pose);

  // Neither option: the identity mount and no trajectory.
  const sc::PosedMotion::Params none = cli::load_motion_params(cli::parse_cluster_options({"in.csv"}));
  CHECK(none.trajectory == nullptr);
  CHECK(none.mount.rotation.coeffs() == Eigen::Quaterniond::Identity().coeffs());
}

TEST_CASE("load_motion_params: a malformed or missing poses file is an input error naming the file and line") {
  const sc::test::TempDir dir("motion_cli", "bad");
  const std::string path = dir.file("bad.tum", "# t tx ty tz qx qy qz qw\n0 0 0 0 0 0 0 1\n0.1 0 0 0 0 0 1\n");
  try {
    cli::load_motion_params(cli::parse_cluster_options({"in.csv", "--poses", path}));
    FAIL("no error");
  } catch (const sc::io::InputError& e) {
    CHECK(e.file() == path);
    CHECK(e.where() == "line 3");
    CHECK(e.what_expected().find("expected 8 numbers") == 0);
  }
  CHECK_THROWS_AS(cli::load_motion_params(cli::parse_cluster_options({"in.csv", "--poses", dir.path("absent.tum")})),
                  sc::io::InputError);
}
