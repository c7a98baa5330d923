// SPDX-License-Identifier: MIT
// `streamclust cluster` and `info` on recordings (ROS 1 bags, rosbag2, MCAP,
// LVX2): a recording clusters into exactly the labels of the same points read
// from CSV; info lists topics; topic choice and missing definitions are
// input errors (exit 4) naming the file.

#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace {

using streamclust::test::run_cli;
using streamclust::test::slurp;
using streamclust::test::TempDir;

std::string data(const std::string& relative) {
  return (std::filesystem::path(__FILE__).parent_path() / "data" / relative).string();
}

/// The labels of every cycle of `input` clustered with the Mid-360 preset.
std::string labels_of(const TempDir& dir, const std::vector<std::string>& input) {
  const std::string out = dir.path("labels.csv");
  std::vector<std::string> args = {"cluster"};
  args.insert(args.end(), input.begin(), input.end());
  for (const char* a : {"--preset", "carc-mid360", "--window-time", "0.2", "--cycles", "all", "--quiet", "--labels"})
    args.emplace_back(a);
  args.push_back(out);
  const auto r = run_cli(args);
  INFO(r.err);
  REQUIRE(r.code == 0);
  return slurp(out);
}

}  // namespace

TEST_CASE("a recording clusters into the labels of its points read from CSV") {
  TempDir dir("cli_recordings", "labels");
  struct Case {
    std::vector<std::string> recording;
    const char* csv;
  };
  const Case cases[] = {
      {{data("recordings/ros1_custom_bz2.bag")}, "recordings/custom.expected.csv"},
      {{data("recordings/ros2_custom_lz4.mcap")}, "recordings/custom.expected.csv"},
      {{data("recordings/ros2_custom_db3")}, "recordings/custom.expected.csv"},
      {{data("recordings/ros1_pc2_two_topics.bag"), "--topic", "/lidar_front"}, "recordings/pc2_livox.expected.csv"},
      {{data("recordings/ros2_pc2_ouster.mcap")}, "recordings/pc2_ouster.expected.csv"},
      {{data("lvx/mid360_type1.lvx2")}, "lvx/mid360_type1.lvx2.expected.csv"},
  };
  for (const Case& c : cases) {
    INFO(c.recording.front());
    const std::string from_recording = labels_of(dir, c.recording);
    const std::string from_csv = labels_of(dir, {data(c.csv), "--time-unit", "ns"});
    CHECK(from_recording.size() > 100);
    CHECK(from_recording == from_csv);
  }
}

TEST_CASE("info lists a recording's topics, then each point-cloud topic") {
  const auto r = run_cli({"info", data("recordings/ros1_pc2_two_topics.bag")});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("format:    bag\n") != std::string::npos);
  CHECK(r.out.find("  /lidar_front  sensor_msgs/PointCloud2  4 messages\n") != std::string::npos);
  CHECK(r.out.find("  /livox/imu  sensor_msgs/Imu  3 messages\n") != std::string::npos);
  CHECK(r.out.find("topic /lidar_front:\n") != std::string::npos);
  CHECK(r.out.find("topic /lidar_rear:\n") != std::string::npos);
  CHECK(r.out.find("points:    480 (480 with finite coordinates)") != std::string::npos);
  CHECK(r.out.find("points:    48 (48 with finite coordinates)") != std::string::npos);
  CHECK(r.out.find("time:      field 'timestamp', 1700000000.000000000 s to 1700000000.395200000 s") != std::string::npos);

  const auto one = run_cli({"info", data("recordings/ros2_custom_zstd.mcap"), "--topic", "/livox/lidar"});
  REQUIRE(one.code == 0);
  CHECK(one.out.find("points:    480 (480 with finite coordinates)") != std::string::npos);
  CHECK(one.out.find("time:      field 'offset_time', 1700000000.000001000 s to 1700000000.395201000 s") !=
        std::string::npos);
}

TEST_CASE("topic choice and missing definitions are input errors") {
  const std::string two = data("recordings/ros1_pc2_two_topics.bag");
  const auto none = run_cli({"cluster", two, "--quiet"});
  CHECK(none.code == 4);
  CHECK(none.err.find(two + ": topics: 2 point-cloud topics: /lidar_front") != std::string::npos);
  CHECK(none.err.find("choose one (--topic NAME)") != std::string::npos);
  const auto wrong = run_cli({"cluster", two, "--topic", "/livox/imu", "--quiet"});
  CHECK(wrong.code == 4);
  CHECK(wrong.err.find("which holds no points") != std::string::npos);
  const auto schemaless = run_cli({"cluster", data("recordings/ros2_no_schema.mcap"), "--quiet"});
  CHECK(schemaless.code == 4);
  CHECK(schemaless.err.find("message type and definition missing") != std::string::npos);
  const auto empty_topic = run_cli({"cluster", two, "--topic", ""});
  CHECK(empty_topic.code == 2);
}

TEST_CASE("info lists an LVX file's LiDARs, then each LiDAR") {
  const auto r = run_cli({"info", data("lvx/two_lidars.lvx2")});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("format:    lvx (lvx2)") != std::string::npos);
  CHECK(r.out.find("lidars:    2\n") != std::string::npos);
  CHECK(r.out.find("  index 0  Mid-360  serial \"47MDK9DF710124\"") != std::string::npos);
  CHECK(r.out.find("lidar 0:\n") != std::string::npos);
  CHECK(r.out.find("lidar 1:\n") != std::string::npos);
  const auto one = run_cli({"info", data("lvx/two_lidars.lvx2"), "--topic", "HAP2301TX000731"});
  REQUIRE(one.code == 0);
  CHECK(one.out.find("lidar HAP2301TX000731:\n") != std::string::npos);
  CHECK(one.out.find("lidar 0:\n") == std::string::npos);
}
