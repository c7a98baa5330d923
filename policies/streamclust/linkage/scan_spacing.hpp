// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// ScanSpacing: a sensor's angular spacing of returns over one window, by
/// direction in the sensor frame, as an immutable table; built from one
/// window of directions (a sensor model's firings or a recording's first
/// window). Read by ScanAdaptiveLinkage.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace streamclust {

/// How ScanSpacing builds its table.
struct ScanSpacingParams {
  /// [deg] side of a table cell (azimuth x elevation), finite, in [0.25, 30]
  float cell_deg = 2.0f;
  /// which quantile of a cell's nearest-neighbour angles the cell keeps, in [0, 1]
  float quantile = 0.5f;
  /// fewest directions that make a cell's own value, >= 1
  int min_samples = 8;
  /// [deg] largest nearest-neighbour angle searched (farther: the
  /// direction has no neighbour and is left out), finite, in (0, 30]
  float max_spacing_deg = 5.0f;
};

/// The typical nearest-neighbour angle [rad] between the returns of one
/// window T_B around each direction of the sensor frame (x forward, z up).
///
/// Built once (`from_directions`, `from_sensor_model`): every direction's
/// nearest neighbour among the window's directions (exact, on a grid of
/// unit vectors), then per table cell (azimuth x elevation, `cell_deg`
/// square) the `quantile` of those angles; cells with fewer than
/// `min_samples` directions (outside the field of view, the sky of a
/// recording) take the mean of their filled neighbours, ring after ring;
/// then a 3 x 3 mean smooths the table. `at(d)` interpolates bilinearly
/// between cell centres (azimuth wraps), so the spacing is continuous in d.
///
/// The table depends on the window's length: twice the window, about
/// 1/sqrt(2) the spacing. Build it from exactly one window T_B.
///
/// Thread safety: immutable after construction; share it through
/// std::shared_ptr<const ScanSpacing> between engines and threads.
///
/// \code
///   std::vector<Eigen::Vector3f> first_window = ...;  // sensor-frame points of the first T_B
///   auto spacing = streamclust::ScanSpacing::from_directions(first_window);
///   float rad = spacing->at(Eigen::Vector3f::UnitX());  // the spacing straight ahead [rad]
/// \endcode
class ScanSpacing {
 public:
  using Params = ScanSpacingParams;

  /// The table of `directions` (sensor frame, any length > 0; zero and
  /// non-finite vectors are skipped), one window of them. Throws
  /// std::invalid_argument for bad Params or when fewer than 2 directions
  /// have a neighbour within max_spacing_deg. O(n) expected (a hash grid;
  /// about 0.1 s for 100k directions) plus O(cells).
  static std::shared_ptr<const ScanSpacing> from_directions(const std::vector<Eigen::Vector3f>& directions,
                                                            const Params& params = Params{}) {
    check(params);
    return std::shared_ptr<const ScanSpacing>(new ScanSpacing(directions, params));
  }

  /// The table of a sensor model's firings over one window of `window_seconds`
  /// [s] from its next firing (`Sensor`: `next()` returning a ray with a
  /// sensor-frame `direction` and a `time` [s], as the simulator's models).
  /// Throws as from_directions, and for a window not finite and > 0.
  template <class Sensor>
  static std::shared_ptr<const ScanSpacing> from_sensor_model(Sensor& sensor, double window_seconds,
                                                              const Params& params = Params{}) {
    if (!(std::isfinite(window_seconds) && window_seconds > 0.0))
      throw error("window_seconds", window_seconds, "finite, > 0 s");
    std::vector<Eigen::Vector3f> directions;
    auto ray = sensor.next();
    const double t0 = ray.time;
    while (ray.time - t0 < window_seconds) {
      directions.push_back(ray.direction);
      ray = sensor.next();
    }
    return from_directions(directions, params);
  }

  /// The spacing [rad] at sensor-frame direction `d` (any length > 0):
  /// bilinear between the four nearest cell centres. O(1), two inverse
  /// trigonometric functions. Deterministic: the same d, the same value.
  float at(const Eigen::Vector3f& d) const {
    const double az = std::atan2(static_cast<double>(d.y()), static_cast<double>(d.x()));
    const double horizontal = std::hypot(static_cast<double>(d.x()), static_cast<double>(d.y()));
    const double el = std::atan2(static_cast<double>(d.z()), horizontal);
    return at_angles(az * kRadToDeg, el * kRadToDeg);
  }

  /// The spacing [rad] at azimuth `azimuth_deg` (any, wraps) and elevation
  /// `elevation_deg` (clamped to [-90, 90]) [deg]. O(1).
  float at_angles(double azimuth_deg, double elevation_deg) const {
    // Continuous cell coordinates, cell centres at integers.
    const double u = (azimuth_deg + 180.0) / cell_deg_ - 0.5;
    const double v = (std::clamp(elevation_deg, -90.0, 90.0) + 90.0) / cell_deg_ - 0.5;
    const double u0 = std::floor(u);
    const double v0 = std::floor(std::clamp(v, 0.0, static_cast<double>(rows_ - 1)));
    const double fu = u - u0;
    const double fv = std::clamp(v - v0, 0.0, 1.0);
    const int c0 = wrap(static_cast<long long>(u0));
    const int c1 = wrap(static_cast<long long>(u0) + 1);
    const int r0 = static_cast<int>(v0);
    const int r1 = std::min(r0 + 1, rows_ - 1);
    const double low = (1.0 - fu) * cell(r0, c0) + fu * cell(r0, c1);
    const double high = (1.0 - fu) * cell(r1, c0) + fu * cell(r1, c1);
    return static_cast<float>((1.0 - fv) * low + fv * high);
  }

  /// The value of cell (row, col) [rad]: row 0 the lowest elevation band
  /// from -90 deg, col 0 the azimuth band from -180 deg. O(1).
  float cell(int row, int col) const { return table_[static_cast<std::size_t>(row) * cols_ + col]; }
  int rows() const { return rows_; }
  int cols() const { return cols_; }
  double cell_deg() const { return cell_deg_; }
  /// Directions that had a nearest neighbour within max_spacing_deg.
  std::size_t directions_used() const { return used_; }
  /// The smallest and largest cell values [rad].
  float min_spacing() const { return *std::min_element(table_.begin(), table_.end()); }
  float max_spacing() const { return *std::max_element(table_.begin(), table_.end()); }
  /// Heap bytes of the table. O(1).
  std::size_t heap_bytes() const { return table_.capacity() * sizeof(float); }

 private:
  static constexpr double kPi = 3.14159265358979323846;
  static constexpr double kRadToDeg = 180.0 / kPi;

  ScanSpacing(const std::vector<Eigen::Vector3f>& directions, const Params& p)
      : cell_deg_(static_cast<double>(p.cell_deg)),
        rows_(std::max(1, static_cast<int>(std::ceil(180.0 / cell_deg_)))),
        cols_(std::max(1, static_cast<int>(std::ceil(360.0 / cell_deg_)))) {
    std::vector<Eigen::Vector3d> units;
    units.reserve(directions.size());
    for (const Eigen::Vector3f& d : directions) {
      const Eigen::Vector3d v = d.cast<double>();
      const double n = v.norm();
      if (std::isfinite(n) && n > 0.0) units.push_back(v / n);
    }
    const std::vector<double> nearest = nearest_angles(units, static_cast<double>(p.max_spacing_deg) / kRadToDeg);
    std::vector<std::vector<float>> per_cell(static_cast<std::size_t>(rows_) * cols_);
    for (std::size_t i = 0; i < units.size(); ++i) {
      if (!(nearest[i] >= 0.0)) continue;
      ++used_;
      per_cell[index_of(units[i])].push_back(static_cast<float>(nearest[i]));
    }
    if (used_ < 2) throw error("directions", static_cast<double>(used_), "at least 2 with a neighbour within max_spacing_deg");
    std::vector<float> raw(per_cell.size(), 0.0f);
    std::vector<std::uint8_t> filled(per_cell.size(), 0);
    for (std::size_t k = 0; k < per_cell.size(); ++k) {
      std::vector<float>& a = per_cell[k];
      if (a.size() < static_cast<std::size_t>(p.min_samples)) continue;
      const auto at = static_cast<std::size_t>(std::llround(static_cast<double>(p.quantile) * static_cast<double>(a.size() - 1)));
      std::nth_element(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(at), a.end());
      raw[k] = a[at];
      filled[k] = 1;
    }
    if (std::find(filled.begin(), filled.end(), std::uint8_t{1}) == filled.end()) {
      // Too few directions for any cell of their own: one value everywhere.
      std::vector<float> all;
      for (const auto& a : per_cell) all.insert(all.end(), a.begin(), a.end());
      const auto at = static_cast<std::size_t>(std::llround(static_cast<double>(p.quantile) * static_cast<double>(all.size() - 1)));
      std::nth_element(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(at), all.end());
      raw.assign(raw.size(), all[at]);
      filled.assign(filled.size(), 1);
    }
    fill_empty(raw, filled);
    table_ = smoothed(raw);
  }

  /// The table cell of unit vector u. O(1).
  std::size_t index_of(const Eigen::Vector3d& u) const {
    const double az = std::atan2(u.y(), u.x()) * kRadToDeg;
    const double el = std::asin(std::clamp(u.z(), -1.0, 1.0)) * kRadToDeg;
    const int col = std::clamp(static_cast<int>(std::floor((az + 180.0) / cell_deg_)), 0, cols_ - 1);
    const int row = std::clamp(static_cast<int>(std::floor((el + 90.0) / cell_deg_)), 0, rows_ - 1);
    return static_cast<std::size_t>(row) * cols_ + col;
  }

  int wrap(long long col) const {
    const long long m = col % cols_;
    return static_cast<int>(m < 0 ? m + cols_ : m);
  }

  /// The angle [rad] from each unit vector to its nearest other one, or -1
  /// when none lies within `max_angle`. A hash grid of side h on the unit
  /// vectors; rings of cells searched until the nearest chord found is
  /// within the ring's reach (exact). O(n) expected for a window's spacing.
  static std::vector<double> nearest_angles(const std::vector<Eigen::Vector3d>& units, double max_angle) {
    std::vector<double> out(units.size(), -1.0);
    if (units.size() < 2) return out;
    // A side of about the mean spacing of n directions over a hemisphere.
    const double h = std::clamp(std::sqrt(2.0 * kPi / static_cast<double>(units.size())), 1e-4, max_angle);
    const double max_chord = 2.0 * std::sin(max_angle / 2.0);
    const auto key_of = [](long long x, long long y, long long z) {
      constexpr long long kOffset = 1 << 20;
      return (static_cast<std::uint64_t>(x + kOffset) << 42) | (static_cast<std::uint64_t>(y + kOffset) << 21) |
             static_cast<std::uint64_t>(z + kOffset);
    };
    const auto cell_of = [h](double c) { return static_cast<long long>(std::floor(c / h)); };
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(units.size());
    for (std::size_t i = 0; i < units.size(); ++i) {
      const Eigen::Vector3d& u = units[i];
      keyed[i] = {key_of(cell_of(u.x()), cell_of(u.y()), cell_of(u.z())), static_cast<std::uint32_t>(i)};
    }
    std::sort(keyed.begin(), keyed.end());
    std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> cells;  // key -> [first, last) of keyed
    cells.reserve(units.size());
    for (std::size_t i = 0; i < keyed.size();) {
      std::size_t j = i;
      while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
      cells.emplace(keyed[i].first, std::make_pair(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)));
      i = j;
    }
    const long long max_ring = static_cast<long long>(std::ceil(max_chord / h));
    for (std::size_t i = 0; i < units.size(); ++i) {
      const Eigen::Vector3d& u = units[i];
      const long long cx = cell_of(u.x()), cy = cell_of(u.y()), cz = cell_of(u.z());
      double best = HUGE_VAL;  // squared chord
      for (long long ring = 1; ring <= max_ring; ++ring) {
        // Only the shell of this ring is new (the inner cube was searched).
        for (long long x = cx - ring; x <= cx + ring; ++x) {
          for (long long y = cy - ring; y <= cy + ring; ++y) {
            for (long long z = cz - ring; z <= cz + ring; ++z) {
              const bool shell = ring == 1 || std::max({std::llabs(x - cx), std::llabs(y - cy), std::llabs(z - cz)}) == ring;
              if (!shell) continue;
              const auto found = cells.find(key_of(x, y, z));
              if (found == cells.end()) continue;
              for (std::uint32_t k = found->second.first; k < found->second.second; ++k) {
                const std::uint32_t j = keyed[k].second;
                if (j == i) continue;
                const double d2 = (units[j] - u).squaredNorm();
                if (d2 < best) best = d2;
              }
            }
          }
        }
        // Every point within ring * h of u lies in the cube searched.
        const double reach = static_cast<double>(ring) * h;
        if (best <= reach * reach) break;
      }
      const double chord = std::sqrt(best);
      if (chord <= max_chord) out[i] = 2.0 * std::asin(std::min(1.0, chord / 2.0));
    }
    return out;
  }

  /// Empty cells take the mean of their filled 8-neighbours, ring after ring
  /// (azimuth wraps), until every cell has a value. O(cells x rings).
  void fill_empty(std::vector<float>& value, std::vector<std::uint8_t>& filled) const {
    bool any_empty = true;
    while (any_empty) {
      any_empty = false;
      std::vector<std::uint8_t> next = filled;
      std::vector<float> next_value = value;
      for (int r = 0; r < rows_; ++r) {
        for (int c = 0; c < cols_; ++c) {
          const std::size_t k = static_cast<std::size_t>(r) * cols_ + c;
          if (filled[k]) continue;
          double sum = 0.0;
          int n = 0;
          for (int dr = -1; dr <= 1; ++dr) {
            const int rr = r + dr;
            if (rr < 0 || rr >= rows_) continue;
            for (int dc = -1; dc <= 1; ++dc) {
              const std::size_t kk = static_cast<std::size_t>(rr) * cols_ + wrap(c + dc);
              if (filled[kk]) {
                sum += value[kk];
                ++n;
              }
            }
          }
          if (n > 0) {
            next_value[k] = static_cast<float>(sum / n);
            next[k] = 1;
          } else {
            any_empty = true;
          }
        }
      }
      filled.swap(next);
      value.swap(next_value);
    }
  }

  /// The 3 x 3 mean of every cell (azimuth wraps; elevation edges average
  /// the rows they have). O(cells).
  std::vector<float> smoothed(const std::vector<float>& value) const {
    std::vector<float> out(value.size());
    for (int r = 0; r < rows_; ++r) {
      for (int c = 0; c < cols_; ++c) {
        double sum = 0.0;
        int n = 0;
        for (int dr = -1; dr <= 1; ++dr) {
          const int rr = r + dr;
          if (rr < 0 || rr >= rows_) continue;
          for (int dc = -1; dc <= 1; ++dc) {
            sum += value[static_cast<std::size_t>(rr) * cols_ + wrap(c + dc)];
            ++n;
          }
        }
        out[static_cast<std::size_t>(r) * cols_ + c] = static_cast<float>(sum / n);
      }
    }
    return out;
  }

  static void check(const Params& p) {
    if (!std::isfinite(p.cell_deg) || p.cell_deg < 0.25f || p.cell_deg > 30.0f)
      throw error("cell_deg", p.cell_deg, "finite, in [0.25, 30] deg");
    if (!std::isfinite(p.quantile) || p.quantile < 0.0f || p.quantile > 1.0f)
      throw error("quantile", p.quantile, "finite, in [0, 1]");
    if (p.min_samples < 1) throw error("min_samples", p.min_samples, ">= 1");
    if (!std::isfinite(p.max_spacing_deg) || !(p.max_spacing_deg > 0.0f) || p.max_spacing_deg > 30.0f)
      throw error("max_spacing_deg", p.max_spacing_deg, "finite, in (0, 30] deg");
  }

  static std::invalid_argument error(const char* name, double value, const char* allowed) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", value);
    return std::invalid_argument(std::string("ScanSpacing: parameter ") + name + " = " + buf +
                                 " is invalid; allowed: " + allowed);
  }

  double cell_deg_;
  int rows_;
  int cols_;
  std::size_t used_ = 0;
  std::vector<float> table_;  ///< [rad], rows_ x cols_, row-major
};

}  // namespace streamclust
