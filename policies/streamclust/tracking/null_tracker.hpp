// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// NullTracker: no tracking (the default): no box is fitted, no track kept.

#include <streamclust/concepts/tracker.hpp>
#include <streamclust/tracking/object_boxes.hpp>
#include <streamclust/tracking/track.hpp>

#include <vector>

namespace streamclust {

/// Tracks nothing; `update` returns no track. Thread safety: any (stateless).
class NullTracker {
 public:
  struct Params {};
  static constexpr bool enabled = false;

  NullTracker() = default;
  explicit NullTracker(const Params&) {}

  const std::vector<tracking::Track>& update(const std::vector<tracking::ObjectObservation>&, double) {
    return tracks_;
  }
  const std::vector<tracking::Track>& tracks() const { return tracks_; }

 private:
  std::vector<tracking::Track> tracks_;
};

static_assert(is_tracker_policy_v<NullTracker>, "NullTracker must model the Tracker policy");

}  // namespace streamclust
