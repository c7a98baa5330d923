// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The laws the engine relies on for a ground policy (concepts/ground.hpp),
/// on a simulated Mid-360 in the office (level, 1 m above the floor, ceiling
/// at 3 m) or on points of your own, through a count window (each point
/// classified as it enters, forgotten with its class as it leaves):
///   - the default Params construct; each class is a SurfaceClass;
///   - replay: a second instance fed the same classify / forget sequence
///     makes the same decisions (they depend only on the points counted);
///   - bounded by the window: after every point of a first stream is
///     forgotten, a second stream is classed as by a fresh instance;
///   - an enabled policy finds structure in a scene with a floor (optional).
/// Cost: O(points) classify and forget calls, three times. Not thread-safe.

#include <streamclust/concepts/ground.hpp>
#include <streamclust/testing/law_result.hpp>
#include <streamclust/testing/livox_streams.hpp>
#include <streamclust/testing/type_name.hpp>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::testing {

/// A point as the ground policy sees it.
struct GroundInput {
  Eigen::Vector3f world;  ///< world frame, +z up [m]
  Eigen::Vector3f ray;    ///< from the sensor to the point, world orientation [m]
};

/// A level sensor at rest `height` metres above the world origin: world =
/// sensor-frame point + (0, 0, height), ray = the point.
inline std::vector<GroundInput> level_sensor_inputs(const std::vector<Point>& stream, float height) {
  std::vector<GroundInput> out;
  out.reserve(stream.size());
  for (const Point& p : stream) {
    const Eigen::Vector3f ray(p.x, p.y, p.z);
    out.push_back({ray + Eigen::Vector3f(0.0f, 0.0f, height), ray});
  }
  return out;
}

template <class G>
struct GroundLawOptions {
  std::vector<typename G::Params> params;  ///< parameter sets to test; empty: the defaults
  /// The points; empty: 12,000 points of a Mid-360 in the office at 200 kHz,
  /// 1 m above the floor.
  std::vector<GroundInput> points;
  std::size_t window = 3000;        ///< points the count window keeps
  bool expect_structure = true;     ///< an enabled policy must class some point as structure
};

namespace internal {

/// Classifies `points` through a count window of `window` points, leaving
/// the last window counted when `forget_rest` is false. Returns the classes.
template <class G>
std::vector<SurfaceClass> classify_through_window(G& ground, const std::vector<GroundInput>& points,
                                                  std::size_t first, std::size_t last, std::size_t window,
                                                  bool forget_rest) {
  std::vector<SurfaceClass> classes;
  std::deque<std::pair<std::size_t, SurfaceClass>> live;
  for (std::size_t i = first; i < last; ++i) {
    while (live.size() >= window) {
      ground.forget(points[live.front().first].world, live.front().second);
      live.pop_front();
    }
    const SurfaceClass c = ground.classify(points[i].world, points[i].ray);
    classes.push_back(c);
    live.emplace_back(i, c);
  }
  if (forget_rest) {
    for (const auto& [i, c] : live) ground.forget(points[i].world, c);
  }
  return classes;
}

}  // namespace internal

/// Every law of a ground policy (see the file comment); the first failure.
template <class G>
LawResult check_ground(const GroundLawOptions<G>& options = {}) {
  static_assert(is_ground_policy_v<G>, "check_ground: G does not model the ground concept (concepts/ground.hpp)");
  const std::string name = "ground " + type_name<G>();
  if (const std::string failure = internal::default_params_failure<G>(name); !failure.empty())
    return law_failed(failure);
  const std::vector<GroundInput> points =
      options.points.empty()
          ? level_sensor_inputs(simulated_livox_stream(LivoxSensor::mid360, "office", 1, 12000, 200000.0), 1.0f)
          : options.points;
  const std::vector<typename G::Params> sets = internal::parameter_sets(options.params);
  const std::size_t half = points.size() / 2;
  const std::size_t window = options.window == 0 ? 1 : options.window;
  std::size_t structure = 0;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const std::string context = name + ", parameter set " + std::to_string(k) + ": ";
    std::optional<G> a, b, c;
    if (const std::string thrown = internal::construct_from(sets[k], a, b, c); !thrown.empty())
      return law_failed(context + "the parameters do not construct: " + thrown);
    const auto first = internal::classify_through_window(*a, points, 0, points.size(), window, true);
    const auto replay = internal::classify_through_window(*b, points, 0, points.size(), window, true);
    for (std::size_t i = 0; i < first.size(); ++i) {
      if (static_cast<int>(first[i]) >= kSurfaceClassCount)
        return law_failed(context + "point " + std::to_string(i) + " is classed " +
                          std::to_string(static_cast<int>(first[i])) + ", not a SurfaceClass");
      structure += first[i] != SurfaceClass::object ? 1u : 0u;
      if (first[i] != replay[i])
        return law_failed(context + "replay: point " + std::to_string(i) + " is classed " +
                          std::to_string(static_cast<int>(replay[i])) + " by a second instance fed the same points, " +
                          std::to_string(static_cast<int>(first[i])) +
                          " by the first: a decision must depend only on the points counted");
    }
    // bounded by the window: the first half, all forgotten, then the second
    internal::classify_through_window(*a, points, 0, half, window, true);
    const auto after = internal::classify_through_window(*a, points, half, points.size(), window, true);
    const auto fresh = internal::classify_through_window(*c, points, half, points.size(), window, true);
    for (std::size_t i = 0; i < fresh.size(); ++i) {
      if (after[i] != fresh[i])
        return law_failed(context + "not bounded by the window: after every point of a first stream was forgotten, "
                          "point " + std::to_string(half + i) + " is classed " +
                          std::to_string(static_cast<int>(after[i])) + ", by a fresh instance " +
                          std::to_string(static_cast<int>(fresh[i])) + " (does forget undo classify?)");
    }
    (void)a->heap_bytes();
  }
  if (G::enabled && options.expect_structure && structure == 0)
    return law_failed(name + ": no point of " + std::to_string(points.size()) +
                      " was classed structure (a scene with a floor)");
  return law_passed(name + ": " + std::to_string(points.size()) + " points, " + std::to_string(structure) +
                    " structure decisions");
}

}  // namespace streamclust::testing
