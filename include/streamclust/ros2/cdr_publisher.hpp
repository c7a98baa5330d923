// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A publisher of CDR payloads on one DDS topic: what a ROS 2 publisher of
/// the type sends, written by the caller's encoder. With a keep-last
/// history a write never blocks on a slow subscriber (the oldest unsent
/// sample is replaced). Counts subscribers matched and subscribers that
/// requested an incompatible QoS.
///
/// Thread-safety: `publish` from one thread at a time; `counters` from any.

#include <streamclust/ros2/dds_domain.hpp>
#include <streamclust/ros2/raw_cdr_type.hpp>
#include <streamclust/ros2/ros2_qos.hpp>

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace streamclust::ros2 {

struct PublicationCounters {
  std::uint64_t published = 0;
  std::uint32_t subscribers = 0;        ///< subscribers matched now
  std::uint32_t subscribers_seen = 0;   ///< ever matched
  std::uint32_t incompatible_qos = 0;   ///< subscribers requesting an incompatible QoS
  std::uint32_t last_incompatible_policy = 0;
};

class CdrPublisher {
 public:
  /// A writer of `dds_type` ("sensor_msgs::msg::dds_::PointCloud2_") on
  /// `dds_topic` ("rt/streamclust/points").
  CdrPublisher(const DdsParticipant& participant, const std::string& dds_topic, const std::string& dds_type,
               const TopicQos& q = default_qos())
      : dds_topic_(dds_topic) {
    ddsi_sertype* type = make_raw_cdr_type(dds_type);
    const QosPointer qos = make_dds_qos(q);
    topic_ = dds_create_topic_sertype(participant.handle(), dds_topic.c_str(), &type, qos.get(), nullptr, nullptr);
    if (topic_ < 0) {
      detail::raw_type_free(type);  // not taken by the domain
      check_dds(topic_, "creating DDS topic " + dds_topic + " (" + dds_type + ")");
    }
    type_ = type;
    dds_listener_t* l = dds_create_listener(this);
    dds_lset_publication_matched(l, on_matched);
    dds_lset_offered_incompatible_qos(l, on_incompatible);
    writer_ = dds_create_writer(participant.handle(), topic_, qos.get(), l);
    dds_delete_listener(l);
    if (writer_ < 0) {
      dds_delete(topic_);
      check_dds(writer_, "creating a DDS writer on " + dds_topic);
    }
  }
  ~CdrPublisher() {
    dds_delete(writer_);
    dds_delete(topic_);
  }
  CdrPublisher(const CdrPublisher&) = delete;
  CdrPublisher& operator=(const CdrPublisher&) = delete;

  /// Sends one message: `payload` holds the encapsulation header and the
  /// body. Throws DdsError when DDS refuses it. O(size) (one copy).
  void publish(const std::uint8_t* payload, std::size_t size) {
    ddsi_serdata* sample = make_raw_cdr_sample(type_, payload, size);
    const dds_return_t rc = dds_writecdr(writer_, sample);
    // dds_writecdr takes the sample's reference once it holds the writer;
    // a writer it cannot hold (deleted, or not a writer) leaves it to us.
    if (rc == DDS_RETCODE_BAD_PARAMETER || rc == DDS_RETCODE_ALREADY_DELETED || rc == DDS_RETCODE_ILLEGAL_OPERATION)
      ddsi_serdata_unref(sample);
    check_dds(rc, "publishing on " + dds_topic_);
    const std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.published;
  }
  template <class Bytes>
  void publish(const Bytes& bytes) {
    publish(bytes.data(), bytes.size());
  }

  /// Waits until every reliable subscriber acknowledged what was
  /// published, at most `timeout`; false when some did not.
  template <class Rep, class Period>
  bool wait_for_acks(std::chrono::duration<Rep, Period> timeout) {
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(timeout).count();
    return dds_wait_for_acks(writer_, static_cast<dds_duration_t>(ns)) == DDS_RETCODE_OK;
  }

  PublicationCounters counters() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return counters_;
  }
  const std::string& dds_topic() const noexcept { return dds_topic_; }

 private:
  static void on_matched(dds_entity_t, dds_publication_matched_status_t status, void* arg) {
    auto& p = *static_cast<CdrPublisher*>(arg);
    const std::lock_guard<std::mutex> lock(p.mutex_);
    p.counters_.subscribers = status.current_count;
    p.counters_.subscribers_seen = status.total_count;
  }
  static void on_incompatible(dds_entity_t, dds_offered_incompatible_qos_status_t status, void* arg) {
    auto& p = *static_cast<CdrPublisher*>(arg);
    const std::lock_guard<std::mutex> lock(p.mutex_);
    p.counters_.incompatible_qos = status.total_count;
    p.counters_.last_incompatible_policy = status.last_policy_id;
  }

  std::string dds_topic_;
  const ddsi_sertype* type_ = nullptr;  // the topic's (owned by the domain)
  dds_entity_t topic_ = 0, writer_ = 0;
  mutable std::mutex mutex_;
  PublicationCounters counters_;
};

}  // namespace streamclust::ros2
