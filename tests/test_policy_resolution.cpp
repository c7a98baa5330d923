// SPDX-License-Identifier: MIT
// Unit tests of the resolution policies: the contract of every resolution of
// the Resolutions list (support/policy_lists.hpp), then the fixed grid and
// the adaptive control loop (convergence, constraints, determinism, metrics,
// fallbacks).

#include <doctest/doctest.h>

#include <streamclust/testing/doctest.hpp>
#include <streamclust/testing/resolution_laws.hpp>

#include "support/invalid_argument.hpp"
#include "support/policy_lists.hpp"

#include <streamclust/resolution/adaptive.hpp>
#include <streamclust/resolution/fixed.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using streamclust::AdaptiveResolution;
using streamclust::AdaptiveStop;
using streamclust::AdaptiveStep;
using streamclust::FixedResolution;
using streamclust::GridSize;
using streamclust::Projected;
using streamclust::RejectReason;

namespace {

using streamclust::test::invalid_argument_message;

Projected coord(float u, float v) {
  Projected p;
  p.u = u;
  p.v = v;
  p.range = 5.0f;
  return p;
}

std::vector<Projected> uniform_cloud(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Projected> out;
  for (std::size_t i = 0; i < n; ++i) {
    const float u = unit(rng);
    out.push_back(coord(u, unit(rng)));
  }
  return out;
}

/// Brute force on a dense H x W count matrix: points / occupied cells.
double dense_mean_multiplicity(const std::vector<Projected>& coords, GridSize g) {
  std::vector<std::uint32_t> counts(std::size_t{g.rows} * g.cols, 0);
  const streamclust::GridShape shape{g.rows, g.cols, false};
  std::size_t points = 0;
  for (const Projected& p : coords) {
    if (!p.accepted()) continue;
    ++counts[shape.cell_of(p.u, p.v)];
    ++points;
  }
  const auto occupied = std::count_if(counts.begin(), counts.end(), [](std::uint32_t c) { return c > 0; });
  return static_cast<double>(points) / static_cast<double>(occupied);
}

bool same_trace(const std::vector<AdaptiveStep>& a, const std::vector<AdaptiveStep>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].grid != b[i].grid || a[i].density_v != b[i].density_v || a[i].density_h != b[i].density_h ||
        a[i].gap_v != b[i].gap_v || a[i].gap_h != b[i].gap_h || a[i].mean_multiplicity != b[i].mean_multiplicity)
      return false;
  }
  return true;
}

}  // namespace

// The test kit's resolution laws (<streamclust/testing/resolution_laws.hpp>).
TEST_CASE_TEMPLATE_DEFINE("resolution contract: the test kit's resolution laws hold", R, resolution_contract_id) {
  STREAMCLUST_CHECK_LAW(streamclust::testing::check_resolution<R>());
}

TEST_CASE_TEMPLATE_APPLY(resolution_contract_id, streamclust::test::Resolutions);

TEST_CASE("FixedResolution: returns its grid, never calibrates") {
  FixedResolution res{{48, 700}};
  CHECK_FALSE(res.needs_calibration());
  CHECK(res.grid() == GridSize{48, 700});
  CHECK(res.calibrate(uniform_cloud(100, 1), 2.0f) == GridSize{48, 700});
  CHECK(res.grid() == GridSize{48, 700});
  CHECK(FixedResolution{{}}.grid() == GridSize{64, 1024});
  CHECK(FixedResolution{{1u << 16, 1u << 15}}.grid() == GridSize{1u << 16, 1u << 15});  // exactly 2^31
  CHECK(invalid_argument_message([] { FixedResolution{{0, 10}}; }).find("rows") != std::string::npos);
  CHECK(invalid_argument_message([] { FixedResolution{{10, 0}}; }).find("cols") != std::string::npos);
  CHECK(invalid_argument_message([] { FixedResolution{{1u << 16, 1u << 16}}; }).find("rows x cols") !=
        std::string::npos);
}

TEST_CASE("AdaptiveResolution: metrics on a hand-made occupancy matrix") {
  // H = 4 rows, W = 5 columns; points at cell centres
  const GridSize g{4, 5};
  const auto cell = [&](std::uint32_t row, std::uint32_t col) {
    return coord((static_cast<float>(col) + 0.5f) / 5.0f, (static_cast<float>(row) + 0.5f) / 4.0f);
  };
  std::vector<Projected> coords = {cell(0, 0), cell(0, 4), cell(2, 1), cell(2, 1), cell(2, 1),
                                   cell(3, 1), cell(3, 2), cell(3, 0)};
  Projected rejected = cell(1, 3);
  rejected.reason = RejectReason::outside_fov;  // must be ignored
  coords.push_back(rejected);
  // V = {(0,0), (0,4), (2,1), (3,0), (3,1), (3,2)}: 6 cells, 8 points
  // active rows {0, 2, 3}, active columns {0, 1, 2, 4}
  // row gaps: row 0 -> 3 (cols 1..3), rows 2, 3 -> 0;  column gaps: col 0 -> 2 (rows 1..2), others 0
  const AdaptiveStep s = AdaptiveResolution::measure(coords, g);
  CHECK(s.grid == g);
  CHECK(s.mean_multiplicity == doctest::Approx(8.0 / 6.0));
  CHECK(s.density_v == doctest::Approx(6.0 / (4.0 * 4.0)));
  CHECK(s.density_h == doctest::Approx(6.0 / (5.0 * 3.0)));
  CHECK(s.gap_h == doctest::Approx((3.0 / 5.0) / 3.0));
  CHECK(s.gap_v == doctest::Approx((2.0 / 4.0) / 4.0));
  CHECK(s.mean_multiplicity == doctest::Approx(dense_mean_multiplicity(coords, g)));
  // leading / trailing empty cells of a line are not gaps
  const AdaptiveStep edge = AdaptiveResolution::measure({cell(1, 2), cell(2, 2)}, g);
  CHECK(edge.gap_v == 0.0f);
  CHECK(edge.gap_h == 0.0f);
  CHECK(edge.density_v == doctest::Approx(2.0 / 4.0));
  CHECK(edge.density_h == doctest::Approx(1.0 / 5.0));
  const AdaptiveStep none = AdaptiveResolution::measure({rejected}, g);
  CHECK(none.mean_multiplicity == 0.0f);
}

TEST_CASE("AdaptiveResolution: a uniform cloud converges below T_M within the aspect constraint") {
  const std::vector<Projected> cloud = uniform_cloud(20000, 42);
  for (const float fov_aspect : {1.0f, 2.0f, 6.1f}) {
    CAPTURE(fov_aspect);
    AdaptiveResolution res{{}};
    REQUIRE(res.needs_calibration());
    CHECK(res.grid() == GridSize{32, 256});
    const GridSize g = res.calibrate(cloud, fov_aspect);
    CHECK_FALSE(res.needs_calibration());
    CHECK(res.grid() == g);
    REQUIRE(g.rows >= 1);
    REQUIRE(g.cols >= 1);
    const auto& trace = res.trace();
    REQUIRE(!trace.empty());
    CHECK(trace.size() <= 50);
    CHECK(trace.size() >= 3);  // the initial grid (M_mu ~ 2.7) is too coarse: it must iterate
    CHECK(trace.front().mean_multiplicity > 2.0f);
    // final M_mu (brute force on a dense matrix) is below T_M
    CHECK(dense_mean_multiplicity(cloud, g) <= 2.0);
    // aspect constraint for every measured grid
    for (const AdaptiveStep& s : trace) {
      const double ratio = static_cast<double>(s.grid.cols) / s.grid.rows;
      CHECK(ratio >= fov_aspect / 4.0 - 1e-9);
      CHECK(ratio <= fov_aspect * 4.0 + 1e-9);
    }
    // refinement rule: a step with M_mu > T_M is followed by a grid with more cells
    for (std::size_t i = 0; i + 1 < trace.size(); ++i) {
      if (trace[i].mean_multiplicity > 2.0f) {
        CHECK(std::uint64_t{trace[i + 1].grid.rows} * trace[i + 1].grid.cols >
              std::uint64_t{trace[i].grid.rows} * trace[i].grid.cols);
      }
    }
    // the result is the last measured grid with M_mu <= T_M
    const auto last_ok = std::find_if(trace.rbegin(), trace.rend(),
                                      [](const AdaptiveStep& s) { return s.mean_multiplicity <= 2.0f; });
    REQUIRE(last_ok != trace.rend());
    CHECK(last_ok->grid == g);
    // deterministic: a fresh instance and a second calibrate give the same trace
    AdaptiveResolution again{{}};
    CHECK(again.calibrate(cloud, fov_aspect) == g);
    CHECK(same_trace(again.trace(), trace));
    const std::vector<AdaptiveStep> first = trace;
    CHECK(res.calibrate(cloud, fov_aspect) == g);
    CHECK(same_trace(res.trace(), first));
  }
}

TEST_CASE("AdaptiveResolution: the control loop reacts to the density of the cloud") {
  // ten times more points in the same window -> a finer grid
  AdaptiveResolution sparse{{}};
  AdaptiveResolution dense{{}};
  const GridSize gs = sparse.calibrate(uniform_cloud(5000, 3), 2.0f);
  const GridSize gd = dense.calibrate(uniform_cloud(50000, 3), 2.0f);
  CHECK(std::uint64_t{gd.rows} * gd.cols > 5 * std::uint64_t{gs.rows} * gs.cols);
  // a thin horizontal band (Livox-like vertical concentration) on a narrow grid
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Projected> band;
  for (int i = 0; i < 30000; ++i) {
    const float u = unit(rng);
    band.push_back(coord(u, 0.45f + 0.1f * unit(rng)));
  }
  AdaptiveResolution res{{}};
  const GridSize g = res.calibrate(band, 6.0f);
  CHECK(dense_mean_multiplicity(band, g) <= 2.0);
  const double ratio = static_cast<double>(g.cols) / g.rows;
  CHECK(ratio >= 1.5 - 1e-9);
  CHECK(ratio <= 24.0 + 1e-9);
}

TEST_CASE("AdaptiveResolution: degenerate input and limits") {
  SUBCASE("empty input keeps the initial grid and records nothing") {
    AdaptiveResolution res{{16, 128}};
    CHECK(res.stop_reason() == AdaptiveStop::not_run);
    const GridSize g = res.calibrate({}, 2.0f);
    CHECK(g == GridSize{16, 128});
    CHECK(res.stop_reason() == AdaptiveStop::no_input);
    CHECK(res.grid() == g);
    CHECK(res.trace().empty());
    CHECK_FALSE(res.needs_calibration());
  }
  SUBCASE("only rejected coordinates count as empty") {
    std::vector<Projected> coords = uniform_cloud(100, 1);
    for (Projected& p : coords) p.reason = RejectReason::too_close;
    AdaptiveResolution res{{}};
    CHECK(res.calibrate(coords, 2.0f) == GridSize{32, 256});
    CHECK(res.trace().empty());
  }
  SUBCASE("a previous trace is cleared by an empty calibration") {
    AdaptiveResolution res{{}};
    res.calibrate(uniform_cloud(2000, 2), 2.0f);
    REQUIRE_FALSE(res.trace().empty());
    res.calibrate({}, 2.0f);
    CHECK(res.trace().empty());
    CHECK(res.grid() == GridSize{32, 256});
  }
  SUBCASE("exact duplicates: refinement stops at max_cells, no zero dimension, bounded iterations") {
    const std::vector<Projected> same(1000, coord(0.3f, 0.7f));
    AdaptiveResolution::Params p;
    p.initial_rows = 16;
    p.initial_cols = 128;
    p.max_cells = 4096;
    AdaptiveResolution res{p};
    const GridSize g = res.calibrate(same, 2.0f);
    CHECK(g.rows >= 1);
    CHECK(g.cols >= 1);
    CHECK(std::uint64_t{g.rows} * g.cols <= 4096);
    CHECK(res.trace().size() < 50);  // stopped at a fixed point, not by the iteration limit
    CHECK(res.trace().back().mean_multiplicity == doctest::Approx(1000.0));
  }
  SUBCASE("all points in one direction: refinement is futile, the coarsest grid is kept") {
    // Exact duplicates, and points along one ray with jitter far below any
    // cell: no grid separates them. With the default max_cells (2^24) the
    // loop must not walk up to a gigantic grid.
    for (const float jitter : {0.0f, 1e-7f}) {
      INFO("jitter " << jitter);
      std::vector<Projected> one_direction;
      for (int i = 0; i < 5000; ++i) one_direction.push_back(coord(0.4f + jitter * static_cast<float>(i % 7), 0.6f));
      AdaptiveResolution res{{}};
      const GridSize g = res.calibrate(one_direction, 4.0f);
      CHECK(res.stop_reason() == AdaptiveStop::refinement_futile);
      CHECK(res.trace().size() == 2);  // one refinement that gained nothing
      CHECK(g == res.trace().front().grid);  // the coarsest grid with the lowest M_mu
      CHECK(res.trace().back().mean_multiplicity == doctest::Approx(5000.0));
    }
  }
  SUBCASE("a repetitive pattern stops refining at its duplicate floor") {
    // 400 distinct directions, each fired 3 times (three turns of a spinning
    // sensor): M_mu cannot fall below 3 > T_M = 2.
    std::vector<Projected> turns;
    for (int turn = 0; turn < 3; ++turn)
      for (int i = 0; i < 400; ++i) turns.push_back(coord(0.05f + 0.9f * static_cast<float>(i) / 400.0f, 0.5f + 0.001f * static_cast<float>(i % 5)));
    AdaptiveResolution res{{}};
    const GridSize g = res.calibrate(turns, 4.0f);
    CHECK(res.stop_reason() == AdaptiveStop::refinement_futile);
    const float mu = AdaptiveResolution::measure(turns, g).mean_multiplicity;
    CHECK(mu >= 3.0f);
    CHECK(mu <= 3.0f * 1.05f);
    // Coarsest within 1 % of the best: no measured grid with (nearly) as low
    // a multiplicity has fewer cells.
    for (const AdaptiveStep& s : res.trace()) {
      if (s.mean_multiplicity <= mu) CHECK(std::uint64_t{s.grid.rows} * s.grid.cols >= std::uint64_t{g.rows} * g.cols);
    }
  }
  SUBCASE("a single point") {
    AdaptiveResolution res{{}};
    const GridSize g = res.calibrate({coord(0.5f, 0.5f)}, 2.0f);
    CHECK(g.rows >= 1);
    CHECK(g.cols >= 1);
    CHECK(res.trace().size() <= 50);
    CHECK(res.stop_reason() != AdaptiveStop::iteration_cap);
    CHECK(res.stop_reason() != AdaptiveStop::refinement_futile);
    CHECK(AdaptiveResolution::measure({coord(0.5f, 0.5f)}, g).mean_multiplicity == doctest::Approx(1.0));
  }
  SUBCASE("max_iterations bounds the trace") {
    AdaptiveResolution::Params p;
    p.max_iterations = 2;
    AdaptiveResolution res{p};
    res.calibrate(uniform_cloud(20000, 4), 2.0f);
    CHECK(res.trace().size() == 2);
  }
  SUBCASE("extreme aspect with tiny grids never yields a zero dimension") {
    AdaptiveResolution::Params p;
    p.initial_rows = 1;
    p.initial_cols = 1;
    p.aspect_factor = 1.0f;
    AdaptiveResolution res{p};
    for (const float aspect : {1e-3f, 0.37f, 1.0f, 3.3f, 1e3f}) {
      const GridSize g = res.calibrate(uniform_cloud(500, 5), aspect);
      CHECK(g.rows >= 1);
      CHECK(g.cols >= 1);
    }
  }
  SUBCASE("invalid fov_aspect throws") {
    AdaptiveResolution res{{}};
    CHECK_THROWS_AS(res.calibrate(uniform_cloud(10, 1), 0.0f), std::invalid_argument);
    CHECK_THROWS_AS(res.calibrate(uniform_cloud(10, 1), std::numeric_limits<float>::quiet_NaN()),
                    std::invalid_argument);
  }
}

TEST_CASE("AdaptiveResolution: invalid Params throw std::invalid_argument naming the parameter") {
  using P = AdaptiveResolution::Params;
  const auto msg = [](const P& p) { return invalid_argument_message([&] { AdaptiveResolution{p}; }); };
  CHECK(msg(P{}).empty());
  P p;
  p = P{};
  p.initial_rows = 0;
  CHECK(msg(p).find("initial_rows") != std::string::npos);
  p = P{};
  p.initial_cols = 0;
  CHECK(msg(p).find("initial_cols") != std::string::npos);
  p = P{};
  p.target_gap = 0.0f;
  CHECK(msg(p).find("target_gap") != std::string::npos);
  p = P{};
  p.target_density = 1.5f;
  CHECK(msg(p).find("target_density") != std::string::npos);
  p = P{};
  p.gain_gap = std::numeric_limits<float>::quiet_NaN();
  CHECK(msg(p).find("gain_gap") != std::string::npos);
  p = P{};
  p.gain_density = -0.1f;
  CHECK(msg(p).find("gain_density") != std::string::npos);
  p = P{};
  p.max_multiplicity = 0.5f;
  CHECK(msg(p).find("max_multiplicity") != std::string::npos);
  p = P{};
  p.aspect_factor = 0.5f;
  CHECK(msg(p).find("aspect_factor") != std::string::npos);
  p = P{};
  p.max_iterations = 0;
  CHECK(msg(p).find("max_iterations") != std::string::npos);
  p = P{};
  p.max_cells = 0;
  CHECK(msg(p).find("max_cells") != std::string::npos);
  p = P{};
  p.max_cells = 1000;
  CHECK(msg(p).find("initial_rows x initial_cols") != std::string::npos);
}
