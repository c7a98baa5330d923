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
#include <utility>
#include <vector>

namespace streamclust {

/// How ScanSpacing builds its table.
struct ScanSpacingParams {
  /// [deg] side of a table cell (azimuth x elevation), finite, in [0.25, 10]
  float cell_deg = 2.0f;
  /// which quantile of a cell's spanning-tree edges the cell keeps, in [0, 1]
  /// (0.5: about the median nearest-neighbour angle; 1: the widest gap)
  float quantile = 0.9f;
  /// fewest directions that make a cell's own value, >= 2
  int min_samples = 8;
  /// [deg] spanning-tree edges longer than this are left out (a gap
  /// between separate parts of the pattern, not a spacing), finite, in (0, 30]
  float max_spacing_deg = 5.0f;
};

/// The typical angle [rad] between neighbouring returns of one window T_B
/// around each direction of the sensor frame (x forward, z up): what a
/// single linkage must bridge there.
///
/// Built once (`from_directions`, `from_sensor_model`): the window's
/// directions are binned in table cells (azimuth x elevation, `cell_deg`
/// square); in each cell with at least `min_samples` of them, the minimum
/// spanning tree of their angles (edges over `max_spacing_deg` left out)
/// and the `quantile` of its edges: 0.5 is about the median nearest-
/// neighbour angle, near 1 the widest gap that keeps the cell's returns
/// connected, which a pattern of traces (the Avia's six beams fire side by
/// side: their nearest neighbours are close along a trace, the traces
/// farther apart) makes several times the former. Cells without a value
/// (outside the field of view, the sky of a recording) take the mean of
/// their filled neighbours, ring after ring; then a 3 x 3 mean smooths the
/// table. `at(d)` interpolates bilinearly between cell centres (azimuth
/// wraps), so the spacing is continuous in d.
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
  /// std::invalid_argument for bad Params or when no cell has min_samples
  /// directions. O(sum over cells of n_cell^2) (a dense Prim per cell;
  /// about 0.1 s for the 100k directions of a Mid-360 or Avia window) plus
  /// O(cells).
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
  /// Directions in cells with a value of their own (min_samples or more).
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
    std::vector<std::vector<Eigen::Vector3d>> per_cell(static_cast<std::size_t>(rows_) * cols_);
    for (const Eigen::Vector3f& d : directions) {
      const Eigen::Vector3d v = d.cast<double>();
      const double n = v.norm();
      if (std::isfinite(n) && n > 0.0) per_cell[index_of(v / n)].push_back(v / n);
    }
    const double max_chord = 2.0 * std::sin(static_cast<double>(p.max_spacing_deg) / kRadToDeg / 2.0);
    std::vector<float> raw(per_cell.size(), 0.0f);
    std::vector<std::uint8_t> filled(per_cell.size(), 0);
    std::vector<double> edges;
    for (std::size_t k = 0; k < per_cell.size(); ++k) {
      if (per_cell[k].size() < static_cast<std::size_t>(p.min_samples)) continue;
      spanning_tree_edges(per_cell[k], max_chord, edges);
      if (edges.empty()) continue;
      const auto at = static_cast<std::size_t>(std::llround(static_cast<double>(p.quantile) * static_cast<double>(edges.size() - 1)));
      std::nth_element(edges.begin(), edges.begin() + static_cast<std::ptrdiff_t>(at), edges.end());
      raw[k] = static_cast<float>(2.0 * std::asin(std::min(1.0, edges[at] / 2.0)));
      filled[k] = 1;
      used_ += per_cell[k].size();
    }
    if (used_ == 0) throw error("directions", static_cast<double>(directions.size()), "enough for one cell of min_samples");
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

  /// The chords of the minimum spanning tree of `units` (a dense Prim),
  /// those up to `max_chord`, into `edges` (cleared). O(n^2).
  static void spanning_tree_edges(const std::vector<Eigen::Vector3d>& units, double max_chord, std::vector<double>& edges) {
    edges.clear();
    const std::size_t n = units.size();
    std::vector<double> best(n, HUGE_VAL);  // squared chord to the tree
    std::vector<std::uint8_t> in_tree(n, 0);
    std::size_t next = 0;
    for (std::size_t added = 0; added < n; ++added) {
      const std::size_t u = next;
      in_tree[u] = 1;
      if (added > 0 && best[u] <= max_chord * max_chord) edges.push_back(std::sqrt(best[u]));
      double nearest = HUGE_VAL;
      for (std::size_t v = 0; v < n; ++v) {
        if (in_tree[v]) continue;
        const double d2 = (units[v] - units[u]).squaredNorm();
        if (d2 < best[v]) best[v] = d2;
        if (best[v] < nearest) {
          nearest = best[v];
          next = v;
        }
      }
    }
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
          const auto [mean, n] = neighbourhood_mean(value, r, c, [&](std::size_t kk) { return filled[kk] != 0; });
          if (n > 0) {
            next_value[k] = static_cast<float>(mean);
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
        const double mean = neighbourhood_mean(value, r, c, [](std::size_t) { return true; }).first;
        out[static_cast<std::size_t>(r) * cols_ + c] = static_cast<float>(mean);
      }
    }
    return out;
  }

  /// The mean of the values of the cells around (r, c), itself included,
  /// that `use(index)` accepts (azimuth wraps; elevation edges have fewer
  /// rows), and how many there were (0: mean 0). O(1).
  template <class Use>
  std::pair<double, int> neighbourhood_mean(const std::vector<float>& value, int r, int c, Use&& use) const {
    double sum = 0.0;
    int n = 0;
    for (int dr = -1; dr <= 1; ++dr) {
      const int rr = r + dr;
      if (rr < 0 || rr >= rows_) continue;
      for (int dc = -1; dc <= 1; ++dc) {
        const std::size_t k = static_cast<std::size_t>(rr) * cols_ + wrap(c + dc);
        if (use(k)) {
          sum += value[k];
          ++n;
        }
      }
    }
    return {n > 0 ? sum / n : 0.0, n};
  }

  static void check(const Params& p) {
    if (!std::isfinite(p.cell_deg) || p.cell_deg < 0.25f || p.cell_deg > 10.0f)
      throw error("cell_deg", p.cell_deg, "finite, in [0.25, 10] deg");
    if (!std::isfinite(p.quantile) || p.quantile < 0.0f || p.quantile > 1.0f)
      throw error("quantile", p.quantile, "finite, in [0, 1]");
    if (p.min_samples < 2) throw error("min_samples", p.min_samples, ">= 2");
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
