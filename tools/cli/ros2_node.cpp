// SPDX-License-Identifier: MIT
// `streamclust ros2`: options, the DDS subscription and publishers, and the
// driver of `cluster` fed by a topic.

#include "cli/ros2_node.hpp"

#include "cli/cluster.hpp"
#include "cli/foxglove_frames.hpp"
#include "cli/json.hpp"
#include "cli/live.hpp"
#include "cli/live_feed.hpp"
#include "cli/live_setup.hpp"
#include "cli/live_status.hpp"
#include "cli/ros2_input.hpp"
#include "cli/ros2_outputs.hpp"
#include "cli/ros2_participant.hpp"
#include "cli/run_setup.hpp"
#include "cli/stop_signals.hpp"

#include <streamclust/io/ros/point_messages.hpp>
#include <streamclust/ros2/cdr_subscription.hpp>
#include <streamclust/ros2/dds_domain.hpp>
#include <streamclust/ros2/publication_watch.hpp>
#include <streamclust/ros2/ros2_names.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <unistd.h>

namespace streamclust::cli {

namespace {

std::chrono::steady_clock::duration seconds_of(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

std::string topic_option(const std::string& option, const std::string& value) {
  try {
    return ros2::resolve_topic(value, "/");
  } catch (const std::invalid_argument& e) {
    throw UsageError(option + ": " + e.what());
  }
}

}  // namespace

Ros2Options parse_ros2_options(const std::vector<std::string>& args) {
  Ros2Options o;
  std::vector<std::string> cluster_args;
  for (ArgCursor c(args); !c.done(); c.next()) {
    const std::string& a = c.option();
    if (a == "--input") {
      o.input = topic_option(a, c.value());
    } else if (a == "--input-type") {
      o.input_type = c.value();
      if (!io::ros::point_message_kind(o.input_type))
        throw UsageError("--input-type: expected livox_ros_driver2/msg/CustomMsg, livox_ros_driver/msg/CustomMsg, "
                         "livox_interfaces/msg/CustomMsg or sensor_msgs/msg/PointCloud2, got '" + o.input_type + "'");
    } else if (a == "--input-qos") {
      const std::string v = c.choice({"auto", "reliable", "best-effort"});
      o.input_qos = v == "reliable" ? InputQos::reliable : v == "best-effort" ? InputQos::best_effort : InputQos::automatic;
    } else if (a == "--imu") {
      o.imu = topic_option(a, c.value());
    } else if (a == "--odom") {
      o.odom = topic_option(a, c.value());
    } else if (a == "--namespace") {
      o.ns = c.value();
      try {
        o.ns = ros2::normalize_namespace(o.ns);
      } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--namespace: ") + e.what());
      }
    } else if (a == "--level-frame") {
      o.level_frame = c.value();
      if (o.level_frame.empty()) throw UsageError("--level-frame: expected a frame name");
    } else if (a == "--depth") {
      const std::size_t d = parse_count(a, c.value());
      if (d < 1 || d > 1000) throw UsageError("--depth: expected 1 to 1000 messages");
      o.depth = static_cast<std::int32_t>(d);
    } else if (a == "--queue") {
      o.queue_messages = parse_count(a, c.value());
      if (o.queue_messages < 1 || o.queue_messages > 100000) throw UsageError("--queue: expected 1 to 100000 messages");
    } else if (a == "--domain") {
      const std::size_t d = parse_count(a, c.value());
      if (d > ros2::kMaxDomainId) throw UsageError("--domain: expected 0 to " + std::to_string(ros2::kMaxDomainId));
      o.domain = static_cast<std::uint32_t>(d);
    } else if (a == "--dds-loopback") {
      o.loopback = true;
    } else if (a == "--duration") {
      o.duration = parse_positive(a, c.value());
    } else if (a == "--idle-exit") {
      o.idle_exit = parse_positive(a, c.value());
    } else if (a == "--wait") {
      o.first_message_timeout = parse_positive(a, c.value());
    } else if (a == "--record") {
      o.record_path = c.value();
    } else if (a == "--record-out") {
      o.record_out_path = c.value();
    } else if (a == "--no-status") {
      o.status = false;
    } else if (a == "--verify") {
      throw UsageError("--verify: the ros2 command does not keep the window's input; verify a --record file with "
                       "cluster --verify");
    } else {
      cluster_args.push_back(a);
    }
  }
  for (const std::string& a : cluster_args) {
    if (a == "--format" || a == "--topic" || a == "--time-unit" || a == "--point-rate" || a == "--time-origin")
      throw UsageError(a + ": an option of recorded inputs; a topic's messages have their own times");
  }
  cluster_args.push_back("ros2:" + o.input);  // cluster's INPUT: names the source in messages and the report
  o.cluster = parse_cluster_options(cluster_args);
  if (o.cluster.quiet) o.status = false;
  if (!o.odom.empty() && !o.cluster.poses_path.empty())
    throw UsageError("--odom and --poses: the poses come from one of them");
  if (!o.odom.empty() && o.cluster.mode == Mode::frame)
    throw UsageError("--odom: poses are a stage of the continuous engine: use --mode continuous");
  if (!o.record_path.empty() && o.record_path == o.record_out_path)
    throw UsageError("--record and --record-out: expected two different files");
  return o;
}

std::string ros2_help() {
  return R"(usage: streamclust ros2 [options]

A ROS 2 node without a ROS installation: subscribes over DDS to a point
topic, clusters it with the presets, policies and outputs of `cluster`, and
publishes every retrieval, stamped with the stream's time in the input's frame.

input:
  --input TOPIC                   the point topic (default /livox/lidar): livox_ros_driver2,
                                  livox_ros_driver or livox_interfaces CustomMsg, or
                                  sensor_msgs/msg/PointCloud2 in any field layout; the type is
                                  learnt from the first publisher discovered
  --input-type TYPE               subscribe at once with this type instead (e.g.
                                  sensor_msgs/msg/PointCloud2)
  --input-qos auto|reliable|best-effort
                                  the subscription's reliability (auto: reliable when the
                                  discovered publisher is, as livox_ros_driver2's are; else best
                                  effort). History keep-last 5 (sensor data); an incompatible
                                  publisher is reported
  --imu TOPIC                     sensor_msgs/msg/Imu: with --ground (the objects presets) and no
                                  --mount or --poses, the mount's roll and pitch from the first
                                  window's accelerometer
  --odom TOPIC                    nav_msgs/msg/Odometry: the sensor's poses, as --poses gives them
                                  offline (world from the odometry's child frame: the LiDAR, or the
                                  vehicle with --mount); points wait for the pose at their time;
                                  the outputs are in the odometry's frame (header.frame_id)
  --queue N                       messages queued between DDS and the engine (default 64); when
                                  full, whole messages are dropped and counted
outputs (besides those of cluster: --labels, --report, --mcap, --tracks, --png, ...):
  --namespace NS                  output topics NS/points (sensor_msgs/msg/PointCloud2: x y z
                                  intensity label class), NS/clusters
                                  (visualization_msgs/msg/MarkerArray), NS/detections
                                  (vision_msgs/msg/Detection3DArray); with --tracks also
                                  NS/tracks (MarkerArray: boxes, ids, speeds, velocity arrows)
                                  and NS/tracked_objects (Detection3DArray: id = track id,
                                  class moving or static); default /streamclust
  --depth N                       output history depth (reliable, keep last; default 5)
  --level-frame NAME              the outputs' frame when the points are placed by a mount (--mount,
                                  the objects presets' ground estimate, --imu gravity): level, z up;
                                  its static transform from the input's frame goes to /tf_static
                                  (default: the input's frame + "_level"); otherwise the outputs
                                  are in the input's frame
  --record FILE.mcap              the input messages as received, with their definitions;
                                  `streamclust cluster FILE.mcap` with the same options gives
                                  the same cycles and labels
  --record-out FILE.mcap          every message published, as sent, with its ROS 2 schema
DDS (Cyclone DDS; CYCLONEDDS_URI configures it as for any Cyclone node):
  --domain N                      the DDS domain (default: ROS_DOMAIN_ID, else 0)
  --dds-loopback                  discovery on 127.0.0.1 only, by unicast (a host without
                                  multicast on loopback; every peer must do the same)
run:
  --wait S                        seconds to wait for a publisher and its first message (default 10)
  --duration S                    stop after S seconds
  --idle-exit S                   stop after S seconds without messages (once messages came)
  --no-status                     no status line on stderr
  (SIGINT or SIGTERM stops cleanly: every output is flushed and valid)
presets, policies and outputs: see streamclust cluster --help.

examples:
  streamclust ros2 --input /livox/lidar --preset objects-mid360
  streamclust ros2 --input /points --input-type sensor_msgs/msg/PointCloud2 --namespace /perception
  streamclust ros2 --preset objects-avia --imu /livox/imu --record run.mcap --report node.json
Exit codes: 0 ok, 2 usage error, 4 input error, 5 out of memory, 6 network error
(DDS could not start, no publisher or no message within --wait).
)";
}

namespace {

/// The node's engine thread state: what the main thread reads for the
/// status line is guarded by `mutex`.
struct NodeRun {
  std::mutex mutex;
  LiveStatus status;
  LatencyHistogram complete;  ///< message arrival to the first retrieval holding all its points [ms]
  std::optional<std::chrono::steady_clock::time_point> started;
  std::uint64_t points = 0;
  int code = kOk;
  std::exception_ptr failure;
  std::atomic<bool> done{false};
};

ros2::Reliability reliability_for(InputQos q, const std::optional<ros2::PublicationInfo>& discovered) {
  if (q == InputQos::reliable) return ros2::Reliability::reliable;
  if (q == InputQos::best_effort) return ros2::Reliability::best_effort;
  return discovered ? discovered->reliability : ros2::Reliability::reliable;
}

}  // namespace

int run_ros2(const Ros2Options& o, std::ostream& out, std::ostream& err) {
  StopSignals signals;
  const bool quiet = o.cluster.quiet;
  const std::string tag = "streamclust: ros2: ";

  const std::unique_ptr<ros2::DdsParticipant> participant = open_participant(o.domain, o.loopback, "ros2");

  // The input's type: given, or learnt from the first publisher of the topic.
  const std::string dds_topic = ros2::dds_topic_name(o.input);
  std::optional<ros2::PublicationInfo> discovered;
  std::string type = o.input_type;
  if (type.empty()) {
    ros2::PublicationWatch watch(*participant);
    discovered = watch.wait_for(dds_topic, seconds_of(o.first_message_timeout), [] { return stop_requested(); });
    if (!discovered) {
      if (stop_requested()) return kOk;
      throw NetworkError("ros2: no publisher of " + o.input + " on DDS domain " + std::to_string(participant->domain()) +
                         " within " + std::to_string(static_cast<int>(o.first_message_timeout)) +
                         " s (check ROS_DOMAIN_ID, the topic name, and discovery: multicast or --dds-loopback)");
    }
    const auto ros_type = ros2::ros_type_name(discovered->dds_type);
    if (!ros_type || !io::ros::point_message_kind(*ros_type))
      throw UsageError("--input " + o.input + ": its publisher sends " + discovered->dds_type +
                       "; expected a Livox CustomMsg or sensor_msgs/msg/PointCloud2");
    type = *ros_type;
  }
  const std::string full_type = io::ros2_schema_name(type);

  // The subscriptions, the input, the outputs.
  ros2::TopicQos qos = ros2::sensor_data_qos();
  qos.reliability = reliability_for(o.input_qos, discovered);
  std::unique_ptr<ros2::CdrSubscription> points_sub, imu_sub, odom_sub;
  std::unique_ptr<Ros2InputRecorder> recorder;
  std::unique_ptr<Ros2Input> input;
  std::unique_ptr<Ros2Outputs> outputs;
  try {
    ros2::CdrSubscription::Options so;
    so.dds_topic = dds_topic;
    so.dds_type = ros2::dds_type_name(full_type);
    so.qos = qos;
    so.queue_messages = o.queue_messages;
    points_sub = std::make_unique<ros2::CdrSubscription>(*participant, so);
    if (!o.imu.empty()) {
      ros2::CdrSubscription::Options io_;
      io_.dds_topic = ros2::dds_topic_name(o.imu);
      io_.dds_type = ros2::dds_type_name("sensor_msgs/msg/Imu");
      io_.qos = ros2::sensor_data_qos();
      io_.queue_messages = 4096;  // 20 s of a 200 Hz IMU
      imu_sub = std::make_unique<ros2::CdrSubscription>(*participant, io_);
    }
    if (!o.odom.empty()) {
      ros2::CdrSubscription::Options oo;
      oo.dds_topic = ros2::dds_topic_name(o.odom);
      oo.dds_type = ros2::dds_type_name("nav_msgs/msg/Odometry");
      oo.qos = ros2::TopicQos{qos.reliability, ros2::Durability::volatile_, 50};
      oo.queue_messages = 4096;  // 20 s of 200 Hz odometry
      odom_sub = std::make_unique<ros2::CdrSubscription>(*participant, oo);
    }
    if (!o.record_path.empty()) {
      try {
        recorder = std::make_unique<Ros2InputRecorder>(o.record_path);
      } catch (const std::runtime_error&) {
        throw UsageError("--record: cannot write '" + o.record_path + "'");
      }
    }
    input = std::make_unique<Ros2Input>(*points_sub, o.input, full_type, imu_sub.get(), o.imu, odom_sub.get(), o.odom,
                                        recorder.get());
    try {
      outputs = std::make_unique<Ros2Outputs>(*participant, o.ns, o.depth, o.record_out_path,
                                              !o.cluster.tracks_path.empty());
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--namespace: ") + e.what());
    } catch (const ros2::DdsError&) {
      throw;
    } catch (const std::runtime_error&) {
      throw UsageError("--record-out: cannot write '" + o.record_out_path + "'");
    }
  } catch (const ros2::DdsError& e) {
    throw NetworkError(std::string("ros2: ") + e.what());
  }
  if (!quiet) {
    err << tag << "subscribed to " << o.input << " (" << full_type << ", " << ros2::describe(qos.reliability)
        << ", DDS domain " << participant->domain() << "); publishing ";
    for (std::size_t i = 0; i < outputs->size(); ++i) err << (i > 0 ? ", " : "") << outputs->topic(i);
    err << "\n";
  }

  // The engine thread: waits for the first message, sets the run up, runs
  // the driver of `cluster`; each retrieval is published.
  LiveFeed::Limits limits;
  limits.duration = seconds_of(o.duration);
  limits.idle_exit = seconds_of(o.idle_exit);
  std::atomic<bool> stop_all{false};
  LiveFeed feed(*input, limits, stop_all);
  NodeRun run;
  ClusterOptions c = o.cluster;
  c.report_cycles_kept = 1200;  // the last minute at 20 Hz; totals count every cycle
  c.cycle_windows = true;

  std::string output_frame;  // the level frame when the engine places points by a mount
  std::thread engine([&] {
    try {
      {
        const std::lock_guard<std::mutex> lock(run.mutex);
        run.started = std::chrono::steady_clock::now();
      }
      if (!feed.wait_for_first(seconds_of(o.first_message_timeout))) {
        if (!stop_all.load()) {
          const ros2::SubscriptionCounters sc = points_sub->counters();
          throw NetworkError("ros2: no message on " + o.input + " within " +
                             std::to_string(static_cast<int>(o.first_message_timeout)) + " s (" +
                             std::to_string(sc.publishers) + " publishers matched, " +
                             std::to_string(sc.incompatible_qos) + " with an incompatible QoS; " +
                             std::to_string(input->counters().malformed) + " malformed messages)");
        }
        run.done.store(true);
        return;
      }
      // --odom: the poses so far become the run's trajectory, which grows
      // as odometry arrives (the first point waited for a pose).
      if (OdometryGate* odometry = input->odometry()) {
        c.trajectory = odometry->start(io::TimeOrigin{static_cast<std::int64_t>(feed.first_time_ns() / 1'000'000'000u)});
      }
      const std::optional<ImuGravity> gravity =
          prepare_live_cluster(c, feed, "ros2:" + o.input, input->fields(), nullptr, "streamclust: ros2", err);
      // With --odom the window is in the odometry's frame (the robot's TF
      // tree links it); placed by a mount alone, in a level frame whose
      // transform from the input's frame goes to /tf_static.
      const bool level = c.setup && c.setup->motion.enabled;
      if (OdometryGate* odometry = input->odometry()) {
        output_frame = odometry->frame_id();
      } else if (level) {
        const Pose& mount = c.setup->motion.posed.mount;
        io::ros2msg::Transform t;
        t.child = input->frame_id();
        t.parent = o.level_frame.empty() ? t.child + "_level" : o.level_frame;
        t.translation = {mount.translation.x(), mount.translation.y(), mount.translation.z()};
        t.rotation = {mount.rotation.x(), mount.rotation.y(), mount.rotation.z(), mount.rotation.w()};
        outputs->publish_static_transform(t, feed.first_time_ns(), *participant);
        output_frame = t.parent;
      }
      c.on_cycle = [&, level](const CycleView& view) {
        const CycleReport& cycle = view.report;
        const std::uint64_t stamp_ns = FoxgloveFrames::nanoseconds(*c.read.time_origin, cycle.time);
        const std::string& frame = level ? output_frame : input->frame_id();
        outputs->publish(stamp_ns, frame, view.points, view.labels);
        if (view.tracks) outputs->publish_tracks(stamp_ns, frame, *view.tracks);
        const auto now = std::chrono::steady_clock::now();
        const std::lock_guard<std::mutex> lock(run.mutex);
        run.points = input->counters().points;
        // Latency counts in steady state: messages that arrived once the
        // engine had cleared the setup's backlog (it first waited for
        // input), and not after the stream ended.
        const auto now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(now.time_since_epoch()).count();
        const auto caught_up = feed.caught_up();
        const std::int64_t steady_from =
            caught_up && feed.end() == LiveEnd::running
                ? std::chrono::duration_cast<std::chrono::nanoseconds>(caught_up->time_since_epoch()).count()
                : std::numeric_limits<std::int64_t>::max();
        auto& done = input->completions();
        while (!done.empty() && done.front().last_time_ns <= static_cast<std::int64_t>(stamp_ns)) {
          if (done.front().arrival_steady_ns >= steady_from)
            run.complete.add(static_cast<double>(now_ns - done.front().arrival_steady_ns) * 1e-6);
          done.pop_front();
        }
        auto& arrivals = feed.arrivals();
        while (!arrivals.empty() && arrivals.front().arrival_steady_ns < steady_from &&
               arrivals.front().last_time_ns <= static_cast<std::int64_t>(stamp_ns))
          arrivals.pop_front();  // before the steady state: not measured
        run.status.on_cycle(cycle, static_cast<std::int64_t>(stamp_ns), arrivals, now_ns, steady_from < now_ns);
      };
      c.report_extra = [&](Json& doc) {
        const ros2::SubscriptionCounters sc = points_sub->counters();
        const Ros2InputCounters& ic = input->counters();
        Json r;
        r["input"] = o.input;
        r["type"] = full_type;
        r["domain"] = participant->domain();
        r["reliability"] = ros2::describe(qos.reliability);
        r["frame_id"] = input->frame_id();
        r["output_frame"] = output_frame.empty() ? input->frame_id() : output_frame;
        if (!input->imu_units().empty()) r["imu_units"] = input->imu_units();
        if (OdometryGate* odometry = input->odometry()) {
          r["odometry"] = {{"topic", o.odom}, {"frame_id", odometry->frame_id()},
                           {"poses", odometry->counters().poses}, {"rejected", odometry->counters().rejected}};
          if (!odometry->counters().last_error.empty()) r["odometry"]["last_rejected"] = odometry->counters().last_error;
        }
        r["end"] = describe(feed.end());
        r["messages"] = {{"received", sc.received}, {"dropped", sc.dropped}, {"lost", sc.lost},
                         {"decoded", ic.messages}, {"malformed", ic.malformed}, {"points", ic.points},
                         {"imu", ic.imu}};
        if (!ic.last_error.empty()) r["last_malformed"] = ic.last_error;
        r["publishers"] = {{"matched", sc.publishers}, {"seen", sc.publishers_seen},
                           {"incompatible_qos", sc.incompatible_qos}};
        Json published = Json::object();
        for (std::size_t i = 0; i < outputs->size(); ++i) {
          const ros2::PublicationCounters pc = outputs->counters(i);
          published[outputs->topic(i)] = {{"messages", pc.published}, {"subscribers", pc.subscribers},
                                           {"incompatible_qos", pc.incompatible_qos}};
        }
        r["published"] = published;
        Json latency;
        {
          const std::lock_guard<std::mutex> lock(run.mutex);
          latency["messages"] = run.status.latency().count();
          latency["median_ms"] = run.status.latency().percentile(50.0);
          latency["p99_ms"] = run.status.latency().percentile(99.0);
          latency["max_ms"] = run.status.latency().max();
          // False: the engine never waited for input (it ran behind the
          // stream throughout), so nothing was measured.
          latency["steady_state"] = feed.caught_up().has_value();
          latency["complete_median_ms"] = run.complete.percentile(50.0);
          latency["complete_p99_ms"] = run.complete.percentile(99.0);
        }
        r["latency"] = latency;
        if (gravity) {
          r["imu_gravity"] = {{"roll_deg", gravity->roll_deg}, {"pitch_deg", gravity->pitch_deg},
                              {"samples", gravity->samples}};
        }
        doc["format"] = "ros2";
        doc["ros2"] = r;
      };
      run.code = run_cluster(c, out, err);
    } catch (...) {
      run.failure = std::current_exception();
    }
    run.done.store(true);
  });

  // The main thread: the stop, the status line, reports of incompatible QoS.
  const bool terminal = ::isatty(2) == 1;
  const auto status_every = terminal ? std::chrono::milliseconds(500) : std::chrono::milliseconds(10000);
  auto last_status = std::chrono::steady_clock::now();
  std::uint32_t incompatible_reported = 0;
  auto status_line = [&] {
    const ros2::SubscriptionCounters sc = points_sub->counters();
    const std::lock_guard<std::mutex> lock(run.mutex);
    const double elapsed =
        run.started ? std::chrono::duration<double>(std::chrono::steady_clock::now() - *run.started).count() : 0.0;
    return run.status.line(elapsed, run.points, sc.lost, sc.dropped, points_sub->size(), o.queue_messages);
  };
  while (!run.done.load()) {
    if (stop_requested()) stop_all.store(true);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const ros2::SubscriptionCounters sc = points_sub->counters();
    if (sc.incompatible_qos > incompatible_reported) {
      incompatible_reported = sc.incompatible_qos;
      err << (terminal && o.status ? "\r\033[K" : "") << tag << "a publisher of " << o.input
          << " offers a QoS this subscription cannot accept (" << ros2::describe_policy(sc.last_incompatible_policy)
          << "; subscription: " << ros2::describe(qos.reliability) << "); try --input-qos best-effort\n";
    }
    const auto now = std::chrono::steady_clock::now();
    if (o.status && now - last_status >= status_every) {
      last_status = now;
      if (terminal) {
        err << "\r" << tag << status_line() << "\033[K" << std::flush;
      } else {
        err << tag << status_line() << "\n";
      }
    }
  }
  engine.join();

  // Every recording is closed (complete) before a failure is reported.
  std::exception_ptr failure = run.failure;
  if (recorder) {
    try {
      recorder->close();
    } catch (const std::runtime_error&) {
      if (!failure) failure = std::make_exception_ptr(UsageError("--record: writing '" + o.record_path + "' failed"));
    }
  }
  try {
    outputs->close();
  } catch (const std::runtime_error&) {
    if (!failure) failure = std::make_exception_ptr(UsageError("--record-out: writing '" + o.record_out_path + "' failed"));
  }
  if (failure) std::rethrow_exception(failure);
  const Ros2InputCounters& ic = input->counters();
  if (!quiet && ic.malformed > 0)
    err << tag << ic.malformed << " malformed messages skipped; the last: " << ic.last_error << "\n";
  if (o.status) {
    if (terminal) err << "\r\033[K";
    err << tag << describe(feed.end()) << "; " << status_line() << "\n";
  }
  return run.code;
}

}  // namespace streamclust::cli
