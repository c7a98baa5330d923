// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The DDS participant of `ros2` and `replay --to ros2://`, with the
/// tool's exit codes: a bad domain id (ROS_DOMAIN_ID) is a usage error (2),
/// DDS failing to start a network error (6).

#include "cli/live.hpp"
#include "cli/options.hpp"

#include <streamclust/ros2/dds_domain.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace streamclust::cli {

/// A participant on `domain` (default: ROS_DOMAIN_ID, else 0), with
/// loopback-only discovery when asked; `command` prefixes errors.
inline std::unique_ptr<ros2::DdsParticipant> open_participant(std::optional<std::uint32_t> domain, bool loopback,
                                                              const std::string& command) {
  try {
    ros2::DomainOptions d;
    d.domain_id = domain;
    d.loopback = loopback;
    return std::make_unique<ros2::DdsParticipant>(d);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  } catch (const ros2::DdsError& e) {
    throw NetworkError(command + ": " + e.what());
  }
}

}  // namespace streamclust::cli
