// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A subscription to one DDS topic that hands its messages, as CDR
/// payloads, to a consumer thread through a bounded queue. Cyclone's
/// listener thread only takes each message (a reference, no copy) and
/// queues it with its arrival time; when the queue is full the message is
/// dropped and counted. Also counted: publishers matched (now and ever),
/// incompatible QoS offered by a publisher (with the policy), and samples
/// DDS reports lost (best effort).
///
/// Thread-safety: `pop` and `size` are for the consumer (any one thread);
/// `counters` for any thread. Destruction deletes the reader first, so no
/// listener call outlives the queue.

#include <streamclust/ros2/dds_domain.hpp>
#include <streamclust/ros2/raw_cdr_type.hpp>
#include <streamclust/ros2/ros2_qos.hpp>

#include <chrono>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>

namespace streamclust::ros2 {

/// A received message: a reference to its payload and when it arrived.
/// Move-only; releases the reference.
class CdrMessage {
 public:
  CdrMessage() = default;
  CdrMessage(RawCdrSample* sample, std::int64_t arrival_steady_ns, std::int64_t source_time_ns)
      : sample_(sample), arrival_steady_ns_(arrival_steady_ns), source_time_ns_(source_time_ns) {}
  ~CdrMessage() { reset(); }
  CdrMessage(CdrMessage&& o) noexcept { *this = std::move(o); }
  CdrMessage& operator=(CdrMessage&& o) noexcept {
    if (this != &o) {
      reset();
      sample_ = o.sample_;
      arrival_steady_ns_ = o.arrival_steady_ns_;
      source_time_ns_ = o.source_time_ns_;
      o.sample_ = nullptr;
    }
    return *this;
  }
  CdrMessage(const CdrMessage&) = delete;
  CdrMessage& operator=(const CdrMessage&) = delete;

  explicit operator bool() const noexcept { return sample_ != nullptr; }
  /// The payload: the 4-byte encapsulation header, then the body.
  const std::uint8_t* data() const noexcept { return sample_->bytes(); }
  std::size_t size() const noexcept { return sample_->size; }
  /// Host steady clock when the listener took it [ns].
  std::int64_t arrival_steady_ns() const noexcept { return arrival_steady_ns_; }
  /// The writer's source timestamp [ns since 1970].
  std::int64_t source_time_ns() const noexcept { return source_time_ns_; }

 private:
  void reset() {
    if (sample_ != nullptr) ddsi_serdata_unref(sample_);
    sample_ = nullptr;
  }
  RawCdrSample* sample_ = nullptr;
  std::int64_t arrival_steady_ns_ = 0, source_time_ns_ = 0;
};

struct SubscriptionCounters {
  std::uint64_t received = 0;            ///< messages taken from DDS
  std::uint64_t dropped = 0;             ///< of those, dropped because the queue was full
  std::uint64_t lost = 0;                ///< samples DDS reports lost before delivery (best effort)
  std::uint32_t publishers = 0;          ///< publishers matched now
  std::uint32_t publishers_seen = 0;     ///< publishers ever matched
  std::uint32_t incompatible_qos = 0;    ///< publishers offering an incompatible QoS
  std::uint32_t last_incompatible_policy = 0;  ///< its policy (describe_policy)
  std::size_t queue_bytes = 0;           ///< payload bytes queued now
};

class CdrSubscription {
 public:
  struct Options {
    std::string dds_topic;          ///< "rt/livox/lidar"
    std::string dds_type;           ///< "livox_ros_driver2::msg::dds_::CustomMsg_"
    TopicQos qos = sensor_data_qos();
    std::size_t queue_messages = 64;                 ///< queued messages at most
    std::size_t queue_bytes = std::size_t{256} << 20;  ///< queued payload bytes at most
  };

  CdrSubscription(const DdsParticipant& participant, Options o) : options_(std::move(o)) {
    ddsi_sertype* type = make_raw_cdr_type(options_.dds_type);
    const QosPointer qos = make_dds_qos(options_.qos);
    topic_ = dds_create_topic_sertype(participant.handle(), options_.dds_topic.c_str(), &type, qos.get(), nullptr,
                                      nullptr);
    if (topic_ < 0) {
      detail::raw_type_free(type);  // not taken by the domain
      check_dds(topic_, "creating DDS topic " + options_.dds_topic + " (" + options_.dds_type + ")");
    }
    dds_listener_t* l = dds_create_listener(this);
    dds_lset_data_available(l, on_data);
    dds_lset_subscription_matched(l, on_matched);
    dds_lset_requested_incompatible_qos(l, on_incompatible);
    dds_lset_sample_lost(l, on_lost);
    reader_ = dds_create_reader(participant.handle(), topic_, qos.get(), l);
    dds_delete_listener(l);
    if (reader_ < 0) {
      dds_delete(topic_);
      check_dds(reader_, "creating a DDS reader on " + options_.dds_topic);
    }
  }
  ~CdrSubscription() {
    dds_delete(reader_);  // waits for a running listener call
    dds_delete(topic_);
  }
  CdrSubscription(const CdrSubscription&) = delete;
  CdrSubscription& operator=(const CdrSubscription&) = delete;

  /// The oldest queued message, or an empty one. O(1).
  CdrMessage pop() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (queue_.empty()) return {};
    CdrMessage m = std::move(queue_.front());
    queue_.pop_front();
    counters_.queue_bytes -= m.size();
    return m;
  }
  std::size_t size() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return queue_.size();
  }
  SubscriptionCounters counters() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return counters_;
  }
  const Options& options() const noexcept { return options_; }

 private:
  static CdrSubscription& self(void* arg) { return *static_cast<CdrSubscription*>(arg); }

  static void on_data(dds_entity_t reader, void* arg) {
    CdrSubscription& s = self(arg);
    constexpr std::uint32_t kBatch = 16;
    ddsi_serdata* samples[kBatch];
    dds_sample_info_t infos[kBatch];
    for (;;) {
      const dds_return_t n = dds_takecdr(reader, samples, kBatch, infos, DDS_ANY_STATE);
      if (n <= 0) return;
      const std::int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::steady_clock::now().time_since_epoch()).count();
      const std::lock_guard<std::mutex> lock(s.mutex_);
      for (dds_return_t i = 0; i < n; ++i) {
        auto* sample = static_cast<RawCdrSample*>(samples[i]);
        if (!infos[i].valid_data) {  // a publisher's state change, no message
          ddsi_serdata_unref(sample);
          continue;
        }
        ++s.counters_.received;
        if (s.queue_.size() >= s.options_.queue_messages ||
            s.counters_.queue_bytes + sample->size > s.options_.queue_bytes) {
          ++s.counters_.dropped;
          ddsi_serdata_unref(sample);
          continue;
        }
        s.counters_.queue_bytes += sample->size;
        s.queue_.emplace_back(sample, now, infos[i].source_timestamp);
      }
    }
  }
  static void on_matched(dds_entity_t, dds_subscription_matched_status_t status, void* arg) {
    CdrSubscription& s = self(arg);
    const std::lock_guard<std::mutex> lock(s.mutex_);
    s.counters_.publishers = status.current_count;
    s.counters_.publishers_seen = status.total_count;
  }
  static void on_incompatible(dds_entity_t, dds_requested_incompatible_qos_status_t status, void* arg) {
    CdrSubscription& s = self(arg);
    const std::lock_guard<std::mutex> lock(s.mutex_);
    s.counters_.incompatible_qos = status.total_count;
    s.counters_.last_incompatible_policy = status.last_policy_id;
  }
  static void on_lost(dds_entity_t, dds_sample_lost_status_t status, void* arg) {
    CdrSubscription& s = self(arg);
    const std::lock_guard<std::mutex> lock(s.mutex_);
    s.counters_.lost = status.total_count;
  }

  Options options_;
  dds_entity_t topic_ = 0, reader_ = 0;
  mutable std::mutex mutex_;
  std::deque<CdrMessage> queue_;
  SubscriptionCounters counters_;
};

}  // namespace streamclust::ros2
