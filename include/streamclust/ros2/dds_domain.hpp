// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A DDS participant on a ROS 2 domain (Cyclone DDS): the domain id from
/// `ROS_DOMAIN_ID` (0 when unset) as ROS 2 nodes take it, the rest of the
/// configuration from `CYCLONEDDS_URI` as Cyclone reads it, or, with
/// `loopback`, discovery on 127.0.0.1 by unicast (no multicast: Linux's `lo`
/// has none), which every participant of the exchange must use.
///
/// Participants of one process on one domain share it: the domain a
/// loopback participant creates lives until the last participant on that
/// domain id in the process is gone, so one participant's end never takes
/// another's entities with it.
///
/// Thread-safety: the participant's handle may be used from any thread
/// (Cyclone's entities are thread-safe); construction and destruction are
/// the owner's, and participants may be made and destroyed concurrently.

#include <dds/dds.h>

#include <cstdint>
#include <cstdlib>
#include <map>
#include <mutex>
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

namespace detail {

/// The domains this process's participants use: per domain id, the domain
/// entity a loopback participant created (0 when Cyclone made the domain
/// implicitly) and how many participants are on it.
class DomainUsers {
 public:
  static DomainUsers& instance() {
    static DomainUsers users;
    return users;
  }

  /// A new participant on `domain_id`, creating the domain with the loopback
  /// configuration first when asked and the domain does not exist yet.
  dds_entity_t join(std::uint32_t domain_id, bool loopback) {
    const std::lock_guard<std::mutex> lock(mutex_);
    Domain& d = domains_[domain_id];
    if (loopback && d.participants == 0) {
      // The domain may exist already without a participant of ours (one
      // made by other code): that one's configuration then holds.
      const dds_entity_t e = dds_create_domain(domain_id, loopback_config().c_str());
      if (e < 0 && e != DDS_RETCODE_PRECONDITION_NOT_MET) {
        release(domain_id, d);
        check_dds(e, "creating DDS domain " + std::to_string(domain_id));
      }
      if (e >= 0) d.entity = e;
    }
    const dds_entity_t participant = dds_create_participant(domain_id, nullptr, nullptr);
    if (participant < 0) {
      if (d.participants == 0) release(domain_id, d);
      check_dds(participant, "creating a DDS participant on domain " + std::to_string(domain_id));
    }
    ++d.participants;
    return participant;
  }

  /// Deletes `participant`, and the domain with the last one.
  void leave(std::uint32_t domain_id, dds_entity_t participant) {
    const std::lock_guard<std::mutex> lock(mutex_);
    dds_delete(participant);
    const auto it = domains_.find(domain_id);
    if (it != domains_.end() && --it->second.participants == 0) release(domain_id, it->second);
  }

 private:
  struct Domain {
    dds_entity_t entity = 0;
    std::size_t participants = 0;
  };
  void release(std::uint32_t domain_id, const Domain& d) {
    if (d.entity > 0) dds_delete(d.entity);
    domains_.erase(domain_id);
  }

  std::mutex mutex_;
  std::map<std::uint32_t, Domain> domains_;
};

}  // namespace detail

/// A participant on the domain. Not copyable.
class DdsParticipant {
 public:
  explicit DdsParticipant(const DomainOptions& o = {}) {
    domain_ = o.domain_id ? *o.domain_id : ros_domain_id_from_environment();
    if (domain_ > kMaxDomainId)
      throw std::invalid_argument("domain id " + std::to_string(domain_) + ": expected 0 to " +
                                  std::to_string(kMaxDomainId));
    handle_ = detail::DomainUsers::instance().join(domain_, o.loopback);
  }
  ~DdsParticipant() { detail::DomainUsers::instance().leave(domain_, handle_); }
  DdsParticipant(const DdsParticipant&) = delete;
  DdsParticipant& operator=(const DdsParticipant&) = delete;

  dds_entity_t handle() const noexcept { return handle_; }
  std::uint32_t domain() const noexcept { return domain_; }

 private:
  std::uint32_t domain_ = 0;
  dds_entity_t handle_ = 0;
};

}  // namespace streamclust::ros2
