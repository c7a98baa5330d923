// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The simulated Livox streams the benchmark kit measures on: a sensor
/// (Mid-360 or Avia, streamclust::sim's models) in a scene of
/// streamclust::sim (office, forest, ...), moving slowly forward as a
/// hand-held sensor, simulated once per process and shared.
///
/// ```cpp
/// namespace bk = streamclust::benchmarking;
/// const bk::Scenario s{bk::Sensor::mid360, "office"};
/// const std::vector<streamclust::sim::SimPoint>& points = bk::simulated_points(s, 2.0);  // 2 s, cached
/// ```
/// Thread-safety: the caches are function-local statics guarded by a mutex;
/// the returned references stay valid for the process's lifetime.

#include <streamclust/motion/trajectory.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/sensors.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/avia_model.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/simulator.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace streamclust::benchmarking {

/// The Livox sensors the kit simulates.
enum class Sensor { mid360, avia };

/// "mid360" or "avia".
inline const char* sensor_name(Sensor s) { return s == Sensor::mid360 ? "mid360" : "avia"; }

/// One simulated stream: a sensor in a scene of sim::make_scene (scene seed 3).
struct Scenario {
  Sensor sensor = Sensor::mid360;
  std::string scene = "office";  ///< a name of sim::kSceneNames
  /// e.g. "mid360_office"
  std::string name() const { return std::string(sensor_name(sensor)) + "_" + scene; }
};

/// The Mid-360 and the Avia in the office.
inline std::vector<Scenario> office_scenarios() { return {{Sensor::mid360, "office"}, {Sensor::avia, "office"}}; }

/// The sensor's field of view as the spherical projection's parameters
/// (streamclust/sensors.hpp's table).
inline SphericalProjection::Params field_of_view(Sensor s) {
  const SensorFacts& spec = s == Sensor::mid360 ? livox_mid360 : livox_avia;
  SphericalProjection::Params f;
  if (s == Sensor::avia) {
    f.azimuth_min_deg = spec.projection_azimuth_min_deg();
    f.azimuth_max_deg = spec.projection_azimuth_max_deg();
  }
  f.elevation_min_deg = spec.projection_elevation_min_deg();
  f.elevation_max_deg = spec.projection_elevation_max_deg();
  return f;
}

namespace detail {

/// The simulator's parameters of every kit stream: 0.5 m/s forward, seed 7.
template <class Model>
typename sim::Simulator<Model>::Params simulator_params() {
  typename sim::Simulator<Model>::Params p;
  p.velocity = Eigen::Vector3f(0.5f, 0.0f, 0.0f);  // slow ego-motion, as a hand-held sensor
  p.seed = 7;
  return p;
}

template <class Model, class F>
auto with_simulator(const Scenario& s, F&& f) {
  sim::Simulator<Model> simulator(Model{}, sim::make_scene(s.scene, 3), simulator_params<Model>());
  return f(simulator);
}

/// Calls `f(simulator)` with a fresh simulator of scenario `s`.
template <class F>
auto with_simulator(const Scenario& s, F&& f) {
  if (s.sensor == Sensor::mid360) return with_simulator<sim::Mid360Model>(s, std::forward<F>(f));
  return with_simulator<sim::AviaModel>(s, std::forward<F>(f));
}

/// A process-wide cache keyed by (scenario, seconds).
template <class T, class Make>
const T& cached(const Scenario& s, double seconds, Make make) {
  static std::mutex mutex;
  static std::map<std::tuple<int, std::string, double>, std::unique_ptr<const T>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[{static_cast<int>(s.sensor), s.scene, seconds}];
  if (!slot) slot = std::make_unique<const T>(make());
  return *slot;
}

}  // namespace detail

/// The first `seconds` of scenario `s`'s stream (time-ordered, t from 0).
/// Simulated on first use, then cached. O(points) the first time.
inline const std::vector<sim::SimPoint>& simulated_points(const Scenario& s, double seconds) {
  return detail::cached<std::vector<sim::SimPoint>>(s, seconds, [&] {
    return detail::with_simulator(s, [&](auto& simulator) {
      std::vector<sim::SimPoint> out;
      out.reserve(static_cast<std::size_t>(seconds * 250000.0));
      while (simulator.time() < seconds) out.push_back(simulator.next());
      return out;
    });
  });
}

/// The sensor's poses over the first `seconds` of scenario `s` (100 Hz, as
/// odometry; for configurations that place points with PosedMotion).
inline std::shared_ptr<const PoseTrajectory> simulated_trajectory(const Scenario& s, double seconds) {
  return detail::cached<std::shared_ptr<const PoseTrajectory>>(s, seconds, [&] {
    return detail::with_simulator(s, [&](auto& simulator) {
      return std::make_shared<const PoseTrajectory>(simulator.trajectory(0.0, seconds + 0.1, 100.0));
    });
  });
}

/// [m] the simulated sensor above the floor or ground at the start.
inline float simulated_sensor_height() { return detail::simulator_params<sim::Mid360Model>().start_position.z(); }

}  // namespace streamclust::benchmarking
