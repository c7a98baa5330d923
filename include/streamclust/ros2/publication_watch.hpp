// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The publishers DDS discovery reports on a topic, with the type each
/// sends and the reliability it offers: how a ROS 2 node learns what type
/// a topic carries before it subscribes (`ros2 topic echo` does the same
/// through its graph cache).
///
/// Thread-safety: one thread polls a watch.

#include <streamclust/ros2/dds_domain.hpp>
#include <streamclust/ros2/ros2_qos.hpp>

#include <chrono>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace streamclust::ros2 {

/// A publisher discovery reported.
struct PublicationInfo {
  std::string dds_topic;
  std::string dds_type;
  Reliability reliability = Reliability::reliable;
  Durability durability = Durability::volatile_;
};

class PublicationWatch {
 public:
  explicit PublicationWatch(const DdsParticipant& participant)
      : reader_(check_dds(dds_create_reader(participant.handle(), DDS_BUILTIN_TOPIC_DCPSPUBLICATION, nullptr, nullptr),
                          "reading DDS publication discovery")) {}
  ~PublicationWatch() { dds_delete(reader_); }
  PublicationWatch(const PublicationWatch&) = delete;
  PublicationWatch& operator=(const PublicationWatch&) = delete;

  /// Publications discovered since the last call (alive ones only). O(new).
  std::vector<PublicationInfo> take() {
    std::vector<PublicationInfo> found;
    constexpr std::size_t kBatch = 16;
    void* samples[kBatch] = {};
    dds_sample_info_t infos[kBatch];
    for (;;) {
      const dds_return_t n = dds_take(reader_, samples, infos, kBatch, kBatch);
      if (n <= 0) break;
      for (dds_return_t i = 0; i < n; ++i) {
        const auto* e = static_cast<const dds_builtintopic_endpoint_t*>(samples[i]);
        if (!infos[i].valid_data || infos[i].instance_state != DDS_IST_ALIVE) continue;
        PublicationInfo p;
        p.dds_topic = e->topic_name != nullptr ? e->topic_name : "";
        p.dds_type = e->type_name != nullptr ? e->type_name : "";
        dds_reliability_kind_t kind = DDS_RELIABILITY_RELIABLE;
        dds_duration_t blocking = 0;
        if (e->qos != nullptr && dds_qget_reliability(e->qos, &kind, &blocking))
          p.reliability = kind == DDS_RELIABILITY_RELIABLE ? Reliability::reliable : Reliability::best_effort;
        dds_durability_kind_t durability = DDS_DURABILITY_VOLATILE;
        if (e->qos != nullptr && dds_qget_durability(e->qos, &durability))
          p.durability = durability == DDS_DURABILITY_VOLATILE ? Durability::volatile_ : Durability::transient_local;
        found.push_back(std::move(p));
      }
      dds_return_loan(reader_, samples, n);
    }
    return found;
  }

  /// Waits until a publisher of `dds_topic` is discovered, at most
  /// `timeout` (false on `stop`); returns it, or nothing.
  template <class StopFlag>
  std::optional<PublicationInfo> wait_for(const std::string& dds_topic, std::chrono::steady_clock::duration timeout,
                                          const StopFlag& stop) {
    const auto until = std::chrono::steady_clock::now() + timeout;
    for (;;) {
      for (PublicationInfo& p : take()) {
        if (p.dds_topic == dds_topic) return std::move(p);
      }
      if (stop() || std::chrono::steady_clock::now() >= until) return std::nullopt;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }

 private:
  dds_entity_t reader_;
};

}  // namespace streamclust::ros2
