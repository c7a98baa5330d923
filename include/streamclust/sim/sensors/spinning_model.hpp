// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A conventional spinning multi-beam LiDAR (e.g. 32 beams, 10 Hz), the
/// repetitive contrast to the Livox patterns.

#include <streamclust/sim/ray.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace streamclust::sim {

/// A spinning sensor with `beams` lasers evenly spread over
/// [elevation_min_deg, elevation_max_deg], turning at `rotation_hz` with
/// `columns` firing columns per turn.
///
/// Firing order: column by column, beams 0 .. beams-1 (bottom to top) within a
/// column; slot i is beam `i mod beams` of column `i / beams`. Column c points
/// at azimuth `azimuth_start_deg + 360 c / columns` (counter-clockwise seen from
/// above, from +x toward +y), repeating every turn. Time of slot i:
/// `start_time + i / point_rate` with point_rate = beams x columns x
/// rotation_hz (defaults: 32 x 1800 x 10 = 576 kHz, 0.2 deg horizontal
/// resolution, 40 / 31 = 1.29 deg vertical spacing). The same directions repeat
/// every turn: coverage stops growing after 1 / rotation_hz.
///
/// Deterministic. `next()` is O(1), allocation-free. Not thread-safe.
///
/// \code
/// streamclust::sim::SpinningModel hdl32;   // 32 beams, -25 .. 15 deg, 10 Hz
/// const streamclust::sim::Ray r = hdl32.next();
/// \endcode
class SpinningModel {
 public:
  struct Params {
    int beams = 32;                    ///< lasers, >= 1
    double elevation_min_deg = -25.0;  ///< lowest beam [deg], > -90
    double elevation_max_deg = 15.0;   ///< highest beam [deg], < 90, >= elevation_min_deg (== only with 1 beam)
    double rotation_hz = 10.0;         ///< turns per second [rev/s], > 0
    int columns = 1800;                ///< firing columns per turn, >= 1
    double azimuth_start_deg = 0.0;    ///< azimuth of column 0 [deg], finite
    double start_time = 0.0;           ///< time of the first firing [s], >= 0
  };

  SpinningModel() : SpinningModel(Params{}) {}

  /// Throws std::invalid_argument naming the parameter when it is out of range.
  explicit SpinningModel(const Params& params) : params_(params) {
    const Params& p = params;
    if (p.beams < 1) fail("beams", std::to_string(p.beams), "[1, inf)");
    if (!(std::isfinite(p.elevation_min_deg) && p.elevation_min_deg > -90.0))
      fail("elevation_min_deg", std::to_string(p.elevation_min_deg), "(-90, 90) [deg]");
    if (!(std::isfinite(p.elevation_max_deg) && p.elevation_max_deg < 90.0 && p.elevation_max_deg >= p.elevation_min_deg))
      fail("elevation_max_deg", std::to_string(p.elevation_max_deg), "[elevation_min_deg, 90) [deg]");
    if (p.beams > 1 && !(p.elevation_max_deg > p.elevation_min_deg))
      fail("elevation_max_deg", std::to_string(p.elevation_max_deg), "(elevation_min_deg, 90) when beams > 1 [deg]");
    if (!(std::isfinite(p.rotation_hz) && p.rotation_hz > 0.0))
      fail("rotation_hz", std::to_string(p.rotation_hz), "(0, inf) [rev/s]");
    if (p.columns < 1) fail("columns", std::to_string(p.columns), "[1, inf)");
    if (!std::isfinite(p.azimuth_start_deg)) fail("azimuth_start_deg", std::to_string(p.azimuth_start_deg), "finite [deg]");
    if (!(std::isfinite(p.start_time) && p.start_time >= 0.0))
      fail("start_time", std::to_string(p.start_time), "[0, inf) [s]");
    point_rate_ = static_cast<double>(p.beams) * static_cast<double>(p.columns) * p.rotation_hz;
  }

  /// The next firing.
  Ray next() {
    constexpr double kDeg = 3.14159265358979323846 / 180.0;
    const auto beams = static_cast<std::uint64_t>(params_.beams);
    const int beam = static_cast<int>(index_ % beams);
    const std::uint64_t column = (index_ / beams) % static_cast<std::uint64_t>(params_.columns);
    const double el = params_.beams == 1 ? params_.elevation_min_deg
                                         : params_.elevation_min_deg + (params_.elevation_max_deg - params_.elevation_min_deg) *
                                                                           static_cast<double>(beam) /
                                                                           static_cast<double>(params_.beams - 1);
    const double az = params_.azimuth_start_deg + 360.0 * static_cast<double>(column) / static_cast<double>(params_.columns);
    Ray r;
    r.time = params_.start_time + static_cast<double>(index_) / point_rate_;
    r.laser = beam;
    const double ce = std::cos(el * kDeg);
    r.direction = Eigen::Vector3f(static_cast<float>(ce * std::cos(az * kDeg)), static_cast<float>(ce * std::sin(az * kDeg)),
                                  static_cast<float>(std::sin(el * kDeg)));
    ++index_;
    return r;
  }

  /// beams x columns x rotation_hz [Hz].
  double point_rate() const { return point_rate_; }

  const Params& params() const { return params_; }

 private:
  [[noreturn]] static void fail(const char* name, const std::string& value, const char* range) {
    std::string m = "SpinningModel::Params::";
    m.append(name).append(" = ").append(value).append(" is out of range ").append(range);
    throw std::invalid_argument(m);
  }

  Params params_;
  double point_rate_ = 0.0;
  std::uint64_t index_ = 0;
};

}  // namespace streamclust::sim
