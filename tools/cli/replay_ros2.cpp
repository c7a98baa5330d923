// SPDX-License-Identifier: MIT
// `streamclust replay --to ros2:///TOPIC`: a ROS 2 LiDAR driver's publisher
// over DDS. A recording whose point topic is CDR is sent as recorded (every
// message's payload unchanged, with its type, at its recorded rate, and its
// sensor_msgs Imu topics on --imu-topic); any other input, or a simulated
// scene, as livox_ros_driver2 CustomMsg (or the driver's PointCloud2)
// messages of --message-seconds each, paced by the points' times.

#include "cli/custom_msg.hpp"
#include "cli/live.hpp"
#include "cli/replay.hpp"
#include "cli/ros2_participant.hpp"
#include "cli/stop_signals.hpp"

#include <streamclust/io/cdr_writer.hpp>
#include <streamclust/io/reader.hpp>
#include <streamclust/io/recording_reader.hpp>
#include <streamclust/io/ros/message_definition.hpp>
#include <streamclust/io/ros/odometry.hpp>
#include <streamclust/io/ros/point_messages.hpp>
#include <streamclust/io/ros2_messages.hpp>
#include <streamclust/ros2/cdr_publisher.hpp>
#include <streamclust/ros2/dds_domain.hpp>
#include <streamclust/ros2/ros2_names.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace streamclust::cli {

namespace {

/// Sends at the recorded rate x speed: sleeps until stream time `t_ns` is
/// due (the first call's time is due at once).
class Pacer {
 public:
  explicit Pacer(double speed) : speed_(speed) {}
  void wait_until(std::uint64_t t_ns) {
    if (speed_ <= 0.0) return;
    const auto now = std::chrono::steady_clock::now();
    if (!first_) {
      first_ = t_ns;
      start_ = now;
      return;
    }
    const double dt = static_cast<double>(static_cast<std::int64_t>(t_ns - *first_)) * 1e-9 / speed_;
    const auto due = start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                  std::chrono::duration<double>(std::max(0.0, dt)));
    if (due > now) std::this_thread::sleep_until(due);
  }

 private:
  double speed_;
  std::optional<std::uint64_t> first_;
  std::chrono::steady_clock::time_point start_;
};

/// The driver's PointCloud2 layout (livox_ros_driver2, xfer_format 0): x y z
/// intensity (float32), tag line (uint8), timestamp (float64, ns), 26 bytes.
void write_driver_point_cloud2(io::CdrWriter& w, const std::string& frame_id,
                               const std::vector<live::LivoxReturn>& returns, std::size_t from, std::size_t to) {
  constexpr std::uint32_t kStep = 26;
  std::vector<std::uint8_t> data((to - from) * kStep);
  for (std::size_t i = from; i < to; ++i) {
    const live::LivoxReturn& r = returns[i];
    std::uint8_t* d = data.data() + (i - from) * kStep;
    const float v[4] = {r.x, r.y, r.z, static_cast<float>(r.reflectivity)};
    std::memcpy(d, v, 16);
    d[16] = r.tag;
    d[17] = 0;
    const double t = static_cast<double>(r.time_ns);
    std::memcpy(d + 18, &t, 8);
  }
  using F = io::ros2msg::PointField;
  static const std::vector<F> fields = {{"x", 0, F::FLOAT32, 1},         {"y", 4, F::FLOAT32, 1},
                                        {"z", 8, F::FLOAT32, 1},         {"intensity", 12, F::FLOAT32, 1},
                                        {"tag", 16, F::UINT8, 1},        {"line", 17, F::UINT8, 1},
                                        {"timestamp", 18, F::FLOAT64, 1}};
  io::ros2msg::Header h;
  const std::uint64_t base = from < to ? returns[from].time_ns : 0;
  h.sec = static_cast<std::int32_t>(base / 1'000'000'000u);
  h.nanosec = static_cast<std::uint32_t>(base % 1'000'000'000u);
  h.frame_id = frame_id;
  io::ros2msg::write_point_cloud2(w, h, static_cast<std::uint32_t>(to - from), fields, kStep, data.data(), data.size(),
                                  true);
}

/// The publishers of a replay and what they sent.
struct Senders {
  std::unique_ptr<ros2::CdrPublisher> points, imu, odom;
  std::uint64_t point_messages = 0, points_sent = 0, imu_messages = 0, odom_messages = 0;
};

/// Waits for `n` subscribers of `p` at most `timeout`; false if they did not come.
bool wait_for_subscribers(const ros2::CdrPublisher& p, std::size_t n, std::chrono::steady_clock::duration timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (p.counters().subscribers < n) {
    if (stop_requested() || std::chrono::steady_clock::now() >= until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

}  // namespace

int run_replay_ros2(const ReplayOptions& o, SimulatedStream simulated, std::ostream& out, std::ostream&) {
  StopSignals signals;
  const Ros2ReplayOptions& r = o.ros2;
  std::string topic, imu_topic, odom_topic;
  try {
    topic = ros2::resolve_topic(r.topic);
    imu_topic = ros2::resolve_topic(r.imu_topic);
    if (!r.odom_topic.empty()) odom_topic = ros2::resolve_topic(r.odom_topic);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--to ros2://: ") + e.what());
  }
  const std::unique_ptr<ros2::DdsParticipant> participant = open_participant(r.domain, r.loopback, "replay");
  const ros2::TopicQos qos{r.best_effort ? ros2::Reliability::best_effort : ros2::Reliability::reliable,
                           ros2::Durability::volatile_, 256};
  const auto wait = std::chrono::duration_cast<std::chrono::steady_clock::duration>(o.emulator.connect_timeout);
  Senders s;
  auto open_points = [&](const std::string& type) {
    try {
      s.points = std::make_unique<ros2::CdrPublisher>(*participant, ros2::dds_topic_name(topic),
                                                      ros2::dds_type_name(type), qos);
      s.imu = std::make_unique<ros2::CdrPublisher>(*participant, ros2::dds_topic_name(imu_topic),
                                                   ros2::dds_type_name("sensor_msgs/msg/Imu"), qos);
      if (!odom_topic.empty())
        s.odom = std::make_unique<ros2::CdrPublisher>(*participant, ros2::dds_topic_name(odom_topic),
                                                      ros2::dds_type_name("nav_msgs/msg/Odometry"), qos);
    } catch (const ros2::DdsError& e) {
      throw NetworkError(std::string("replay: ") + e.what());
    }
    if (r.subscribers > 0 && !wait_for_subscribers(*s.points, r.subscribers, wait) && !stop_requested()) {
      throw NetworkError("replay: " + std::to_string(s.points->counters().subscribers) + " of " +
                         std::to_string(r.subscribers) + " subscribers of " + topic + " within " +
                         std::to_string(static_cast<int>(std::chrono::duration<double>(wait).count())) +
                         " s (check ROS_DOMAIN_ID and discovery: multicast or --dds-loopback on both sides)");
    }
  };

  Pacer pacer(o.emulator.speed);
  io::CdrWriter w;
  const io::Format format = o.simulate ? io::Format::csv : io::detect_format(o.input);
  const bool recording = !o.simulate && (format == io::Format::mcap || format == io::Format::rosbag2_sqlite);
  std::unique_ptr<io::RecordingSource> source;
  std::size_t point_topic = 0;
  if (recording) {
    source = io::detail::open_recording(o.input, format);
    point_topic = io::choose_point_topic(*source, o.read.topic);
    if (source->topics()[point_topic].message_encoding != "cdr") source.reset();  // decoded and re-encoded below
  }

  if (source) {
    // A ROS 2 recording: its messages as recorded.
    const io::RecordingTopic& pt = source->topics()[point_topic];
    open_points(io::ros2_schema_name(pt.type));
    std::vector<bool> imu_topics, odom_topics;
    for (const io::RecordingTopic& t : source->topics()) {
      const bool cdr = t.message_encoding == "cdr";
      imu_topics.push_back(cdr && io::ros::MessageDefinitions::normalize(t.type) == "sensor_msgs/Imu");
      odom_topics.push_back(cdr && s.odom && io::ros::is_odometry_type(t.type));
    }
    io::RecordingMessage m;
    while (!stop_requested() && source->next(m)) {
      if (m.topic != point_topic && !imu_topics[m.topic] && !odom_topics[m.topic]) continue;
      pacer.wait_until(m.log_time_ns);
      if (m.topic == point_topic) {
        s.points->publish(m.data, m.size);
        ++s.point_messages;
      } else if (imu_topics[m.topic]) {
        s.imu->publish(m.data, m.size);
        ++s.imu_messages;
      } else {
        s.odom->publish(m.data, m.size);
        ++s.odom_messages;
      }
    }
  } else {
    // Points: CustomMsg (or the driver's PointCloud2) messages, and a resting IMU with --imu.
    open_points(r.point_cloud2 ? "sensor_msgs/msg/PointCloud2" : "livox_ros_driver2/msg/CustomMsg");
    std::unique_ptr<io::PointReader> reader;
    std::vector<io::Record> records;
    std::int64_t origin_s = 0;
    if (o.simulate) {
      records = std::move(simulated.records);
      origin_s = std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch())
                     .count();
    } else {
      reader = io::open_reader(o.input, o.read);
    }
    const auto span = static_cast<std::uint64_t>(std::llround(r.message_seconds * 1e9));
    std::vector<live::LivoxReturn> pending;
    std::uint64_t next_imu_ns = 0;
    auto send_imu_until = [&](std::uint64_t until_ns) {
      if (!o.emulator.imu_mount) return;
      // As livox_ros_driver2 publishes a Livox IMU: acceleration in g (the
      // device's unit, copied unchanged), angular rate in rad/s.
      constexpr double deg = 3.14159265358979323846 / 180.0;
      const double roll = (*o.emulator.imu_mount)[0] * deg, pitch = (*o.emulator.imu_mount)[1] * deg;
      io::ros2msg::Imu imu;
      imu.orientation_covariance[0] = -1.0;  // orientation unknown
      imu.linear_acceleration = {-std::sin(pitch), std::sin(roll) * std::cos(pitch), std::cos(roll) * std::cos(pitch)};
      if (next_imu_ns == 0) next_imu_ns = until_ns;
      for (; next_imu_ns <= until_ns; next_imu_ns += 5'000'000) {  // 200 Hz
        io::ros2msg::Header h;
        h.sec = static_cast<std::int32_t>(next_imu_ns / 1'000'000'000u);
        h.nanosec = static_cast<std::uint32_t>(next_imu_ns % 1'000'000'000u);
        h.frame_id = "livox_frame";
        io::ros2msg::write_imu(w, h, imu);
        s.imu->publish(w.bytes());
        ++s.imu_messages;
      }
    };
    // --odom-topic with --simulate: the sensor's trajectory, each pose sent
    // before the points it covers.
    std::size_t next_pose = 0;
    auto send_odom_until = [&](std::uint64_t until_ns) {
      if (!s.odom) return;
      const std::vector<StampedPose>& poses = simulated.trajectory;
      for (; next_pose < poses.size(); ++next_pose) {
        const StampedPose& p = poses[next_pose];
        const auto t_ns = static_cast<std::uint64_t>(origin_s * 1'000'000'000 + std::llround(p.time * 1e9));
        io::ros2msg::Header h;
        h.sec = static_cast<std::int32_t>(t_ns / 1'000'000'000u);
        h.nanosec = static_cast<std::uint32_t>(t_ns % 1'000'000'000u);
        h.frame_id = "odom";
        io::ros2msg::Odometry odom;
        odom.child_frame_id = "livox_frame";
        odom.position = {p.pose.translation.x(), p.pose.translation.y(), p.pose.translation.z()};
        odom.orientation = {p.pose.rotation.x(), p.pose.rotation.y(), p.pose.rotation.z(), p.pose.rotation.w()};
        io::ros2msg::write_odometry(w, h, odom);
        s.odom->publish(w.bytes());
        ++s.odom_messages;
        if (t_ns >= until_ns) {
          ++next_pose;
          break;  // the first pose at or after the points' end covers them
        }
      }
    };
    auto flush = [&] {
      if (pending.empty()) return;
      const std::uint64_t last = pending.back().time_ns;
      pacer.wait_until(last);
      send_imu_until(last);
      send_odom_until(last);
      if (r.point_cloud2) {
        write_driver_point_cloud2(w, "livox_frame", pending, 0, pending.size());
      } else {
        write_custom_msg(w, "livox_frame", pending, 0, pending.size());
      }
      s.points->publish(w.bytes());
      ++s.point_messages;
      s.points_sent += pending.size();
      pending.clear();
    };
    std::size_t at = 0;
    for (;;) {
      if (stop_requested()) break;
      if (reader) {
        records.clear();
        if (reader->read(records, 4096) == 0) break;
        origin_s = reader->time_origin().seconds;
      } else if (at > 0) {
        break;  // the simulated stream was read in one go
      }
      at = records.size();
      for (const io::Record& rec : records) {
        if (!std::isfinite(rec.t)) continue;
        live::LivoxReturn ret;
        ret.x = rec.x;
        ret.y = rec.y;
        ret.z = rec.z;
        ret.reflectivity = static_cast<std::uint8_t>(std::clamp(std::lround(rec.intensity), 0L, 255L));
        ret.time_ns = static_cast<std::uint64_t>(origin_s * 1'000'000'000 + std::llround(rec.t * 1e9));
        if (!pending.empty() && (ret.time_ns < pending.front().time_ns || ret.time_ns - pending.front().time_ns >= span))
          flush();
        pending.push_back(ret);
      }
    }
    if (!stop_requested()) {
      flush();
      send_odom_until(std::numeric_limits<std::uint64_t>::max());  // the rest of the trajectory
    }
  }

  // Reliable delivery: what is still unacknowledged gets up to --wait.
  const bool acked = s.points->wait_for_acks(wait) && s.imu->wait_for_acks(wait) && (!s.odom || s.odom->wait_for_acks(wait));
  if (!o.quiet) {
    out << "streamclust: replay: " << s.point_messages << " point messages";
    if (s.points_sent > 0) out << " (" << s.points_sent << " points)";
    out << " on " << topic << ", " << s.imu_messages << " IMU messages on " << imu_topic;
    if (s.odom) out << ", " << s.odom_messages << " odometry messages on " << odom_topic;
    out << "; "
        << s.points->counters().subscribers << " subscribers"
        << (acked ? "" : "; not every message was acknowledged") << (stop_requested() ? "; stopped by a signal" : "")
        << "\n";
  }
  return kOk;
}

}  // namespace streamclust::cli
