// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// KalmanTrackerParams: the settings of KalmanTracker (kalman_tracker.hpp),
/// with their units and ranges, and their validation.

#include <streamclust/detail/parameter_check.hpp>

#include <cstddef>
#include <cstdint>

namespace streamclust {

/// The settings of KalmanTracker; what each rule does is told there.
struct KalmanTrackerParams {
  float gate_distance = 1.5f;          ///< [m] association distance beyond the prediction's uncertainty, (0, 100]
  float gate_height = 0.5f;            ///< [m] farther above or below a track's box: not paired by position, [0, 100]
  std::size_t birth_points = 30;       ///< points an observation needs to start a track, [1, 1000000]
  float birth_clearance = 1.0f;        ///< [m] an observation whose lowest point is this far above the ground under it starts no track, (0, 1000]
  float birth_neighbourhood = 3.0f;    ///< [m] where that ground is unknown, the lowest point of the observations centred this near stands for it, [0, 100]
  float birth_max_length = 10.0f;      ///< [m] an observation longer than this starts no track (walls, buildings, terrain in one component), (0, 1000]
  float birth_max_area = 30.0f;        ///< [m^2] nor one whose footprint is larger (a bus: 12 x 2.5 m; a wide crown: 5 x 5 m), (0, 1000000]
  float birth_flatness = 0.1f;         ///< an observation lower than this fraction of its length starts no track (a patch of ground or ceiling), [0, 1]
  float birth_min_width = 0.08f;       ///< [m] an observation narrower than this and over 2.5 times as long starts no track (a piece of wall seen flat), [0, 10]
  float birth_ceiling_gap = 0.3f;      ///< [m] a top this near the ceiling starts no track (but a pillar's), [0, 10]
  std::uint32_t confirm_hits = 3;      ///< retrievals a track is seen in before it is confirmed, [1, 1000]
  double coast_seconds = 1.0;          ///< [s] a confirmed track unseen this long is dropped, [0, 100]
  double tentative_coast_seconds = 0.2;  ///< [s] the same for a tentative track, [0, 100]
  double out_of_sight_seconds = 0.4;   ///< [s] the same for a static one with nothing between it and the sensor, [0, 100]
  float acceleration_noise = 0.5f;     ///< [m/s^2] white acceleration of the motion model (spectral density: its square, m^2/s^3), (0, 100]
  float group_margin = 0.3f;           ///< [m] a box holding two confirmed tracks' predictions this far inside its edges is a group, [0, 10]
  float position_noise = 0.15f;        ///< [m] centre of a box seen on two sides, (0, 10]
  float partial_position_noise = 0.4f;  ///< [m] centre of any other box, (0, 10]
  float initial_speed_noise = 3.0f;    ///< [m/s] velocity uncertainty of a new track without a window velocity, (0, 100]
  float moving_speed = 0.4f;           ///< [m/s] speed above which a track can move, (0, 100]
  float extent_smoothing = 0.3f;       ///< weight of a new box's extent, height and heading, (0, 1]
  float restart_speed = 2.0f;          ///< [m/s] a static track whose windows show motion this fast..., (0, 100]
  std::uint32_t restart_updates = 3;   ///< ...in this many successive updates starts moving at it, [1, 1000]
  std::uint32_t ceiling_hide_updates = 3;  ///< a static track reaching the ceiling this often in a row: set aside, [0, 1000]

  /// Throws std::invalid_argument naming the first setting out of range.
  void validate() const {
    check(gate_distance > 0.0f && gate_distance <= 100.0f, "gate_distance", gate_distance, "(0, 100] m");
    check(gate_height >= 0.0f && gate_height <= 100.0f, "gate_height", gate_height, "[0, 100] m");
    check(birth_points >= 1 && birth_points <= 1000000, "birth_points", static_cast<double>(birth_points),
          "[1, 1000000]");
    check(birth_clearance > 0.0f && birth_clearance <= 1000.0f, "birth_clearance", birth_clearance, "(0, 1000] m");
    check(birth_neighbourhood >= 0.0f && birth_neighbourhood <= 100.0f, "birth_neighbourhood", birth_neighbourhood,
          "[0, 100] m");
    check(birth_max_length > 0.0f && birth_max_length <= 1000.0f, "birth_max_length", birth_max_length,
          "(0, 1000] m");
    check(birth_max_area > 0.0f && birth_max_area <= 1e6f, "birth_max_area", birth_max_area, "(0, 1000000] m^2");
    check(birth_flatness >= 0.0f && birth_flatness <= 1.0f, "birth_flatness", birth_flatness, "[0, 1]");
    check(birth_min_width >= 0.0f && birth_min_width <= 10.0f, "birth_min_width", birth_min_width, "[0, 10] m");
    check(birth_ceiling_gap >= 0.0f && birth_ceiling_gap <= 10.0f, "birth_ceiling_gap", birth_ceiling_gap,
          "[0, 10] m");
    check(confirm_hits >= 1 && confirm_hits <= 1000, "confirm_hits", confirm_hits, "[1, 1000]");
    check(coast_seconds >= 0.0 && coast_seconds <= 100.0, "coast_seconds", coast_seconds, "[0, 100] s");
    check(tentative_coast_seconds >= 0.0 && tentative_coast_seconds <= 100.0, "tentative_coast_seconds",
          tentative_coast_seconds, "[0, 100] s");
    check(out_of_sight_seconds >= 0.0 && out_of_sight_seconds <= 100.0, "out_of_sight_seconds", out_of_sight_seconds,
          "[0, 100] s");
    check(acceleration_noise > 0.0f && acceleration_noise <= 100.0f, "acceleration_noise", acceleration_noise,
          "(0, 100] m/s^2");
    check(group_margin >= 0.0f && group_margin <= 10.0f, "group_margin", group_margin, "[0, 10] m");
    check(position_noise > 0.0f && position_noise <= 10.0f, "position_noise", position_noise, "(0, 10] m");
    check(partial_position_noise > 0.0f && partial_position_noise <= 10.0f, "partial_position_noise",
          partial_position_noise, "(0, 10] m");
    check(initial_speed_noise > 0.0f && initial_speed_noise <= 100.0f, "initial_speed_noise", initial_speed_noise,
          "(0, 100] m/s");
    check(moving_speed > 0.0f && moving_speed <= 100.0f, "moving_speed", moving_speed, "(0, 100] m/s");
    check(extent_smoothing > 0.0f && extent_smoothing <= 1.0f, "extent_smoothing", extent_smoothing, "(0, 1]");
    check(restart_speed > 0.0f && restart_speed <= 100.0f, "restart_speed", restart_speed, "(0, 100] m/s");
    check(restart_updates >= 1 && restart_updates <= 1000, "restart_updates", restart_updates, "[1, 1000]");
    check(ceiling_hide_updates <= 1000, "ceiling_hide_updates", ceiling_hide_updates, "[0, 1000]");
  }

 private:
  static void check(bool ok, const char* name, double value, const char* allowed) {
    detail::require_parameter(ok, "KalmanTracker", name, value, allowed);
  }
};

}  // namespace streamclust
