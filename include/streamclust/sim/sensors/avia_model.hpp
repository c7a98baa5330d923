// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A best-estimate model of the Livox Avia (240 kHz, 6 beams, 70.4 x 77.2 deg,
/// dense centre): three rotating prisms, first-order (thin-prism) optics.

#include <streamclust/sensors.hpp>
#include <streamclust/sim/ray.hpp>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace streamclust::sim {

/// Livox Avia as three rotating wedge prisms (no real table exists to check
/// it against; the numbers are the published best estimate quoted in the data
/// README).
///
/// Thin-prism (first-order) optics: prism k deviates the beam by
/// delta_k = (n - 1) wedge_k (n = 1.51; wedges 30.8856, 29.7735, 3.1351 deg
/// give 15.75, 15.18, 1.60 deg) in the direction of its rotation angle
/// 2 pi f_k t + phase_k (f = -131.5463, 40.8032, 213.1611 rev/s); the three
/// deviations add as 2D vectors (h to the left, v up). Their sum reaches at
/// most 32.535 deg, so the sum is scaled by `fov_scale` = 35.2 / 32.535 to make
/// the disc radius the half horizontal FOV (70.4 / 2 deg). Beam j is offset
/// along v (the vertical, the scan plane's long axis) by `beam_offset_deg[j]`
/// (-2.99 .. +3.04 deg), which makes the vertical extent about
/// 35.2 + 3.0 = 38.2 deg either side (spec 77.2 / 2 = 38.6). The angular
/// vector (h, v) maps to a direction equidistantly: off-axis angle |(h, v)|
/// about +x, in the direction (h, v) of the y-z plane.
///
/// Firing order: slot i is beam `i mod 6` at time `start_time + i / point_rate`
/// (240 kHz: the six 40 kHz beams interleaved).
///
/// Deterministic. `next()` is O(1) (three sin/cos pairs plus one), allocation
/// free. Not thread-safe: one model per thread.
///
/// \code
/// streamclust::sim::AviaModel avia;    // 240 kHz, six beams
/// const streamclust::sim::Ray r = avia.next();
/// \endcode
class AviaModel {
 public:
  struct Params {
    std::array<double, 3> prism_hz{{-131.5463, 40.8032, 213.1611}};  ///< rotation rates [rev/s], finite
    std::array<double, 3> wedge_deg{{30.8856, 29.7735, 3.1351}};     ///< wedge angles [deg], [0, 60)
    std::array<double, 3> phase_rad{{0.0, 0.0, 0.0}};                ///< prism angles at t = 0 [rad], finite
    double refractive_index = 1.51;                                   ///< (1, 3]
    double fov_scale = livox_avia.horizontal_fov_deg / 2.0 / 32.535042;  ///< scale on the summed deflection (1 = raw thin-prism), (0, 3]
    std::array<double, 6> beam_offset_deg{{-2.99, -1.86, -0.62, 0.62, 1.86, 3.04}};  ///< vertical beam offsets [deg], |.| < 30
    double point_rate = livox_avia.point_rate_hz;  ///< firings per second over all six beams [Hz], > 0
    double start_time = 0.0;       ///< time of the first firing [s], >= 0
  };

  static constexpr int kBeams = livox_avia.lasers;

  AviaModel() : AviaModel(Params{}) {}

  /// Throws std::invalid_argument naming the parameter when it is out of range.
  explicit AviaModel(const Params& params) : params_(params) {
    const Params& p = params;
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(p.prism_hz[k])) fail("prism_hz", k, p.prism_hz[k], "finite [rev/s]");
      if (!(std::isfinite(p.wedge_deg[k]) && p.wedge_deg[k] >= 0.0 && p.wedge_deg[k] < 60.0))
        fail("wedge_deg", k, p.wedge_deg[k], "[0, 60) [deg]");
      if (!std::isfinite(p.phase_rad[k])) fail("phase_rad", k, p.phase_rad[k], "finite [rad]");
    }
    if (!(std::isfinite(p.refractive_index) && p.refractive_index > 1.0 && p.refractive_index <= 3.0))
      fail("refractive_index", -1, p.refractive_index, "(1, 3]");
    if (!(std::isfinite(p.fov_scale) && p.fov_scale > 0.0 && p.fov_scale <= 3.0))
      fail("fov_scale", -1, p.fov_scale, "(0, 3]");
    for (int j = 0; j < kBeams; ++j)
      if (!(std::isfinite(p.beam_offset_deg[j]) && std::fabs(p.beam_offset_deg[j]) < 30.0))
        fail("beam_offset_deg", j, p.beam_offset_deg[j], "(-30, 30) [deg]");
    if (!(std::isfinite(p.point_rate) && p.point_rate > 0.0)) fail("point_rate", -1, p.point_rate, "(0, inf) [Hz]");
    if (!(std::isfinite(p.start_time) && p.start_time >= 0.0)) fail("start_time", -1, p.start_time, "[0, inf) [s]");
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) {
      deflection_deg_[k] = (p.refractive_index - 1.0) * p.wedge_deg[k] * p.fov_scale;
      sum += deflection_deg_[k];
    }
    if (!(sum + 30.0 < 180.0)) fail("fov_scale", -1, p.fov_scale, "small enough that the pattern stays below 150 deg off axis");
  }

  /// The next firing: beam `i mod 6` at time `start_time + i / point_rate`.
  Ray next() {
    const double t = params_.start_time + static_cast<double>(index_) / params_.point_rate;
    const int beam = static_cast<int>(index_ % kBeams);
    ++index_;
    Ray r;
    r.direction = direction(t, beam);
    r.time = t;
    r.laser = beam;
    return r;
  }

  /// Firings per second [Hz].
  double point_rate() const { return params_.point_rate; }

  const Params& params() const { return params_; }

  /// The unit direction of `beam` (0..5) at time t [s]. Pure.
  Eigen::Vector3f direction(double t, int beam) const {
    constexpr double kPi = 3.14159265358979323846;
    constexpr double kTwoPi = 2.0 * kPi;
    double h = 0.0;
    double v = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double u = params_.prism_hz[k] * t;
      const double g = kTwoPi * (u - std::floor(u)) + params_.phase_rad[k];
      h += deflection_deg_[k] * std::cos(g);
      v += deflection_deg_[k] * std::sin(g);
    }
    v += params_.beam_offset_deg[((beam % kBeams) + kBeams) % kBeams];
    const double off = std::sqrt(h * h + v * v);  // [deg]
    if (off <= 0.0) return Eigen::Vector3f::UnitX();
    const double s = std::sin(off * kPi / 180.0) / off;
    return Eigen::Vector3f(static_cast<float>(std::cos(off * kPi / 180.0)), static_cast<float>(s * h),
                           static_cast<float>(s * v));
  }

 private:
  [[noreturn]] static void fail(const char* name, int index, double value, const char* range) {
    std::string m = "AviaModel::Params::";
    m.append(name);
    if (index >= 0) m.append("[").append(std::to_string(index)).append("]");
    m.append(" = ").append(std::to_string(value)).append(" is out of range ").append(range);
    throw std::invalid_argument(m);
  }

  Params params_;
  double deflection_deg_[3] = {0.0, 0.0, 0.0};
  std::uint64_t index_ = 0;
};

}  // namespace streamclust::sim
