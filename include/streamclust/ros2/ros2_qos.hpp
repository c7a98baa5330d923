// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The QoS settings ROS 2 endpoints use (rmw/qos_profiles.h), as DDS QoS:
///
/// | profile | reliability | durability | history |
/// |---|---|---|---|
/// | sensor data | best effort | volatile | keep last 5 |
/// | default (`create_publisher(topic, N)`) | reliable | volatile | keep last N (10) |
///
/// Matching (requested vs offered): a best-effort reader matches every
/// writer, a reliable reader only reliable writers; a volatile reader
/// matches volatile and transient-local writers. An unmatched pair is
/// reported by DDS as an incompatible QoS (its policy named by
/// `describe_policy`).

#include <dds/dds.h>

#include <cstdint>
#include <memory>
#include <string>

namespace streamclust::ros2 {

enum class Reliability { best_effort, reliable };
enum class Durability { volatile_, transient_local };

struct TopicQos {
  Reliability reliability = Reliability::reliable;
  Durability durability = Durability::volatile_;
  std::int32_t depth = 10;  ///< keep last `depth` samples
};

/// ROS 2's sensor-data profile.
inline TopicQos sensor_data_qos() { return {Reliability::best_effort, Durability::volatile_, 5}; }
/// ROS 2's default profile with a history of `depth`.
inline TopicQos default_qos(std::int32_t depth = 10) { return {Reliability::reliable, Durability::volatile_, depth}; }

inline const char* describe(Reliability r) { return r == Reliability::reliable ? "reliable" : "best effort"; }

/// Owns a dds_qos_t.
using QosPointer = std::unique_ptr<dds_qos_t, void (*)(dds_qos_t*)>;

/// `q` as DDS QoS (XCDR1 data representation, as ROS 2 uses).
inline QosPointer make_dds_qos(const TopicQos& q) {
  QosPointer p(dds_create_qos(), dds_delete_qos);
  dds_qset_reliability(p.get(), q.reliability == Reliability::reliable ? DDS_RELIABILITY_RELIABLE
                                                                       : DDS_RELIABILITY_BEST_EFFORT,
                       DDS_SECS(1));
  dds_qset_durability(p.get(), q.durability == Durability::volatile_ ? DDS_DURABILITY_VOLATILE
                                                                     : DDS_DURABILITY_TRANSIENT_LOCAL);
  dds_qset_history(p.get(), DDS_HISTORY_KEEP_LAST, q.depth);
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(p.get(), 1, &xcdr1);
  return p;
}

/// The name of the QoS policy an incompatible-QoS status reports.
inline std::string describe_policy(std::uint32_t policy_id) {
  switch (policy_id) {
    case DDS_RELIABILITY_QOS_POLICY_ID: return "reliability";
    case DDS_DURABILITY_QOS_POLICY_ID: return "durability";
    case DDS_DEADLINE_QOS_POLICY_ID: return "deadline";
    case DDS_LIVELINESS_QOS_POLICY_ID: return "liveliness";
    case DDS_OWNERSHIP_QOS_POLICY_ID: return "ownership";
    case DDS_PRESENTATION_QOS_POLICY_ID: return "presentation";
    case DDS_DESTINATIONORDER_QOS_POLICY_ID: return "destination order";
    case DDS_DATA_REPRESENTATION_QOS_POLICY_ID: return "data representation";
    case DDS_TYPE_CONSISTENCY_ENFORCEMENT_QOS_POLICY_ID: return "type consistency";
    default: return "policy " + std::to_string(policy_id);
  }
}

}  // namespace streamclust::ros2
