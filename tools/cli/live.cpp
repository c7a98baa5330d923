// SPDX-License-Identifier: MIT
// `streamclust live`: options, the connection with the LiDAR, the receiver and
// engine threads, and the driver of `cluster` fed by the live stream.

#include "cli/live.hpp"

#include "cli/cluster.hpp"
#include "cli/foxglove_frames.hpp"
#include "cli/json.hpp"
#include "cli/live_feed.hpp"
#include "cli/live_sessions.hpp"
#include "cli/live_status.hpp"
#include "cli/run_setup.hpp"
#include "live/foxglove_server.hpp"

#include <streamclust/live/sdk1_packets.hpp>
#include <streamclust/live/sdk2_packets.hpp>
#include <streamclust/motion/imu_gravity.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include <unistd.h>

namespace streamclust::cli {

namespace {

std::atomic<bool> g_stop_requested{false};

extern "C" void request_stop(int) { g_stop_requested.store(true); }

/// SIGINT and SIGTERM end the stream cleanly while installed (the previous
/// handlers come back after the run).
class StopSignals {
 public:
  StopSignals() {
    g_stop_requested.store(false);
    struct sigaction a {};
    a.sa_handler = request_stop;
    sigemptyset(&a.sa_mask);
    ::sigaction(SIGINT, &a, &old_int_);
    ::sigaction(SIGTERM, &a, &old_term_);
  }
  ~StopSignals() {
    ::sigaction(SIGINT, &old_int_, nullptr);
    ::sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

live::LivoxPacketFormat packet_format(LivoxProtocol protocol) {
  return protocol == LivoxProtocol::sdk2 ? live::sdk2_packet_format() : live::sdk1_packet_format();
}

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

std::uint32_t parse_address_option(const std::string& option, const std::string& value) {
  const auto a = live::parse_address(value);
  if (!a) throw UsageError(option + ": expected a dotted IPv4 address (e.g. 192.168.1.50), got '" + value + "'");
  return *a;
}

}  // namespace

std::pair<std::string, std::uint16_t> parse_foxglove_endpoint(const std::string& text) {
  const auto colon = text.rfind(':');
  const std::string address = colon == std::string::npos ? "0.0.0.0" : text.substr(0, colon);
  const std::string port = colon == std::string::npos ? text : text.substr(colon + 1);
  std::int64_t p = 0;
  if (!io::detail::parse_int64(port, p) || p < 0 || p > 65535 || address.empty())
    throw UsageError("--foxglove: expected [ADDRESS:]PORT (e.g. 8765 or 127.0.0.1:8765), got '" + text + "'");
  return {address, static_cast<std::uint16_t>(p)};
}

LivoxSourceUrl parse_livox_url(const std::string& text) {
  try {
    return live::parse_livox_source_url(text);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

LiveOptions parse_live_options(const std::vector<std::string>& args) {
  LiveOptions o;
  std::vector<std::string> cluster_args;
  for (ArgCursor c(args); !c.done(); c.next()) {
    const std::string& a = c.option();
    if (a == "--configure") {
      o.configure = true;
    } else if (a == "--lidar") {
      const std::string v = c.value();
      if (v.empty()) throw UsageError("--lidar: expected a serial number or an IPv4 address");
      o.lidars.push_back(v);
    } else if (a == "--discovery-address") {
      o.discovery_address = parse_address_option(a, c.value());
    } else if (a == "--data-type") {
      const std::string v = c.choice({"1", "2", "3"});
      o.data_type = static_cast<std::uint8_t>(v[0] - '0');
    } else if (a == "--work-mode") {
      c.choice({"sampling"});
      o.work_mode_sampling = true;
    } else if (a == "--duration") {
      o.duration = parse_positive(a, c.value());
    } else if (a == "--idle-exit") {
      o.idle_exit = parse_positive(a, c.value());
    } else if (a == "--wait") {
      o.first_packet_timeout = parse_positive(a, c.value());
    } else if (a == "--record") {
      o.record_path = c.value();
    } else if (a == "--foxglove") {
      o.foxglove = c.value();
      parse_foxglove_endpoint(o.foxglove);  // a usage error now, not after the LiDAR answered
    } else if (a == "--queue") {
      o.queue_packets = parse_count(a, c.value());
      if (o.queue_packets < 2 || o.queue_packets > (1u << 20)) throw UsageError("--queue: expected 2 to 1048576 packets");
    } else if (a == "--reorder") {
      const std::string v = c.value();
      std::int64_t n = 0;
      if (!io::detail::parse_int64(v, n) || n < 0 || n > 1024) throw UsageError("--reorder: expected 0 to 1024 packets, got '" + v + "'");
      o.reorder_packets = static_cast<std::size_t>(n);
    } else if (a == "--no-status") {
      o.status = false;
    } else if (a == "--verify") {
      throw UsageError("--verify: the live command does not keep the window's input; verify a --record file with cluster --verify");
    } else if (a.rfind("livox-sdk", 0) == 0 && a.find("://") != std::string::npos) {
      if (!o.source_text.empty()) throw UsageError("more than one SOURCE: '" + o.source_text + "' and '" + a + "'");
      o.source_text = a;
    } else {
      cluster_args.push_back(a);  // an option of `cluster` (its parser takes its value) or a stray argument
    }
  }
  if (o.source_text.empty()) {
    for (const std::string& a : cluster_args) {
      if (!a.empty() && a[0] != '-' && a.find("://") != std::string::npos) o.source = parse_livox_url(a);  // names the problem
    }
    throw UsageError("missing SOURCE (e.g. livox-sdk2://192.168.1.50; see streamclust live --help)");
  }
  o.source = parse_livox_url(o.source_text);
  cluster_args.push_back(o.source_text);  // cluster's INPUT: names the source in messages and the report
  for (const std::string& a : cluster_args) {
    if (a == "--format" || a == "--topic" || a == "--time-unit" || a == "--point-rate" || a == "--time-origin")
      throw UsageError(a + ": an option of recorded inputs; a live source has its own times");
  }
  o.cluster = parse_cluster_options(cluster_args);
  if (o.cluster.quiet) o.status = false;
  if (o.source.protocol == LivoxProtocol::sdk1 && (o.configure || o.data_type || o.work_mode_sampling))
    throw UsageError("--configure, --data-type and --work-mode are SDK2 options (SDK1 always handshakes)");
  if (!o.configure && (o.data_type || o.work_mode_sampling))
    throw UsageError("--data-type and --work-mode are written to the LiDAR by --configure");
  return o;
}

std::string live_help() {
  return R"(usage: streamclust live SOURCE [options]

Clusters a Livox LiDAR's stream as it arrives over the network, without ROS
or the Livox SDK, with the presets, policies and outputs of `cluster`.

SOURCE:
  livox-sdk2://[HOST_IP][:PORT]   Mid-360, Mid-360S, HAP: points on PORT (default 56301),
                                  IMU on PORT+100, commands from PORT-200
  livox-sdk1://[HOST_IP][:PORT]   Avia, Mid-40, Mid-70, Horizon, Tele-15: broadcasts heard on
                                  PORT (default 55000), commands from PORT+500, data and IMU on
                                  PORT+1000; always handshakes and sends heartbeats
  HOST_IP is this host's address on the LiDAR's network (default: every interface).
the LiDAR:
  --configure                     SDK2: discovery, then point the LiDAR's point and IMU streams at
                                  this host (without it the LiDAR's stored destination is used)
  --lidar SERIAL|IP               the LiDAR to use (default: the first one heard; a serial number
                                  is found by discovery); others on the port are counted as
                                  foreign and never mixed in. One LiDAR per run
  With --ground (the objects presets) and no --mount or --poses, a LiDAR with an IMU gives the
  mount's roll and pitch from the first window's accelerometer (at rest) instead of the plane search.
  --discovery-address IP          where discovery requests go (default 255.255.255.255)
  --data-type 1|2|3               SDK2 --configure: int32 mm, int16 cm or spherical points
  --work-mode sampling            SDK2 --configure: also start sampling
  --wait S                        seconds to wait for discovery, handshake and first packet (default 10)
run:
  --duration S                    stop after S seconds
  --idle-exit S                   stop after S seconds without packets
  (SIGINT or SIGTERM stops cleanly: every output is flushed and valid)
  --queue N                       receiver-to-engine queue per LiDAR in packets (default 4096:
                                  about 2 s of a Mid-360); when full, whole packets are dropped
                                  and counted
  --reorder N                     packets held to undo network reordering (default 8, 4 ms)
  --no-status                     no status line on stderr
outputs (besides those of cluster: --labels, --report, --mcap, --png, --png-every, ...):
  --foxglove [ADDR:]PORT          a Foxglove live view (WebSocket, protocol foxglove.websocket.v1):
                                  /streamclust/points (the window coloured by label),
                                  /streamclust/clusters (boxes with ids), /streamclust/raw (the
                                  points received since the last cycle); ADDR default 0.0.0.0.
                                  A slow viewer loses frames and never slows clustering
  --record FILE.mcap              the raw input as livox_ros_driver2/msg/CustomMsg on /livox/lidar
                                  and sensor_msgs/msg/Imu on /livox/imu; `streamclust cluster
                                  FILE.mcap` with the same options gives the same cycles and labels
presets, policies and outputs: see streamclust cluster --help.

examples:
  streamclust live livox-sdk2://192.168.1.50 --preset objects-mid360 --labels live.csv --cycles all
  streamclust live livox-sdk2://192.168.1.50 --configure --lidar 47MDL9T0020193 --record run.mcap
  streamclust live livox-sdk1://192.168.1.50 --preset objects-avia --duration 60 --report live.json
Exit codes: 0 ok, 2 usage error, 4 input error, 5 out of memory, 6 network error
(a port that cannot be bound, no LiDAR answering or streaming).
)";
}

int run_live(const LiveOptions& options, std::ostream& out, std::ostream& err) {
  LiveOptions o = options;
  StopSignals signals;
  const auto wait = seconds(o.first_packet_timeout);

  // The connection: which LiDAR, and where its packets arrive.
  std::unique_ptr<Sdk1Session> sdk1;
  std::vector<live::Endpoint> ports;
  std::vector<std::uint32_t> devices;
  std::string lidar_name;
  if (o.source.protocol == LivoxProtocol::sdk2) {
    std::uint32_t host = o.source.host_address;
    const bool by_serial = std::any_of(o.lidars.begin(), o.lidars.end(),
                                       [](const std::string& l) { return !live::parse_address(l); });
    if (o.configure || by_serial) {
      const FoundLidar lidar = discover_sdk2(o, wait, err);
      lidar_name = lidar.model + " " + lidar.serial;
      devices.push_back(lidar.address);
      if (o.configure) host = configure_sdk2(o, lidar, err);
    } else {
      for (const std::string& l : o.lidars) devices.push_back(*live::parse_address(l));
    }
    ports.push_back(live::Endpoint{host, o.source.port});
    ports.push_back(live::Endpoint{host, static_cast<std::uint16_t>(o.source.port + 100)});
  } else {
    sdk1 = std::make_unique<Sdk1Session>(o, wait, err);
    lidar_name = sdk1->lidar().model + " " + sdk1->lidar().serial;
    devices.push_back(sdk1->lidar().address);
    ports.push_back(sdk1->data_endpoint());
  }
  if (devices.size() > 1)
    throw UsageError("--lidar: one LiDAR per live run (start one run per LiDAR, each with its own outputs)");

  live::ReceiverOptions ro;
  ro.ports = ports;
  ro.devices = devices;
  ro.queue_packets = o.queue_packets;
  ro.socket_buffer_bytes = o.socket_buffer_bytes;
  if (sdk1) ro.on_tick = [s = sdk1.get()](std::chrono::steady_clock::time_point now) { s->heartbeat(now); };
  std::unique_ptr<live::LivoxReceiver> receiver;
  try {
    receiver = std::make_unique<live::LivoxReceiver>(ro);
  } catch (const std::system_error& e) {
    throw NetworkError(std::string("live: ") + e.what());
  }
  if (sdk1) sdk1->start_sampling();  // the data port is bound: nothing the LiDAR sends is lost
  receiver->start();

  live::LivoxStream stream(packet_format(o.source.protocol),
                           live::LivoxStream::Options{o.reorder_packets, 1'000'000'000});
  std::unique_ptr<LiveRecorder> recorder;
  if (!o.record_path.empty()) {
    try {
      recorder = std::make_unique<LiveRecorder>(o.record_path);
    } catch (const std::runtime_error&) {
      throw UsageError("--record: cannot write '" + o.record_path + "'");
    }
  }
  LiveFeed::Limits limits;
  limits.duration = seconds(o.duration);
  limits.idle_exit = seconds(o.idle_exit);
  LiveFeed feed(*receiver, 0, stream, limits, g_stop_requested, recorder.get());
  const std::string where = live::format_endpoint(ports.front());
  if (!feed.wait_for_first(wait)) {
    if (g_stop_requested.load()) return kOk;
    throw NetworkError("live: no " + std::string(o.source.protocol == LivoxProtocol::sdk2 ? "SDK2" : "SDK1") +
                       " point packet on UDP " + where + " within " + std::to_string(o.first_packet_timeout) +
                       " s (" + std::to_string(receiver->stats().foreign) + " datagrams from other addresses" +
                       (o.source.protocol == LivoxProtocol::sdk2 && !o.configure
                            ? "; is the LiDAR's destination this host? try --configure"
                            : "") + ")");
  }
  if (lidar_name.empty()) lidar_name = "LiDAR at " + live::format_address(receiver->device_address(0));

  // The run's time base, and its setup from the first window (the IMU's
  // gravity for the mount when the LiDAR has one and no mount is given).
  ClusterOptions& c = o.cluster;
  c.read.time_origin = io::TimeOrigin{static_cast<std::int64_t>(feed.first_time_ns() / 1'000'000'000u)};
  // The live view's raw points: what the driver's reader hands out between cycles.
  std::vector<io::Record> raw_since_cycle;
  bool tap_raw = false;  // set once the driver reads, with a live view
  c.open_input = [&feed, &c, &raw_since_cycle, &tap_raw, name = o.source_text] {
    auto reader = std::make_unique<LiveReader>(feed, name, *c.read.time_origin);
    if (tap_raw) reader->tap(&raw_since_cycle);
    return std::unique_ptr<io::PointReader>(std::move(reader));
  };
  std::optional<ImuGravity> gravity;
  if (c.mode == Mode::continuous) {
    std::vector<Eigen::Vector3f> first_window;
    if (c.ground) first_window = first_window_points(c);
    std::vector<std::array<float, 3>> accelerations;
    for (const live::LivoxImuSample& s : feed.take_imu()) accelerations.push_back(s.acceleration);
    if (c.ground && !c.mount_deg && c.poses_path.empty()) {
      gravity = gravity_from_accelerometer(accelerations);
      if (gravity) {
        c.mount_deg = std::array<double, 3>{gravity->roll_deg, gravity->pitch_deg, 0.0};
        if (!c.quiet) {
          char line[200];
          std::snprintf(line, sizeof line, "streamclust: live: gravity from the IMU (%zu samples): roll %.1f deg, "
                        "pitch %.1f deg\n", gravity->samples, printable_deg(gravity->roll_deg),
                        printable_deg(gravity->pitch_deg));
          err << line;
        }
      }
    }
    try {
      c.setup = std::make_shared<const RunSetup>(make_run_setup(c, !c.report_path.empty(), err,
                                                                c.ground ? &first_window : nullptr));
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  feed.keep_history(false);

  // The live view.
  std::unique_ptr<live::FoxgloveServer> view;
  std::uint32_t view_points = 0, view_clusters = 0, view_raw = 0;
  FoxgloveFrames frames;
  if (!o.foxglove.empty()) {
    const auto [address, port] = parse_foxglove_endpoint(o.foxglove);
    try {
      view = std::make_unique<live::FoxgloveServer>(live::FoxgloveServer::Options{address, port, "streamclust live"});
    } catch (const std::exception& e) {
      throw NetworkError(std::string("--foxglove: ") + e.what());
    }
    auto channel = [&](const char* topic, const char* type, const char* schema) {
      return view->advertise({0, topic, "cdr", schema, io::foxglove::ros2_definition(type), "ros2msg"});
    };
    view_points = channel(FoxgloveFrames::kPointsTopic, FoxgloveFrames::kPointCloudType, FoxgloveFrames::kPointCloudSchema);
    view_clusters =
        channel(FoxgloveFrames::kClustersTopic, FoxgloveFrames::kSceneUpdateType, FoxgloveFrames::kSceneUpdateSchema);
    view_raw = channel(FoxgloveFrames::kRawTopic, FoxgloveFrames::kPointCloudType, FoxgloveFrames::kPointCloudSchema);
    c.cycle_windows = true;
    if (!c.quiet) err << "streamclust: live: Foxglove live view on ws://" << address << ":" << view->port() << "\n";
  }
  tap_raw = view != nullptr;

  // The cycles: status line and latency.
  LiveStatus status;
  const bool terminal = ::isatty(2) == 1;
  auto last_status = std::chrono::steady_clock::now();
  const auto status_every = terminal ? std::chrono::milliseconds(500) : std::chrono::milliseconds(10000);
  auto status_line = [&] {
    const live::ReceiverStats rs = receiver->stats();
    return status.line(std::chrono::duration<double>(feed.elapsed()).count(), stream.counters().returns,
                       stream.order().lost, rs.queue_drops + rs.kernel_drops, feed.queue_depth(), o.queue_packets);
  };
  c.on_cycle = [&](const CycleReport& cycle, const std::vector<io::Record>& points,
                   const std::vector<std::int64_t>& labels) {
    if (view) {  // never waits for a client: a slow one loses frames (live/foxglove_server.hpp)
      const std::uint64_t log_ns = FoxgloveFrames::nanoseconds(*c.read.time_origin, cycle.time);
      frames.build(points, labels, log_ns);
      frames.build_raw(raw_since_cycle, log_ns);
      view->publish(view_points, log_ns, frames.point_cloud().data(), frames.point_cloud().size());
      view->publish(view_clusters, log_ns, frames.scene_update().data(), frames.scene_update().size());
      view->publish(view_raw, log_ns, frames.raw_cloud().data(), frames.raw_cloud().size());
    }
    raw_since_cycle.clear();
    const auto now = std::chrono::steady_clock::now();
    const double cycle_s = static_cast<double>(c.read.time_origin->seconds) + cycle.time;
    const auto cycle_ns = static_cast<std::int64_t>(std::llround(cycle_s * 1e9));
    // Latency counts in steady state: not the first cycle (its packets
    // waited for the first window's calibration) nor the last after the
    // stream ended (they waited for the end to be noticed).
    const bool steady = status.cycles() > 0 && feed.end() == LiveEnd::running;
    status.on_cycle(cycle, cycle_ns, feed.arrivals(),
                    std::chrono::duration_cast<std::chrono::nanoseconds>(now.time_since_epoch()).count(), steady);
    if (o.status && now - last_status >= status_every) {
      last_status = now;
      err << (terminal ? "\r" : "") << "streamclust: live: " << status_line() << (terminal ? "\033[K" : "\n")
          << std::flush;
    }
  };
  c.report_extra = [&](Json& doc) {
    const live::ReceiverStats rs = receiver->stats();
    const live::LivoxStreamCounters& sc = stream.counters();
    const live::OrderCounters& oc = stream.order();
    Json l;
    l["source"] = o.source_text;
    l["protocol"] = o.source.protocol == LivoxProtocol::sdk2 ? "livox-sdk2" : "livox-sdk1";
    l["lidar"] = lidar_name;
    l["address"] = live::format_address(receiver->device_address(0));
    l["time_sync"] = live::describe(stream.clock().sync());
    l["clock_epochs"] = sc.epochs;
    l["clock_offset_ns"] = stream.clock().offset_ns();
    l["end"] = describe(feed.end());
    Json counts;
    counts["datagrams"] = rs.datagrams;
    counts["bytes"] = rs.bytes;
    counts["point_packets"] = sc.point_packets;
    counts["imu_packets"] = sc.imu_packets;
    counts["returns"] = sc.returns;
    counts["empty_slots"] = sc.empty_slots;
    counts["lost"] = oc.lost;
    counts["late"] = oc.late;
    counts["duplicates"] = oc.duplicates;
    counts["counter_jumps"] = oc.counter_jumps;
    counts["malformed"] = sc.malformed_total();
    counts["foreign"] = rs.foreign;
    counts["oversize"] = rs.oversize;
    counts["queue_drops"] = rs.queue_drops;
    if (rs.kernel_drops_known) counts["kernel_drops"] = rs.kernel_drops;
    l["packets"] = counts;
    l["socket_buffer_bytes"] = rs.socket_buffer_bytes;
    Json latency;
    latency["packets"] = status.latency().count();
    latency["median_ms"] = status.latency().percentile(50.0);
    latency["p99_ms"] = status.latency().percentile(99.0);
    latency["max_ms"] = status.latency().max();
    l["latency"] = latency;
    if (view) {
      const live::FoxgloveServer::Stats v = view->stats();
      l["foxglove"] = {{"port", view->port()}, {"messages_sent", v.messages_sent},
                       {"messages_dropped", v.messages_dropped}, {"publishes_dropped", v.publishes_dropped}};
    }
    if (gravity) {
      l["imu_gravity"] = {{"roll_deg", gravity->roll_deg}, {"pitch_deg", gravity->pitch_deg},
                          {"samples", gravity->samples}};
    }
    doc["format"] = l["protocol"];
    doc["live"] = l;
  };

  int code = kOk;
  try {
    code = run_cluster(c, out, err);
  } catch (...) {
    receiver->stop();
    if (recorder) recorder->close();
    throw;
  }
  receiver->stop();
  if (recorder) {
    try {
      recorder->close();
    } catch (const std::runtime_error&) {
      throw UsageError("--record: writing '" + o.record_path + "' failed");
    }
  }
  if (o.status) {
    if (terminal) err << "\r\033[K";
    err << "streamclust: live: " << describe(feed.end()) << "; " << status_line() << "\n";
  }
  return code;
}

}  // namespace streamclust::cli
