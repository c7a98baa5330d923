// SPDX-License-Identifier: MIT
// `streamclust live` against `streamclust replay` (the emulated LiDAR) on
// loopback, both in-process, with real UDP sockets: the live run's labels
// equal `cluster` on its own --record file cycle for cycle, and the
// recorded points are the input's (within the data type's quantum, 1 us);
// discovery, configure and the SDK1 handshake; faults counted, not mixed in.

#include <doctest/doctest.h>

#include <streamclust/io/reader.hpp>

#include <nlohmann/json.hpp>

#include "support/cli_checks.hpp"
#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
using streamclust::test::check_offline_equal;
using streamclust::test::read_json;
using streamclust::test::run_cli;
using streamclust::test::RunResult;
using streamclust::test::slurp;
using streamclust::test::TempDir;

namespace {

/// True once some socket of this host holds UDP `port` (Linux /proc/net/udp;
/// looking never takes the port from the program under test).
bool udp_port_held(unsigned port) {
  std::ifstream f("/proc/net/udp");
  std::string line;
  std::getline(f, line);
  while (std::getline(f, line)) {
    std::istringstream s(line);
    std::string slot, local;
    s >> slot >> local;
    const auto colon = local.find(':');
    if (colon != std::string::npos && std::stoul(local.substr(colon + 1), nullptr, 16) == port) return true;
  }
  return false;
}

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define STREAMCLUST_LIVE_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define STREAMCLUST_LIVE_TEST_SANITIZED 1
#endif
#endif

/// The emulated LiDAR sends at its real rate, or at half of it in a
/// sanitizer build, where the live run's queue also holds a whole test
/// stream (16384 packets; default 4096): there the engine runs several
/// times slower, and on a shared two-core machine the receiver thread can
/// miss its turn long enough for the socket buffer to overflow. The
/// exactness checked here needs nothing lost; the sustained rate is the
/// benchmark's. (The device clock then runs at twice the host's rate: one
/// epoch still, as a clock jump is a step between packets.)
#ifdef STREAMCLUST_LIVE_TEST_SANITIZED
constexpr const char* kReplaySpeed = "0.5";
constexpr const char* kLiveQueue = "16384";
#else
constexpr const char* kReplaySpeed = "1";
constexpr const char* kLiveQueue = "4096";
#endif

/// `live ARGS --queue kLiveQueue` on its own thread; `join` returns its result.
class LiveThread {
 public:
  LiveThread(std::vector<std::string> args, unsigned wait_for_port) {
    args.insert(args.begin(), "live");
    args.insert(args.end(), {"--queue", kLiveQueue});
    thread_ = std::thread([this, args] { result_ = run_cli(args); });
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!udp_port_held(wait_for_port) && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  RunResult join() {
    thread_.join();
    return result_;
  }

 private:
  std::thread thread_;
  RunResult result_;
};

/// `replay ARGS --speed kReplaySpeed`.
RunResult replay(std::vector<std::string> args) {
  args.insert(args.begin(), "replay");
  args.insert(args.end(), {"--speed", kReplaySpeed});
  return run_cli(args);
}

std::vector<streamclust::io::Record> read_records(const std::string& path) {
  auto reader = streamclust::io::open_reader(path, {});
  std::vector<streamclust::io::Record> all, chunk;
  while (chunk.clear(), reader->read(chunk, 65536) > 0) all.insert(all.end(), chunk.begin(), chunk.end());
  return all;
}

std::vector<streamclust::io::Record> finite(const std::vector<streamclust::io::Record>& in) {
  std::vector<streamclust::io::Record> out;
  for (const auto& r : in)
    if (std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.z)) out.push_back(r);
  return out;
}

/// Every recorded point is the input's point at the same position, within
/// `metres` (the data type's quantum) and 1 us of relative time.
void check_same_points(const std::string& input, const std::string& recorded, double metres) {
  const auto a = finite(read_records(input));
  const auto b = read_records(recorded);
  REQUIRE(a.size() == b.size());
  double worst_m = 0.0, worst_us = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = std::hypot(a[i].x - b[i].x, a[i].y - b[i].y, a[i].z - b[i].z);
    worst_m = std::max(worst_m, d);
    worst_us = std::max(worst_us, std::abs((a[i].t - a[0].t) - (b[i].t - b[0].t)) * 1e6);
  }
  CAPTURE(worst_m);
  CAPTURE(worst_us);
  CHECK(worst_m <= metres);
  CHECK(worst_us <= 1.0);
}

/// `seconds` of a simulated Mid-360 in the office, as `dir`/office.csv.
std::string simulated_office(const TempDir& dir, const std::string& seconds) {
  const std::string path = dir.path("office.csv");
  REQUIRE(run_cli({"simulate", "--sensor", "mid360", "--seconds", seconds, "--out", path, "-q"}).code == 0);
  return path;
}

/// A passive SDK2 run with the carc-mid360 preset on 127.0.0.1:`port` (labels
/// of every cycle, recording and report in `dir`) against `replay ARGS` from
/// `device`; both must succeed. Returns the replay's result and the report.
std::pair<RunResult, nlohmann::json> run_passive_sdk2(const TempDir& dir, unsigned port, const std::string& device,
                                                      std::vector<std::string> replay_args) {
  const std::string url = "livox-sdk2://127.0.0.1:" + std::to_string(port);
  LiveThread live({url, "--idle-exit", "0.5", "--labels", dir.path("live.csv"), "--cycles", "all", "--record",
                   dir.path("live.mcap"), "--report", dir.path("live.json"), "--preset", "carc-mid360", "-q"},
                  port);
  replay_args.insert(replay_args.end(), {"--to", url, "--device-address", device});
  const RunResult sent = replay(replay_args);
  const RunResult got = live.join();
  REQUIRE_MESSAGE(sent.code == 0, sent.err);
  REQUIRE_MESSAGE(got.code == 0, got.err);
  return {sent, read_json(dir.path("live.json"))};
}

/// The number after `label` in a line of text (the replay's summary,
/// "... corrupted 52 (10 oversize; 4810 returns)"; live's messages).
double number_after(const std::string& text, const std::string& label) {
  const auto at = text.find(label);
  REQUIRE_MESSAGE(at != std::string::npos, "no '", label, "' in: ", text);
  return std::stod(text.substr(at + label.size()));
}

}  // namespace

TEST_CASE("live SDK2, passive: every data type; labels equal cluster on the --record file; points are the input's") {
  TempDir dir("cli_live", "sdk2");
  const std::string input = dir.path("office.csv");
  REQUIRE(run_cli({"simulate", "--sensor", "mid360", "--scene", "office", "--seconds", "1.2", "--out", input, "-q"})
              .code == 0);
  const std::vector<std::string> preset{"--preset", "carc-mid360", "--window-time", "0.2"};
  const struct {
    const char* type;
    double quantum_m;
  } types[] = {{"1", 0.0009}, {"2", 0.0087}, {"3", 0.004}};  // 0.5 mm (5 mm) per axis; spherical: angle x range
  unsigned port = 47301;
  for (const auto& t : types) {
    const std::string type = t.type;
    CAPTURE(type);
    const std::string url = "livox-sdk2://127.0.0.1:" + std::to_string(port);
    std::vector<std::string> args{url, "--idle-exit", "0.5", "--labels", dir.path("live.csv"), "--cycles", "all",
                                  "--record", dir.path("live.mcap"), "--report", dir.path("live.json"), "-q"};
    args.insert(args.end(), preset.begin(), preset.end());
    LiveThread live(args, port);
    const RunResult sent = replay({input, "--to", url, "--device-address", "127.0.0.2", "--data-type",
                                    t.type, "-q"});
    const RunResult got = live.join();
    REQUIRE_MESSAGE(sent.code == 0, sent.err);
    REQUIRE_MESSAGE(got.code == 0, got.err);
    const auto report = read_json(dir.path("live.json"));
    INFO("packets: ", report["live"]["packets"].dump());
    const auto& packets = report["live"]["packets"];
    CHECK(packets["lost"] == 0);
    CHECK(packets["queue_drops"] == 0);
    CHECK(packets["malformed"] == 0);
    CHECK(report["live"]["protocol"] == "livox-sdk2");
    CHECK(report["live"]["end"] == "--idle-exit: no packets");
    check_same_points(input, dir.path("live.mcap"), t.quantum_m);
    check_offline_equal(dir, dir.path("live.csv"), dir.path("live.mcap"), preset);
    port += 2;
  }
}

TEST_CASE("live SDK2 --configure: discovery finds the LiDAR by serial number, points its streams at the host and "
          "sets its data type and work mode; its IMU's gravity mounts the objects preset") {
  TempDir dir("cli_live", "configure");
  const std::string url = "livox-sdk2://127.0.0.9:47401";
  // Not quiet: the setup's messages say where the mount came from.
  LiveThread live({url, "--configure", "--lidar", "EMU2CONFIG", "--discovery-address", "127.0.0.8", "--wait", "60",
                   "--data-type", "3", "--work-mode", "sampling", "--idle-exit", "0.5", "--report",
                   dir.path("live.json"), "--preset", "objects-mid360", "--foxglove", "127.0.0.1:0", "--no-status"},
                  56000);
  // A Mid-360 rolled 4 deg and pitched 12 deg down, at rest: its IMU reads gravity in that frame.
  const RunResult sent = replay({"--simulate", "--sensor", "mid360", "--seconds", "1.0", "--mount", "4,12,0",
                                  "--imu", "4,12", "--to", "livox-sdk2://127.0.0.9:1000", "--device-address",
                                  "127.0.0.8", "--serial", "EMU2CONFIG", "--wait-configure"});
  const RunResult got = live.join();
  REQUIRE_MESSAGE(sent.code == 0, sent.err);
  REQUIRE_MESSAGE(got.code == 0, got.err);
  const auto report = read_json(dir.path("live.json"));
  INFO("packets: ", report["live"]["packets"].dump());
  INFO("live: ", got.err);
  CHECK(report["live"]["address"] == "127.0.0.8");
  // The device took the parameter write's data type (spherical) and work mode (sampling, 0x01), and sent that type.
  CHECK(sent.out.find("configured by the host: data type 3, work mode 0x1\n") != std::string::npos);
  CHECK(report["live"]["data_type"] == 3);
  // Gravity from the IMU gives the mount; the plane search only measures the height.
  const auto& gravity = report["live"]["imu_gravity"];
  REQUIRE(gravity.is_object());
  CHECK(std::abs(gravity["roll_deg"].get<double>() - 4.0) < 0.05);  // exact readings: float rounding only
  CHECK(std::abs(gravity["pitch_deg"].get<double>() - 12.0) < 0.05);
  CHECK(gravity["samples"].get<int>() >= 90);  // 200 Hz over the first window
  CHECK(got.err.find("gravity from the IMU") != std::string::npos);
  CHECK(got.err.find("(the mount given is used)") != std::string::npos);
  CHECK_FALSE(report["ground"].contains("estimated_mount"));
  // The floor the plane search sees agrees with the IMU: both conventions place the sensor alike.
  const auto plane = got.err.find("ground of the first window: ");
  REQUIRE(plane != std::string::npos);
  CHECK(std::abs(number_after(got.err.substr(plane), "roll ") - 4.0) < 1.0);
  CHECK(std::abs(number_after(got.err.substr(plane), "pitch ") - 12.0) < 1.0);
  // The live view served every cycle (no viewer connected: nothing sent, nothing dropped).
  CHECK(report["live"]["foxglove"]["port"].get<int>() > 0);
  CHECK(report["live"]["foxglove"]["publishes_dropped"] == 0);
  CHECK(report["live"]["packets"]["point_packets"].get<int>() > 1000);
  CHECK(report["live"]["packets"]["lost"] == 0);
}

TEST_CASE("live SDK1: broadcast, handshake, heartbeats; every data type equals cluster on its recording") {
  TempDir dir("cli_live", "sdk1");
  const std::string avia = dir.path("avia.csv"), mid40 = dir.path("mid40.csv");
  REQUIRE(run_cli({"simulate", "--sensor", "avia", "--scene", "office", "--seconds", "1.2", "--out", avia, "-q"}).code == 0);
  REQUIRE(run_cli({"simulate", "--sensor", "mid40", "--scene", "office", "--seconds", "1.2", "--out", mid40, "-q"}).code == 0);
  const std::vector<std::string> preset{"--preset", "carc-avia", "--window-time", "0.2"};
  unsigned port = 45000, device = 20;
  for (const std::string type : {"0", "1", "2", "3", "4", "5", "7", "8"}) {
    CAPTURE(type);
    const std::string input = (type[0] == '0' || type[0] == '1') ? mid40 : avia;
    const std::string url = "livox-sdk1://127.0.0.1:" + std::to_string(port);
    std::vector<std::string> args{url, "--idle-exit", "0.5", "--labels", dir.path("live.csv"), "--cycles", "all",
                                  "--record", dir.path("live.mcap"), "--report", dir.path("live.json"), "-q"};
    args.insert(args.end(), preset.begin(), preset.end());
    LiveThread live(args, port);
    const RunResult sent = replay({input, "--to", url, "--device-address",
                                    "127.0.0." + std::to_string(device), "--data-type", type, "-q"});
    const RunResult got = live.join();
    REQUIRE_MESSAGE(sent.code == 0, sent.err);
    REQUIRE_MESSAGE(got.code == 0, got.err);
    const auto report = read_json(dir.path("live.json"));
    INFO("packets: ", report["live"]["packets"].dump());
    CHECK(report["live"]["protocol"] == "livox-sdk1");
    CHECK(report["live"]["packets"]["lost"] == 0);
    const bool spherical = type[0] == '1' || type[0] == '3' || type[0] == '5' || type[0] == '8';
    check_same_points(input, dir.path("live.mcap"), spherical ? 0.004 : 0.0009);
    check_offline_equal(dir, dir.path("live.csv"), dir.path("live.mcap"), preset);
    port += 1100;  // listen, command (+500) and data (+1000) ports of the next run
    ++device;
  }
}

TEST_CASE("live: loss, duplicates and reordering are counted and undone; a clock jump and a reboot start new "
          "clock epochs; GPS time is reported") {
  TempDir dir("cli_live", "faults");
  const std::string input = simulated_office(dir, "1.5");
  const auto report = run_passive_sdk2(dir, 47501, "127.0.0.3",
                                       {input, "--drop", "0.02", "--duplicate", "0.02", "--swap", "0.05", "--time-sync",
                                        "gps", "--clock-jump", "0.4:3600", "--reboot-at", "0.8", "-q"})
                          .second;
  INFO("packets: ", report["live"]["packets"].dump());
  const auto& packets = report["live"]["packets"];
  CHECK(packets["lost"].get<int>() > 10);        // about 2 % of 3,100 packets
  CHECK(packets["lost"].get<int>() < 150);
  CHECK(packets["duplicates"].get<int>() > 10);
  CHECK(packets["late"] == 0);                   // every swap within the reorder window
  CHECK(report["live"]["clock_epochs"] == 3);    // the clock jump and the reboot
  CHECK(report["live"]["time_sync"] == "GPS");
  // No flood of rejections: the stream stays in order across the reboot.
  CHECK(report["totals"]["rejected"]["time_backwards"].get<int>() == 0);
  CHECK(report["totals"]["rejected"]["time_jump"].get<int>() == 0);
  check_offline_equal(dir, dir.path("live.csv"), dir.path("live.mcap"), {"--preset", "carc-mid360"});
}

TEST_CASE("live SDK2: the packet counter wraps at 65535 unnoticed; damaged datagrams are counted and skipped; "
          "PTP time is reported") {
  TempDir dir("cli_live", "damaged");
  const std::string input = simulated_office(dir, "1.2");
  // 2,500 packets from counter 65000: the counter wraps after 536.
  const auto run = run_passive_sdk2(dir, 46901, "127.0.0.7",
                                    {input, "--first-counter", "65000", "--corrupt", "0.03", "--time-sync", "ptp"});
  const RunResult& sent = run.first;  // no structured binding: INFO captures it (clang 14)
  const nlohmann::json& report = run.second;
  INFO("packets: ", report["live"]["packets"].dump());
  INFO("replay: ", sent.out);
  const auto packets_sent = static_cast<std::uint64_t>(number_after(sent.out, "replay: "));
  const auto returns_sent = static_cast<std::uint64_t>(number_after(sent.out, "point packets ("));
  const auto damaged = static_cast<std::uint64_t>(number_after(sent.out, "corrupted "));
  const auto oversize = static_cast<std::uint64_t>(number_after(sent.out, "corrupted " + std::to_string(damaged) + " ("));
  const auto damaged_returns = static_cast<std::uint64_t>(number_after(sent.out, "oversize; "));
  CHECK(packets_sent > 2000);
  CHECK(damaged > 30);  // about 3 % of 2,500, every fifth oversize
  CHECK(oversize > 5);
  const auto& packets = report["live"]["packets"];
  CHECK(packets["oversize"] == oversize);
  CHECK(packets["malformed"] == damaged - oversize);
  // Each damaged packet is one gap in the counter, across the wrap too; nothing else is missing.
  CHECK(packets["lost"] == damaged);
  CHECK(packets["counter_jumps"] == 0);
  CHECK(packets["late"] == 0);
  CHECK(packets["point_packets"] == packets_sent - damaged);
  CHECK(packets["returns"] == returns_sent - damaged_returns);
  CHECK(report["live"]["time_sync"] == "PTP");
  CHECK(report["live"]["clock_epochs"] == 1);
  check_offline_equal(dir, dir.path("live.csv"), dir.path("live.mcap"), {"--preset", "carc-mid360"});
}

TEST_CASE("live: a second LiDAR on the same port is counted as foreign and never mixed in") {
  TempDir dir("cli_live", "two");
  const std::string input = dir.path("office.csv");
  const std::string forest = dir.path("forest.csv");
  REQUIRE(run_cli({"simulate", "--sensor", "mid360", "--seconds", "1.0", "--out", input, "-q"}).code == 0);
  REQUIRE(run_cli({"simulate", "--sensor", "mid360", "--scene", "forest", "--seconds", "1.0", "--out", forest, "-q"})
              .code == 0);
  const std::string url = "livox-sdk2://127.0.0.1:47701";
  LiveThread live({url, "--lidar", "127.0.0.4", "--idle-exit", "0.5", "--labels", dir.path("live.csv"), "--cycles",
                   "all", "--record", dir.path("live.mcap"), "--report", dir.path("live.json"), "--preset",
                   "carc-mid360", "-q"},
                  47701);
  RunResult other;
  std::thread second([&] {  // another Mid-360 streaming to the same port (its own point and IMU ports)
    other = replay({forest, "--to", url, "--device-address", "127.0.0.5", "-q"});
  });
  const RunResult sent = replay({input, "--to", url, "--device-address", "127.0.0.4", "-q"});
  second.join();
  const RunResult got = live.join();
  REQUIRE_MESSAGE(sent.code == 0, sent.err);
  REQUIRE_MESSAGE(other.code == 0, other.err);
  REQUIRE_MESSAGE(got.code == 0, got.err);
  const auto report = read_json(dir.path("live.json"));
  INFO("packets: ", report["live"]["packets"].dump());
  CHECK(report["live"]["address"] == "127.0.0.4");
  CHECK(report["live"]["packets"]["foreign"].get<int>() > 500);  // the forest's 680 packets (most rays hit nothing)
  CHECK(report["live"]["packets"]["lost"] == 0);
  check_same_points(input, dir.path("live.mcap"), 0.0009);  // only the chosen LiDAR's points
  check_offline_equal(dir, dir.path("live.csv"), dir.path("live.mcap"), {"--preset", "carc-mid360"});
}

TEST_CASE("live: SIGINT under load ends the run cleanly; every output is complete and replays to the same labels") {
  TempDir dir("cli_live", "sigint");
  const std::string input = dir.path("office.csv");
  REQUIRE(run_cli({"simulate", "--sensor", "mid360", "--seconds", "4", "--out", input, "-q"}).code == 0);
  const std::string url = "livox-sdk2://127.0.0.1:47801";
  LiveThread live({url, "--labels", dir.path("live.csv"), "--cycles", "all", "--record", dir.path("live.mcap"),
                   "--report", dir.path("live.json"), "--mcap", dir.path("view.mcap"), "--preset", "carc-mid360",
                   "-q"},
                  47801);
  std::thread interrupt([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(2000));  // half of the stream sent
    std::raise(SIGINT);  // live's handler is installed while it runs
  });
  const RunResult sent = replay({input, "--to", url, "--device-address", "127.0.0.6", "-q"});
  interrupt.join();
  const RunResult got = live.join();
  REQUIRE_MESSAGE(got.code == 0, got.err);
  CHECK(sent.code == 0);
  const auto report = read_json(dir.path("live.json"));
  INFO("packets: ", report["live"]["packets"].dump());
  CHECK(report["live"]["end"] == "stopped by a signal");
  CHECK(report["live"]["packets"]["point_packets"].get<int>() < 7000);  // stopped before the 8,334 packets were sent
  CHECK(report["totals"]["cycles"].get<int>() > 3);
  // The recording and the view are complete MCAP files; the recording replays to the live labels.
  CHECK(run_cli({"info", dir.path("view.mcap")}).code == 0);
  check_offline_equal(dir, dir.path("live.csv"), dir.path("live.mcap"), {"--preset", "carc-mid360"});
}

TEST_CASE("live: bad sources and options are usage errors; silence is a network error (exit 6)") {
  CHECK(run_cli({"live"}).code == 2);
  CHECK(run_cli({"live", "udp://1.2.3.4"}).code == 2);
  const RunResult bad_host = run_cli({"live", "livox-sdk2://1.2.3"});
  CHECK(bad_host.code == 2);
  CHECK(bad_host.err.find("dotted IPv4") != std::string::npos);
  CHECK(run_cli({"live", "livox-sdk2://:70000"}).code == 2);
  CHECK(run_cli({"live", "livox-sdk1://", "--configure"}).code == 2);
  CHECK(run_cli({"live", "livox-sdk2://", "--verify"}).code == 2);
  CHECK(run_cli({"live", "livox-sdk2://", "--format", "csv"}).code == 2);
  const RunResult silent = run_cli({"live", "livox-sdk2://127.0.0.1:47601", "--wait", "0.3", "-q"});
  CHECK(silent.code == 6);
  CHECK(silent.err.find("127.0.0.1:47601") != std::string::npos);
  CHECK(run_cli({"replay", "--simulate"}).code == 2);  // no --to
  CHECK(run_cli({"replay", "--simulate", "--to", "livox-sdk2://", "--data-type", "7"}).code == 2);
  CHECK(run_cli({"replay", "--simulate", "--to", "livox-sdk2://", "--corrupt", "1.5"}).code == 2);
  CHECK(run_cli({"replay", "--simulate", "--to", "livox-sdk2://", "--first-counter", "65536"}).code == 2);
  const RunResult no_counter = run_cli({"replay", "--simulate", "--to", "livox-sdk1://", "--first-counter", "1"});
  CHECK(no_counter.code == 2);
  CHECK(no_counter.err.find("SDK2") != std::string::npos);
}

TEST_CASE("live: two LiDARs on one port, one engine each; every output per LiDAR equals cluster on its recording") {
  TempDir dir("cli_live", "several");
  const std::string office = dir.path("office.csv"), forest = dir.path("forest.csv");
  REQUIRE(run_cli({"simulate", "--sensor", "mid360", "--seconds", "1.0", "--out", office, "-q"}).code == 0);
  REQUIRE(run_cli({"simulate", "--sensor", "mid360", "--scene", "forest", "--seconds", "1.0", "--out", forest, "-q"})
              .code == 0);
  const std::string url = "livox-sdk2://127.0.0.1:47751";
  LiveThread live({url, "--lidar", "127.0.0.14", "--lidar", "127.0.0.15", "--idle-exit", "0.5", "--labels",
                   dir.path("live.csv"), "--cycles", "all", "--record", dir.path("live.mcap"), "--report",
                   dir.path("live.json"), "--preset", "carc-mid360", "-q"},
                  47751);
  RunResult second;
  std::thread other([&] { second = replay({forest, "--to", url, "--device-address", "127.0.0.15", "-q"}); });
  const RunResult first = replay({office, "--to", url, "--device-address", "127.0.0.14", "-q"});
  other.join();
  const RunResult got = live.join();
  REQUIRE_MESSAGE(first.code == 0, first.err);
  REQUIRE_MESSAGE(second.code == 0, second.err);
  REQUIRE_MESSAGE(got.code == 0, got.err);
  CHECK_FALSE(fs::exists(dir.path("live.csv")));  // one output per LiDAR, none shared
  for (const auto& lidar : {std::pair<std::string, std::string>{"127.0.0.14", office}, {"127.0.0.15", forest}}) {
    const std::string id = lidar.first, input = lidar.second;  // (no structured binding: CAPTURE needs a variable)
    CAPTURE(id);
    const auto report = read_json(dir.path("live-" + id + ".json"));
    INFO("packets: ", report["live"]["packets"].dump());
    CHECK(report["live"]["address"] == id);
    CHECK(report["live"]["packets"]["lost"] == 0);
    CHECK(report["live"]["packets"]["queue_drops"] == 0);
    check_same_points(input, dir.path("live-" + id + ".mcap"), 0.0009);  // only this LiDAR's points
    check_offline_equal(dir, dir.path("live-" + id + ".csv"), dir.path("live-" + id + ".mcap"),
                        {"--preset", "carc-mid360"});
  }
  // Standard output cannot be shared by several LiDARs.
  const RunResult shared = run_cli({"live", url, "--lidar", "127.0.0.14", "--lidar", "127.0.0.15", "--labels", "-",
                                    "--wait", "0.2", "-q"});
  CHECK(shared.code == 2);
  CHECK(shared.err.find("one per LiDAR") != std::string::npos);
}

TEST_CASE("live SDK1: two LiDARs, one handshake and engine each, share the data port; each equals cluster on its recording") {
  TempDir dir("cli_live", "several_sdk1");
  const std::string office = dir.path("office.csv"), forest = dir.path("forest.csv");
  REQUIRE(run_cli({"simulate", "--sensor", "avia", "--seconds", "1.0", "--out", office, "-q"}).code == 0);
  REQUIRE(run_cli({"simulate", "--sensor", "avia", "--scene", "forest", "--seconds", "1.0", "--out", forest, "-q"})
              .code == 0);
  const std::string url = "livox-sdk1://127.0.0.1:53500";
  LiveThread live({url, "--lidar", "127.0.0.16", "--lidar", "127.0.0.17", "--idle-exit", "0.5", "--labels",
                   dir.path("live.csv"), "--cycles", "all", "--record", dir.path("live.mcap"), "--report",
                   dir.path("live.json"), "--preset", "carc-avia", "-q"},
                  53500);
  RunResult second;
  std::thread other([&] { second = replay({forest, "--to", url, "--device-address", "127.0.0.17", "-q"}); });
  const RunResult first = replay({office, "--to", url, "--device-address", "127.0.0.16", "-q"});
  other.join();
  const RunResult got = live.join();
  REQUIRE_MESSAGE(first.code == 0, first.err);
  REQUIRE_MESSAGE(second.code == 0, second.err);
  REQUIRE_MESSAGE(got.code == 0, got.err);
  for (const auto& lidar : {std::pair<std::string, std::string>{"127.0.0.16", office}, {"127.0.0.17", forest}}) {
    const std::string id = lidar.first, input = lidar.second;
    CAPTURE(id);
    const auto report = read_json(dir.path("live-" + id + ".json"));
    INFO("packets: ", report["live"]["packets"].dump());
    CHECK(report["live"]["address"] == id);
    CHECK(report["live"]["protocol"] == "livox-sdk1");
    CHECK(report["live"]["packets"]["lost"] == 0);
    check_same_points(input, dir.path("live-" + id + ".mcap"), 0.0009);
    check_offline_equal(dir, dir.path("live-" + id + ".csv"), dir.path("live-" + id + ".mcap"),
                        {"--preset", "carc-avia"});
  }
}

TEST_CASE("live: a LiDAR of the run that never sends fails the run (exit 6); the others stop with complete outputs") {
  TempDir dir("cli_live", "one_silent");
  const std::string office = simulated_office(dir, "3.0");
  const std::string url = "livox-sdk2://127.0.0.1:47771";
  LiveThread live({url, "--lidar", "127.0.0.18", "--lidar", "127.0.0.19", "--wait", "1", "--labels",
                   dir.path("live.csv"), "--cycles", "all", "--record", dir.path("live.mcap"), "--report",
                   dir.path("live.json"), "--preset", "carc-mid360", "-q"},
                  47771);
  const RunResult sent = replay({office, "--to", url, "--device-address", "127.0.0.18", "-q"});
  const RunResult got = live.join();
  CHECK_MESSAGE(sent.code == 0, sent.err);
  CHECK(got.code == 6);
  INFO("stderr: ", got.err);
  CHECK(got.err.find("no SDK2 point packet from LiDAR at 127.0.0.19") != std::string::npos);
  const auto report = read_json(dir.path("live-127.0.0.18.json"));
  CHECK(report["live"]["end"] == "stopped: another LiDAR of the run failed");
  CHECK(report["live"]["packets"]["returns"] > 0);
  // What the stopped LiDAR's run wrote is whole: its recording replays to
  // the labels it wrote.
  check_offline_equal(dir, dir.path("live-127.0.0.18.csv"), dir.path("live-127.0.0.18.mcap"),
                      {"--preset", "carc-mid360"});
}
