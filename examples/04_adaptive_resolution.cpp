// SPDX-License-Identifier: MIT
// Example 4: how the adaptive loop picks the range grid for each scan
// pattern. For every simulated sensor, window T_B and multiplicity target
// T_M it calibrates AdaptiveResolution on the first window's directions and
// prints the chosen grid, the iterations, why the loop stopped and the final
// mean multiplicity. Then the same controller initialises the continuous
// engine and the frame baseline. Usage: example_04_adaptive_resolution
// (the table in docs/adaptive-resolution.md is this program's output).

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/sim/sensors/avia_model.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/sensors/risley_pair_model.hpp>
#include <streamclust/sim/sensors/spinning_model.hpp>
#include <streamclust/streamclust.hpp>

#include <cstdio>
#include <string>
#include <vector>

namespace sc = streamclust;

namespace {

struct Pattern {
  std::string name;
  sc::SphericalProjection::Params fov;
  std::vector<sc::sim::Ray> rays;  // 0.5 s of firings
};

sc::SphericalProjection::Params fov(float azimuth_half_deg, float elevation_min_deg, float elevation_max_deg) {
  sc::SphericalProjection::Params f;
  f.azimuth_min_deg = -azimuth_half_deg;
  f.azimuth_max_deg = azimuth_half_deg;
  f.elevation_min_deg = elevation_min_deg;
  f.elevation_max_deg = elevation_max_deg;
  return f;
}

template <class Sensor>
Pattern record(std::string name, Sensor sensor, const sc::SphericalProjection::Params& f, double seconds) {
  Pattern p{std::move(name), f, {}};
  for (sc::sim::Ray r = sensor.next(); r.time < seconds; r = sensor.next()) p.rays.push_back(r);
  return p;
}

// The directions of the rays fired in [0, window) s, projected (a sphere of 10 m).
std::vector<sc::Projected> first_window(const Pattern& p, const sc::SphericalProjection& projection, double window) {
  std::vector<sc::Projected> coords;
  for (const sc::sim::Ray& r : p.rays) {
    if (r.time >= window) break;
    coords.push_back(projection.project(r.direction * 10.0f));
  }
  return coords;
}

}  // namespace

int main() {
  std::vector<Pattern> patterns;
  patterns.push_back(record("Mid-360", sc::sim::Mid360Model(), sc::field_of_view_of(sc::livox_mid360), 0.5));
  patterns.push_back(record("Mid-40", sc::sim::RisleyPairModel::mid40(), sc::field_of_view_of(sc::livox_mid40), 0.5));
  patterns.push_back(record("Mid-70", sc::sim::RisleyPairModel::mid70(), sc::field_of_view_of(sc::livox_mid70), 0.5));
  patterns.push_back(record("Avia", sc::sim::AviaModel(sc::sim::AviaModel::Params{}), sc::field_of_view_of(sc::livox_avia), 0.5));
  patterns.push_back(record("spinning-32", sc::sim::SpinningModel(sc::sim::SpinningModel::Params{}),
                            fov(180.0f, -25.5f, 15.5f), 0.5));

  std::printf("| sensor | T_B [s] | T_M | points | grid (H x W) | iterations | stop | final M_mu |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const Pattern& p : patterns) {
    const sc::SphericalProjection projection(p.fov);
    for (const double window : {0.1, 0.5}) {
      const std::vector<sc::Projected> coords = first_window(p, projection, window);
      for (const float t_m : {1.25f, 2.0f}) {
        sc::AdaptiveResolution::Params params;  // paper defaults: T_G 0.1, T_D 0.9, lambda 0.2
        params.max_multiplicity = t_m;
        sc::AdaptiveResolution loop(params);
        const sc::GridSize grid = loop.calibrate(coords, projection.fov_aspect());
        const float mu = sc::AdaptiveResolution::measure(coords, grid).mean_multiplicity;
        std::printf("| %s | %.1f | %.2f | %zu | %u x %u | %zu | %s | %.3f |\n", p.name.c_str(), window,
                    static_cast<double>(t_m), coords.size(), grid.rows, grid.cols, loop.trace().size(),
                    sc::to_string(loop.stop_reason()), static_cast<double>(mu));
      }
    }
  }

  // One controller type, three consumers: the continuous engine calibrates on
  // its first window, the batch clusterer (here the frame baseline) on the
  // frame it is given. Same policy, same input -> same grid.
  const Pattern& mid360 = patterns.front();
  sc::CArcParams carc = sc::carc_mid360_params();
  carc.window_seconds = 0.1;
  auto engine = sc::make_carc(carc);
  std::vector<sc::Point> frame;
  for (const sc::sim::Ray& r : mid360.rays) {
    if (r.time >= 0.1) break;
    const Eigen::Vector3f xyz = r.direction * 10.0f;
    frame.push_back(sc::Point{xyz.x(), xyz.y(), xyz.z(), 0.0f, r.time});
  }
  for (const sc::Point& p : frame) engine.insert(p);
  engine.complete_calibration();  // the stream ends before a point completes the window
  engine.retrieve();
  sc::BatchClusterer<sc::FrameBaselineConfig> baseline(sc::to_clusterer_params<sc::FrameBaselineConfig>(carc),
                                                       sc::BatchMode::range_image);
  const sc::BatchResult& frame_result = baseline.cluster(frame);
  std::printf("\nMid-360, T_B 0.1 s: C-ARC engine grid %u x %u, frame baseline grid %u x %u\n", engine.grid().rows,
              engine.grid().cols, frame_result.grid.rows, frame_result.grid.cols);
  return engine.grid().rows == frame_result.grid.rows && engine.grid().cols == frame_result.grid.cols ? 0 : 1;
}
