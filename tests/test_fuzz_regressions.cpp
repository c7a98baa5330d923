// SPDX-License-Identifier: MIT
// Inputs the fuzz targets found (fuzz/, docs/fuzzing.md), kept in
// tests/data/fuzz/: each must now end in the documented clean error, in the
// library and through the tool.

#include <doctest/doctest.h>

#include <streamclust/io/error.hpp>
#include <streamclust/io/reader.hpp>
#include <streamclust/io/tum.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/motion/tum_poses.hpp>

#include "cli/options.hpp"

#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace io = streamclust::io;
namespace sc = streamclust;

namespace {

/// A file of tests/data/fuzz.
std::string fuzz_input(const char* name) {
  // <source>/tests/test_fuzz_regressions.cpp -> <source>/tests/data/fuzz/<name>
  return (std::filesystem::path(__FILE__).parent_path() / "data" / "fuzz" / name).string();
}

/// The InputError reading `path` as a TUM trajectory throws ("" if none).
std::string tum_error(const std::string& path) {
  try {
    sc::PoseTrajectory trajectory(sc::to_stamped_poses(io::read_tum(path)));
  } catch (const io::InputError& e) {
    return e.where() + ": " + e.what_expected();
  }
  return "";
}

/// The InputError reading every record of `path` throws, as "where: expected" ("" if none).
std::string read_error(const std::string& path) {
  try {
    auto reader = io::open_reader(path);
    std::vector<io::Record> chunk;
    while (chunk.clear(), reader->read(chunk, 4096) > 0) {
    }
  } catch (const io::InputError& e) {
    return e.where() + ": " + e.what_expected();
  }
  return "";
}

/// The arguments of a fuzz_cli_options input: one per line.
std::vector<std::string> argument_lines(const std::string& path) {
  std::istringstream in(sc::test::slurp(path));
  std::vector<std::string> args;
  for (std::string line; std::getline(in, line);) args.push_back(line);
  return args;
}

/// The UsageError message of `streamclust cluster` on the arguments of `path` ("" if none).
std::string cluster_usage_error(const std::string& path) {
  try {
    sc::cli::parse_cluster_options(argument_lines(path));
  } catch (const sc::cli::UsageError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("fuzz_tum: a quaternion whose norm overflows is an InputError naming its line, exit 4 in the tool") {
  // 1e155 squared is beyond the double range: the norm is inf. read_tum
  // accepted it and to_stamped_poses then threw std::invalid_argument, which
  // the tool reported as a usage error (exit 2) instead of an input error.
  const std::string path = fuzz_input("tum_quaternion_overflow.tum");
  CHECK(tum_error(path) == "line 2: expected a rotation quaternion (qx qy qz qw) of norm near 1, found norm inf");

  const sc::test::TempDir tmp("fuzz_regressions", "tum_overflow");
  const std::string points = tmp.file("points.csv", "x,y,z,t\n1,2,3,0\n1,2,3.1,0.01\n");
  const auto r = sc::test::run_cli({"cluster", points, "--poses", path, "--quiet"});
  CHECK(r.code == 4);
  CHECK(r.err.find("input error: " + path + ": line 2: ") != std::string::npos);
}

TEST_CASE("fuzz_cli_options: a cycle number beyond uint64 is a usage error, not a conversion out of range") {
  // --cycles 5444400000000000000000: the check converted the double to
  // uint64 before comparing (undefined behaviour beyond 2^64).
  const std::string path = fuzz_input("cli_cycles_beyond_uint64.args");
  CHECK(cluster_usage_error(path) ==
        "--cycles: expected all, last or a comma-separated list of cycle numbers >= 0, got '5444400000000000000000'");
  const auto r = sc::test::run_cli({"cluster", "scan.csv", "--cycles", "1e22"});
  CHECK(r.code == 2);
  CHECK(r.err.find("--cycles: expected all, last or") != std::string::npos);
}

TEST_CASE("fuzz_cli_options: a mask beyond INT_MAX is refused by the option check") {
  // --mask 3000000001 wrapped to the odd int -1294967295, which passed the
  // option check (only the engine refused it, naming mask_size).
  CHECK(cluster_usage_error(fuzz_input("cli_mask_beyond_int.args")) ==
        "--mask: expected an odd number of cells from 1 to 255");
  const auto r = sc::test::run_cli({"evaluate", "--mask", "3000000001"});
  CHECK(r.code == 2);
  CHECK(r.err == "streamclust: --mask: expected an odd number of cells from 1 to 255\n");
}

TEST_CASE("fuzz_cli_options: a positive value that rounds to 0 as a float is refused") {
  // --sensor-height 12001e-300 passed the check as a double and became the
  // float 0, which the ground model reads as "height unknown".
  CHECK(cluster_usage_error(fuzz_input("cli_sensor_height_underflow.args")) ==
        "--sensor-height: expected a positive number, got '12001e-300'");
  for (const char* option : {"--theta", "--distance", "--min-distance", "--max-multiplicity"}) {
    INFO(option);
    const auto r = sc::test::run_cli({"cluster", "scan.csv", option, "1e-300"});
    CHECK(r.code == 2);
    CHECK(r.err == std::string("streamclust: ") + option + ": expected a positive number, got '1e-300'\n");
  }
  const auto r = sc::test::run_cli({"evaluate", "--objects", "--height", "1e-60"});
  CHECK(r.code == 2);
  CHECK(r.err == "streamclust: --height: expected a positive number, got '1e-60'\n");
}

TEST_CASE("fuzz_bag: a PointCloud2 of width 0 and height 2e9 is checked against its data, not looped over") {
  // Message 3 declares height 2013265921, width 0, row_step 3120 and 3120
  // bytes of data. The data-size check skipped clouds of width 0, and the
  // point loop then ran 2e9 empty rows (15 s under the fuzzer's sanitizers).
  const std::string path = fuzz_input("bag_cloud_tall_and_empty.bag");
  const std::string expected =
      "message 3 on /livox/lidar (record at byte 8622 (chunk), decompressed byte 1582), payload byte 171: "
      "data holds 3120 bytes: expected height x row_step = 2013265921 x 3120";
  CHECK(read_error(path) == expected);
  const auto r = sc::test::run_cli({"cluster", path, "--quiet"});
  CHECK(r.code == 4);
  CHECK(r.err == "streamclust: input error: " + path + ": " + expected + "\n");
}
