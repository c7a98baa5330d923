// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Realistic inputs for the test kit from the scan simulator (streamclust::sim):
/// Livox Mid-360 and Avia streams of the ready-made scenes, as exactness
/// stream sources, and candidate pairs as a mask search meets them (points
/// of nearby rays, revisits of the same direction, depth jumps).
/// Deterministic for a seed. Cost: one ray cast per point.

#include <streamclust/point_traits.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/avia_model.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/simulator.hpp>
#include <streamclust/testing/exactness_run.hpp>
#include <streamclust/types.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace streamclust::testing {

/// The Livox sensor of a simulated stream.
enum class LivoxSensor { mid360, avia };

/// `length` points of `sensor` (level, 1 m above the floor or ground,
/// at rest) in the ready-made scene `scene` ("office", "forest", "street",
/// "hills"; placed from `seed`), firing at `point_rate` [Hz]: the real
/// scan pattern sampled `point_rate` times a second, so the stream spans
/// length / point_rate seconds (200 kHz / 240 kHz: the real sensors' density).
/// The scan starts at a time drawn from the seed. Sensor frame, stream time.
inline std::vector<Point> simulated_livox_stream(LivoxSensor sensor, std::string_view scene, std::uint64_t seed,
                                                 std::size_t length, double point_rate) {
  sim::Simulator<sim::Mid360Model>::Params sp;  // the same Params for every sensor model
  sp.seed = seed + 1;
  const double start = 0.01 * static_cast<double>(seed % 50);  // [s]
  std::vector<Point> out;
  out.reserve(length);
  const auto run = [&](auto simulator) {
    while (out.size() < length) {
      const sim::SimPoint p = simulator.next();
      out.push_back(Point{p.x, p.y, p.z, p.intensity, p.t});
    }
  };
  if (sensor == LivoxSensor::mid360) {
    sim::Mid360Model::Params mp;
    mp.point_rate = point_rate;
    mp.start_time = start;
    sim::Simulator<sim::Mid360Model> simulator(sim::Mid360Model(mp), sim::make_scene(scene, seed), sp);
    run(std::move(simulator));
  } else {
    sim::AviaModel::Params ap;
    ap.point_rate = point_rate;
    ap.start_time = start;
    sim::Simulator<sim::AviaModel>::Params avia;
    avia.seed = sp.seed;
    sim::Simulator<sim::AviaModel> simulator(sim::AviaModel(ap), sim::make_scene(scene, seed), avia);
    run(std::move(simulator));
  }
  return out;
}

/// Simulated stream sources for the exactness check: a Mid-360 and an Avia
/// in the office and a Mid-360 in the street, sampled at `point_rate` [Hz]
/// (default 2 kHz: 320 points span 0.16 s, so that short windows turn over),
/// and a Mid-360 in the forest at its real 200 kHz (dense: crowded cells).
inline std::vector<StreamSource> livox_stream_sources(double point_rate = 2000.0) {
  struct Spec {
    const char* name;
    LivoxSensor sensor;
    const char* scene;
    double rate;
  };
  const Spec specs[] = {{"mid360 office", LivoxSensor::mid360, "office", point_rate},
                        {"avia office", LivoxSensor::avia, "office", point_rate},
                        {"mid360 street", LivoxSensor::mid360, "street", point_rate},
                        {"mid360 forest, 200 kHz", LivoxSensor::mid360, "forest", 200000.0}};
  std::vector<StreamSource> sources;
  for (const Spec& s : specs) {
    sources.push_back({s.name, [s](std::uint64_t seed, std::size_t length) {
                         return simulated_livox_stream(s.sensor, s.scene, seed, length, s.rate);
                       }});
  }
  return sources;
}

/// The random and adversarial sources followed by the Livox ones.
inline std::vector<StreamSource> random_and_livox_stream_sources() {
  std::vector<StreamSource> sources = random_stream_sources();
  for (StreamSource& s : livox_stream_sources()) sources.push_back(std::move(s));
  return sources;
}

/// About `count` pairs of Samples as a mask search meets them in real scans:
/// a Mid-360 and an Avia at their real rates in the office and the forest,
/// each point paired with up to four earlier points whose rays lie within
/// 0.5 degrees of its own (the same or an adjacent direction bin): surfaces
/// seen face-on and at grazing angles, revisits, edges and depth jumps.
inline std::vector<std::pair<Sample, Sample>> livox_candidate_pairs(std::size_t count, std::uint64_t seed) {
  std::vector<std::pair<Sample, Sample>> pairs;
  constexpr double kBin = 0.5 * 3.14159265358979323846 / 180.0;  // [rad]
  const struct {
    LivoxSensor sensor;
    const char* scene;
    double rate;
  } runs[] = {{LivoxSensor::mid360, "office", 200000.0},
              {LivoxSensor::avia, "office", 240000.0},
              {LivoxSensor::mid360, "forest", 200000.0},
              {LivoxSensor::avia, "street", 240000.0}};
  const std::size_t per_run = count / 4 + 1;
  for (const auto& r : runs) {
    const std::vector<Point> stream = simulated_livox_stream(r.sensor, r.scene, seed, per_run, r.rate);
    std::unordered_map<std::int64_t, std::vector<std::size_t>> bins;  // direction bin -> points, in order
    std::vector<Sample> samples;
    samples.reserve(stream.size());
    std::size_t made = 0;
    for (const Point& p : stream) {
      const Eigen::Vector3f pos(p.x, p.y, p.z);
      const float range = pos.norm();
      if (!(range > 0.0f)) continue;
      samples.push_back(make_sample(pos, range, p.intensity, p.t));
      const auto az = static_cast<std::int64_t>(std::floor(std::atan2(p.y, p.x) / kBin));
      const auto el = static_cast<std::int64_t>(std::floor(std::asin(p.z / range) / kBin));
      const std::size_t me = samples.size() - 1;
      int taken = 0;
      for (std::int64_t da = 0; da <= 1 && taken < 4; ++da) {
        const auto it = bins.find((az - da) * 100000 + el);
        if (it == bins.end()) continue;
        for (auto k = it->second.rbegin(); k != it->second.rend() && taken < 4; ++k, ++taken)
          pairs.emplace_back(samples[me], samples[*k]);
      }
      bins[az * 100000 + el].push_back(me);
      made += static_cast<std::size_t>(taken);
      if (made >= per_run) break;
    }
  }
  return pairs;
}

}  // namespace streamclust::testing
