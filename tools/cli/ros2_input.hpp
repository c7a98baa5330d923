// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The input of `streamclust ros2`: a point topic's messages (Livox
/// CustomMsg of livox_ros_driver2, livox_ros_driver or livox_interfaces, or
/// sensor_msgs/msg/PointCloud2 in any field layout), decoded from their CDR
/// payloads into points with absolute times, and an optional
/// sensor_msgs/msg/Imu topic's accelerations. A message that does not
/// decode is counted and skipped (its error kept for the report); the
/// stream goes on. `--record` keeps the payloads as received.
///
/// Not thread-safe: the engine thread owns it; Cyclone's listener thread
/// only fills the subscriptions' queues.

#include "cli/live_feed.hpp"
#include "cli/ros2_input_recorder.hpp"
#include "cli/ros2_odometry.hpp"

#include <streamclust/io/error.hpp>
#include <streamclust/io/ros/known_definitions.hpp>
#include <streamclust/io/ros/message_decoder.hpp>
#include <streamclust/io/ros/point_messages.hpp>
#include <streamclust/ros2/cdr_subscription.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace streamclust::cli {

/// Counts of what the input decoded.
struct Ros2InputCounters {
  std::uint64_t messages = 0;    ///< point messages decoded
  std::uint64_t points = 0;
  std::uint64_t malformed = 0;   ///< point or IMU messages that did not decode (skipped)
  std::uint64_t imu = 0;         ///< IMU samples decoded
  std::string last_error;        ///< the last malformed message's error
};

class Ros2Input final : public LiveInput {
 public:
  /// `type` is the point topic's ROS 2 type ("sensor_msgs/msg/PointCloud2");
  /// `imu` and `odometry` may be null; `recorder` (may be null) receives
  /// every message.
  Ros2Input(ros2::CdrSubscription& points, const std::string& topic, const std::string& type,
            ros2::CdrSubscription* imu, const std::string& imu_topic, ros2::CdrSubscription* odometry,
            const std::string& odometry_topic, Ros2InputRecorder* recorder)
      : points_(points), imu_(imu), recorder_(recorder) {
    if (odometry != nullptr) odometry_.emplace(*odometry, odometry_topic, recorder);
    const auto definition = io::ros::known_definition(type, io::ros::Encoding::cdr);
    if (!definition) throw std::invalid_argument("topic " + topic + ": type " + type + " holds no points this tool reads");
    decoder_.emplace(type, *definition, io::ros::Encoding::cdr);
    origin_.file = "ros2:" + topic;
    if (imu_ != nullptr) {
      imu_definitions_.emplace("sensor_msgs/msg/Imu", imu_definition_text());
      imu_decoder_.emplace(*imu_definitions_, io::ros::Encoding::cdr);
      imu_origin_.file = "ros2:" + imu_topic;
    }
    if (recorder_ != nullptr) {
      points_channel_ = recorder_->add_topic(topic, type, *definition);
      if (imu_ != nullptr) imu_channel_ = recorder_->add_topic(imu_topic, "sensor_msgs/msg/Imu", imu_definition_text());
    }
  }

  bool poll(std::vector<LivePoint>& points, std::vector<live::LivoxImuSample>& imu,
            std::vector<live::PacketArrival>& arrivals) override {
    bool any = false;
    if (imu_ != nullptr) {
      for (int burst = 0; burst < 64; ++burst) {
        ros2::CdrMessage m = imu_->pop();
        if (!m) break;
        take_imu(m, imu);
        any = true;
      }
    }
    if (odometry_ && odometry_->poll()) any = true;
    for (int burst = 0; burst < 16; ++burst) {
      ros2::CdrMessage m = points_.pop();
      if (!m) break;
      take_points(m, odometry_ ? held_ : points, arrivals);
      any = true;
    }
    if (odometry_) release(points, odometry_->covered_until_ns());
    return any;
  }
  /// At the end: the points the odometry never covered go too (the engine
  /// rejects them, as `cluster --poses` does).
  void flush(std::vector<LivePoint>& points, std::vector<live::PacketArrival>&) override {
    release(points, std::numeric_limits<std::uint64_t>::max());
  }
  std::string error() const override { return {}; }
  std::size_t queue_depth() const override { return points_.size(); }

  const Ros2InputCounters& counters() const noexcept { return counters_; }
  /// The odometry (--odom), or null.
  OdometryGate* odometry() { return odometry_ ? &*odometry_ : nullptr; }
  /// Arrivals of the messages decoded, by their last point's time, oldest
  /// first; the caller pops what it has accounted for.
  std::deque<live::PacketArrival>& completions() { return completions_; }
  /// The IMU's acceleration unit as found from its first sample ("" before one came).
  std::string imu_units() const { return imu_in_g_ ? (*imu_in_g_ ? "g" : "m/s^2") : ""; }
  /// The frame of the last point message ("" before one came).
  const std::string& frame_id() const noexcept { return frame_id_; }
  /// The point fields of the last message, and its time field.
  LiveInputFields fields() const {
    LiveInputFields f;
    f.fields = decoder_->fields();
    f.time_field = decoder_->time_field().empty() ? std::string("header.stamp") : decoder_->time_field();
    return f;
  }

 private:
  void take_points(const ros2::CdrMessage& m, std::vector<LivePoint>& points,
                   std::vector<live::PacketArrival>& arrivals) {
    const std::size_t before = points.size();
    origin_.prefix = "message " + std::to_string(counters_.messages + counters_.malformed + 1) + ", payload byte ";
    try {
      decoder_->decode(m.data(), m.size(), origin_, points);
    } catch (const io::InputError& e) {
      points.resize(before);
      ++counters_.malformed;
      counters_.last_error = e.what();
      return;
    }
    ++counters_.messages;
    counters_.points += points.size() - before;
    frame_id_ = decoder_->frame_id();
    if (points.size() > before) {
      std::uint64_t first = points[before].t_ns, last = first;
      for (std::size_t i = before; i < points.size(); ++i) {
        first = std::min(first, points[i].t_ns);
        last = std::max(last, points[i].t_ns);
      }
      // The headline latency: to the first retrieval holding points of the
      // message; `completions` (its last point) also waits for the next one.
      arrivals.push_back({static_cast<std::int64_t>(first), m.arrival_steady_ns()});
      completions_.push_back({static_cast<std::int64_t>(last), m.arrival_steady_ns()});
      if (completions_.size() > 20000) completions_.pop_front();
      if (recorder_ != nullptr) recorder_->add(points_channel_, points[before].t_ns, m.data(), m.size());
    }
  }

  /// Moves the held points up to `until_ns` into `points`, in order.
  void release(std::vector<LivePoint>& points, std::uint64_t until_ns) {
    std::size_t n = 0;
    while (n < held_.size() && held_[n].t_ns <= until_ns) ++n;
    points.insert(points.end(), held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(n));
    held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(n));
  }

  void take_imu(const ros2::CdrMessage& m, std::vector<live::LivoxImuSample>& imu) {
    imu_origin_.prefix = "message " + std::to_string(++imu_seen_) + ", payload byte ";
    try {
      imu_decoder_->decode(m.data(), m.size(), imu_origin_, imu_message_);
    } catch (const io::InputError& e) {
      ++counters_.malformed;
      counters_.last_error = e.what();
      return;
    }
    auto value = [&](const char* path) {
      const io::ros::Leaf* l = imu_message_.find(path);
      return l != nullptr ? imu_message_.real(l->primitive, l->offset) : 0.0;
    };
    // The gravity estimate takes g. sensor_msgs/Imu says m/s^2, but
    // livox_ros_driver2 copies the Livox IMU's g unchanged: the first
    // sample's magnitude tells which (at rest 1 or 9.8; anything below
    // 4.9 is read as g).
    constexpr double kStandardGravity = 9.80665;  // [m/s^2]
    if (!imu_in_g_) {
      const double a = std::hypot(value("linear_acceleration.x"), value("linear_acceleration.y"),
                                  value("linear_acceleration.z"));
      imu_in_g_ = a < kStandardGravity / 2;
    }
    const double scale = *imu_in_g_ ? 1.0 : 1.0 / kStandardGravity;
    live::LivoxImuSample s;
    s.time_ns = static_cast<std::uint64_t>(value("header.stamp.sec")) * 1'000'000'000u +
                static_cast<std::uint64_t>(value("header.stamp.nanosec"));
    s.gyro = {static_cast<float>(value("angular_velocity.x")), static_cast<float>(value("angular_velocity.y")),
              static_cast<float>(value("angular_velocity.z"))};
    s.acceleration = {static_cast<float>(value("linear_acceleration.x") * scale),
                      static_cast<float>(value("linear_acceleration.y") * scale),
                      static_cast<float>(value("linear_acceleration.z") * scale)};
    imu.push_back(s);
    ++counters_.imu;
    if (recorder_ != nullptr) recorder_->add(imu_channel_, s.time_ns, m.data(), m.size());
  }

  static std::string imu_definition_text() { return LiveRecorder::imu_definition(); }

  ros2::CdrSubscription& points_;
  ros2::CdrSubscription* imu_;
  Ros2InputRecorder* recorder_;
  std::optional<io::ros::PointMessageDecoder> decoder_;
  std::optional<io::ros::MessageDefinitions> imu_definitions_;
  std::optional<io::ros::MessageDecoder> imu_decoder_;
  io::ros::DecodedMessage imu_message_;
  io::detail::BufferOrigin origin_, imu_origin_;
  std::uint16_t points_channel_ = 0, imu_channel_ = 0;
  std::uint64_t imu_seen_ = 0;
  std::optional<bool> imu_in_g_;  // decided by the first IMU sample
  Ros2InputCounters counters_;
  std::string frame_id_;
  std::deque<live::PacketArrival> completions_;
  std::optional<OdometryGate> odometry_;
  std::vector<LivePoint> held_;  // decoded points waiting for the odometry to cover them
};

}  // namespace streamclust::cli
