// SPDX-License-Identifier: MIT
// `streamclust cluster` and `info` on recordings (ROS 1 bags, rosbag2, MCAP,
// LVX2): a recording clusters into exactly the labels of the same points read
// from CSV; info lists topics; topic choice and missing definitions are
// input errors (exit 4) naming the file.

#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

#include <streamclust/io/mcap_reader.hpp>
#include <streamclust/io/ros/message_decoder.hpp>

#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
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

TEST_CASE("--mcap: every cycle's window and boxes, as the labels file has them") {
  namespace io = streamclust::io;
  namespace ros = streamclust::io::ros;
  TempDir dir("cli_recordings", "mcap");
  const std::string mcap_path = dir.path("out.mcap"), labels_path = dir.path("labels.csv");
  const auto r = run_cli({"cluster", data("recordings/ros1_custom_lz4.bag"), "--preset", "carc-mid360", "--window-time",
                          "0.2", "--quiet", "--cycles", "all", "--labels", labels_path, "--mcap", mcap_path});
  INFO(r.err);
  REQUIRE(r.code == 0);
  // The labels file, per cycle: the labels of rows that are window points (not -1).
  std::map<std::uint64_t, std::multiset<std::int64_t>> want;
  {
    std::istringstream in(slurp(labels_path));
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      const auto c1 = line.find(','), c3 = line.rfind(',');
      const std::uint64_t cycle = std::stoull(line.substr(0, c1));
      const std::int64_t label = std::stoll(line.substr(c3 + 1));
      if (label != -1) want[cycle].insert(label);
    }
  }
  REQUIRE(want.size() > 1);
  io::McapReader mcap(mcap_path);
  REQUIRE(mcap.topics().size() == 2);
  CHECK(mcap.topics()[0].name == "/streamclust/points");
  CHECK(mcap.topics()[0].type == "foxglove_msgs/msg/PointCloud");
  CHECK(mcap.topics()[1].type == "foxglove_msgs/msg/SceneUpdate");
  std::vector<ros::MessageDefinitions> defs;
  for (const auto& t : mcap.topics()) defs.emplace_back(t.type, *t.definition);
  ros::DecodedMessage decoded;
  io::RecordingMessage m;
  std::uint64_t cycle = 0, updates = 0;
  while (mcap.next(m)) {
    ros::MessageDecoder decoder(defs[m.topic], ros::Encoding::cdr);
    decoder.decode(m.data, m.size, m.origin, decoded);  // every field as the schema says, nothing left over
    CHECK(m.log_time_ns >= 1700000000ull * 1000000000ull);
    if (m.topic == 0) {
      const ros::Leaf* data = decoded.find("data");
      REQUIRE(data != nullptr);
      std::multiset<std::int64_t> labels;
      for (std::size_t i = 0; i < data->count / 20; ++i)
        labels.insert(decoded.integer(ros::Primitive::int32, data->offset + 20 * i + 12));
      CHECK(labels == want[cycle]);
      ++cycle;
    } else {
      std::set<std::string> ids, expected;
      for (std::size_t k = 0; const ros::Leaf* id = decoded.find("entities." + std::to_string(k) + ".id"); ++k)
        ids.insert(id->text);
      for (const std::int64_t l : want[updates])
        if (l >= 0) expected.insert(std::to_string(l));
      CHECK(ids == expected);
      ++updates;
    }
  }
  CHECK(cycle == want.size());
  CHECK(updates == want.size());
}

TEST_CASE("--png: the last cycle's picture; --png-every N: every N-th cycle's") {
  TempDir dir("cli_recordings", "png");
  const auto png_size = [](const std::string& path) {
    const std::string b = slurp(path);
    REQUIRE(b.size() > 33);
    CHECK(b.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
    const auto be32 = [&](std::size_t at) {
      return (static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) << 24) |
             (static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 16) |
             (static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 2])) << 8) |
             static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 3]));
    };
    return std::make_pair(be32(16), be32(20));  // IHDR width, height
  };
  const std::string input = data("recordings/ros2_custom_zstd.mcap");
  const auto one = run_cli({"cluster", input, "--quiet", "--png", dir.path("last.png")});
  INFO(one.err);
  REQUIRE(one.code == 0);
  const auto [w, h] = png_size(dir.path("last.png"));
  CHECK(std::max(w, h) >= 900);  // 900 px on the longer side of the points' extent, plus the margin
  const auto series = run_cli({"cluster", input, "--quiet", "--window-time", "0.2", "--png", dir.path("s.png"),
                               "--png-every", "2"});
  REQUIRE(series.code == 0);
  CHECK(std::filesystem::exists(dir.path("s_000000.png")));
  CHECK(std::filesystem::exists(dir.path("s_000002.png")));
  CHECK_FALSE(std::filesystem::exists(dir.path("s_000001.png")));
  CHECK_FALSE(std::filesystem::exists(dir.path("s.png")));
  png_size(dir.path("s_000002.png"));
  CHECK(run_cli({"cluster", input, "--png", dir.path("x.png"), "--png-every", "0"}).code == 2);
}
