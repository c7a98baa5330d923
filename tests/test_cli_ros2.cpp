// SPDX-License-Identifier: MIT
// `streamclust ros2` (in-process) against `streamclust replay --to ros2://`
// (a separate process: the messages cross Cyclone DDS's network path) on
// loopback discovery, each case on a DDS domain of its own: the node's
// labels equal `cluster` on its --record file and on the recording replayed
// to it, cycle for cycle; PointCloud2 and CustomMsg inputs; malformed CDR
// counted and skipped; a publisher that leaves and comes back; a late
// subscriber of the outputs; an incompatible QoS reported; participants of
// one process sharing a domain.

#include <doctest/doctest.h>

#ifdef STREAMCLUST_TOOL_ROS2

#include "cli/custom_msg.hpp"

#include <streamclust/io/cdr_writer.hpp>
#include <streamclust/io/mcap_reader.hpp>
#include <streamclust/io/ros/message_decoder.hpp>
#include <streamclust/io/ros/message_definition.hpp>
#include <streamclust/io/ros2_messages.hpp>
#include <streamclust/ros2/cdr_publisher.hpp>
#include <streamclust/ros2/cdr_subscription.hpp>
#include <streamclust/ros2/dds_domain.hpp>
#include <streamclust/ros2/ros2_names.hpp>

#include <nlohmann/json.hpp>

#include "support/cli_checks.hpp"
#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fcntl.h>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <spawn.h>
#include <sys/wait.h>

extern char** environ;

using streamclust::test::check_offline_equal;
using streamclust::test::read_json;
using streamclust::test::run_cli;
using streamclust::test::RunResult;
using streamclust::test::slurp;
using streamclust::test::TempDir;

namespace {

/// `streamclust ARGS` as a process of its own (the tool CTest names in
/// STREAMCLUST_TOOL), its output in `log`; in-process when that is unset
/// (then both DDS participants share one process and deliver locally).
int run_tool_process(std::vector<std::string> args, const std::string& log) {
  const char* tool = std::getenv("STREAMCLUST_TOOL");
  if (tool == nullptr || *tool == '\0') {
    const RunResult r = run_cli(args);
    std::ofstream(log) << r.out << r.err;
    return r.code;
  }
  args.insert(args.begin(), tool);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, tool, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  REQUIRE_MESSAGE(rc == 0, "cannot start ", tool);
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// `ros2 ARGS` on its own thread; `join` returns its result.
class NodeThread {
 public:
  explicit NodeThread(std::vector<std::string> args) {
    args.insert(args.begin(), "ros2");
    thread_ = std::thread([this, args] { result_ = run_cli(args); });
  }
  ~NodeThread() {
    if (thread_.joinable()) thread_.join();  // a failed check left it running: it ends by --wait or --idle-exit
  }
  NodeThread(const NodeThread&) = delete;
  NodeThread& operator=(const NodeThread&) = delete;
  RunResult join() {
    thread_.join();
    return result_;
  }

 private:
  std::thread thread_;
  RunResult result_;
};

/// `replay ARGS --to ros2:///TOPIC` on domain `domain` with loopback discovery, as a process.
int replay_to(const TempDir& dir, unsigned domain, const std::string& topic, std::vector<std::string> args,
              const std::string& log_name = "replay.log") {
  args.insert(args.begin(), "replay");
  args.insert(args.end(), {"--to", "ros2://" + topic, "--dds-loopback", "--domain", std::to_string(domain)});
  const int code = run_tool_process(args, dir.path(log_name));
  INFO("replay: ", slurp(dir.path(log_name)));
  CHECK(code == 0);
  return code;
}

/// Messages per topic of an MCAP file, each decoded with its schema's definition.
std::map<std::string, std::size_t> decoded_messages(const std::string& path) {
  streamclust::io::McapReader reader(path);
  std::vector<std::optional<streamclust::io::ros::MessageDefinitions>> definitions;
  for (const auto& t : reader.topics())
    definitions.emplace_back(std::in_place, t.type, t.definition.value_or(""));
  std::map<std::string, std::size_t> counts;
  streamclust::io::RecordingMessage m;
  streamclust::io::ros::DecodedMessage decoded;
  while (reader.next(m)) {
    streamclust::io::ros::MessageDecoder decoder(*definitions[m.topic], streamclust::io::ros::Encoding::cdr);
    decoder.decode(m.data, m.size, m.origin, decoded);
    ++counts[reader.topics()[m.topic].name];
  }
  return counts;
}

const std::vector<std::string> kPreset{"--preset", "carc-mid360", "--window-time", "0.2"};

/// The node's common arguments on `domain`: loopback discovery, every
/// cycle's labels, input recording and report in `dir`, ends 1.5 s after
/// the last message.
std::vector<std::string> node_args(const TempDir& dir, unsigned domain, std::vector<std::string> more = {}) {
  std::vector<std::string> a{"--dds-loopback", "--domain",  std::to_string(domain), "--idle-exit", "1.5",
                             "--wait",         "30",        "--labels", dir.path("node.csv"), "--cycles", "all",
                             "--record",       dir.path("in.mcap"), "--report", dir.path("node.json"), "-q"};
  a.insert(a.end(), kPreset.begin(), kPreset.end());
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

}  // namespace

TEST_CASE("ros2: CustomMsg from a simulated Mid-360; labels equal cluster on the node's --record and on that "
          "recording replayed as recorded; --record-out holds every output message") {
  TempDir dir("cli_ros2", "custom");
  constexpr unsigned kDomain = 61;
  NodeThread node(node_args(dir, kDomain, {"--record-out", dir.path("out.mcap")}));
  replay_to(dir, kDomain, "/livox/lidar", {"--simulate", "--sensor", "mid360", "--scene", "office", "--seconds", "1.5"});
  const RunResult got = node.join();
  REQUIRE_MESSAGE(got.code == 0, got.err);
  const auto report = read_json(dir.path("node.json"));
  INFO("ros2: ", report["ros2"].dump());
  CHECK(report["ros2"]["type"] == "livox_ros_driver2/msg/CustomMsg");
  CHECK(report["ros2"]["reliability"] == "reliable");  // as the replay (the driver) offers
  CHECK(report["ros2"]["frame_id"] == "livox_frame");
  CHECK(report["ros2"]["output_frame"] == "livox_frame");  // no mount: the input's frame
  CHECK(report["ros2"]["messages"]["received"] == 15);  // 1.5 s in 100 ms messages
  CHECK(report["ros2"]["messages"]["dropped"] == 0);
  CHECK(report["ros2"]["messages"]["malformed"] == 0);
  check_offline_equal(dir, dir.path("node.csv"), dir.path("in.mcap"), kPreset);

  // Every cycle published on the three topics, each message decodable.
  const std::size_t cycles = report["cycles"].size();
  const auto published = decoded_messages(dir.path("out.mcap"));
  CHECK(published.at("/streamclust/points") == report["totals"]["cycles"].get<std::size_t>());
  CHECK(published.at("/streamclust/clusters") == published.at("/streamclust/points"));
  CHECK(published.at("/streamclust/detections") == published.at("/streamclust/points"));
  CHECK(cycles > 10);

  // The recording replayed as recorded: the same labels again.
  TempDir again("cli_ros2", "custom_again");
  NodeThread second(node_args(again, kDomain + 1));
  replay_to(again, kDomain + 1, "/livox/lidar", {dir.path("in.mcap")});
  const RunResult got2 = second.join();
  REQUIRE_MESSAGE(got2.code == 0, got2.err);
  check_offline_equal(again, again.path("node.csv"), dir.path("in.mcap"), kPreset);
}

TEST_CASE("ros2: the Livox driver's PointCloud2, type learnt from the publisher; IMU gravity for the objects preset") {
  TempDir dir("cli_ros2", "pc2");
  constexpr unsigned kDomain = 63;
  std::vector<std::string> args{"--dds-loopback", "--domain", std::to_string(kDomain), "--idle-exit", "1.5",
                                "--wait", "30", "--labels", dir.path("node.csv"), "--cycles", "all", "--record",
                                dir.path("in.mcap"), "--report", dir.path("node.json"), "--preset", "objects-mid360",
                                "--imu", "/livox/imu", "--input", "/points"};
  NodeThread node(args);
  replay_to(dir, kDomain, "/points",
            {"--simulate", "--sensor", "mid360", "--seconds", "1.5", "--mount", "4,12,0", "--imu", "4,12",
             "--message", "pointcloud2", "--message-seconds", "0.05"});
  const RunResult got = node.join();
  REQUIRE_MESSAGE(got.code == 0, got.err);
  const auto report = read_json(dir.path("node.json"));
  INFO("ros2: ", report["ros2"].dump());
  CHECK(report["ros2"]["type"] == "sensor_msgs/msg/PointCloud2");
  CHECK(report["ros2"]["messages"]["received"] == 30);
  CHECK(report["ros2"]["messages"]["imu"].get<int>() >= 90);
  CHECK(report["ros2"]["messages"]["malformed"] == 0);
  CHECK(got.err.find("gravity from the IMU") != std::string::npos);
  CHECK(report["ros2"]["imu_units"] == "g");  // as livox_ros_driver2 (and so replay) sends them
  // Placed by the IMU's mount: the outputs are in the level frame.
  CHECK(report["ros2"]["output_frame"] == "livox_frame_level");
  // cluster does not read the recording's IMU topic: it takes the mount the node's IMU gave.
  const auto& gravity = report["ros2"]["imu_gravity"];
  REQUIRE(gravity.is_object());
  CHECK(std::abs(gravity["roll_deg"].get<double>() - 4.0) < 0.05);
  CHECK(std::abs(gravity["pitch_deg"].get<double>() - 12.0) < 0.05);
  char mount[96];
  std::snprintf(mount, sizeof mount, "%.17g,%.17g,0", gravity["roll_deg"].get<double>(),
                gravity["pitch_deg"].get<double>());
  check_offline_equal(dir, dir.path("node.csv"), dir.path("in.mcap"), {"--preset", "objects-mid360", "--mount", mount});
}

TEST_CASE("ros2 --odom: a moving sensor's odometry places the points as cluster --poses does from the recording") {
  TempDir dir("cli_ros2", "odom");
  constexpr unsigned kDomain = 73;
  NodeThread node(node_args(dir, kDomain, {"--odom", "/odom"}));
  replay_to(dir, kDomain, "/livox/lidar",
            {"--simulate", "--sensor", "mid360", "--scene", "street", "--seconds", "1.5", "--ego-speed", "1.5",
             "--odom-topic", "/odom"});
  const RunResult got = node.join();
  REQUIRE_MESSAGE(got.code == 0, got.err);
  const auto report = read_json(dir.path("node.json"));
  INFO("ros2: ", report["ros2"].dump());
  CHECK(report["ros2"]["odometry"]["poses"].get<int>() >= 290);  // 200 Hz over 1.5 s
  CHECK(report["ros2"]["odometry"]["rejected"] == 0);
  CHECK(report["ros2"]["output_frame"] == "odom");
  CHECK(report["totals"]["rejected"]["no_pose"] == 0);  // every point waited for its pose
  // The recording holds the odometry: `cluster --poses` reads it from there.
  std::vector<std::string> posed = kPreset;
  posed.insert(posed.end(), {"--poses", dir.path("in.mcap")});
  check_offline_equal(dir, dir.path("node.csv"), dir.path("in.mcap"), posed);
  // Without the poses the same points cluster differently (the sensor moved 2 m).
  const RunResult unposed = run_cli({"cluster", dir.path("in.mcap"), "--labels", dir.path("unposed.csv"), "--cycles",
                                     "all", "-q", "--preset", "carc-mid360", "--window-time", "0.2"});
  REQUIRE(unposed.code == 0);
  CHECK(slurp(dir.path("unposed.csv")) != slurp(dir.path("node.csv")));
  // A recording without odometry: the error names the file and lists its topics.
  const RunResult none = run_cli({"cluster", dir.path("in.mcap"), "--poses",
                                  (std::filesystem::path(__FILE__).parent_path() / "data/recordings/ros2_custom_lz4.mcap").string(),
                                  "-q"});
  CHECK(none.code == 4);
  CHECK(none.err.find("no nav_msgs/Odometry topic; topics: /livox/lidar") != std::string::npos);
}

TEST_CASE("ros2: malformed CDR from a publisher is counted and skipped; the stream goes on") {
  TempDir dir("cli_ros2", "malformed");
  constexpr unsigned kDomain = 65;
  NodeThread node(node_args(dir, kDomain, {"--input-type", "livox_ros_driver2/msg/CustomMsg"}));
  {
    namespace r2 = streamclust::ros2;
    r2::DdsParticipant participant(r2::DomainOptions{kDomain, true});
    r2::CdrPublisher pub(participant, r2::dds_topic_name("/livox/lidar"),
                         r2::dds_type_name("livox_ros_driver2/msg/CustomMsg"), r2::default_qos(256));
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (pub.counters().subscribers == 0 && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    REQUIRE(pub.counters().subscribers == 1);
    // 20 messages of a scan line sweeping 2 m ahead; every fifth one damaged.
    streamclust::io::CdrWriter w;
    std::vector<streamclust::live::LivoxReturn> returns;
    const std::uint64_t t0 = 1'700'000'000'000'000'000ull;
    for (int k = 0; k < 20; ++k) {
      returns.clear();
      for (int i = 0; i < 2000; ++i) {
        streamclust::live::LivoxReturn r;
        const double a = (k * 2000 + i) * 1e-4;
        r.x = 2.0f + static_cast<float>(std::sin(a * 50.0));
        r.y = static_cast<float>(std::cos(a * 7.0));
        r.z = static_cast<float>(std::sin(a * 3.0)) * 0.5f;
        r.reflectivity = 40;
        r.time_ns = t0 + static_cast<std::uint64_t>(k * 2000 + i) * 10'000u;  // 100 kHz
        returns.push_back(r);
      }
      streamclust::cli::write_custom_msg(w, "lidar", returns, 0, returns.size());
      std::vector<std::uint8_t> bytes = w.bytes();
      if (k % 5 == 2) bytes.resize(bytes.size() / 2);          // truncated
      if (k % 5 == 4) bytes[1] = 0x07;                         // XCDR2 header: not plain CDR
      pub.publish(bytes);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    CHECK(pub.wait_for_acks(std::chrono::seconds(10)));
  }
  const RunResult got = node.join();
  REQUIRE_MESSAGE(got.code == 0, got.err);
  const auto report = read_json(dir.path("node.json"));
  INFO("ros2: ", report["ros2"].dump());
  CHECK(report["ros2"]["messages"]["received"] == 20);
  CHECK(report["ros2"]["messages"]["malformed"] == 8);
  CHECK(report["ros2"]["messages"]["decoded"] == 12);
  CHECK(report["ros2"]["last_malformed"].get<std::string>().find("ros2:/livox/lidar") != std::string::npos);
  check_offline_equal(dir, dir.path("node.csv"), dir.path("in.mcap"), kPreset);
}

TEST_CASE("ros2: a publisher that leaves and comes back; a late subscriber of the outputs gets what follows") {
  TempDir dir("cli_ros2", "rejoin");
  constexpr unsigned kDomain = 67;
  // The node waits out the gap between the publishers: the second starts
  // after a participant of the test's own and its discovery, seconds under
  // the sanitizers on a busy machine.
  NodeThread node(node_args(dir, kDomain, {"--idle-exit", "12"}));
  replay_to(dir, kDomain, "/livox/lidar", {"--simulate", "--sensor", "mid360", "--seconds", "1.0", "-q"}, "first.log");
  // A late subscriber of the labelled clouds, while the publisher is away.
  namespace r2 = streamclust::ros2;
  r2::DdsParticipant participant(r2::DomainOptions{kDomain, true});
  r2::CdrSubscription::Options so;
  so.dds_topic = r2::dds_topic_name("/streamclust/points");
  so.dds_type = r2::dds_type_name("sensor_msgs/msg/PointCloud2");
  so.qos = r2::default_qos(5);
  so.queue_messages = 1000;
  r2::CdrSubscription late(participant, so);
  // And one that asks for transient-local durability, which volatile writers do not offer.
  so.dds_topic = r2::dds_topic_name("/streamclust/clusters");
  so.dds_type = r2::dds_type_name("visualization_msgs/msg/MarkerArray");
  so.qos.durability = r2::Durability::transient_local;
  r2::CdrSubscription durable(participant, so);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  replay_to(dir, kDomain, "/livox/lidar", {"--simulate", "--sensor", "mid360", "--seconds", "1.0", "--seed", "2",
                                           "-q"}, "second.log");
  const RunResult got = node.join();
  REQUIRE_MESSAGE(got.code == 0, got.err);
  const auto report = read_json(dir.path("node.json"));
  INFO("ros2: ", report["ros2"].dump());
  CHECK(report["ros2"]["publishers"]["seen"] == 2);
  CHECK(report["ros2"]["messages"]["received"] == 20);
  CHECK(report["ros2"]["latency"]["steady_state"] == true);
  check_offline_equal(dir, dir.path("node.csv"), dir.path("in.mcap"), kPreset);
  // The durable subscriber was refused and counted, and got nothing.
  CHECK(report["ros2"]["published"]["/streamclust/clusters"]["incompatible_qos"] == 1);
  CHECK(durable.counters().received == 0);
  CHECK(durable.counters().incompatible_qos == 1);  // and the subscriber hears why, as DDS reports it on both sides
  // The late subscriber: the second publisher's cycles, each a PointCloud2 with the node's fields.
  const auto counters = late.counters();
  CHECK(counters.received >= 15);
  CHECK(counters.received < report["totals"]["cycles"].get<std::uint64_t>());
  streamclust::io::ros::MessageDefinitions defs("sensor_msgs/msg/PointCloud2",
                                               streamclust::io::ros2msg::ros2_definition("sensor_msgs/PointCloud2"));
  streamclust::io::ros::MessageDecoder decoder(defs, streamclust::io::ros::Encoding::cdr);
  streamclust::io::ros::DecodedMessage decoded;
  std::size_t checked = 0;
  for (auto m = late.pop(); m; m = late.pop()) {
    decoder.decode(m.data(), m.size(), {"late", "byte ", 0}, decoded);
    const auto* width = decoded.find("width");
    const auto* step = decoded.find("point_step");
    REQUIRE(width != nullptr);
    REQUIRE(step != nullptr);
    CHECK(decoded.integer(step->primitive, step->offset) == 21);
    CHECK(decoded.integer(width->primitive, width->offset) > 1000);
    ++checked;
  }
  CHECK(checked == counters.received);
}

TEST_CASE("ros2: an incompatible QoS is reported, not silent") {
  TempDir dir("cli_ros2", "qos");
  constexpr unsigned kDomain = 69;
  // A reliable subscription cannot take a best-effort publisher's messages.
  // The node waits 12 s: the publisher is a process of its own, which under
  // the sanitizers, beside another test, took more than 4 s to appear.
  NodeThread node({"--dds-loopback", "--domain", std::to_string(kDomain), "--input-qos", "reliable", "--input-type",
                   "livox_ros_driver2/msg/CustomMsg", "--wait", "12", "--no-status"});
  CHECK(run_tool_process({"replay", "--simulate", "--sensor", "mid360", "--seconds", "1.0", "--to",
                          "ros2:///livox/lidar", "--dds-loopback", "--domain", std::to_string(kDomain), "--qos",
                          "best-effort", "--subscribers", "0", "-q"},
                         dir.path("replay.log")) == 0);
  const RunResult got = node.join();
  INFO("ros2: ", got.err);
  CHECK(got.code == 6);
  CHECK(got.err.find("offers a QoS this subscription cannot accept (reliability") != std::string::npos);
  CHECK(got.err.find("1 with an incompatible QoS") != std::string::npos);
}

TEST_CASE("ros2: participants of one process share their domain; the first one's end leaves the others working") {
  namespace r2 = streamclust::ros2;
  constexpr unsigned kDomain = 75;
  // The first participant creates the domain (loopback discovery): as the
  // node's does when a test's publisher comes after it, or the other way.
  auto first = std::make_unique<r2::DdsParticipant>(r2::DomainOptions{kDomain, true});
  r2::DdsParticipant second(r2::DomainOptions{kDomain, true});
  r2::CdrPublisher pub(second, r2::dds_topic_name("/shared"), r2::dds_type_name("std_msgs/msg/String"),
                       r2::default_qos(16));
  first.reset();
  r2::DdsParticipant third(r2::DomainOptions{kDomain, true});
  r2::CdrSubscription::Options so;
  so.dds_topic = r2::dds_topic_name("/shared");
  so.dds_type = r2::dds_type_name("std_msgs/msg/String");
  so.qos = r2::default_qos(16);
  r2::CdrSubscription sub(third, so);
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (pub.counters().subscribers == 0 && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  REQUIRE(pub.counters().subscribers == 1);
  // A std_msgs/String "hi": the CDR little-endian header, the length with its NUL, the text.
  const std::vector<std::uint8_t> hello = {0, 1, 0, 0, 3, 0, 0, 0, 'h', 'i', 0, 0};
  REQUIRE_NOTHROW(pub.publish(hello));
  CHECK(pub.wait_for_acks(std::chrono::seconds(10)));
  while (sub.size() == 0 && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const r2::CdrMessage got = sub.pop();
  REQUIRE(got.size() >= hello.size());
  CHECK(std::vector<std::uint8_t>(got.data(), got.data() + hello.size()) == hello);
}

TEST_CASE("ros2: bad options are usage errors (exit 2) naming the problem") {
  const struct {
    std::vector<std::string> args;
    const char* message;
  } cases[] = {
      {{"ros2", "--input", "/livox//lidar"}, "empty token"},
      {{"ros2", "--input", "/9lidar"}, "must not start with a digit"},
      {{"ros2", "--namespace", "/a b"}, "character ' '"},
      {{"ros2", "--input-type", "std_msgs/msg/String"}, "--input-type: expected"},
      {{"ros2", "--record", "x.mcap", "--record-out", "x.mcap"}, "two different files"},
      {{"ros2", "--verify"}, "--record file with cluster --verify"},
      {{"replay", "--simulate", "--to", "ros2:///livox/lidar", "--drop", "0.1"}, "--drop: an option of Livox targets"},
      {{"replay", "--simulate", "--to", "livox-sdk2://127.0.0.1", "--message", "custom"},
       "--message: an option of --to ros2:///TOPIC"},
  };
  for (const auto& c : cases) {
    const RunResult r = run_cli(c.args);
    CAPTURE(c.message);
    CHECK(r.code == 2);
    CHECK(r.err.find(c.message) != std::string::npos);
  }
}

#endif  // STREAMCLUST_TOOL_ROS2
