// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// AdaptiveResolution: C-ARC's exponential control loop choosing the grid
/// size from the first window (paper, section "Adaptive Range Grid Projection").

#include <streamclust/concepts/resolution.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {

/// One iteration of AdaptiveResolution's control loop: the grid that was
/// measured and its metrics (all dimensionless).
struct AdaptiveStep {
  GridSize grid;                    ///< rows (H, vertical) x cols (W, horizontal) measured
  float density_v = 0.0f;           ///< D_v = |V| / (H |A_c|): mean fraction of occupied cells per active column
  float density_h = 0.0f;           ///< D_h = |V| / (W |A_r|): mean fraction of occupied cells per active row
  float gap_v = 0.0f;               ///< G_v: mean over active columns of (longest interior empty run) / H
  float gap_h = 0.0f;               ///< G_h: mean over active rows of (longest interior empty run) / W
  float mean_multiplicity = 0.0f;   ///< M_mu = points / |V|
};

/// Why AdaptiveResolution's last calibrate() stopped (see its class comment).
enum class AdaptiveStop : std::uint8_t {
  not_run,            ///< calibrate() has not been called
  no_input,           ///< no accepted coordinate: the initial grid was kept
  converged,          ///< M_mu <= T_M and stable within 1 %
  fixed_point,        ///< the update proposed an already measured grid
  refinement_futile,  ///< refining no longer lowered M_mu enough (shared directions)
  iteration_cap,      ///< max_iterations grids measured
};

/// Lower-case name of `s` ("converged", ...), for reports.
inline const char* to_string(AdaptiveStop s) {
  switch (s) {
    case AdaptiveStop::not_run: return "not_run";
    case AdaptiveStop::no_input: return "no_input";
    case AdaptiveStop::converged: return "converged";
    case AdaptiveStop::fixed_point: return "fixed_point";
    case AdaptiveStop::refinement_futile: return "refinement_futile";
    case AdaptiveStop::iteration_cap: return "iteration_cap";
  }
  return "unknown";
}

/// Chooses the grid from the projected coordinates of the first window with
/// the exponential control loop of C-ARC, so the grid fits the sensor's scan
/// pattern and the chosen window T_B.
///
/// Metrics, measured on the occupancy matrix F (H rows x W columns) of the
/// accepted coordinates, with V the occupied cells, A_c / A_r the columns /
/// rows holding at least one occupied cell:
/// - density D_v = |V| / (H |A_c|), D_h = |V| / (W |A_r|) (the paper's formulas);
/// - maximum gap G_v, G_h. DEFINITION CHOSEN HERE (the paper only says
///   "relative length of the longest consecutive sequence of empty cells"):
///   for every active column, the longest run of empty cells lying strictly
///   between two occupied cells of that column (leading and trailing empties
///   are outside the column's active span: sky, FOV margins), divided by H;
///   G_v is the MEAN of that over the active columns (a maximum over columns
///   would be dominated by one sparse column). G_h likewise over active rows,
///   divided by W. Runs are not followed across the azimuth seam.
/// - mean multiplicity M_mu = points / |V|.
///
/// Update, per iteration (d in {v: rows, h: cols}):
/// - if M_mu > T_M (too many collisions) the grid is refined uniformly:
///   N_d <- max(N_d + 1, ceil(N_d sqrt(r))) for both axes with
///   r = max(M_mu / T_M, (M_mu - 1) / (T_M - 1)): for points scattered over
///   the cells (Poisson occupancy) the excess M_mu - 1 scales with 1 / cells,
///   so this aims at T_M in one step (the plain ratio M_mu / T_M approaches
///   T_M = 1.25 in many tiny steps);
/// - otherwise N_d <- floor(N_d exp(lambda_D e_D - lambda_G e_G)) with
///   e_D = (D_d - T_D) / T_D and e_G = (G_d - T_G) / T_G;
/// - then constraints: N_d >= 1; cols / rows within
///   [fov_aspect / aspect_factor, fov_aspect x aspect_factor] (a grid with
///   square angular cells has cols / rows = fov_aspect; a ratio outside is
///   projected onto the interval keeping rows x cols); rows x cols <= the
///   cell limit (both scaled down): max_cells, and at most
///   max_cells_per_point cells per accepted point (never fewer than the
///   initial grid's). The initial grid is constrained the same way before
///   the first measurement.
///
/// Why a limit per point: N points occupy at most N cells, so a grid of 64
/// cells per point is at least 98 % empty whatever the points' layout; the
/// sensors' first windows settle at 3-20 cells per point
/// (docs/adaptive-resolution.md). Without it, points crowded into a tiny
/// solid angle with a little jitter (a sensor facing a wall at close range)
/// keep lowering M_mu as the cells shrink and drive the loop to max_cells:
/// a 16.8 M cell grid, 537 MB of bucket-grid index.
///
/// Stopping (the paper: "once M_mu stabilises"), reported by stop_reason():
/// - `converged`: M_mu <= T_M and its relative change from the previous
///   iteration < 1 %;
/// - `fixed_point`: the update leaves the grid unchanged, or proposes a grid
///   already measured (a cycle);
/// - `refinement_futile`: a uniform refinement lowered the excess M_mu - 1 by
///   less than a tenth of the ideal 1 / cells scaling (duplicates: by
///   nothing; steps whose ideal gain is < 10 % are not judged). Finer cells cannot separate points that share a direction: exact
///   duplicates, all points along one ray, or a repetitive (spinning) sensor
///   that fired the same directions on several turns, whose M_mu cannot drop
///   below the number of turns in the window;
/// - `iteration_cap`: max_iterations grids were measured.
/// The result is the last measured grid with M_mu <= T_M. If no measured
/// grid reaches T_M (documented fallback, typically `refinement_futile`), the
/// result is the COARSEST measured grid whose M_mu is within 1 % of the
/// lowest measured M_mu: refining further would only add empty cells (for
/// points all in one direction that is the initial grid, never a max_cells
/// grid). Every measured grid is in `trace()`.
///
/// Degenerate input: no accepted coordinate (an empty window) -> the initial
/// grid is kept unchanged, the trace is empty, stop_reason() is `no_input`,
/// needs_calibration() becomes false. One point: M_mu = 1 <= T_M, the loop
/// converges near the initial grid. Never a zero dimension, never more than
/// max_iterations iterations; deterministic.
///
/// Complexity of calibrate: O(iterations x N log N) for N accepted points
/// (two sorts of cell indices per iteration; no H x W matrix is allocated).
/// Thread safety: not thread-safe (calibrate mutates); const members may be
/// read concurrently when no calibrate runs.
///
/// Usage:
/// \code
///   streamclust::AdaptiveResolution res{{}};                  // paper defaults
///   std::vector<streamclust::Projected> first_window = ...;   // from the projection
///   streamclust::GridSize g = res.calibrate(first_window, projection.fov_aspect());
///   for (const auto& s : res.trace()) { /* s.grid, s.mean_multiplicity, ... */ }
/// \endcode
class AdaptiveResolution {
 public:
  struct Params {
    std::uint32_t initial_rows = 32;     ///< [cells] starting H, >= 1
    std::uint32_t initial_cols = 256;    ///< [cells] starting W, >= 1; H x W <= max_cells
    float target_gap = 0.1f;             ///< T_G, (0, 1]
    float target_density = 0.9f;         ///< T_D, (0, 1]
    float gain_gap = 0.2f;               ///< lambda_G, [0, 10]
    float gain_density = 0.2f;           ///< lambda_D, [0, 10]
    float max_multiplicity = 2.0f;       ///< T_M [points per occupied cell], [1, 1e6]
    float aspect_factor = 4.0f;          ///< cols/rows within [fov_aspect / f, fov_aspect x f], f in [1, 1e6]
    std::uint32_t max_iterations = 50;   ///< grids measured at most, [1, 10000]
    std::uint32_t max_cells = 1u << 24;  ///< [cells] upper bound on H x W, [1, 2^31]
    float max_cells_per_point = 64.0f;   ///< [cells per accepted point] bound on H x W, [1, 1e6]
  };

  /// Validates `params`; throws std::invalid_argument naming the parameter,
  /// its value and the allowed range.
  explicit AdaptiveResolution(const Params& params)
      : params_(params), grid_{params.initial_rows, params.initial_cols} {
    check_range("initial_rows", params.initial_rows, 1.0, 4294967295.0, "[1, 2^32) cells");
    check_range("initial_cols", params.initial_cols, 1.0, 4294967295.0, "[1, 2^32) cells");
    check_range("target_gap", params.target_gap, 0.0, 1.0, "(0, 1]", true);
    check_range("target_density", params.target_density, 0.0, 1.0, "(0, 1]", true);
    check_range("gain_gap", params.gain_gap, 0.0, 10.0, "[0, 10]");
    check_range("gain_density", params.gain_density, 0.0, 10.0, "[0, 10]");
    check_range("max_multiplicity", params.max_multiplicity, 1.0, 1e6, "[1, 1e6] points per cell");
    check_range("aspect_factor", params.aspect_factor, 1.0, 1e6, "[1, 1e6]");
    check_range("max_iterations", params.max_iterations, 1.0, 10000.0, "[1, 10000]");
    check_range("max_cells", params.max_cells, 1.0, 2147483648.0, "[1, 2^31] cells");
    check_range("max_cells_per_point", params.max_cells_per_point, 1.0, 1e6, "[1, 1e6] cells per point");
    const double cells = static_cast<double>(params.initial_rows) * static_cast<double>(params.initial_cols);
    if (cells > static_cast<double>(params.max_cells))
      throw error("initial_rows x initial_cols", cells, "[1, max_cells] cells");
  }

  /// True until calibrate() has been called.
  bool needs_calibration() const { return !calibrated_; }

  /// The initial grid before calibration, the calibrated grid afterwards.
  GridSize grid() const { return grid_; }

  /// Run the control loop on `coords` (entries not accepted are ignored) and
  /// keep the resulting grid. `fov_aspect` is the projection's horizontal /
  /// vertical FOV extent (finite, > 0; otherwise std::invalid_argument).
  /// Clears and refills trace(). Deterministic.
  GridSize calibrate(const std::vector<Projected>& coords, float fov_aspect) {
    if (!std::isfinite(fov_aspect) || !(fov_aspect > 0.0f))
      throw error("fov_aspect (argument of calibrate)", fov_aspect, "finite, > 0");
    trace_.clear();
    calibrated_ = true;
    const bool any = std::any_of(coords.begin(), coords.end(), [](const Projected& p) { return p.accepted(); });
    if (!any) {
      grid_ = GridSize{params_.initial_rows, params_.initial_cols};  // documented fallback
      stop_ = AdaptiveStop::no_input;
      return grid_;
    }
    const auto accepted = static_cast<double>(
        std::count_if(coords.begin(), coords.end(), [](const Projected& p) { return p.accepted(); }));
    const double initial_cells = static_cast<double>(params_.initial_rows) * static_cast<double>(params_.initial_cols);
    cell_limit_ = std::min(static_cast<double>(params_.max_cells),
                           std::max(initial_cells, static_cast<double>(params_.max_cells_per_point) * accepted));
    std::vector<CellIndex> keys;
    std::vector<CellIndex> scratch;
    std::vector<GridSize> visited;
    GridSize g = constrain(params_.initial_rows, params_.initial_cols, fov_aspect);
    stop_ = AdaptiveStop::iteration_cap;
    for (std::uint32_t it = 0; it < params_.max_iterations; ++it) {
      const AdaptiveStep step = measure_into(coords, g, keys, scratch);
      trace_.push_back(step);
      const float mu = step.mean_multiplicity;
      if (trace_.size() >= 2) {
        const float previous_mu = trace_[trace_.size() - 2].mean_multiplicity;
        const bool stable = std::fabs(mu - previous_mu) < 0.01f * previous_mu;
        if (stable && mu <= params_.max_multiplicity) {
          stop_ = AdaptiveStop::converged;
          break;
        }
        if (previous_mu > params_.max_multiplicity && refinement_futile(trace_[trace_.size() - 2], step)) {
          stop_ = AdaptiveStop::refinement_futile;
          break;
        }
      }
      visited.push_back(g);
      const GridSize next = propose(step, fov_aspect);
      if (std::find(visited.begin(), visited.end(), next) != visited.end()) {
        stop_ = AdaptiveStop::fixed_point;
        break;
      }
      g = next;
    }
    grid_ = choose_result();
    return grid_;
  }

  /// Why the last calibrate() stopped (`not_run` before the first).
  AdaptiveStop stop_reason() const { return stop_; }

  /// The iterations of the last calibrate() (empty before, or after a
  /// calibrate without accepted coordinates).
  const std::vector<AdaptiveStep>& trace() const { return trace_; }

  /// The metrics of `coords` (accepted entries only) on `grid`, as used by
  /// the control loop (see the class comment). All zero when no entry is
  /// accepted. O(N log N).
  static AdaptiveStep measure(const std::vector<Projected>& coords, GridSize grid) {
    std::vector<CellIndex> keys;
    std::vector<CellIndex> scratch;
    return measure_into(coords, grid, keys, scratch);
  }

  const Params& params() const { return params_; }

 private:
  struct LineStats {
    std::size_t lines = 0;     ///< active lines
    double gap_sum = 0.0;      ///< sum of longest interior empty runs [cells]
  };

  /// Scan sorted unique keys (line * length + position) into active-line
  /// count and the sum of per-line longest interior runs of empty cells.
  static LineStats scan_lines(const std::vector<CellIndex>& sorted, std::uint32_t length) {
    LineStats s;
    std::uint32_t line = 0;
    std::uint32_t last = 0;
    std::uint32_t longest = 0;
    bool open = false;
    for (const CellIndex key : sorted) {
      const std::uint32_t l = key / length;
      const std::uint32_t pos = key % length;
      if (!open || l != line) {
        if (open) s.gap_sum += longest;
        ++s.lines;
        line = l;
        longest = 0;
        open = true;
      } else {
        longest = std::max(longest, pos - last - 1u);
      }
      last = pos;
    }
    if (open) s.gap_sum += longest;
    return s;
  }

  static AdaptiveStep measure_into(const std::vector<Projected>& coords, GridSize grid,
                                   std::vector<CellIndex>& keys, std::vector<CellIndex>& scratch) {
    AdaptiveStep step;
    step.grid = grid;
    const GridShape shape{grid.rows, grid.cols, false};
    keys.clear();
    for (const Projected& p : coords)
      if (p.accepted()) keys.push_back(shape.cell_of(p.u, p.v));
    const std::size_t points = keys.size();
    if (points == 0) return step;
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    const double occupied = static_cast<double>(keys.size());
    const LineStats rows = scan_lines(keys, grid.cols);  // row-major: lines are rows
    scratch.clear();
    for (const CellIndex key : keys) scratch.push_back((key % grid.cols) * grid.rows + key / grid.cols);
    std::sort(scratch.begin(), scratch.end());
    const LineStats cols = scan_lines(scratch, grid.rows);  // column-major: lines are columns
    const double h = grid.rows;
    const double w = grid.cols;
    step.density_v = static_cast<float>(occupied / (h * static_cast<double>(cols.lines)));
    step.density_h = static_cast<float>(occupied / (w * static_cast<double>(rows.lines)));
    step.gap_v = static_cast<float>(cols.gap_sum / (h * static_cast<double>(cols.lines)));
    step.gap_h = static_cast<float>(rows.gap_sum / (w * static_cast<double>(rows.lines)));
    step.mean_multiplicity = static_cast<float>(static_cast<double>(points) / occupied);
    return step;
  }

  /// Next grid from the measured step (refinement or exponential rule), constrained.
  GridSize propose(const AdaptiveStep& s, float fov_aspect) const {
    const double rows = s.grid.rows;
    const double cols = s.grid.cols;
    const double mu = s.mean_multiplicity;
    const double t_m = params_.max_multiplicity;
    if (mu > t_m) {
      // Cells needed: Poisson occupancy gives M_mu - 1 ~ points / (2 cells),
      // so the excess over 1 must shrink by (mu - 1) / (T_M - 1); never less
      // than the plain ratio mu / T_M.
      const double excess_ratio = (mu - 1.0) / std::max(t_m - 1.0, 1e-3);
      const double factor = std::sqrt(std::max(mu / t_m, excess_ratio));
      return constrain(std::max(rows + 1.0, std::ceil(rows * factor)), std::max(cols + 1.0, std::ceil(cols * factor)),
                       fov_aspect);
    }
    const double t_d = params_.target_density;
    const double t_g = params_.target_gap;
    const double l_d = params_.gain_density;
    const double l_g = params_.gain_gap;
    const auto rule = [&](double n, double density, double gap) {
      const double e_d = (density - t_d) / t_d;
      const double e_g = (gap - t_g) / t_g;
      return std::floor(n * std::exp(l_d * e_d - l_g * e_g));
    };
    return constrain(rule(rows, s.density_v, s.gap_v), rule(cols, s.density_h, s.gap_h), fov_aspect);
  }

  /// Apply N >= 1, the aspect interval and the cell limit; round to integers.
  GridSize constrain(double rows, double cols, float fov_aspect) const {
    const double max_cells = cell_limit_;
    const double lo = static_cast<double>(fov_aspect) / params_.aspect_factor;
    const double hi = static_cast<double>(fov_aspect) * params_.aspect_factor;
    rows = std::min(std::max(rows, 1.0), max_cells);
    cols = std::min(std::max(cols, 1.0), max_cells);
    const double ratio = cols / rows;
    if (ratio < lo || ratio > hi) {
      const double product = rows * cols;
      const double r = std::min(std::max(ratio, lo), hi);
      rows = std::sqrt(product / r);
      cols = std::sqrt(product * r);
    }
    if (rows * cols > max_cells) {
      const double k = std::sqrt(max_cells / (rows * cols));
      rows *= k;
      cols *= k;
    }
    const double r_int = std::min(std::max(std::round(rows), 1.0), max_cells);
    const double cap = std::max(1.0, std::floor(max_cells / r_int));
    const double c_min = std::max(1.0, std::ceil(lo * r_int - 1e-9));
    const double c_max = std::min(std::floor(hi * r_int + 1e-9), cap);
    double c_int = std::round(cols);
    if (c_min <= c_max)
      c_int = std::min(std::max(c_int, c_min), c_max);
    else
      c_int = std::min(std::max(c_int, 1.0), cap);  // no integer fits the aspect interval: best effort
    return GridSize{static_cast<std::uint32_t>(r_int), static_cast<std::uint32_t>(c_int)};
  }

  static std::invalid_argument error(const char* name, double value, const char* allowed) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", value);
    return std::invalid_argument(std::string("AdaptiveResolution: parameter ") + name + " = " + buf +
                                 " is invalid; allowed: " + allowed);
  }

  template <class T>
  static void check_range(const char* name, T value, double lo, double hi, const char* allowed,
                          bool exclusive_lo = false) {
    const double v = static_cast<double>(value);
    const bool ok = std::isfinite(v) && (exclusive_lo ? v > lo : v >= lo) && v <= hi;
    if (!ok) throw error(name, v, allowed);
  }

  static std::uint64_t cells(GridSize g) { return std::uint64_t{g.rows} * g.cols; }

  /// True when refining `before` into `after` lowered the excess multiplicity
  /// M_mu - 1 by less than a tenth of what the added cells give points in
  /// distinct directions (Poisson occupancy: M_mu - 1 ~ points / (2 cells)):
  /// the pattern is at its duplicate floor, finer grids only add empty cells.
  /// Only steps adding >= 10 % of the cells' worth of gain are judged.
  static bool refinement_futile(const AdaptiveStep& before, const AdaptiveStep& after) {
    const double ideal_gain = 1.0 - static_cast<double>(cells(before.grid)) / static_cast<double>(cells(after.grid));
    const double excess_before = static_cast<double>(before.mean_multiplicity) - 1.0;
    const double excess_after = static_cast<double>(after.mean_multiplicity) - 1.0;
    const double gain = excess_before > 0.0 ? 1.0 - excess_after / excess_before : 0.0;
    // Small steps (near T_M) are not judged: cell boundaries shift, M_mu is noisy.
    return ideal_gain >= 0.1 && gain < 0.1 * ideal_gain;
  }

  /// The last measured grid with M_mu <= T_M; without one, the coarsest
  /// grid within 1 % of the lowest M_mu measured. `trace_` is not empty.
  GridSize choose_result() const {
    for (auto it = trace_.rbegin(); it != trace_.rend(); ++it) {
      if (it->mean_multiplicity <= params_.max_multiplicity) return it->grid;
    }
    float lowest = trace_.front().mean_multiplicity;
    for (const AdaptiveStep& s : trace_) lowest = std::min(lowest, s.mean_multiplicity);
    const AdaptiveStep* best = nullptr;
    for (const AdaptiveStep& s : trace_) {
      if (s.mean_multiplicity > 1.01f * lowest) continue;
      if (best == nullptr || cells(s.grid) < cells(best->grid)) best = &s;
    }
    return best->grid;
  }

  Params params_;
  GridSize grid_;
  double cell_limit_ = 0.0;  ///< [cells] the last calibrate's bound on H x W (max_cells, per point)
  std::vector<AdaptiveStep> trace_;
  AdaptiveStop stop_ = AdaptiveStop::not_run;
  bool calibrated_ = false;
};

}  // namespace streamclust

static_assert(streamclust::is_resolution_policy_v<streamclust::AdaptiveResolution>,
              "STREAMCLUST_RESOLUTION_POLICY_INVALID: AdaptiveResolution");
