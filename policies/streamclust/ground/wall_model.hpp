// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// WallModel: large vertical planes (walls, facades) in the sliding window,
/// from per-voxel line fits of the points' horizontal positions.

#include <streamclust/detail/parameter_check.hpp>
#include <streamclust/ground/cell_table.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace streamclust {

/// The window's points in cubic voxels of `voxel_size`. A voxel sums the
/// positions of its object and wall points (integers in 1/1024 of a voxel,
/// so removal is exact) and counts every point it holds.
///
/// A vertical plane crosses a voxel as a line in the horizontal plane: the
/// voxel is a wall voxel when its points fit one line (RMS distance at most
/// `max_rms`, spread along it at least a fifth of a voxel, `min_points` or
/// more; a voxel with fewer, a far wall's, fits the five voxels of its
/// column centred on it) and that line is large: the voxels stepping a voxel
/// at a time along it, and up and down, hold points it explains (RMS at most
/// `max_rms`; one empty voxel is bridged), and those points cover
/// `min_length` along the line and `min_height` in height (each voxel's
/// points cover their mean -/+ sqrt(3) standard deviations: the few points
/// an edge's noise spills into the next voxel do not stretch a cabinet to a
/// wall). A trunk, a pole or a pillar curves away from the line within a
/// voxel or two; a car's side or a cabinet's front is not as tall as a wall,
/// a cabinet or a shelf not as long. A voxel whose own points do not make a
/// wall (a wall's foot beside the floor, a tree's crown against a facade, a
/// corner the wall only grazes) takes the line of a neighbouring wall voxel
/// (above, below, then its 8 horizontal neighbours) that passes through it.
/// A point lies on a wall when it is within `tolerance` of its voxel's wall
/// line: a cabinet against the wall keeps all but its back few centimetres.
///
/// Ground and ceiling points count in a voxel but not in its line (a floor
/// or a ceiling fills the voxel's footprint). A voxel's verdict is cached
/// and refreshed once it has counted max(8, a quarter of its points) points
/// since (every other point while it is too sparse for a line of its own):
/// a point's decision depends only on the points counted before it (a
/// replay of the stream makes the same decisions).
///
/// Cost per point: one voxel lookup and eight integer sums; a refresh up to
/// about 20 lookups and line tests (5 per step for a far wall's stacks), 10
/// more to borrow. Memory: 104 bytes per live voxel plus the table. Thread
/// safety: none.
class WallModel {
 public:
  struct Params {
    float voxel_size = 0.5f;      ///< [m] voxel edge, [0.1, 5]
    float max_rms = 0.05f;        ///< [m] a wall's points about its line, (0, 1]
    float tolerance = 0.08f;      ///< [m] a point this close to a wall's line lies on the wall, (0, 1]
    float min_length = 2.0f;      ///< [m] a wall's horizontal extent at least, [0, 20]
    float min_height = 2.0f;      ///< [m] a wall's vertical extent at least, [0, 20]
    std::uint32_t min_points = 6; ///< points of a voxel that fit its own line, [3, 100000]
  };

  /// Throws std::invalid_argument naming a parameter outside its range.
  explicit WallModel(const Params& params) : params_(params) {
    check(params.voxel_size >= 0.1f && params.voxel_size <= 5.0f, "voxel_size", params.voxel_size, "[0.1, 5] m");
    check(params.max_rms > 0.0f && params.max_rms <= 1.0f, "max_rms", params.max_rms, "(0, 1] m");
    check(params.tolerance > 0.0f && params.tolerance <= 1.0f, "tolerance", params.tolerance, "(0, 1] m");
    check(params.min_length >= 0.0f && params.min_length <= 20.0f, "min_length", params.min_length, "[0, 20] m");
    check(params.min_height >= 0.0f && params.min_height <= 20.0f, "min_height", params.min_height, "[0, 20] m");
    check(params.min_points >= 3 && params.min_points <= 100000, "min_points", static_cast<float>(params.min_points),
          "[3, 100000]");
    inverse_voxel_ = 1.0 / static_cast<double>(params.voxel_size);
  }
  WallModel() : WallModel(Params{}) {}

  /// A point entered into the model: its voxel and whether it lies on a wall.
  struct Entry {
    std::uint32_t voxel = CellTable<int>::kNone;
    bool on_wall = false;
  };

  /// Counts the point at `world` [m] in its voxel and decides, from the
  /// points counted before it, whether it lies on a wall. Amortised O(1).
  Entry enter(const Eigen::Vector3f& world) {
    const Key k = key_of(world);
    Entry e;
    e.voxel = voxels_.find_or_create_packed(k.packed());
    Voxel& v = voxels_[e.voxel];
    if (!v.verdict_made || v.since_verdict >= refresh_after(v.points)) refresh(k, e.voxel);
    const Voxel& fresh = voxels_[e.voxel];
    e.on_wall = fresh.wall && std::fabs(fresh.normal_x * world.x() + fresh.normal_y * world.y() - fresh.offset) <=
                                  static_cast<double>(params_.tolerance);
    ++voxels_[e.voxel].points;
    ++voxels_[e.voxel].since_verdict;
    return e;
  }

  /// Adds an entered point to its voxel's line sums: an object or a wall
  /// point. O(1).
  void add_to_line(const Entry& e, const Eigen::Vector3f& world) { voxels_[e.voxel].line.add(local_of(world)); }

  /// Uncounts a point `enter` counted; `in_line`: add_to_line took it too.
  /// O(1) expected.
  void forget(const Eigen::Vector3f& world, bool in_line) {
    const Key k = key_of(world);
    const std::uint32_t i = voxels_.find_packed(k.packed());
    Voxel& v = voxels_[i];
    if (in_line) v.line.remove(local_of(world));
    if (--v.points == 0) voxels_.release_packed(k.packed());
  }

  /// Voxels holding window points.
  std::size_t live_voxels() const { return voxels_.size(); }
  std::size_t heap_bytes() const { return voxels_.heap_bytes(); }
  const Params& params() const { return params_; }

 private:
  static constexpr std::uint32_t kRefreshMin = 8;  ///< points a fitted voxel counts between refreshes, at least
  static constexpr std::int32_t kStackHalf = 2;    ///< a sparse voxel's line: the voxels this far above and below too
  static constexpr std::int64_t kUnits = 1024;  ///< sub-voxel position units per voxel edge
  static constexpr int kBits = 21;              ///< bits of each voxel coordinate in a packed key

  static void check(bool ok, const char* name, float value, const char* allowed) {
    detail::require_parameter(ok, "WallModel", name, static_cast<double>(value), allowed);
  }

  struct Key {
    std::int32_t ix, iy, iz;
    /// 21 bits a coordinate: +-2^20 voxels (+-524 km of 0.5 m voxels); farther
    /// voxels share keys, which costs a verdict, never a count.
    std::uint64_t packed() const {
      constexpr std::uint64_t mask = (std::uint64_t{1} << kBits) - 1;
      return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(ix)) & mask) << (2 * kBits) |
             (static_cast<std::uint64_t>(static_cast<std::uint32_t>(iy)) & mask) << kBits |
             (static_cast<std::uint64_t>(static_cast<std::uint32_t>(iz)) & mask);
    }
  };
  static std::int32_t voxel_index(double scaled) {
    return static_cast<std::int32_t>(std::clamp(std::floor(scaled), -2147483648.0, 2147483647.0));
  }
  Key key_of(const Eigen::Vector3f& p) const {
    return Key{voxel_index(p.x() * inverse_voxel_), voxel_index(p.y() * inverse_voxel_),
               voxel_index(p.z() * inverse_voxel_)};
  }
  /// A position within its voxel, in 1/kUnits of the voxel, in [0, kUnits).
  struct Local {
    std::int64_t u, v, w;  ///< x, y, z
  };
  Local local_of(const Eigen::Vector3f& p) const {
    const auto within = [](double scaled) {
      const double f = scaled - std::floor(scaled);
      return std::clamp(static_cast<std::int64_t>(f * static_cast<double>(kUnits)), std::int64_t{0}, kUnits - 1);
    };
    return Local{within(p.x() * inverse_voxel_), within(p.y() * inverse_voxel_), within(p.z() * inverse_voxel_)};
  }

  /// Sums of a voxel's line points (local units): exact under add/remove.
  struct LineSums {
    std::int64_t n = 0, su = 0, sv = 0, suu = 0, suv = 0, svv = 0, sw = 0, sww = 0;
    void add(Local l) {
      ++n, su += l.u, sv += l.v, suu += l.u * l.u, suv += l.u * l.v, svv += l.v * l.v, sw += l.w, sww += l.w * l.w;
    }
    void remove(Local l) {
      --n, su -= l.u, sv -= l.v, suu -= l.u * l.u, suv -= l.u * l.v, svv -= l.v * l.v, sw -= l.w, sww -= l.w * l.w;
    }
    void add(const LineSums& o) {
      n += o.n, su += o.su, sv += o.sv, suu += o.suu, suv += o.suv, svv += o.svv, sw += o.sw, sww += o.sww;
    }
  };

  struct Voxel {
    LineSums line;
    std::uint32_t points = 0;         ///< every point counted, structure too
    std::uint32_t since_verdict = 0;  ///< points counted since the verdict
    bool verdict_made = false;
    bool wall = false;
    bool own = false;  ///< the wall line is the voxel's own fit (not borrowed)
    double normal_x = 0.0, normal_y = 0.0, offset = 0.0;  ///< wall line: normal . (x, y) = offset [m]
  };

  /// A line in the horizontal plane, world metres: normal . (x, y) = offset.
  struct Line {
    double normal_x, normal_y, offset;
    double centre_x, centre_y;  ///< the fitted points' centroid
  };

  /// The world position [m] of local unit (0, 0) of voxel k, and the metres per unit.
  double corner(std::int32_t i) const { return static_cast<double>(i) * static_cast<double>(params_.voxel_size); }
  double metres_per_unit() const { return static_cast<double>(params_.voxel_size) / static_cast<double>(kUnits); }

  /// The line fitted to voxel (key k)'s line points when they fit one
  /// (enough points, RMS about it <= max_rms, spread along it >= a fifth
  /// of a voxel). O(1).
  bool fit(Key k, const LineSums& s, Line& out) const {
    if (s.n < static_cast<std::int64_t>(params_.min_points)) return false;
    const double n = static_cast<double>(s.n), unit = metres_per_unit();
    const double mu = static_cast<double>(s.su) / n, mv = static_cast<double>(s.sv) / n;
    // Covariance in units^2; the +0.5 of a unit's centre cancels.
    const double a = static_cast<double>(s.suu) / n - mu * mu, b = static_cast<double>(s.suv) / n - mu * mv,
                 c = static_cast<double>(s.svv) / n - mv * mv;
    const double half_trace = 0.5 * (a + c), spread = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
    const double minor = std::max(0.0, half_trace - spread), major = half_trace + spread;
    const double rms = std::sqrt(minor) * unit, along = std::sqrt(major) * unit;
    if (rms > static_cast<double>(params_.max_rms) || along < 0.2 * static_cast<double>(params_.voxel_size)) return false;
    // The normal: the minor axis of [[a, b], [b, c]].
    double nx = b, ny = minor - a;
    if (std::fabs(a - minor) < std::fabs(c - minor)) nx = minor - c, ny = b;
    const double norm = std::hypot(nx, ny);
    if (norm <= 0.0) nx = 1.0, ny = 0.0; else nx /= norm, ny /= norm;
    out.centre_x = corner(k.ix) + (mu + 0.5) * unit;
    out.centre_y = corner(k.iy) + (mv + 0.5) * unit;
    out.normal_x = nx;
    out.normal_y = ny;
    out.offset = nx * out.centre_x + ny * out.centre_y;
    return true;
  }

  /// Points a voxel of `points` counts before its verdict is refreshed:
  /// every other point while it is too sparse for a line of its own.
  std::uint32_t refresh_after(std::uint32_t points) const {
    return points < params_.min_points ? 2u : std::max(kRefreshMin, points / 4);
  }

  /// The line sums of voxel k (empty when it holds no point). One lookup.
  LineSums line_sums(Key k) const {
    const std::uint32_t j = voxels_.find_packed(k.packed());
    return j == CellTable<Voxel>::kNone ? LineSums{} : voxels_[j].line;
  }

  /// The line sums of voxel k and the kStackHalf voxels above and below it
  /// (one column: the same local frame). 2 kStackHalf + 1 lookups.
  LineSums stack_sums(Key k) const {
    LineSums sum;
    for (std::int32_t dz = -kStackHalf; dz <= kStackHalf; ++dz) {
      const std::uint32_t j = voxels_.find_packed(Key{k.ix, k.iy, k.iz + dz}.packed());
      if (j == CellTable<Voxel>::kNone) continue;
      sum.add(voxels_[j].line);
    }
    return sum;
  }

  /// True when `s` (line sums of voxel k, or of its stack) holds a line
  /// point and `line` explains them (RMS distance <= max_rms). O(1).
  bool explains(const Line& line, Key k, const LineSums& s) const {
    if (s.n < 1) return false;
    const double n = static_cast<double>(s.n), unit = metres_per_unit();
    // Distance of a point at local units (u, v): nx u' + ny v' + e, where
    // u' = (u + 0.5) unit and e = nx corner_x + ny corner_y - offset.
    const double e = line.normal_x * corner(k.ix) + line.normal_y * corner(k.iy) - line.offset +
                     0.5 * unit * (line.normal_x + line.normal_y);
    const double nu = line.normal_x * unit, nv = line.normal_y * unit;
    const double squares = nu * nu * static_cast<double>(s.suu) + 2.0 * nu * nv * static_cast<double>(s.suv) +
                           nv * nv * static_cast<double>(s.svv) +
                           2.0 * e * (nu * static_cast<double>(s.su) + nv * static_cast<double>(s.sv)) + n * e * e;
    const double rms = static_cast<double>(params_.max_rms);
    return squares <= n * rms * rms;
  }

  /// Where a voxel's (or stack's) points lie along the line or in height
  /// [m]: mean -/+ sqrt(3) standard deviations (the ends of points spread
  /// evenly; a sliver of points in a voxel covers a sliver of it).
  struct Interval {
    double lo, hi;
  };
  Interval covered(const Line& line, Key k, const LineSums& s, bool vertical) const {
    const double n = static_cast<double>(s.n), unit = metres_per_unit();
    double mean = 0.0, variance = 0.0;
    if (vertical) {
      const double mw = static_cast<double>(s.sw) / n;
      mean = corner(k.iz) + (mw + 0.5) * unit;
      variance = (static_cast<double>(s.sww) / n - mw * mw) * unit * unit;
    } else {
      const double tx = -line.normal_y, ty = line.normal_x;  // along the line
      const double mu = static_cast<double>(s.su) / n, mv = static_cast<double>(s.sv) / n;
      const double a = static_cast<double>(s.suu) / n - mu * mu, b = static_cast<double>(s.suv) / n - mu * mv,
                   c = static_cast<double>(s.svv) / n - mv * mv;
      mean = tx * (corner(k.ix) + (mu + 0.5) * unit) + ty * (corner(k.iy) + (mv + 0.5) * unit);
      variance = (tx * tx * a + 2.0 * tx * ty * b + ty * ty * c) * unit * unit;
    }
    const double half = std::sqrt(3.0 * std::max(0.0, variance));
    return Interval{mean - half, mean + half};
  }

  /// The extent [m] of the plane of `line` through voxel k whose line
  /// points are `own`: along the line (horizontal) or in height (vertical),
  /// the union of the covered intervals of k and of the voxels stepping a
  /// voxel at a time from the line's centre on both sides that hold points
  /// the line explains (one empty voxel is bridged: a sparse far wall; two
  /// end the plane); `stacked`: horizontal steps read the column's stack
  /// (stack_sums). Stops once it reaches `needed`. At most about 2 needed /
  /// voxel + 4 steps of 1 (5 stacked) lookups.
  double extent(const Line& line, Key k, const LineSums& own, bool vertical, bool stacked, double needed) const {
    const double step = static_cast<double>(params_.voxel_size);
    constexpr double kInf = std::numeric_limits<double>::infinity();
    Interval total = own.n > 0 ? covered(line, k, own, vertical) : Interval{kInf, -kInf};
    for (const int side : {+1, -1}) {
      Key last = k;
      bool gap = false;  // the voxel before was empty
      for (int i = 1; total.hi - total.lo < needed && i <= 64; ++i) {
        Key next = k;
        if (vertical) {
          next.iz = k.iz + side * i;
        } else {
          const double along = static_cast<double>(side) * step * static_cast<double>(i);
          next.ix = voxel_index((line.centre_x - line.normal_y * along) * inverse_voxel_);
          next.iy = voxel_index((line.centre_y + line.normal_x * along) * inverse_voxel_);
        }
        if (next.ix == last.ix && next.iy == last.iy && next.iz == last.iz) continue;  // a diagonal step
        last = next;
        const LineSums sums = stacked && !vertical ? stack_sums(next) : line_sums(next);
        if (sums.n == 0) {
          if (gap) break;
          gap = true;
          continue;
        }
        if (!explains(line, next, sums)) break;
        gap = false;
        const Interval more = covered(line, next, sums, vertical);
        total = Interval{std::min(total.lo, more.lo), std::max(total.hi, more.hi)};
      }
    }
    return total.hi - total.lo;
  }

  /// Recomputes voxel i's (key k) verdict: its own line when large (a
  /// voxel too sparse for a line fits its column's stack, stack_sums), else
  /// a neighbouring wall voxel's own line that passes through it.
  void refresh(Key k, std::uint32_t i) {
    Voxel& v = voxels_[i];
    v.verdict_made = true;
    v.since_verdict = 0;
    v.wall = v.own = false;
    Line line{};
    const bool stacked = v.line.n < static_cast<std::int64_t>(params_.min_points);
    const LineSums own = stacked ? stack_sums(k) : v.line;
    // Heights from the voxel's own points: a stack's sum heights in five frames.
    if (fit(k, own, line) &&
        extent(line, k, own, false, stacked, static_cast<double>(params_.min_length)) >= params_.min_length &&
        extent(line, k, v.line, true, false, static_cast<double>(params_.min_height)) >= params_.min_height) {
      set_wall(voxels_[i], line, true);
      return;
    }
    borrow(k, i);
  }

  /// Voxel i (key k) takes the own line of a neighbouring wall voxel that
  /// passes through it: above, below, then the 8 horizontal neighbours.
  void borrow(Key k, std::uint32_t i) {
    constexpr std::int32_t kOrder[10][3] = {{0, 0, 1},  {0, 0, -1}, {-1, 0, 0}, {1, 0, 0},  {0, -1, 0},
                                            {0, 1, 0},  {-1, -1, 0}, {1, -1, 0}, {-1, 1, 0}, {1, 1, 0}};
    const double size = static_cast<double>(params_.voxel_size);
    const double centre_x = corner(k.ix) + 0.5 * size, centre_y = corner(k.iy) + 0.5 * size;
    const double reach = 0.7072 * size + static_cast<double>(params_.tolerance);  // half a diagonal
    for (const auto& d : kOrder) {
      const Key n{k.ix + d[0], k.iy + d[1], k.iz + d[2]};
      const std::uint32_t j = voxels_.find_packed(n.packed());
      if (j == CellTable<Voxel>::kNone) continue;
      const Voxel& other = voxels_[j];
      if (!other.wall || !other.own) continue;
      if (std::fabs(other.normal_x * centre_x + other.normal_y * centre_y - other.offset) > reach) continue;
      Line line{other.normal_x, other.normal_y, other.offset, 0.0, 0.0};
      set_wall(voxels_[i], line, false);
      return;
    }
  }

  static void set_wall(Voxel& v, const Line& line, bool own) {
    v.wall = true;
    v.own = own;
    v.normal_x = line.normal_x;
    v.normal_y = line.normal_y;
    v.offset = line.offset;
  }

  Params params_;
  CellTable<Voxel> voxels_;
  double inverse_voxel_ = 2.0;
};

}  // namespace streamclust
