// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust evaluate --tracks`: are the tracks the objects, with their
/// velocities? Simulates one scenario with the objects' truth boxes and
/// velocities (sim::Scene::object_state), runs the tracking methods on the
/// same stream and scores every retrieval of a 20 Hz schedule after the
/// first window with eval::TrackMetricsAccumulator:
/// - objects: the objects preset with poses, its components' oriented boxes
///   and in-window velocities (tracking::ObjectBoxes) into KalmanTracker;
/// - objects-centroid: the same boxes into CentroidTracker (what the
///   component ids and the in-window velocity add);
/// - centroid: the peer, what multiple-object-tracking-lidar users run: per
///   window, the frame pipeline's RANSAC ground (and indoors ceiling)
///   removal on the sensor-frame points, Euclidean clustering of the rest in
///   the world frame (each point moved by its own pose: the peer gets the
///   poses too), the centroids of clusters of 10 or more points no wider
///   than --peer-max-extent into CentroidTracker.
/// Results and definitions: docs/evaluation.md, section "Tracks".

#include "cli/json.hpp"
#include "cli/options.hpp"
#include "cli/simulate.hpp"

#include <streamclust/eval/track_metrics.hpp>

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace streamclust::cli {

/// Everything `streamclust evaluate --tracks` needs.
struct EvaluateTracksOptions {
  SimulateOptions scenario;      ///< sensor, scene, mount, duration (default 4 s), seed, ego-motion, noise
  float height = 0.0f;           ///< [m] sensor above the ground; 0: 1.0, or 2.5 when mounted upside down
  double window_seconds = 0.5;   ///< T_B [s]
  double rate_hz = 20.0;         ///< retrievals per second of stream time
  bool run_objects = true, run_objects_centroid = true, run_centroid = true;
  eval::TrackMetricOptions metrics;  ///< match distance, rated points (50), still speed
  float peer_distance = 0.6f;    ///< [m] the peer's Euclidean radius
  float plane_distance = 0.1f;   ///< [m] the peer's ground (ceiling) inlier tolerance
  float peer_max_extent = 10.0f;  ///< [m] the peer drops clusters longer than this (walls, buildings)
  std::string frame_ceiling = "auto";  ///< the peer removes a ceiling: on, off, auto (the office)
  std::size_t ransac_iterations = 100;
  std::string tracks_path;       ///< the objects method's tracks as a tracks CSV ("" = none)
  std::string json_path;
  bool quiet = false;
};

/// Parses the options of `evaluate --tracks` (`args` without "--tracks").
/// Throws UsageError naming the option.
EvaluateTracksOptions parse_evaluate_tracks_options(const std::vector<std::string>& args);

/// One method's scores.
struct TracksMethodResult {
  std::string name;  ///< objects, objects-centroid or centroid
  eval::TrackMetrics metrics;
  double id_switches_per_object_4s = 0.0;  ///< id switches / objects, scaled to a 4 s stream
  std::vector<double> cost_ms;  ///< per scored retrieval: boxes (or centroids) and tracker [ms]
  double cost_median_ms = 0.0;
  double cost_p99_ms = 0.0;
};

/// The outcome of one run.
struct TracksEvaluation {
  std::size_t records = 0;
  float height = 0.0f;             ///< [m]
  double scored_seconds = 0.0;     ///< stream time from the first to the last scored retrieval [s]
  std::size_t moving_objects = 0;  ///< objects of the scene that move
  std::vector<TracksMethodResult> methods;
};

/// Simulates the scenario and runs the methods (tools/cli/evaluate_tracks.cpp).
TracksEvaluation evaluate_tracks(const EvaluateTracksOptions& o);

/// The run as JSON.
Json tracks_evaluation_json(const EvaluateTracksOptions& o, const TracksEvaluation& e);

/// The human-readable table.
void print_tracks_evaluation(std::ostream& out, const EvaluateTracksOptions& o, const TracksEvaluation& e);

/// Runs `streamclust evaluate --tracks`: 0; throws UsageError (exit 2) and
/// std::runtime_error for an unwritable output (exit 4).
int run_evaluate_tracks(const EvaluateTracksOptions& o, std::ostream& out);

/// The help of `evaluate --tracks`.
const char* evaluate_tracks_help();

}  // namespace streamclust::cli
