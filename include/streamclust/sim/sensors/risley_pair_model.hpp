// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// An analytic model of a two-prism Risley scanner: Livox Mid-40 and Mid-70.

#include <streamclust/sensors.hpp>
#include <streamclust/sim/ray.hpp>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace streamclust::sim {

/// Two counter-rotating prisms (Livox Mid-40 / Mid-70): a two-rotor harmonic
/// model in the tangent plane x = 1.
///
/// At time t [s], with w_k = 2 pi f_k:
///
///     a = A1 cos(w1 t + p1) + A2 cos(w2 t + p2)      (toward +y, left)
///     b = A1 sin(w1 t + p1) + A2 sin(w2 t + p2)      (toward +z, up)
///     r = |(a, b)|,  off-axis angle = theta(r),  direction =
///     (cos theta, sin theta a / r, sin theta b / r)
///
/// With `radial_poly` all zero, theta(r) = atan(r): the pure tangent-plane
/// model, direction = (1, a, b) / |(1, a, b)|. Otherwise theta(r) = c1 r +
/// c2 r^2 + c3 r^3 + c4 r^4 [rad], a radial profile that captures the real
/// optics' non-linearity (the rim of the real Mid-70 reaches 35.2 deg where
/// atan(A1 + A2) is only 32.8 deg). The prisms turn at
/// +121.567 and -77.733 Hz (7294 / -4664 rpm). The amplitudes and phases of
/// the presets are a complex least-squares fit of the tangent-plane
/// coordinates (tan az, tan el / cos az) of all 400,000 rows of the real
/// tables at those rates (they agree with the data README: Mid-40 0.1745 /
/// 0.1713, Mid-70 0.316 / 0.329). Residual RMS of the model against the
/// tables, in tangent-plane units: Mid-40 0.0027 (about 0.15 deg), Mid-70
/// 0.039 (about 1.6 deg near the rim; the real Mid-70 optics are not a pure
/// two-rotor sum at its wide angles). Statistics that matter for clustering
/// agree much closer: see docs/simulation-sensors.md.
///
/// Deterministic. `next()` is O(1) (two or three sin/cos pairs), allocation-free. Not
/// thread-safe: one model per thread.
///
/// \code
/// auto mid70 = streamclust::sim::RisleyPairModel::mid70();   // 100 kHz
/// const streamclust::sim::Ray r = mid70.next();
/// \endcode
class RisleyPairModel {
 public:
  struct Params {
    double prism1_hz = 121.567;      ///< rotation rate of prism 1 [rev/s], signed, finite, != 0
    double prism2_hz = -77.733;      ///< rotation rate of prism 2 [rev/s], signed, finite, != 0
    double amplitude1 = 0.17445;     ///< deflection of prism 1 in the tangent plane [tan units], > 0
    double amplitude2 = 0.17133;     ///< deflection of prism 2 [tan units], > 0; A1 + A2 < 10
    double phase1 = 0.0035;          ///< prism 1 angle at t = 0 [rad], finite
    double phase2 = -0.0091;         ///< prism 2 angle at t = 0 [rad], finite
    std::array<double, 4> radial_poly{{0.978346, 0.070375, -0.430569, 0.401795}};  ///< theta(r) = c1 r + .. + c4 r^4 [rad]; all 0: atan(r). Must rise on [0, A1 + A2] and stay below pi/2
    double point_rate = livox_mid40.point_rate_hz;  ///< firings per second [Hz], > 0
    double start_time = 0.0;         ///< time of the first firing [s], >= 0
  };

  /// Livox Mid-40: 38.4 deg circular FOV (the defaults of Params).
  static RisleyPairModel mid40() { return RisleyPairModel(Params{}); }

  /// Livox Mid-70: 70.4 deg circular FOV, dense centre.
  static RisleyPairModel mid70() {
    Params p;
    p.amplitude1 = 0.31572;
    p.amplitude2 = 0.32944;
    p.phase1 = -3.1382;
    p.phase2 = 3.1325;
    p.radial_poly = {{0.763986, 0.327458, -0.699873, 0.999959}};
    p.point_rate = livox_mid70.point_rate_hz;
    return RisleyPairModel(p);
  }

  RisleyPairModel() : RisleyPairModel(Params{}) {}

  /// Throws std::invalid_argument naming the parameter when it is out of range.
  explicit RisleyPairModel(const Params& params) : params_(params) {
    const Params& p = params;
    if (!(std::isfinite(p.prism1_hz) && p.prism1_hz != 0.0)) fail("prism1_hz", p.prism1_hz, "finite, != 0 [rev/s]");
    if (!(std::isfinite(p.prism2_hz) && p.prism2_hz != 0.0)) fail("prism2_hz", p.prism2_hz, "finite, != 0 [rev/s]");
    if (!(std::isfinite(p.amplitude1) && p.amplitude1 > 0.0)) fail("amplitude1", p.amplitude1, "(0, 10)");
    if (!(std::isfinite(p.amplitude2) && p.amplitude2 > 0.0)) fail("amplitude2", p.amplitude2, "(0, 10)");
    if (!(p.amplitude1 + p.amplitude2 < 10.0)) fail("amplitude1 + amplitude2", p.amplitude1 + p.amplitude2, "(0, 10)");
    if (!std::isfinite(p.phase1)) fail("phase1", p.phase1, "finite [rad]");
    if (!std::isfinite(p.phase2)) fail("phase2", p.phase2, "finite [rad]");
    if (!(std::isfinite(p.point_rate) && p.point_rate > 0.0)) fail("point_rate", p.point_rate, "(0, inf) [Hz]");
    if (!(std::isfinite(p.start_time) && p.start_time >= 0.0)) fail("start_time", p.start_time, "[0, inf) [s]");
    for (double c : p.radial_poly)
      if (!std::isfinite(c)) fail("radial_poly", c, "finite coefficients");
    use_poly_ = p.radial_poly[0] != 0.0 || p.radial_poly[1] != 0.0 || p.radial_poly[2] != 0.0 || p.radial_poly[3] != 0.0;
    if (use_poly_) {
      // theta must rise from 0 and stay below pi/2 over the reachable radii.
      const double rmax = p.amplitude1 + p.amplitude2;
      double prev = 0.0;
      for (int i = 1; i <= 256; ++i) {
        const double th = theta(rmax * i / 256.0);
        if (!(th > prev && th < 1.5707963267948966)) fail("radial_poly", th, "theta(r) rising in (0, pi/2) on [0, A1 + A2]");
        prev = th;
      }
    }
  }

  /// The next firing, time `start_time + i / point_rate`, laser 0.
  Ray next() {
    const double t = params_.start_time + static_cast<double>(index_) / params_.point_rate;
    ++index_;
    Ray r;
    r.direction = direction(t);
    r.time = t;
    r.laser = 0;
    return r;
  }

  /// Firings per second [Hz].
  double point_rate() const { return params_.point_rate; }

  const Params& params() const { return params_; }

  /// The unit direction at time t [s]. Pure.
  Eigen::Vector3f direction(double t) const {
    constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
    // Reduce the turns first so precision holds for long streams.
    const double u1 = params_.prism1_hz * t;
    const double u2 = params_.prism2_hz * t;
    const double g1 = kTwoPi * (u1 - std::floor(u1)) + params_.phase1;
    const double g2 = kTwoPi * (u2 - std::floor(u2)) + params_.phase2;
    const double a = params_.amplitude1 * std::cos(g1) + params_.amplitude2 * std::cos(g2);
    const double b = params_.amplitude1 * std::sin(g1) + params_.amplitude2 * std::sin(g2);
    if (!use_poly_) {
      const double inv = 1.0 / std::sqrt(1.0 + a * a + b * b);
      return Eigen::Vector3f(static_cast<float>(inv), static_cast<float>(a * inv), static_cast<float>(b * inv));
    }
    const double r = std::sqrt(a * a + b * b);
    if (r <= 0.0) return Eigen::Vector3f::UnitX();
    const double th = theta(r);
    const double s = std::sin(th) / r;
    return Eigen::Vector3f(static_cast<float>(std::cos(th)), static_cast<float>(s * a), static_cast<float>(s * b));
  }

 private:
  [[noreturn]] static void fail(const char* name, double value, const char* range) {
    std::string m = "RisleyPairModel::Params::";
    m.append(name).append(" = ").append(std::to_string(value)).append(" is out of range ").append(range);
    throw std::invalid_argument(m);
  }

  double theta(double r) const {
    const auto& c = params_.radial_poly;
    return r * (c[0] + r * (c[1] + r * (c[2] + r * c[3])));
  }

  Params params_;
  bool use_poly_ = false;
  std::uint64_t index_ = 0;
};

}  // namespace streamclust::sim
