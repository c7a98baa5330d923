// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Track and TrackState: what a tracker reports per retrieval.

#include <streamclust/tracking/oriented_box.hpp>
#include <streamclust/types.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>

namespace streamclust {
namespace tracking {

/// Where a track stands.
enum class TrackState {
  tentative,  ///< seen, not yet often enough to be reported as an object
  confirmed,  ///< seen in this retrieval and confirmed
  coasting,   ///< confirmed, not seen in this retrieval: predicted
};

/// "tentative", "confirmed" or "coasting".
inline const char* to_string(TrackState s) {
  switch (s) {
    case TrackState::tentative: return "tentative";
    case TrackState::confirmed: return "confirmed";
    case TrackState::coasting: return "coasting";
  }
  return "unknown";
}

/// One tracked object at a retrieval's time, in the world frame of the
/// engine's points (poses or mount; z up).
struct Track {
  std::uint64_t id = 0;                    ///< the track's own id: never reused, never changes
  ComponentId cluster_id = kNoComponent;   ///< the component seen this retrieval, kNoComponent when coasting
  Eigen::Vector3f position = Eigen::Vector3f::Zero();  ///< [m] box centre
  Eigen::Vector3f velocity = Eigen::Vector3f::Zero();  ///< [m/s] zero while the track is static; vz always 0
  float length = 0.0f, width = 0.0f, height = 0.0f;    ///< [m] the box's, smoothed
  float yaw = 0.0f;        ///< [rad] the box's heading; the direction of travel once moving, in (-pi, pi]
  std::size_t points = 0;  ///< points of the component seen (0 when coasting)
  TrackState state = TrackState::tentative;
  bool moving = false;     ///< the speed stands clear of zero (see the tracker's rule)
  float speed_error = 0.0f;  ///< [m/s] standard deviation of each velocity component
  std::uint32_t hits = 0;    ///< retrievals the track was seen in
  double first_seen = 0.0;   ///< [s]
  double last_seen = 0.0;    ///< [s]
  BoxQuality box_quality = BoxQuality::few_points;  ///< the last box seen
};

}  // namespace tracking
}  // namespace streamclust
