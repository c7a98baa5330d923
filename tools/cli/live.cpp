// SPDX-License-Identifier: MIT
// `streamclust live`: options, the connection with the LiDAR, the receiver and
// engine threads, and the driver of `cluster` fed by the live stream.

#include "cli/live.hpp"

#include "cli/cluster.hpp"
#include "cli/foxglove_frames.hpp"
#include "cli/json.hpp"
#include "cli/line_stream.hpp"
#include "cli/live_feed.hpp"
#include "cli/live_setup.hpp"
#include "cli/live_status.hpp"
#include "cli/stop_signals.hpp"
#include "cli/run_setup.hpp"
#include "live/foxglove_server.hpp"

#include <streamclust/live/live_counters.hpp>
#include <streamclust/live/livox_connection.hpp>
#include <streamclust/live/sdk1_packets.hpp>
#include <streamclust/live/sdk2_packets.hpp>
#include <streamclust/motion/imu_gravity.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

namespace streamclust::cli {

namespace {

live::LivoxPacketFormat packet_format(LivoxProtocol protocol) {
  return protocol == LivoxProtocol::sdk2 ? live::sdk2_packet_format() : live::sdk1_packet_format();
}

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

/// Seconds as a person writes them: "10", "0.5".
std::string format_seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", s);
  return text;
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

std::optional<ImuGravity> prepare_live_cluster(ClusterOptions& c, LiveFeed& feed, const std::string& name,
                                               const LiveInputFields& fields, LiveTap* tap, const std::string& tag,
                                               std::ostream& err) {
  c.read.time_origin = io::TimeOrigin{static_cast<std::int64_t>(feed.first_time_ns() / 1'000'000'000u)};
  c.open_input = [&feed, &c, tap, name, fields] {
    auto reader = std::make_unique<LiveReader>(feed, name, *c.read.time_origin, fields.fields, fields.time_field);
    if (tap != nullptr && tap->on) reader->tap(&tap->records);
    return std::unique_ptr<io::PointReader>(std::move(reader));
  };
  std::optional<ImuGravity> gravity;
  if (c.mode == Mode::continuous) {
    std::vector<Eigen::Vector3f> first_window;
    std::vector<double> first_window_times;
    const bool needs_first_window = c.ground || linkage_fits_sensor(c);
    if (needs_first_window) first_window = first_window_points(c, &first_window_times);
    std::vector<std::array<float, 3>> accelerations;
    for (const live::LivoxImuSample& s : feed.take_imu()) accelerations.push_back(s.acceleration);
    if (c.ground && !c.mount_deg && c.poses_path.empty() && !c.trajectory) {
      gravity = gravity_from_accelerometer(accelerations);
      if (gravity) {
        c.mount_deg = std::array<double, 3>{gravity->roll_deg, gravity->pitch_deg, 0.0};
        if (!c.quiet) {
          char line[200];
          std::snprintf(line, sizeof line, ": gravity from the IMU (%zu samples): roll %.1f deg, pitch %.1f deg\n",
                        gravity->samples, printable_deg(gravity->roll_deg), printable_deg(gravity->pitch_deg));
          err << tag << line;
        }
      }
    }
    try {
      c.setup = std::make_shared<const RunSetup>(make_run_setup(c, !c.report_path.empty(), err,
                                                                needs_first_window ? &first_window : nullptr,
                                                                &first_window_times));
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  feed.keep_history(false);
  if (tap != nullptr) tap->on = true;
  return gravity;
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
                                  foreign and never mixed in. Repeat it for several LiDARs,
                                  one engine thread each; every output FILE.ext becomes
                                  FILE-ID.ext and live view topics /lidar_ID/... (ID: the value)
  With --ground (the objects presets) and no --mount or --poses, a LiDAR with an IMU gives the
  mount's roll and pitch from the first window's accelerometer (at rest) instead of the plane search.
  --discovery-address IP          where discovery requests go (default 255.255.255.255)
  --data-type 1|2|3               SDK2 --configure: int32 mm, int16 cm or spherical points
  --work-mode sampling            SDK2 --configure: also start sampling
  --wait S                        seconds to wait for discovery, handshake and first packet (default 10)
run:
  --duration S                    stop after S seconds
  --idle-exit S                   stop after S seconds without packets (once packets came)
  (SIGINT or SIGTERM stops cleanly: every output is flushed and valid)
  --queue N                       receiver-to-engine queue per LiDAR in packets (default 4096:
                                  about 2 s of a Mid-360); when full, whole packets are dropped
                                  and counted
  --reorder N                     packets held to undo network reordering (default 8, 4 ms)
  --no-status                     no status line on stderr
outputs (besides those of cluster: --labels, --report, --mcap, --tracks, --png, --png-every, ...):
  --foxglove [ADDR:]PORT          a Foxglove live view (WebSocket, protocol foxglove.websocket.v1):
                                  /streamclust/points (the window coloured by label),
                                  /streamclust/clusters (boxes with ids), /streamclust/raw (the
                                  points received since the last cycle), with --tracks also
                                  /streamclust/tracks (tracked boxes, ids, speeds, velocity
                                  arrows); ADDR default 0.0.0.0. A slow viewer loses frames and
                                  never slows clustering
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

namespace {

/// One LiDAR of a run: its stream, feed, outputs, status and engine
/// thread. Thread-safety: the engine thread owns everything but `status`,
/// `started`, `returns` and `lost` (its figures for the status line, read
/// by the main thread under `status_mutex`) and `done`.
struct LidarPipeline {
  LidarPipeline(std::size_t device_index, const live::LivoxPacketFormat& format, const LiveOptions& o)
      : device(device_index), stream(format, live::LivoxStream::Options{o.reorder_packets, 1'000'000'000}) {}

  std::size_t device = 0;         ///< the receiver's device index
  std::string id;                 ///< in output names and topics; empty with one LiDAR
  std::string name;               ///< "MID-360 47MDL9T0020193", or "LiDAR at ADDRESS" once heard
  ClusterOptions cluster;         ///< the run's options with this LiDAR's output names
  std::string record_path;
  live::LivoxStream stream;
  std::unique_ptr<LiveRecorder> recorder;
  std::unique_ptr<LivoxInput> input;
  std::unique_ptr<LiveFeed> feed;
  std::uint32_t view_points = 0, view_clusters = 0, view_raw = 0, view_tracks = 0;  ///< live view channels (tracks: with --tracks)
  std::mutex status_mutex;
  LiveStatus status;
  std::optional<std::chrono::steady_clock::time_point> started;  ///< when the feed began waiting
  std::uint64_t returns = 0, lost = 0;  ///< the stream's counters at the last cycle
  int code = kOk;
  std::exception_ptr failure;
  std::atomic<bool> done{false};
};

/// `path` with `-ID` before its extension (`live.csv` -> `live-ID.csv`);
/// unchanged without an id. Standard output ("-") cannot be shared.
std::string output_for(const std::string& option, const std::string& path, const std::string& id) {
  if (path.empty() || id.empty()) return path;
  if (path == "-") throw UsageError(option + " -: with several LiDARs every output is a file (one per LiDAR)");
  const std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + "-" + id + p.extension().string())).string();
}

/// A --lidar value as a file-name and topic part: letters, digits, '.',
/// '-' kept, anything else '_'.
std::string lidar_id(const std::string& lidar) {
  std::string id = lidar;
  for (char& ch : id)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '.' && ch != '-') ch = '_';
  return id;
}

/// A live run's report lists its last minute of cycles at 20 Hz (its
/// totals count every cycle): memory stays fixed however long it runs.
constexpr std::size_t kReportCyclesKept = 1200;

/// The run's shared parts, read by every engine thread.
struct SharedRun {
  const LiveOptions& options;
  live::LivoxReceiver& receiver;
  live::FoxgloveServer* view;
  const std::atomic<bool>& stop_all;
};

/// One LiDAR's engine thread: waits for its first packet, sets the run up
/// from its first window (the IMU's gravity when it has one), then runs the
/// driver of `cluster` on its stream until the stream ends.
int run_pipeline(LidarPipeline& p, const SharedRun& run, std::ostream& out, std::ostream& err) {
  const LiveOptions& o = run.options;
  LiveFeed::Limits limits;
  limits.duration = seconds(o.duration);
  limits.idle_exit = seconds(o.idle_exit);
  p.input = std::make_unique<LivoxInput>(run.receiver, p.device, p.stream, p.recorder.get());
  p.feed = std::make_unique<LiveFeed>(*p.input, limits, run.stop_all);
  LiveFeed& feed = *p.feed;
  {
    const std::lock_guard<std::mutex> lock(p.status_mutex);
    p.started = std::chrono::steady_clock::now();
  }
  if (!feed.wait_for_first(seconds(o.first_packet_timeout))) {
    if (run.stop_all.load()) return kOk;
    const double waited = o.duration > 0.0 ? std::min(o.duration, o.first_packet_timeout) : o.first_packet_timeout;
    const std::string where = live::format_endpoint(run.receiver.local(0));
    throw NetworkError("live: no " + std::string(o.source.protocol == LivoxProtocol::sdk2 ? "SDK2" : "SDK1") +
                       " point packet" + (p.id.empty() ? "" : " from " + p.name) + " on UDP " + where + " within " +
                       format_seconds(waited) + " s (" +
                       std::to_string(run.receiver.stats().foreign) + " datagrams from other addresses" +
                       (o.source.protocol == LivoxProtocol::sdk2 && !o.configure
                            ? "; is the LiDAR's destination this host? try --configure"
                            : "") + ")");
  }
  if (p.name.empty()) p.name = "LiDAR at " + live::format_address(run.receiver.device_address(p.device));

  ClusterOptions& c = p.cluster;
  LiveTap raw_since_cycle;  // the live view's raw points
  const std::optional<ImuGravity> gravity =
      prepare_live_cluster(c, feed, o.source_text, LiveInputFields{}, run.view ? &raw_since_cycle : nullptr,
                           "streamclust: live", err);
  if (run.view) c.cycle_windows = true;

  // The cycles: the live view and the latency.
  FoxgloveFrames frames;
  c.on_cycle = [&](const CycleView& view) {
    const CycleReport& cycle = view.report;
    if (run.view) {  // never waits for a client: a slow one loses frames (live/foxglove_server.hpp)
      const std::uint64_t log_ns = FoxgloveFrames::nanoseconds(*c.read.time_origin, cycle.time);
      frames.build(view.points, view.labels, log_ns);
      frames.build_raw(raw_since_cycle.records, log_ns);
      run.view->publish(p.view_points, log_ns, frames.point_cloud().data(), frames.point_cloud().size());
      run.view->publish(p.view_clusters, log_ns, frames.scene_update().data(), frames.scene_update().size());
      run.view->publish(p.view_raw, log_ns, frames.raw_cloud().data(), frames.raw_cloud().size());
      if (view.tracks) {
        frames.build_tracks(*view.tracks, log_ns);
        run.view->publish(p.view_tracks, log_ns, frames.tracks_update().data(), frames.tracks_update().size());
      }
    }
    raw_since_cycle.records.clear();
    const auto now = std::chrono::steady_clock::now();
    const double cycle_s = static_cast<double>(c.read.time_origin->seconds) + cycle.time;
    const auto cycle_ns = static_cast<std::int64_t>(std::llround(cycle_s * 1e9));
    const std::lock_guard<std::mutex> lock(p.status_mutex);
    p.returns = p.stream.counters().returns;
    p.lost = p.stream.order().lost;
    // Latency counts in steady state: not the first cycle (its packets
    // waited for the first window's calibration) nor the last after the
    // stream ended (they waited for the end to be noticed).
    const bool steady = p.status.cycles() > 0 && feed.end() == LiveEnd::running;
    p.status.on_cycle(cycle, cycle_ns, feed.arrivals(),
                      std::chrono::duration_cast<std::chrono::nanoseconds>(now.time_since_epoch()).count(), steady);
  };
  c.report_extra = [&](Json& doc) {
    const live::ReceiverStats rs = run.receiver.stats();
    const live::LivoxStreamCounters& sc = p.stream.counters();
    Json l;
    l["source"] = o.source_text;
    l["protocol"] = o.source.protocol == LivoxProtocol::sdk2 ? "livox-sdk2" : "livox-sdk1";
    l["lidar"] = p.name;
    l["address"] = live::format_address(run.receiver.device_address(p.device));
    l["time_sync"] = live::describe(p.stream.clock().sync());
    l["data_type"] = sc.data_type;
    l["clock_epochs"] = sc.epochs;
    l["clock_offset_ns"] = p.stream.clock().offset_ns();
    l["end"] = feed.end() == LiveEnd::stop_requested && !stop_requested() ? "stopped: another LiDAR of the run failed"
                                                                                 : describe(feed.end());
    Json counts;
    live::for_each_counter(live::live_counters(run.receiver, p.device, p.stream),
                           [&counts](const char* name, std::uint64_t value) { counts[name] = value; });
    l["packets"] = counts;
    l["socket_buffer_bytes"] = rs.socket_buffer_bytes;
    Json latency;
    {
      const std::lock_guard<std::mutex> lock(p.status_mutex);
      latency["packets"] = p.status.latency().count();
      latency["median_ms"] = p.status.latency().percentile(50.0);
      latency["p99_ms"] = p.status.latency().percentile(99.0);
      latency["max_ms"] = p.status.latency().max();
    }
    l["latency"] = latency;
    if (run.view) {
      const live::FoxgloveServer::Stats v = run.view->stats();
      l["foxglove"] = {{"port", run.view->port()}, {"messages_sent", v.messages_sent},
                       {"messages_dropped", v.messages_dropped}, {"publishes_dropped", v.publishes_dropped}};
    }
    if (gravity) {
      l["imu_gravity"] = {{"roll_deg", gravity->roll_deg}, {"pitch_deg", gravity->pitch_deg},
                          {"samples", gravity->samples}};
    }
    doc["format"] = l["protocol"];
    doc["live"] = l;
  };
  return run_cluster(c, out, err);
}

}  // namespace

int run_live(const LiveOptions& options, std::ostream& out, std::ostream& err) {
  const LiveOptions& o = options;
  StopSignals signals;
  const auto wait = seconds(o.first_packet_timeout);

  // The connection: each chosen LiDAR found, configured or shaken hands
  // with, one receiver queue each.
  if (o.source.protocol == LivoxProtocol::sdk1 && o.lidars.size() > live::kMaxSdk1Lidars)
    throw UsageError("--lidar: at most " + std::to_string(live::kMaxSdk1Lidars) + " SDK1 LiDARs per run");
  live::LivoxConnectionOptions co;
  co.source = o.source;
  co.lidars = o.lidars;
  co.configure = o.configure;
  co.discovery_address = o.discovery_address;
  co.data_type = o.data_type;
  co.work_mode_sampling = o.work_mode_sampling;
  co.wait = wait;
  co.queue_packets = o.queue_packets;
  co.socket_buffer_bytes = o.socket_buffer_bytes;
  co.notes = o.cluster.quiet ? nullptr : &err;
  live::LivoxConnection connection(co);
  live::LivoxReceiver& receiver = connection.receiver();

  // One pipeline per LiDAR; with several, every output name and live view
  // topic carries the LiDAR's id.
  const bool several = connection.lidars() > 1;
  const live::LivoxPacketFormat format = packet_format(o.source.protocol);
  std::vector<std::unique_ptr<LidarPipeline>> pipelines;
  for (std::size_t i = 0; i < connection.lidars(); ++i) {
    auto p = std::make_unique<LidarPipeline>(i, format, o);
    p->id = several ? lidar_id(o.lidars[i]) : std::string();
    p->name = connection.lidar_name(i);
    p->cluster = o.cluster;
    ClusterOptions& c = p->cluster;
    c.report_cycles_kept = kReportCyclesKept;
    c.labels_path = output_for("--labels", c.labels_path, p->id);
    c.report_path = output_for("--report", c.report_path, p->id);
    c.ply_path = output_for("--ply", c.ply_path, p->id);
    c.pcd_path = output_for("--pcd", c.pcd_path, p->id);
    c.mcap_path = output_for("--mcap", c.mcap_path, p->id);
    c.tracks_path = output_for("--tracks", c.tracks_path, p->id);
    c.png_path = output_for("--png", c.png_path, p->id);
    p->record_path = output_for("--record", o.record_path, p->id);
    if (!p->record_path.empty()) {
      try {
        p->recorder = std::make_unique<LiveRecorder>(p->record_path);
      } catch (const std::runtime_error&) {
        throw UsageError("--record: cannot write '" + p->record_path + "'");
      }
    }
    pipelines.push_back(std::move(p));
  }

  // The live view: one server, three channels per LiDAR (four with --tracks).
  std::unique_ptr<live::FoxgloveServer> view;
  if (!o.foxglove.empty()) {
    const auto [address, port] = parse_foxglove_endpoint(o.foxglove);
    try {
      view = std::make_unique<live::FoxgloveServer>(live::FoxgloveServer::Options{address, port, "streamclust live"});
    } catch (const std::exception& e) {
      throw NetworkError(std::string("--foxglove: ") + e.what());
    }
    for (auto& p : pipelines) {
      std::string prefix = p->id.empty() ? std::string() : "/lidar_" + p->id;
      std::replace(prefix.begin(), prefix.end(), '.', '_');  // a ROS-style name
      std::replace(prefix.begin(), prefix.end(), '-', '_');
      auto channel = [&](const char* topic, const char* type, const char* schema) {
        return view->advertise({0, prefix + topic, "cdr", schema, io::foxglove::ros2_definition(type), "ros2msg"});
      };
      p->view_points = channel(FoxgloveFrames::kPointsTopic, FoxgloveFrames::kPointCloudType,
                               FoxgloveFrames::kPointCloudSchema);
      p->view_clusters = channel(FoxgloveFrames::kClustersTopic, FoxgloveFrames::kSceneUpdateType,
                                 FoxgloveFrames::kSceneUpdateSchema);
      p->view_raw = channel(FoxgloveFrames::kRawTopic, FoxgloveFrames::kPointCloudType,
                            FoxgloveFrames::kPointCloudSchema);
      if (!p->cluster.tracks_path.empty()) {
        p->view_tracks = channel(FoxgloveFrames::kTracksTopic, FoxgloveFrames::kSceneUpdateType,
                                 FoxgloveFrames::kSceneUpdateSchema);
      }
    }
    if (!o.cluster.quiet) err << "streamclust: live: Foxglove live view on ws://" << address << ":" << view->port() << "\n";
  }

  connection.start();

  // The engine threads. With several LiDARs each writes whole lines tagged
  // with its id; the main thread keeps the status lines and the stop.
  std::atomic<bool> stop_all{false};
  const SharedRun shared{o, receiver, view.get(), stop_all};
  std::mutex terminal_mutex;
  std::vector<std::thread> engines;
  for (auto& p : pipelines) {
    engines.emplace_back([&, pipeline = p.get()] {
      std::unique_ptr<LineStream> tagged_out, tagged_err;
      if (several) {
        tagged_out = std::make_unique<LineStream>(out, terminal_mutex, "[" + pipeline->id + "] ");
        tagged_err = std::make_unique<LineStream>(err, terminal_mutex, "[" + pipeline->id + "] ");
      }
      try {
        pipeline->code = run_pipeline(*pipeline, shared, several ? *tagged_out : out, several ? *tagged_err : err);
      } catch (...) {
        pipeline->failure = std::current_exception();
      }
      pipeline->done.store(true);
    });
  }

  const bool terminal = ::isatty(2) == 1;
  const auto status_every = terminal ? std::chrono::milliseconds(500) : std::chrono::milliseconds(10000);
  auto status_line = [&](LidarPipeline& p) {
    const live::ReceiverStats rs = receiver.stats();
    const std::size_t depth = receiver.queue(p.device).size();
    const std::lock_guard<std::mutex> lock(p.status_mutex);
    const double elapsed = p.started ? std::chrono::duration<double>(std::chrono::steady_clock::now() - *p.started).count() : 0.0;
    return (p.id.empty() ? std::string() : "[" + p.id + "] ") +
           p.status.line(elapsed, p.returns, p.lost, receiver.queue_drops(p.device) + rs.kernel_drops, depth,
                         o.queue_packets);
  };
  auto last_status = std::chrono::steady_clock::now();
  for (;;) {
    const bool all_done = std::all_of(pipelines.begin(), pipelines.end(), [](const auto& p) { return p->done.load(); });
    if (all_done) break;
    const bool failed = std::any_of(pipelines.begin(), pipelines.end(), [](const auto& p) { return p->failure != nullptr && p->done.load(); });
    if (stop_requested() || failed) stop_all.store(true);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const auto now = std::chrono::steady_clock::now();
    if (o.status && now - last_status >= status_every) {
      last_status = now;
      const std::lock_guard<std::mutex> lock(terminal_mutex);
      if (terminal && !several) {
        err << "\rstreamclust: live: " << status_line(*pipelines.front()) << "\033[K" << std::flush;
      } else {
        for (auto& p : pipelines) err << "streamclust: live: " << status_line(*p) << "\n";
      }
    }
  }
  for (std::thread& t : engines) t.join();
  connection.stop();

  // Every recording is closed (complete) before a failure is reported.
  std::exception_ptr failure;
  int code = kOk;
  for (auto& p : pipelines) {
    if (p->recorder) {
      try {
        p->recorder->close();
      } catch (const std::runtime_error&) {
        if (!failure) failure = std::make_exception_ptr(UsageError("--record: writing '" + p->record_path + "' failed"));
      }
    }
    if (p->failure && !failure) failure = p->failure;
    if (code == kOk) code = p->code;
  }
  if (failure) std::rethrow_exception(failure);
  if (o.status) {
    if (terminal && !several) err << "\r\033[K";
    for (auto& p : pipelines) {
      p->returns = p->stream.counters().returns;  // the engine threads have ended
      p->lost = p->stream.order().lost;
      err << "streamclust: live: " << (p->feed ? describe(p->feed->end()) : "not started") << "; " << status_line(*p) << "\n";
    }
  }
  return code;
}

}  // namespace streamclust::cli
