// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Statistics of a scan pattern that matter for clustering, used to compare an
/// analytic sensor model with a real firing table: FOV extents, angular
/// density by region (centre vs periphery) and coverage growth over time.
///
/// Angles (all in degrees, sensor frame x forward, y left, z up):
/// - azimuth   = atan2(y, x) in (-180, 180]
/// - elevation = asin(z) in [-90, 90]
/// - off-axis  = acos(x) in [0, 180], the angle from the forward axis
///
/// The functions are pure (thread-safe on distinct or const inputs) and
/// throw std::invalid_argument, naming the argument, on empty input or bad
/// settings.
///
/// \code
/// namespace sim = streamclust::sim;
/// auto model = sim::RisleyPairModel::mid40();
/// const std::vector<sim::Ray> rays = sim::collect(model, 0.5);       // 0.5 s of firings
/// const sim::FovExtents fov = sim::fov_extents(rays);                 // 0.5 / 99.5 percentiles
/// const sim::DensityContrast d = sim::density_contrast(
///     rays, {sim::AngularCoordinate::off_axis, 0.0, 6.0}, {{sim::AngularCoordinate::off_axis, 16.0, 19.0}});
/// sim::CoverageGrid grid;                                             // 0.5 deg cells
/// grid.azimuth_min_deg = grid.elevation_min_deg = -20.0;
/// grid.azimuth_max_deg = grid.elevation_max_deg = 20.0;
/// grid.max_off_axis_deg = 18.5;                                       // only cells inside the circle
/// const std::vector<double> cov = sim::coverage_growth(rays, grid);  // after 0.1 .. 0.5 s
/// \endcode

#include <streamclust/sim/ray.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::sim {

namespace detail {
constexpr double kPatternPi = 3.14159265358979323846;
constexpr double kPatternRadToDeg = 180.0 / kPatternPi;

[[noreturn]] inline void pattern_stats_fail(const char* where, const char* what) {
  std::string m = where;
  m.append(": ").append(what);
  throw std::invalid_argument(m);
}

/// Nearest-rank percentile of v (sorted in place by nth_element), p in [0, 100].
inline double percentile(std::vector<double>& v, double p) {
  const double pos = p / 100.0 * static_cast<double>(v.size() - 1);
  const auto k = static_cast<std::size_t>(std::llround(pos));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}
}  // namespace detail

/// atan2(y, x) [deg], (-180, 180].
inline double azimuth_deg(const Eigen::Vector3f& d) {
  return std::atan2(static_cast<double>(d.y()), static_cast<double>(d.x())) * detail::kPatternRadToDeg;
}

/// asin(z) [deg], [-90, 90].
inline double elevation_deg(const Eigen::Vector3f& d) {
  return std::asin(std::clamp(static_cast<double>(d.z()), -1.0, 1.0)) * detail::kPatternRadToDeg;
}

/// Angle from the forward (+x) axis [deg], [0, 180].
inline double off_axis_deg(const Eigen::Vector3f& d) {
  return std::acos(std::clamp(static_cast<double>(d.x()), -1.0, 1.0)) * detail::kPatternRadToDeg;
}

/// The rays a sensor model fires in its first `seconds` [s] from the next
/// firing on (times t with t - t_first < seconds). O(seconds x point_rate).
template <class Sensor>
std::vector<Ray> collect(Sensor& sensor, double seconds) {
  if (!(std::isfinite(seconds) && seconds >= 0.0)) detail::pattern_stats_fail("collect", "seconds must be finite and >= 0");
  std::vector<Ray> out;
  out.reserve(static_cast<std::size_t>(seconds * sensor.point_rate()) + 1);
  Ray r = sensor.next();
  const double t0 = r.time;
  while (r.time - t0 < seconds) {
    out.push_back(r);
    r = sensor.next();
  }
  return out;
}

/// The field of view a ray set spans [deg], each bound a percentile so a few
/// stray rays do not decide it.
struct FovExtents {
  double azimuth_min = 0.0;
  double azimuth_max = 0.0;
  double elevation_min = 0.0;
  double elevation_max = 0.0;
  double off_axis_max = 0.0;  ///< the upper percentile of the off-axis angle (a circular FOV's radius)
};

/// Percentile extents (nearest rank; defaults 0.5 / 99.5). O(n) expected.
inline FovExtents fov_extents(const std::vector<Ray>& rays, double lower_percent = 0.5, double upper_percent = 99.5) {
  if (rays.empty()) detail::pattern_stats_fail("fov_extents", "rays is empty");
  if (!(lower_percent >= 0.0 && lower_percent <= upper_percent && upper_percent <= 100.0))
    detail::pattern_stats_fail("fov_extents", "need 0 <= lower_percent <= upper_percent <= 100");
  std::vector<double> az(rays.size());
  std::vector<double> el(rays.size());
  std::vector<double> off(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    az[i] = azimuth_deg(rays[i].direction);
    el[i] = elevation_deg(rays[i].direction);
    off[i] = off_axis_deg(rays[i].direction);
  }
  FovExtents f;
  f.azimuth_min = detail::percentile(az, lower_percent);
  f.azimuth_max = detail::percentile(az, upper_percent);
  f.elevation_min = detail::percentile(el, lower_percent);
  f.elevation_max = detail::percentile(el, upper_percent);
  f.off_axis_max = detail::percentile(off, upper_percent);
  return f;
}

/// Which angle a Band bounds.
enum class AngularCoordinate {
  off_axis,  ///< a disc (lo = 0) or an annulus around the forward axis: forward-looking sensors
  elevation  ///< a latitude band over the full azimuth: 360-degree sensors
};

/// A region of the sphere: lo_deg <= coordinate < hi_deg.
struct Band {
  AngularCoordinate coordinate = AngularCoordinate::off_axis;
  double lo_deg = 0.0;
  double hi_deg = 0.0;
};

/// Solid angle of a band [square degrees]: 2 pi (cos lo - cos hi) for an
/// off-axis band, 2 pi (sin hi - sin lo) for an elevation band (in sr,
/// times (180 / pi)^2).
inline double solid_angle_sq_deg(const Band& b) {
  const double lo = b.lo_deg / detail::kPatternRadToDeg;
  const double hi = b.hi_deg / detail::kPatternRadToDeg;
  const double sr = b.coordinate == AngularCoordinate::off_axis ? 2.0 * detail::kPatternPi * (std::cos(lo) - std::cos(hi))
                                                                : 2.0 * detail::kPatternPi * (std::sin(hi) - std::sin(lo));
  return sr * detail::kPatternRadToDeg * detail::kPatternRadToDeg;
}

/// Whether direction d lies in band b.
inline bool contains(const Band& b, const Eigen::Vector3f& d) {
  const double a = b.coordinate == AngularCoordinate::off_axis ? off_axis_deg(d) : elevation_deg(d);
  return a >= b.lo_deg && a < b.hi_deg;
}

/// Angular density of a centre region against a periphery.
struct DensityContrast {
  double centre = 0.0;     ///< fraction of all rays per square degree in the centre region [1/deg^2]
  double periphery = 0.0;  ///< same, over the union of the periphery bands [1/deg^2]
  double ratio = 0.0;      ///< centre / periphery (infinity when the periphery is empty)
};

/// Points per square degree (normalized by the ray count, so independent of
/// duration and rate) in `centre` and in the union of `periphery` (bands
/// assumed disjoint). O(n x bands).
inline DensityContrast density_contrast(const std::vector<Ray>& rays, const Band& centre, const std::vector<Band>& periphery) {
  if (rays.empty()) detail::pattern_stats_fail("density_contrast", "rays is empty");
  if (!(centre.hi_deg > centre.lo_deg)) detail::pattern_stats_fail("density_contrast", "centre: need hi_deg > lo_deg");
  if (periphery.empty()) detail::pattern_stats_fail("density_contrast", "periphery is empty");
  double sa_p = 0.0;
  for (const Band& b : periphery) {
    if (!(b.hi_deg > b.lo_deg)) detail::pattern_stats_fail("density_contrast", "periphery: need hi_deg > lo_deg");
    sa_p += solid_angle_sq_deg(b);
  }
  std::size_t n_c = 0;
  std::size_t n_p = 0;
  for (const Ray& r : rays) {
    if (contains(centre, r.direction)) ++n_c;
    for (const Band& b : periphery)
      if (contains(b, r.direction)) {
        ++n_p;
        break;
      }
  }
  const double n = static_cast<double>(rays.size());
  DensityContrast d;
  d.centre = static_cast<double>(n_c) / n / solid_angle_sq_deg(centre);
  d.periphery = static_cast<double>(n_p) / n / sa_p;
  d.ratio = d.periphery > 0.0 ? d.centre / d.periphery : HUGE_VAL;
  return d;
}

/// A fixed azimuth x elevation grid over (part of) the FOV for coverage.
struct CoverageGrid {
  double azimuth_min_deg = -180.0;   ///< [deg]
  double azimuth_max_deg = 180.0;    ///< [deg], > azimuth_min_deg
  double elevation_min_deg = -90.0;  ///< [deg]
  double elevation_max_deg = 90.0;   ///< [deg], > elevation_min_deg
  double cell_deg = 0.5;             ///< cell side in azimuth and elevation [deg], > 0
  double max_off_axis_deg = 180.0;   ///< only cells whose centre is at most this far off +x count (circular FOVs) [deg]
};

/// Fraction of the grid's counted cells hit by the rays fired within each
/// `after_s` [s] of the first ray (t - t_first < after). Rays outside the grid
/// or in uncounted cells are ignored. O(n + cells).
inline std::vector<double> coverage_growth(const std::vector<Ray>& rays, const CoverageGrid& g,
                                           const std::vector<double>& after_s = {0.1, 0.2, 0.3, 0.4, 0.5}) {
  if (rays.empty()) detail::pattern_stats_fail("coverage_growth", "rays is empty");
  if (!(g.cell_deg > 0.0 && g.azimuth_max_deg > g.azimuth_min_deg && g.elevation_max_deg > g.elevation_min_deg))
    detail::pattern_stats_fail("coverage_growth", "grid: need cell_deg > 0 and max > min");
  const auto na = static_cast<std::size_t>(std::ceil((g.azimuth_max_deg - g.azimuth_min_deg) / g.cell_deg - 1e-9));
  const auto ne = static_cast<std::size_t>(std::ceil((g.elevation_max_deg - g.elevation_min_deg) / g.cell_deg - 1e-9));
  if (na * ne > (std::size_t{1} << 26)) detail::pattern_stats_fail("coverage_growth", "grid: more than 2^26 cells");
  // 0 = not counted, 1 = counted and not hit yet, 2 = hit.
  std::vector<std::uint8_t> cell(na * ne, 0);
  std::size_t counted = 0;
  const double limit_cos = std::cos(g.max_off_axis_deg / detail::kPatternRadToDeg);
  for (std::size_t j = 0; j < ne; ++j)
    for (std::size_t i = 0; i < na; ++i) {
      const double az = (g.azimuth_min_deg + (static_cast<double>(i) + 0.5) * g.cell_deg) / detail::kPatternRadToDeg;
      const double el = (g.elevation_min_deg + (static_cast<double>(j) + 0.5) * g.cell_deg) / detail::kPatternRadToDeg;
      if (std::cos(el) * std::cos(az) >= limit_cos) {
        cell[j * na + i] = 1;
        ++counted;
      }
    }
  if (counted == 0) detail::pattern_stats_fail("coverage_growth", "grid: no cell is counted");
  std::vector<double> out(after_s.size(), 0.0);
  std::vector<std::size_t> order(after_s.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return after_s[a] < after_s[b]; });
  const double t0 = rays.front().time;
  std::size_t hit = 0;
  std::size_t next_ray = 0;
  for (std::size_t k : order) {
    for (; next_ray < rays.size() && rays[next_ray].time - t0 < after_s[k]; ++next_ray) {
      const Eigen::Vector3f& d = rays[next_ray].direction;
      const double fa = (azimuth_deg(d) - g.azimuth_min_deg) / g.cell_deg;
      const double fe = (elevation_deg(d) - g.elevation_min_deg) / g.cell_deg;
      if (!(fa >= 0.0 && fe >= 0.0)) continue;
      const auto i = static_cast<std::size_t>(fa);
      const auto j = static_cast<std::size_t>(fe);
      if (i >= na || j >= ne) continue;
      std::uint8_t& c = cell[j * na + i];
      if (c == 1) {
        c = 2;
        ++hit;
      }
    }
    out[k] = static_cast<double>(hit) / static_cast<double>(counted);
  }
  return out;
}

}  // namespace streamclust::sim
