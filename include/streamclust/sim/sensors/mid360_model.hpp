// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// An analytic model of the Livox Mid-360 scan pattern (200 kHz, 4 lasers,
/// 360 x 59 degrees), fitted to Livox's official firing table.

#include <streamclust/sensors.hpp>
#include <streamclust/sim/ray.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace streamclust::sim {

/// Analytic Livox Mid-360: per laser, azimuth and elevation as a linear turn
/// plus a Fourier series, fitted to the official table.
///
/// Firing order: slot i is laser `i mod 4` at time `start_time + i / point_rate`.
/// For laser L at time t [s], with theta = 2 pi 10 t (the 10 Hz fundamental)
/// and phi = 2 pi f_rot t, f_rot = 65670/360 = 182.4167 rev/s:
///
///     azimuth   = a0_L - 65670 t + sum_{h=1..6} (A_Lh cos h theta + B_Lh sin h theta)
///                 + sum_{m=-3..3} (P_Lm cos(phi + m theta) + Q_Lm sin(phi + m theta))   [deg]
///     elevation = e0_L + sum_{h=1..6} (C_Lh cos h theta + D_Lh sin h theta)
///                 + sum_{m=-3..3} (U_Lm cos(phi + m theta) + V_Lm sin(phi + m theta))   [deg]
///
/// Direction: (cos el cos az, cos el sin az, sin el), x forward, y left, z up.
/// The azimuth sweeps the full 360 deg many times in every 0.1 s (about 18
/// turns), with a +-28 deg 10 Hz wobble; the elevation cycles over about
/// -7.2 .. 52.2 deg with a 10 Hz fundamental (amplitude 23.5 deg) and
/// 20 / 30 Hz harmonics, so rays dwell longer near the elevation extremes.
///
/// How the constants were obtained: an unweighted linear least-squares fit,
/// per laser, of the unwrapped azimuth and of the elevation of all 200,000
/// slots of that laser in `patterns/mid360_u16le.bin` (t = i x 5 us) on the
/// basis above (azimuth rate fitted freely: -65670.00 deg/s for every laser,
/// then fixed to -65670). Residual RMS / max against the table: lasers 0 and 3
/// azimuth 0.16 / 0.58 deg, elevation 0.09 / 0.34 deg; lasers 1 and 2 azimuth
/// 0.06 / 0.20 deg, elevation 0.03 / 0.11 deg. The phi terms carry each
/// laser's offset across the scan (laser 0 / 3 about +-3.1 deg, 1 / 2 about
/// +-1.0 deg in azimuth). The fitting program is not part
/// of the repository (see docs/simulation-sensors.md).
///
/// Deterministic. Each `next()` is O(1) (four sin/cos pairs, ~60 multiply-adds) and allocates
/// nothing. Not thread-safe: one model per thread; `point_rate()` is const.
///
/// \code
/// streamclust::sim::Mid360Model mid360;            // 200 kHz from t = 0
/// for (int i = 0; i < 20000; ++i) {                 // 0.1 s
///   const streamclust::sim::Ray r = mid360.next();  // r.direction, r.time, r.laser
/// }
/// \endcode
class Mid360Model {
 public:
  struct Params {
    double point_rate = livox_mid360.point_rate_hz;  ///< firings per second over all 4 lasers [Hz], > 0 (real sensor: 200 kHz)
    double start_time = 0.0;       ///< time of the first firing [s], finite, >= 0
  };

  static constexpr int kLasers = livox_mid360.lasers;

  Mid360Model() : Mid360Model(Params{}) {}

  /// Throws std::invalid_argument naming the parameter when it is out of range.
  explicit Mid360Model(const Params& params) : params_(params) {
    if (!(std::isfinite(params.point_rate) && params.point_rate > 0.0))
      fail("point_rate", params.point_rate, "(0, inf) [Hz]");
    if (!(std::isfinite(params.start_time) && params.start_time >= 0.0))
      fail("start_time", params.start_time, "[0, inf) [s]");
  }

  /// The next firing: laser `i mod 4`, time `start_time + i / point_rate`.
  Ray next() {
    const double t = params_.start_time + static_cast<double>(index_) / params_.point_rate;
    const int laser = static_cast<int>(index_ % kLasers);
    ++index_;
    Ray r;
    r.direction = direction(t, laser);
    r.time = t;
    r.laser = laser;
    return r;
  }

  /// Firings per second [Hz].
  double point_rate() const { return params_.point_rate; }

  const Params& params() const { return params_; }

  /// The unit direction of `laser` (0..3) at time `t` [s]. Pure function.
  static Eigen::Vector3f direction(double t, int laser) {
    constexpr double kPi = 3.14159265358979323846;
    constexpr double kTwoPi = 2.0 * kPi;
    constexpr double kDeg = kPi / 180.0;
    constexpr double kRotHz = 65670.0 / 360.0;  // azimuth turns per second (negative sense)
    const Fit& f = fit(laser);
    const double frac10 = 10.0 * t - std::floor(10.0 * t);
    const double frac_rot = kRotHz * t - std::floor(kRotHz * t);
    const double theta = kTwoPi * frac10;
    const double phi = kTwoPi * frac_rot;
    // cos/sin of h theta, h = 1 .. 6, by the angle-addition recurrence.
    double ch[7];
    double sh[7];
    ch[0] = 1.0;
    sh[0] = 0.0;
    ch[1] = std::cos(theta);
    sh[1] = std::sin(theta);
    for (int h = 2; h <= 6; ++h) {
      ch[h] = ch[h - 1] * ch[1] - sh[h - 1] * sh[1];
      sh[h] = sh[h - 1] * ch[1] + ch[h - 1] * sh[1];
    }
    double az = f.az0 - 360.0 * frac_rot;
    double el = f.el0;
    for (int h = 1; h <= 6; ++h) {
      az += f.az_harm[2 * h - 2] * ch[h] + f.az_harm[2 * h - 1] * sh[h];
      el += f.el_harm[2 * h - 2] * ch[h] + f.el_harm[2 * h - 1] * sh[h];
    }
    const double cp = std::cos(phi);
    const double sp = std::sin(phi);
    for (int m = -3; m <= 3; ++m) {
      const double cm = ch[m < 0 ? -m : m];
      const double sm = m < 0 ? -sh[-m] : sh[m];
      const double c = cp * cm - sp * sm;  // cos(phi + m theta)
      const double s = sp * cm + cp * sm;  // sin(phi + m theta)
      const int k = 2 * (m + 3);
      az += f.az_rot[k] * c + f.az_rot[k + 1] * s;
      el += f.el_rot[k] * c + f.el_rot[k + 1] * s;
    }
    const double ca = std::cos(az * kDeg);
    const double sa = std::sin(az * kDeg);
    const double ce = std::cos(el * kDeg);
    const double se = std::sin(el * kDeg);
    return Eigen::Vector3f(static_cast<float>(ce * ca), static_cast<float>(ce * sa), static_cast<float>(se));
  }

 private:
  struct Fit {
    double az0;           // [deg]
    double az_harm[12];   // cos/sin of 10, 20, .., 60 Hz [deg]
    double az_rot[14];    // cos / sin of phi + m theta, m = -3 .. 3 [deg]
    double el0;           // [deg]
    double el_harm[12];   // [deg]
    double el_rot[14];    // [deg]
  };

  static const Fit& fit(int laser) {
    // Fitted to patterns/mid360_u16le.bin; see the class comment.
    static const Fit kFits[kLasers] = {
        {269.351,
         {-0.239769, 28.474, -0.0476033, 2.36778, -0.0415233, 2.70732, -0.0138229, 0.543547, -0.00841745, 0.309293, -0.00365272, 0.096672},
         {-0.00601045, -0.14609, -0.0201636, -0.647468, 0.0013551, -0.00896543, 0.0389547, 3.14713, 0.00105665, 0.582016, -0.00248348, 0.272391, -0.00134167, 0.128817},
         20.4597,
         {23.5511, 0.274906, 1.13257, 0.0217909, 2.3067, 0.0252465, 0.225702, 0.00533648, 0.157967, 0.00328898, 0.0336306, 0.00101496},
         {0.0763025, -0.00275411, 0.540849, -0.0168002, 0.157593, -0.00347428, 2.76455, -0.0302952, 0.253409, -0.000235328, 0.116775, 0.000696718, 0.046591, 0.000396112}},
        {269.679,
         {-0.24791, 28.3823, -0.0482258, 2.32761, -0.0431801, 2.6762, -0.0138836, 0.527039, -0.00837175, 0.29885, -0.00345928, 0.0912336},
         {-0.00177795, -0.0476944, -0.0056029, -0.214212, 0.000439467, -0.00311568, 0.00692362, 1.04691, -0.00083736, 0.192172, -0.00139868, 0.089284, -0.000721983, 0.0419451},
         20.4472,
         {23.4951, 0.281692, 1.11666, 0.0222164, 2.29357, 0.0271519, 0.220528, 0.00549144, 0.154794, 0.00348446, 0.0322371, 0.00107779},
         {0.0249951, -0.000755955, 0.179157, -0.00461463, 0.0519207, -0.000840555, 0.920652, -0.00479326, 0.0838435, 0.000461896, 0.0384403, 0.000487181, 0.0152705, 0.000251415}},
        {270.008,
         {-0.2567, 28.3822, -0.0495579, 2.32757, -0.0455476, 2.67611, -0.0144122, 0.526972, -0.00869936, 0.298797, -0.00343802, 0.0911821},
         {0.00147461, 0.0476298, 0.00446164, 0.214185, -0.000496128, 0.00307483, -0.000972513, -1.04701, 0.00196667, -0.192179, 0.00193159, -0.0892881, 0.000979914, -0.0419685},
         20.4473,
         {23.4951, 0.289071, 1.11669, 0.0229311, 2.2936, 0.0293229, 0.220592, 0.00579093, 0.154865, 0.0037677, 0.0323017, 0.00118642},
         {-0.0250286, 0.000681111, -0.179224, 0.0037563, -0.0519648, 0.000599305, -0.920718, -0.000452073, -0.0838579, -0.000917446, -0.0384547, -0.000711461, -0.0152722, -0.000326525}},
        {270.336,
         {-0.266238, 28.4738, -0.0516958, 2.36766, -0.048764, 2.70711, -0.015455, 0.543391, -0.00941679, 0.309107, -0.00365291, 0.0964603},
         {0.00388585, 0.14608, 0.0102247, 0.647599, -0.00148924, 0.00887066, 0.0151784, -3.14741, 0.00952954, -0.582023, 0.00766704, -0.272366, 0.00395893, -0.128852},
         20.4598,
         {23.551, 0.297124, 1.13272, 0.0239637, 2.30681, 0.0318368, 0.22589, 0.00628522, 0.158164, 0.0041674, 0.0338539, 0.00135553},
         {-0.076421, 0.00162209, -0.541116, 0.00849634, -0.157681, 0.000890608, -2.76472, -0.0172826, -0.253446, -0.00441599, -0.11682, -0.00297808, -0.0466572, -0.00139716}},
    };
    const int l = ((laser % kLasers) + kLasers) % kLasers;
    return kFits[l];
  }

  [[noreturn]] static void fail(const char* name, double value, const char* range) {
    std::string m = "Mid360Model::Params::";
    m.append(name).append(" = ").append(std::to_string(value)).append(" is out of range ").append(range);
    throw std::invalid_argument(m);
  }

  Params params_;
  std::uint64_t index_ = 0;
};

}  // namespace streamclust::sim
