// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A DDS participant on a ROS 2 domain (Cyclone DDS): the domain id from
/// `ROS_DOMAIN_ID` (0 when unset) as ROS 2 nodes take it, the rest of the
/// configuration from `CYCLONEDDS_URI` as Cyclone reads it, or, with
/// `loopback`, discovery on 127.0.0.1 by unicast (no multicast: Linux's `lo`
/// has none), which every participant of the exchange must use.
///
/// Thread-safety: the participant's handle may be used from any thread
/// (Cyclone's entities are thread-safe); construction and destruction are
/// the owner's.

#include <dds/dds.h>

#include <cstdint>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>

namespace streamclust::ros2 {

/// A DDS call that failed, naming the call and Cyclone's reason.
class DdsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws DdsError when `rc` (a Cyclone return code or entity) is an error.
inline dds_return_t check_dds(dds_return_t rc, const std::string& what) {
  if (rc < 0) throw DdsError(what + ": " + dds_strretcode(rc));
  return rc;
}

/// The largest domain id whose RTPS ports fit in 16 bits (7400 + 250 d + ...).
inline constexpr std::uint32_t kMaxDomainId = 232;

/// The domain of `ROS_DOMAIN_ID`, 0 when unset or empty. Throws
/// std::invalid_argument for a value that is not a number in [0, 232].
inline std::uint32_t ros_domain_id_from_environment() {
  const char* v = std::getenv("ROS_DOMAIN_ID");
  if (v == nullptr || *v == '\0') return 0;
  char* end = nullptr;
  const unsigned long id = std::strtoul(v, &end, 10);
  if (*end != '\0' || id > kMaxDomainId || v[0] == '-')
    throw std::invalid_argument(std::string("ROS_DOMAIN_ID '") + v + "': expected a domain id from 0 to " +
                                std::to_string(kMaxDomainId) + " (ROS 2 recommends 0 to 101)");
  return static_cast<std::uint32_t>(id);
}

/// Cyclone's configuration for discovery on the loopback interface only:
/// unicast to 127.0.0.1 at the ports of the first `participants` indices.
inline std::string loopback_config(std::uint32_t participants = 20) {
  return "<General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
         "<AllowMulticast>false</AllowMulticast></General>"
         "<Discovery><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>" +
         std::to_string(participants) +
         "</MaxAutoParticipantIndex><Peers><Peer Address=\"127.0.0.1\"/></Peers></Discovery>";
}

struct DomainOptions {
  std::optional<std::uint32_t> domain_id;  ///< default: ROS_DOMAIN_ID, else 0
  bool loopback = false;                   ///< discovery on 127.0.0.1 by unicast (loopback_config)
};

/// A participant on the domain. Not copyable.
class DdsParticipant {
 public:
  explicit DdsParticipant(const DomainOptions& o = {}) {
    domain_ = o.domain_id ? *o.domain_id : ros_domain_id_from_environment();
    if (domain_ > kMaxDomainId)
      throw std::invalid_argument("domain id " + std::to_string(domain_) + ": expected 0 to " +
                                  std::to_string(kMaxDomainId));
    if (o.loopback) {
      // The domain may exist already in this process (another participant
      // on it): that one's configuration then holds.
      const dds_entity_t d = dds_create_domain(domain_, loopback_config().c_str());
      if (d < 0 && d != DDS_RETCODE_PRECONDITION_NOT_MET) check_dds(d, "creating DDS domain " + std::to_string(domain_));
      if (d >= 0) domain_entity_ = d;
    }
    handle_ = check_dds(dds_create_participant(domain_, nullptr, nullptr),
                        "creating a DDS participant on domain " + std::to_string(domain_));
  }
  ~DdsParticipant() {
    if (handle_ > 0) dds_delete(handle_);
    if (domain_entity_ > 0) dds_delete(domain_entity_);
  }
  DdsParticipant(const DdsParticipant&) = delete;
  DdsParticipant& operator=(const DdsParticipant&) = delete;

  dds_entity_t handle() const noexcept { return handle_; }
  std::uint32_t domain() const noexcept { return domain_; }

 private:
  std::uint32_t domain_ = 0;
  dds_entity_t domain_entity_ = 0;
  dds_entity_t handle_ = 0;
};

}  // namespace streamclust::ros2
