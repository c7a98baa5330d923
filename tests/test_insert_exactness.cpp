// SPDX-License-Identifier: MIT
// The insertion fast paths (docs/design-decisions.md: link_many, compact points)
// against their reference formulations: the branch-free AngularLinkage, on
// Samples and on its compact payload, against the original branchy code, bit
// for bit (the reference below is that code, kept on purpose); the
// EuclideanLinkage payload against the distance on Samples; and the
// division-free mask iteration against the definition of the mask, cell for
// cell and in order.

#include <doctest/doctest.h>

#include <streamclust/detail/mask.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/combinators.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/types.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace {

using streamclust::AngularLinkage;
using streamclust::Sample;

/// The AngularLinkage decision as first written (branch on the canonical
/// order, then the same float operations): the reference the optimised
/// operator() must equal on every input.
struct ReferenceAngular {
  float sin_theta, cos_theta, sin_min, cos_min;

  explicit ReferenceAngular(const AngularLinkage::Params& params) {
    constexpr double deg = 3.14159265358979323846 / 180.0;
    sin_theta = static_cast<float>(std::sin(static_cast<double>(params.theta_deg) * deg));
    cos_theta = static_cast<float>(std::cos(static_cast<double>(params.theta_deg) * deg));
    sin_min = static_cast<float>(std::sin(static_cast<double>(params.min_ray_angle_deg) * deg));
    cos_min = static_cast<float>(std::cos(static_cast<double>(params.min_ray_angle_deg) * deg));
  }
  // Equal ranges are ordered by direction alone since the compact payload
  // (the payload holds no position). Without
  // FMA contraction the order of tied operands does not change the result.
  static bool precedes(const Sample& a, const Sample& b) {
    if (a.range != b.range) return a.range > b.range;
    for (int i = 0; i < 3; ++i)
      if (a.direction[i] != b.direction[i]) return a.direction[i] > b.direction[i];
    return true;
  }
  static float cross_norm(const Eigen::Vector3f& u, const Eigen::Vector3f& v) {
    const float x = u.y() * v.z() - u.z() * v.y();
    const float y = u.z() * v.x() - u.x() * v.z();
    const float z = u.x() * v.y() - u.y() * v.x();
    return std::sqrt(x * x + y * y + z * z);
  }
  bool operator()(const Sample& a, const Sample& b) const {
    const bool a_first = precedes(a, b);
    const Sample& p = a_first ? a : b;
    const Sample& q = a_first ? b : a;
    const float d1 = p.range;
    const float d2 = q.range;
    float cos_a = p.direction.dot(q.direction);
    float sin_a = cross_norm(p.direction, q.direction);
    if (sin_a < sin_min && cos_a > 0.0f) {
      sin_a = sin_min;
      cos_a = cos_min;
    }
    return d2 * sin_a * cos_theta > (d1 - d2 * cos_a) * sin_theta;
  }
};

Sample sample_at(const Eigen::Vector3f& p) {
  return streamclust::make_sample(p, p.norm(), 0.0f, 0.0);
}

}  // namespace

TEST_CASE("AngularLinkage: the branch-free canonical order decides exactly as the reference, both orders, "
          "on Samples and on payloads") {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<float> coord(-20.0f, 20.0f);
  std::uniform_real_distribution<float> jitter(-0.05f, 0.05f);
  std::uniform_int_distribution<int> kind(0, 6);
  const AngularLinkage::Params settings[] = {{10.0f, 0.2f}, {30.0f, 0.2f}, {80.0f, 0.0f}, {45.0f, 5.0f}, {1.0f, 0.0f}};
  std::size_t linked = 0;
  std::size_t ties = 0;
  std::size_t pairs = 0;
  for (const auto& params : settings) {
    const AngularLinkage fast{params};
    const ReferenceAngular reference{params};
    for (int i = 0; i < 40000; ++i) {
      const Eigen::Vector3f pa(coord(rng), coord(rng), coord(rng));
      Sample a = sample_at(pa);
      Sample b;
      switch (kind(rng)) {
        case 0:  // unrelated
          b = sample_at(Eigen::Vector3f(coord(rng), coord(rng), coord(rng)));
          break;
        case 1:  // a close neighbour (the common case in the engine)
          b = sample_at(pa + Eigen::Vector3f(jitter(rng), jitter(rng), jitter(rng)));
          break;
        case 2:  // equal ranges, positions differ: the tie is broken by direction
          b = sample_at(Eigen::Vector3f(pa.y(), pa.x(), pa.z()));
          b.range = a.range;
          ++ties;
          break;
        case 3:  // equal range and position, direction differs in one coordinate
          b = a;
          b.direction[static_cast<int>(rng() % 3u)] += 1e-3f;
          ++ties;
          break;
        case 4:  // identical samples
          b = a;
          ++ties;
          break;
        case 5:  // on an axis: the same ray with +0 and -0 components, equal or noisy range
          a = sample_at(Eigen::Vector3f(pa.x(), 0.0f, 0.0f));
          b = sample_at(Eigen::Vector3f(pa.x() * (1.0f + jitter(rng) * 0.01f * static_cast<float>(rng() % 2u)), -0.0f,
                                        -0.0f));
          ties += a.range == b.range ? 1u : 0u;
          break;
        default:  // near-coincident rays (the floor on alpha), range differs by noise
          b = sample_at(pa * (1.0f + jitter(rng) * 0.01f));
          break;
      }
      const bool ab = fast(a, b);
      const bool ba = fast(b, a);
      REQUIRE(ab == reference(a, b));
      REQUIRE(ba == reference(b, a));
      // the engine's path: the same decisions on the compact payloads
      const AngularLinkage::Payload qa = AngularLinkage::make_payload(a);
      const AngularLinkage::Payload qb = AngularLinkage::make_payload(b);
      REQUIRE(fast(qa, qb) == ab);
      REQUIRE(fast(qb, qa) == ba);
      linked += ab ? 1u : 0u;
      ++pairs;
    }
  }
  // the sample exercised both outcomes and the tie paths
  CHECK(linked > pairs / 10);
  CHECK(linked < pairs - pairs / 10);
  CHECK(ties > pairs / 3);
}

TEST_CASE("EuclideanLinkage and the combinators: the payload decides exactly as the Samples, both orders") {
  using streamclust::AllOf;
  using streamclust::AnyOf;
  using streamclust::EuclideanLinkage;
  std::mt19937 rng(77);
  std::uniform_real_distribution<float> coord(-20.0f, 20.0f);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::size_t linked = 0;
  std::size_t pairs = 0;
  for (const float d : {0.05f, 0.3f, 1.0f}) {
    const EuclideanLinkage link{{d}};
    const AllOf<AngularLinkage, AngularLinkage> band{{{5.0f, 0.2f}, {40.0f, 0.0f}}};
    const AnyOf<EuclideanLinkage, EuclideanLinkage> either{{{d}, {2.0f * d}}};
    for (int i = 0; i < 40000; ++i) {
      const Eigen::Vector3f pa(coord(rng), coord(rng), coord(rng));
      const Sample a = sample_at(pa);
      Sample b;
      switch (i % 4) {
        case 0:  // identical
          b = a;
          break;
        case 1:  // at about the threshold distance: rounding decides
          b = sample_at(pa + Eigen::Vector3f(unit(rng), unit(rng), unit(rng)).normalized() * d);
          break;
        case 2:  // within a few thresholds
          b = sample_at(pa + 3.0f * d * Eigen::Vector3f(unit(rng), unit(rng), unit(rng)));
          break;
        default:  // equal ranges, other ray
          b = sample_at(Eigen::Vector3f(pa.y(), pa.x(), pa.z()));
          b.range = a.range;
          break;
      }
      // the reference: the criterion on the Samples' Eigen positions
      const bool expected = (a.position - b.position).squaredNorm() <= d * d;
      const EuclideanLinkage::Payload qa = EuclideanLinkage::make_payload(a);
      const EuclideanLinkage::Payload qb = EuclideanLinkage::make_payload(b);
      REQUIRE(link(a, b) == expected);
      REQUIRE(link(qa, qb) == expected);
      REQUIRE(link(qb, qa) == link(b, a));
      // combinators of one payload type: payload == children on the Samples
      const AngularLinkage::Payload ra = AngularLinkage::make_payload(a);
      const AngularLinkage::Payload rb = AngularLinkage::make_payload(b);
      REQUIRE(band(ra, rb) == (band.child<0>()(a, b) && band.child<1>()(a, b)));
      REQUIRE(band(b, a) == band(rb, ra));
      REQUIRE(either(qa, qb) == (either.child<0>()(a, b) || either.child<1>()(a, b)));
      REQUIRE(either(b, a) == either(qb, qa));
      linked += expected ? 1u : 0u;
      ++pairs;
    }
  }
  CHECK(linked > pairs / 10);
  CHECK(linked < pairs - pairs / 10);
}

TEST_CASE("for_each_mask_cell visits exactly the mask's cells, each once, in row-major order from col - half") {
  using streamclust::CellIndex;
  using streamclust::GridShape;
  // The definition, cell by cell: rows within `half` (clamped), then the
  // columns col - half .. col + half left to right, wrapped or clamped; a
  // wrapped mask as wide as the grid is every column once, from column 0.
  auto reference = [](const GridShape& grid, CellIndex center, int half) {
    std::vector<CellIndex> out;
    const int row = static_cast<int>(grid.row_of(center));
    const int col = static_cast<int>(grid.col_of(center));
    const int cols = static_cast<int>(grid.cols);
    for (int r = 0; r < static_cast<int>(grid.rows); ++r) {
      if (r < row - half || r > row + half) continue;
      const auto at = [&](int c) { out.push_back(static_cast<CellIndex>(r * cols + c)); };
      if (grid.wrap_columns && 2 * half + 1 >= cols) {
        for (int c = 0; c < cols; ++c) at(c);
        continue;
      }
      for (int k = -half; k <= half; ++k) {
        int c = col + k;
        if (grid.wrap_columns) {
          c = (c + cols) % cols;
        } else if (c < 0 || c >= cols) {
          continue;
        }
        at(c);
      }
    }
    return out;
  };
  std::size_t checked = 0;
  for (const bool wrap : {true, false}) {
    for (std::uint32_t rows : {1u, 2u, 5u, 9u}) {
      for (std::uint32_t cols : {1u, 2u, 3u, 4u, 5u, 7u, 12u}) {
        const GridShape grid{rows, cols, wrap};
        for (int half : {0, 1, 2, 3, 6}) {
          for (CellIndex c = 0; c < grid.cell_count(); ++c) {
            std::vector<CellIndex> got;
            streamclust::detail::for_each_mask_cell(grid, c, half, [&](CellIndex m) { got.push_back(m); });
            REQUIRE(got == reference(grid, c, half));
            ++checked;
          }
        }
      }
    }
  }
  CHECK(checked > 1000);
}
