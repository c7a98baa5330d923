// SPDX-License-Identifier: MIT
// `streamclust replay`: options and the run of the Livox emulator.

#include "cli/replay.hpp"

#include <streamclust/io/reader.hpp>

#include <cstdio>
#include <memory>
#include <string>

namespace streamclust::cli {

#ifndef STREAMCLUST_TOOL_ROS2
int run_replay_ros2(const ReplayOptions&, SimulatedStream, std::ostream&, std::ostream&) {
  throw UsageError("--to ros2://: this streamclust was built without ROS 2 support (it needs Cyclone DDS: "
                   "apt-get install cyclonedds-dev, then build again)");
}
#endif

namespace {

double parse_probability(const std::string& option, const std::string& value) {
  const double p = parse_number(option, value);
  if (!(p >= 0.0 && p <= 1.0)) throw UsageError(option + ": expected a probability in [0, 1], got '" + value + "'");
  return p;
}

}  // namespace

ReplayOptions parse_replay_options(const std::vector<std::string>& args) {
  ReplayOptions o;
  bool to_given = false, ego_speed_given = false, first_counter_given = false;
  std::vector<std::string> ros2_only, livox_only;  // options of one kind of target
  for (ArgCursor c(args); !c.done(); c.next()) {
    const std::string& a = c.option();
    if (parse_input_option(c, o.read)) continue;
    // --speed is the replay's rate; the simulated sensor's own motion is
    // --ego-speed here (simulate's --speed).
    if (o.simulate && a != "--speed" && parse_simulation_option(c, o.simulation)) continue;
    if (a == "--simulate") {
      o.simulate = true;
    } else if (a == "--ego-speed") {
      o.simulation.speed = static_cast<float>(parse_number(a, c.value()));
      ego_speed_given = true;
    } else if (a == "--to") {
      const std::string v = c.value();
      if (v.rfind("ros2://", 0) == 0) {
        o.ros2.topic = v.substr(7);
        if (o.ros2.topic.empty()) throw UsageError("--to ros2:///TOPIC: expected a topic (e.g. ros2:///livox/lidar)");
      } else {
        o.emulator.target = parse_livox_url(v);
      }
      to_given = true;
    } else if (a == "--imu-topic") {
      o.ros2.imu_topic = c.value();
      ros2_only.push_back(a);
    } else if (a == "--odom-topic") {
      o.ros2.odom_topic = c.value();
      ros2_only.push_back(a);
    } else if (a == "--message") {
      o.ros2.point_cloud2 = c.choice({"custom", "pointcloud2"}) == "pointcloud2";
      ros2_only.push_back(a);
    } else if (a == "--qos") {
      o.ros2.best_effort = c.choice({"reliable", "best-effort"}) == "best-effort";
      ros2_only.push_back(a);
    } else if (a == "--subscribers") {
      const std::string v = c.value();
      std::int64_t n = 0;
      if (!io::detail::parse_int64(v, n) || n < 0 || n > 1000) throw UsageError("--subscribers: expected 0 to 1000, got '" + v + "'");
      o.ros2.subscribers = static_cast<std::size_t>(n);
      ros2_only.push_back(a);
    } else if (a == "--domain") {
      const std::size_t d = parse_count(a, c.value());
      if (d > 232) throw UsageError("--domain: expected 0 to 232");
      o.ros2.domain = static_cast<std::uint32_t>(d);
      ros2_only.push_back(a);
    } else if (a == "--dds-loopback") {
      o.ros2.loopback = true;
      ros2_only.push_back(a);
    } else if (a == "--message-seconds") {
      o.ros2.message_seconds = parse_positive(a, c.value());
      if (o.ros2.message_seconds > 4.0) throw UsageError("--message-seconds: expected at most 4 s (CustomMsg offsets are 32-bit ns)");
      ros2_only.push_back(a);
    } else if (a == "--device-address") {
      livox_only.push_back(a);
      const std::string v = c.value();
      const auto address = live::parse_address(v);
      if (!address) throw UsageError("--device-address: expected a dotted IPv4 address, got '" + v + "'");
      o.emulator.device_address = *address;
    } else if (a == "--serial") {
      livox_only.push_back(a);
      o.emulator.serial = c.value();
      if (o.emulator.serial.empty() || o.emulator.serial.size() > 16)
        throw UsageError("--serial: expected 1 to 16 characters");
    } else if (a == "--data-type") {
      livox_only.push_back(a);
      const std::string v = c.value();
      std::int64_t n = 0;
      if (!io::detail::parse_int64(v, n) || n < 0 || n > 17) throw UsageError("--data-type: expected a Livox point data type, got '" + v + "'");
      o.emulator.data_type = static_cast<std::uint8_t>(n);
    } else if (a == "--speed") {
      o.emulator.speed = parse_number(a, c.value());
      if (!(o.emulator.speed >= 0.0 && o.emulator.speed <= 1000.0))
        throw UsageError("--speed: expected a factor in [0, 1000] (0: as fast as possible)");
    } else if (a == "--wait-configure") {
      livox_only.push_back(a);
      o.emulator.wait_for_configure = true;
    } else if (a == "--drop") {
      livox_only.push_back(a);
      o.emulator.drop = parse_probability(a, c.value());
    } else if (a == "--duplicate") {
      livox_only.push_back(a);
      o.emulator.duplicate = parse_probability(a, c.value());
    } else if (a == "--swap") {
      livox_only.push_back(a);
      o.emulator.swap = parse_probability(a, c.value());
    } else if (a == "--corrupt") {
      livox_only.push_back(a);
      o.emulator.corrupt = parse_probability(a, c.value());
    } else if (a == "--first-counter") {
      livox_only.push_back(a);
      const std::string v = c.value();
      std::int64_t n = 0;
      if (!io::detail::parse_int64(v, n) || n < 0 || n > 65535) throw UsageError("--first-counter: expected 0 to 65535, got '" + v + "'");
      o.emulator.first_counter = static_cast<std::uint16_t>(n);
      first_counter_given = true;
    } else if (a == "--fault-seed") {
      o.emulator.seed = parse_count(a, c.value());
    } else if (a == "--reboot-at") {
      livox_only.push_back(a);
      o.emulator.reboot_at = parse_number(a, c.value());
      if (!(*o.emulator.reboot_at > 0.0)) throw UsageError("--reboot-at: expected seconds > 0 of the stream");
    } else if (a == "--clock-jump") {
      livox_only.push_back(a);
      const std::string v = c.value();
      const auto colon = v.find(':');
      if (colon == std::string::npos) throw UsageError("--clock-jump: expected AT:SECONDS (e.g. 1.5:3600), got '" + v + "'");
      o.emulator.clock_jump = std::make_pair(parse_number(a, v.substr(0, colon)), parse_number(a, v.substr(colon + 1)));
      if (!(o.emulator.clock_jump->first > 0.0) || !(std::abs(o.emulator.clock_jump->second) < 1e9))
        throw UsageError("--clock-jump: expected AT > 0 and |SECONDS| < 1e9");
    } else if (a == "--time-sync") {
      livox_only.push_back(a);
      const std::string v = c.choice({"none", "ptp", "gps"});
      o.emulator.sync = v == "ptp"   ? live::LivoxTimeSync::ptp
                        : v == "gps" ? live::LivoxTimeSync::gps
                                     : live::LivoxTimeSync::none;
    } else if (a == "--imu") {
      const std::array<double, 3> m = parse_mount(c.value() + ",0");
      o.emulator.imu_mount = std::array<double, 2>{m[0], m[1]};
    } else if (a == "--wait") {
      o.emulator.connect_timeout =
          std::chrono::milliseconds(static_cast<std::int64_t>(parse_positive(a, c.value()) * 1000.0));
    } else if (a == "--quiet" || a == "-q") {
      o.quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError("unknown option '" + a + "' (see streamclust replay --help)");
    } else if (o.input.empty()) {
      o.input = a;
    } else {
      throw UsageError("more than one INPUT: '" + o.input + "' and '" + a + "'");
    }
  }
  if (!to_given) throw UsageError("missing --to livox-sdk2://HOST[:PORT], livox-sdk1://HOST[:PORT] or ros2:///TOPIC");
  if (o.simulate == !o.input.empty()) throw UsageError("expected either INPUT or --simulate (see streamclust replay --help)");
  if (ego_speed_given && !o.simulate) throw UsageError("--ego-speed: only with --simulate (the simulated sensor's motion)");
  if (o.simulate) validate_simulation_options(o.simulation);
  if (!o.ros2.topic.empty()) {
    if (!livox_only.empty()) throw UsageError(livox_only.front() + ": an option of Livox targets (livox-sdk2://, livox-sdk1://)");
    return o;
  }
  if (!ros2_only.empty()) throw UsageError(ros2_only.front() + ": an option of --to ros2:///TOPIC");
  const bool sdk2 = o.emulator.target.protocol == LivoxProtocol::sdk2;
  const int t = o.emulator.data_type.value_or(sdk2 ? 1 : 2);
  if (sdk2 ? !(t >= 1 && t <= 3) : !(t <= 5 || t == 7 || t == 8))
    throw UsageError(sdk2 ? "--data-type: SDK2 point data types are 1, 2 and 3"
                          : "--data-type: SDK1 point data types are 0-5, 7 and 8");
  if (o.emulator.wait_for_configure && !sdk2) throw UsageError("--wait-configure: an SDK2 device's mode (SDK1 always handshakes)");
  if (first_counter_given && !sdk2) throw UsageError("--first-counter: SDK2 packets have a counter (SDK1 packets have none)");
  return o;
}

std::string replay_help() {
  return R"(usage: streamclust replay INPUT --to URL [options]
       streamclust replay --simulate [scenario options] --to URL [options]

Emulates a Livox LiDAR on the network: sends INPUT (a point file or recording
that cluster reads) or a simulated scene as the device's UDP packets at the
device's rate, or as a ROS 2 driver's messages, for `streamclust live`,
`streamclust ros2` and anyone without the hardware.

  --to livox-sdk2://HOST[:PORT]   a Mid-360: point packets to HOST:PORT (default 56301) from
                                  port 56300, IMU to PORT+100 from 56400
  --to livox-sdk1://HOST[:PORT]   an Avia: broadcasts to HOST:PORT (default 55000) from its
                                  command port 65000, answers the handshake, streams to the
                                  host's data port, stops when the heartbeats stop
  --to ros2:///TOPIC              a ROS 2 driver over DDS (Cyclone DDS): a recording's messages
                                  of its point topic as recorded (CDR), anything else as
                                  livox_ros_driver2/msg/CustomMsg messages; IMU messages on
                                  --imu-topic
  --device-address IP             the LiDAR's address (on loopback e.g. 127.0.0.2; default: any)
  --serial SN                     its serial number / broadcast code
  --data-type N                   SDK2: 1 (int32 mm, default), 2 (int16 cm), 3 (spherical);
                                  SDK1: 0-5, 7, 8 (default 2, extended Cartesian)
  --wait-configure                SDK2: answer discovery and wait for a host's parameter write
  --speed X                       x the recorded rate (default 1; 0: as fast as possible)
  --imu ROLL,PITCH                send a resting IMU's samples (200 Hz) for this mount [deg]
  --time-sync none|ptp|gps        the clock's sync type (ptp, gps: Unix time; SDK1 GPS as UTC fields)
  --wait S                        seconds to wait for a host or subscribers (default 10)
ros2 targets:
  --message custom|pointcloud2    what non-ROS 2 input becomes: CustomMsg (default) or the Livox
                                  driver's sensor_msgs/msg/PointCloud2 (x y z intensity tag line
                                  timestamp)
  --message-seconds S             seconds of points per message (default 0.1: the driver's 10 Hz)
  --imu-topic TOPIC               the IMU messages' topic (default /livox/imu)
  --odom-topic TOPIC              also the sensor's poses as nav_msgs/msg/Odometry (frame odom,
                                  child livox_frame): --simulate's trajectory (200 Hz), or a
                                  recording's odometry topic as recorded
  --qos reliable|best-effort      the publishers' reliability (default reliable, keep last 256,
                                  as livox_ros_driver2 publishes)
  --subscribers N                 wait for N subscribers of the point topic before sending
                                  (default 1, at most --wait seconds; 0: send at once)
  --domain N                      the DDS domain (default: ROS_DOMAIN_ID, else 0)
  --dds-loopback                  discovery on 127.0.0.1 only, by unicast
faults (Livox targets):
  --drop P  --duplicate P  --swap P   per point packet (swap: sent after the next one)
  --corrupt P                     per point packet: a damaged datagram instead (in turn truncated,
                                  too long, unknown data type, wrong CRC (SDK1: bad time type),
                                  oversize: 2000 bytes)
  --fault-seed N                  their random seed (default 1)
  --clock-jump AT:S               at AT seconds of stream, the clock jumps by S seconds
  --reboot-at AT                  at AT seconds, a reboot: clock from 0, packet counter from 0
  --first-counter N               SDK2: the first packet's counter (udp_cnt; e.g. 65000 wraps
                                  after 536 packets, a quarter of a second)
input: --format, --topic, --time-unit, --point-rate, --time-origin as for cluster;
--simulate takes simulate's scenario options (--sensor, --scene, --seconds, --seed, ...),
with the sensor's ego-motion as --ego-speed M/S (here --speed is the replay's rate).

examples:
  streamclust replay --simulate --sensor mid360 --scene office --seconds 10 --to livox-sdk2://127.0.0.1
  streamclust replay run.mcap --to livox-sdk2://192.168.1.50 --device-address 192.168.1.150
  streamclust replay run.mcap --to ros2:///livox/lidar
Exit codes: 0 ok, 2 usage error, 4 input error, 6 network error.
)";
}

int run_replay(const ReplayOptions& o, std::ostream& out, std::ostream& err) {
  if (!o.ros2.topic.empty()) return run_replay_ros2(o, o.simulate ? simulate_stream(o.simulation) : SimulatedStream{}, out, err);
  LivoxEmulator emulator(o.emulator);
  // A simulated stream is made before the host connects: a configured or
  // handshaken device streams at once.
  std::vector<io::Record> simulated;
  if (o.simulate) simulated = simulate_records(o.simulation);
  emulator.connect();
  bool host_present = true;
  if (o.simulate) {
    host_present = emulator.send(simulated);
  } else {
    auto reader = io::open_reader(o.input, o.read);
    std::vector<io::Record> chunk;
    while (host_present && (chunk.clear(), reader->read(chunk, 4096) > 0)) host_present = emulator.send(chunk);
  }
  if (host_present) host_present = emulator.finish();
  const EmulatorCounters& c = emulator.counters();
  if (!o.quiet) {
    out << "streamclust: replay: " << c.packets << " point packets (" << c.returns << " returns), " << c.imu_packets
        << " IMU packets; dropped " << c.dropped << ", duplicated " << c.duplicated << ", swapped " << c.swapped
        << ", corrupted " << c.corrupted << " (" << c.oversize << " oversize; " << c.corrupted_returns << " returns)"
        << (host_present ? "" : "; the host went away") << "\n";
    if (o.emulator.wait_for_configure) {
      out << "streamclust: replay: configured by the host: data type " << int{emulator.data_type()} << ", work mode ";
      if (const auto mode = emulator.work_mode()) {
        out << "0x" << std::hex << int{*mode} << std::dec;
      } else {
        out << "not written";
      }
      out << "\n";
    }
  }
  (void)err;
  return kOk;
}

}  // namespace streamclust::cli
