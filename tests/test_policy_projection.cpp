// SPDX-License-Identifier: MIT
// Unit tests of the projection policies: the contract of every projection of
// the Projections list (support/policy_lists.hpp), then each projection's
// round trips, inclusive FOV edges, the azimuth seam, every rejection reason
// and parameter validation.

#include <doctest/doctest.h>

#include <streamclust/testing/doctest.hpp>
#include <streamclust/testing/projection_laws.hpp>

#include "support/constants.hpp"
#include "support/directions.hpp"
#include "support/invalid_argument.hpp"
#include "support/policy_hooks.hpp"
#include "support/policy_lists.hpp"

#include <streamclust/projection/cylindrical.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/sensors.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

using streamclust::CylindricalProjection;
using streamclust::Projected;
using streamclust::RejectReason;
using streamclust::SphericalProjection;

namespace {

using streamclust::test::direction_deg;
using streamclust::test::invalid_argument_message;
using streamclust::test::kDeg;
using streamclust::test::kInf;
using streamclust::test::kNaN;

}  // namespace

// The test kit's projection laws (<streamclust/testing/projection_laws.hpp>)
// at the defaults and 5 random parameter sets (narrower fields of view:
// some points rejected).
TEST_CASE_TEMPLATE_DEFINE("projection contract: the test kit's projection laws hold", P, projection_contract_id) {
  streamclust::testing::ProjectionLawOptions<P> options;
  std::mt19937_64 rng(8);
  options.params.resize(6);
  for (std::size_t k = 1; k < options.params.size(); ++k)
    streamclust::test::RandomParams<P>::draw(options.params[k], rng);
  options.expect_rejections = true;
  STREAMCLUST_CHECK_LAW(streamclust::testing::check_projection<P>(options));
}

TEST_CASE_TEMPLATE_APPLY(projection_contract_id, streamclust::test::Projections);

TEST_CASE("SphericalProjection: project(unproject(u, v, r)) returns (u, v, r)") {
  const SphericalProjection full{{}};
  const SphericalProjection avia{{streamclust::livox_avia.projection_azimuth_min_deg(), streamclust::livox_avia.projection_azimuth_max_deg(), streamclust::livox_avia.projection_elevation_min_deg(), streamclust::livox_avia.projection_elevation_max_deg(), 0.1f}};
  const SphericalProjection behind{{90.0f, 270.0f, -30.0f, 10.0f, 0.5f}};
  for (const SphericalProjection* proj : {&full, &avia, &behind}) {
    const bool wraps = proj->wraps_horizontally();
    for (int i = 0; i <= 20; ++i) {
      for (int j = 0; j <= 20; ++j) {
        for (const float r : {0.6f, 10.0f, 150.0f}) {
          const float u = wraps ? 0.049f * static_cast<float>(i) : 0.05f * static_cast<float>(i);
          // avoid the poles of the full sphere, where azimuth is undefined
          const float v = proj == &full ? 0.02f + 0.048f * static_cast<float>(j) : 0.05f * static_cast<float>(j);
          const Projected p = proj->project(proj->unproject(u, v, r));
          REQUIRE(p.accepted());
          float du = std::fabs(p.u - u);
          if (wraps) du = std::min(du, 1.0f - du);  // u = 0 and u = 1 are the same seam
          CHECK(du < 2e-5f);
          CHECK(std::fabs(p.v - v) < 2e-5f);
          CHECK(std::fabs(p.range - r) < 1e-5f * r);
        }
      }
    }
  }
}

TEST_CASE("SphericalProjection: u, v and range of known directions") {
  const SphericalProjection proj{{}};
  const Projected front = proj.project(Eigen::Vector3f(2.0f, 0.0f, 0.0f));
  REQUIRE(front.accepted());
  CHECK(front.u == doctest::Approx(0.5));
  CHECK(front.v == doctest::Approx(0.5));
  CHECK(front.range == doctest::Approx(2.0));
  const Projected left_up = proj.project(Eigen::Vector3f(0.0f, 3.0f, 3.0f));  // az 90, el 45
  CHECK(left_up.u == doctest::Approx(0.75));
  CHECK(left_up.v == doctest::Approx(0.75));
  CHECK(left_up.range == doctest::Approx(std::sqrt(18.0)));
  CHECK(proj.fov_aspect() == doctest::Approx(2.0));
  CHECK(proj.wraps_horizontally());
  const SphericalProjection narrow{{-35.0f, 35.0f, -10.0f, 10.0f, 0.1f}};
  CHECK_FALSE(narrow.wraps_horizontally());
  CHECK(narrow.fov_aspect() == doctest::Approx(3.5));
}

TEST_CASE("SphericalProjection: FOV bounds are inclusive, just outside is rejected") {
  const SphericalProjection proj{{-45.0f, 45.0f, -10.0f, 20.0f, 0.1f}};
  const auto at = [&](double az, double el) { return proj.project(5.0f * direction_deg(az, el)); };
  const Projected right_edge = at(45.0, 0.0);
  REQUIRE(right_edge.accepted());
  CHECK(right_edge.u == doctest::Approx(1.0));
  const Projected left_edge = at(-45.0, 0.0);
  REQUIRE(left_edge.accepted());
  CHECK(left_edge.u == doctest::Approx(0.0));
  const Projected top = at(0.0, 20.0);
  REQUIRE(top.accepted());
  CHECK(top.v == doctest::Approx(1.0));
  const Projected bottom = at(0.0, -10.0);
  REQUIRE(bottom.accepted());
  CHECK(bottom.v == doctest::Approx(0.0));
  const Projected corner = at(45.0, 20.0);
  REQUIRE(corner.accepted());
  CHECK(corner.u <= 1.0f);
  CHECK(corner.v <= 1.0f);
  // exact diagonal: atan2(1, 1) = 45 deg
  CHECK(proj.project(Eigen::Vector3f(3.0f, 3.0f, 0.0f)).accepted());
  CHECK(proj.project(Eigen::Vector3f(3.0f, -3.0f, 0.0f)).accepted());
  CHECK(at(45.01, 0.0).reason == RejectReason::outside_fov);
  CHECK(at(-45.01, 0.0).reason == RejectReason::outside_fov);
  CHECK(at(0.0, 20.01).reason == RejectReason::outside_fov);
  CHECK(at(0.0, -10.01).reason == RejectReason::outside_fov);
  CHECK(at(180.0, 0.0).reason == RejectReason::outside_fov);
  CHECK(at(0.0, 90.0).reason == RejectReason::outside_fov);
}

TEST_CASE("SphericalProjection: FOV that does not contain azimuth 0 (behind the sensor)") {
  const SphericalProjection proj{{90.0f, 270.0f, -30.0f, 30.0f, 0.1f}};
  CHECK_FALSE(proj.wraps_horizontally());
  const Projected back = proj.project(Eigen::Vector3f(-4.0f, 0.0f, 0.0f));
  REQUIRE(back.accepted());
  CHECK(back.u == doctest::Approx(0.5));
  const Projected back_right = proj.project(Eigen::Vector3f(-4.0f, -4.0f, 0.0f));  // az -135 = 225
  REQUIRE(back_right.accepted());
  CHECK(back_right.u == doctest::Approx(0.75));
  CHECK(proj.project(Eigen::Vector3f(4.0f, 0.0f, 0.0f)).reason == RejectReason::outside_fov);
  CHECK(proj.project(Eigen::Vector3f(4.0f, 1.0f, 0.0f)).reason == RejectReason::outside_fov);
}

TEST_CASE("SphericalProjection: the azimuth seam wraps (az = +180 and -180 deg both give u = 0)") {
  const SphericalProjection proj{{}};
  REQUIRE(proj.wraps_horizontally());
  const Projected plus = proj.project(Eigen::Vector3f(-5.0f, 0.0f, 0.0f));    // atan2(+0, -5) = +pi
  const Projected minus = proj.project(Eigen::Vector3f(-5.0f, -0.0f, 0.0f));  // atan2(-0, -5) = -pi
  REQUIRE(plus.accepted());
  REQUIRE(minus.accepted());
  CHECK(plus.u == 0.0f);
  CHECK(minus.u == 0.0f);
  const streamclust::GridShape shape{16, 360, true};
  const Projected just_above = proj.project(Eigen::Vector3f(-5.0f, 1e-3f, 0.0f));   // az just below +180
  const Projected just_below = proj.project(Eigen::Vector3f(-5.0f, -1e-3f, 0.0f));  // az just above -180
  CHECK(just_above.u > 0.99f);
  CHECK(just_above.u < 1.0f);
  CHECK(just_below.u < 0.01f);
  CHECK(shape.col_of(shape.cell_of(just_above.u, just_above.v)) == 359u);
  CHECK(shape.col_of(shape.cell_of(just_below.u, just_below.v)) == 0u);
  // a wrapping FOV that starts elsewhere folds as well
  const SphericalProjection shifted{{0.0f, 360.0f, -90.0f, 90.0f, 0.1f}};
  REQUIRE(shifted.wraps_horizontally());
  CHECK(shifted.project(Eigen::Vector3f(5.0f, 0.0f, 0.0f)).u == 0.0f);
  CHECK(shifted.project(Eigen::Vector3f(-5.0f, 0.0f, 0.0f)).u == doctest::Approx(0.5));
  CHECK(shifted.project(Eigen::Vector3f(0.0f, -5.0f, 0.0f)).u == doctest::Approx(0.75));
  // u stays in [0, 1) for random directions
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-10.0f, 10.0f);
  for (int i = 0; i < 20000; ++i) {
    const float x = coord(rng);
    const float y = coord(rng);
    const float z = coord(rng);
    const Projected p = proj.project(Eigen::Vector3f(x, y, z));
    if (!p.accepted()) continue;
    CHECK(p.u >= 0.0f);
    CHECK(p.u < 1.0f);
    CHECK(p.v >= 0.0f);
    CHECK(p.v <= 1.0f);
  }
}

TEST_CASE("SphericalProjection: rejection reasons and their order") {
  const SphericalProjection proj{{-45.0f, 45.0f, -10.0f, 20.0f, 0.5f}};
  CHECK(proj.project(Eigen::Vector3f(kNaN, 1.0f, 1.0f)).reason == RejectReason::non_finite);
  CHECK(proj.project(Eigen::Vector3f(1.0f, kNaN, 1.0f)).reason == RejectReason::non_finite);
  CHECK(proj.project(Eigen::Vector3f(1.0f, 1.0f, kNaN)).reason == RejectReason::non_finite);
  CHECK(proj.project(Eigen::Vector3f(kInf, 0.0f, 0.0f)).reason == RejectReason::non_finite);
  CHECK(proj.project(Eigen::Vector3f(0.0f, -kInf, 0.0f)).reason == RejectReason::non_finite);
  CHECK(proj.project(Eigen::Vector3f(0.0f, 0.0f, kNaN)).reason == RejectReason::non_finite);  // before too_close
  CHECK(proj.project(Eigen::Vector3f(0.0f, 0.0f, 0.0f)).reason == RejectReason::too_close);
  CHECK(proj.project(Eigen::Vector3f(0.3f, 0.0f, 0.0f)).reason == RejectReason::too_close);
  CHECK(proj.project(Eigen::Vector3f(-0.3f, 0.0f, 0.0f)).reason == RejectReason::too_close);  // before outside_fov
  CHECK(proj.project(Eigen::Vector3f(0.5f, 0.0f, 0.0f)).accepted());  // range == min_range
  CHECK(proj.project(Eigen::Vector3f(-3.0f, 0.0f, 0.0f)).reason == RejectReason::outside_fov);
  CHECK(proj.project(Eigen::Vector3f(3.0f, 0.0f, 3.0f)).reason == RejectReason::outside_fov);
  CHECK(proj.project(Eigen::Vector3f(3e19f, 0.0f, 0.0f)).reason == RejectReason::non_finite);  // range overflows
  // zero range is rejected even without a minimum range
  const SphericalProjection no_min{{-180.0f, 180.0f, -90.0f, 90.0f, 0.0f}};
  CHECK(no_min.project(Eigen::Vector3f(0.0f, 0.0f, 0.0f)).reason == RejectReason::too_close);
  CHECK(no_min.project(Eigen::Vector3f(-0.0f, 0.0f, -0.0f)).reason == RejectReason::too_close);
  CHECK(no_min.project(Eigen::Vector3f(1e-3f, 0.0f, 0.0f)).accepted());
}

TEST_CASE("SphericalProjection: invalid Params throw std::invalid_argument naming the parameter") {
  using P = SphericalProjection::Params;
  const auto msg = [](const P& p) { return invalid_argument_message([&] { SphericalProjection{p}; }); };
  CHECK(msg(P{}).empty());
  CHECK(msg(P{10.0f, 10.0f, -90.0f, 90.0f, 0.1f}).find("azimuth") != std::string::npos);
  CHECK(msg(P{10.0f, -10.0f, -90.0f, 90.0f, 0.1f}).find("azimuth") != std::string::npos);
  CHECK(msg(P{-180.0f, 181.0f, -90.0f, 90.0f, 0.1f}).find("azimuth") != std::string::npos);
  CHECK(msg(P{kNaN, 180.0f, -90.0f, 90.0f, 0.1f}).find("azimuth_min_deg") != std::string::npos);
  CHECK(msg(P{-180.0f, kInf, -90.0f, 90.0f, 0.1f}).find("azimuth_max_deg") != std::string::npos);
  CHECK(msg(P{-180.0f, 180.0f, -91.0f, 90.0f, 0.1f}).find("elevation_min_deg") != std::string::npos);
  CHECK(msg(P{-180.0f, 180.0f, -90.0f, 90.5f, 0.1f}).find("elevation_max_deg") != std::string::npos);
  CHECK(msg(P{-180.0f, 180.0f, 10.0f, 10.0f, 0.1f}).find("elevation") != std::string::npos);
  CHECK(msg(P{-180.0f, 180.0f, 10.0f, -10.0f, 0.1f}).find("elevation") != std::string::npos);
  CHECK(msg(P{-180.0f, 180.0f, -90.0f, 90.0f, -0.1f}).find("min_range") != std::string::npos);
  CHECK(msg(P{-180.0f, 180.0f, -90.0f, 90.0f, kNaN}).find("min_range") != std::string::npos);
  const std::string m = msg(P{-180.0f, 180.0f, -90.0f, 90.0f, -2.5f});
  CHECK(m.find("-2.5") != std::string::npos);
  CHECK(m.find(">= 0") != std::string::npos);
  // a span of 360 within the tolerance wraps, a clearly smaller one does not
  CHECK(SphericalProjection{P{-180.0f, 180.0005f, -90.0f, 90.0f, 0.1f}}.wraps_horizontally());
  CHECK_FALSE(SphericalProjection{P{-180.0f, 179.9f, -90.0f, 90.0f, 0.1f}}.wraps_horizontally());
}

TEST_CASE("CylindricalProjection: round trip, bounds, rejections, aspect") {
  const CylindricalProjection proj{{-60.0f, 60.0f, -2.0f, 4.0f, 0.5f, 10.0f}};
  CHECK_FALSE(proj.wraps_horizontally());
  const double expected_aspect = (120.0 * kDeg) / (6.0 / 10.0);
  CHECK(proj.fov_aspect() == doctest::Approx(expected_aspect));
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 20; ++j) {
      for (const float hd : {1.0f, 12.0f, 80.0f}) {
        const float u = 0.05f * static_cast<float>(i);
        const float v = 0.05f * static_cast<float>(j);
        const Eigen::Vector3f pt = proj.unproject(u, v, hd);
        const Projected p = proj.project(pt);
        REQUIRE(p.accepted());
        CHECK(std::fabs(p.u - u) < 2e-5f);
        CHECK(std::fabs(p.v - v) < 2e-5f);
        CHECK(p.range == doctest::Approx(pt.norm()));
        CHECK(std::hypot(pt.x(), pt.y()) == doctest::Approx(hd));
      }
    }
  }
  CHECK(proj.project(Eigen::Vector3f(5.0f, 0.0f, 4.0f)).accepted());  // z == z_max
  CHECK(proj.project(Eigen::Vector3f(5.0f, 0.0f, 4.0f)).v == doctest::Approx(1.0));
  CHECK(proj.project(Eigen::Vector3f(5.0f, 0.0f, -2.0f)).v == doctest::Approx(0.0));
  CHECK(proj.project(Eigen::Vector3f(5.0f, 0.0f, 4.01f)).reason == RejectReason::outside_fov);
  CHECK(proj.project(Eigen::Vector3f(5.0f, 0.0f, -2.01f)).reason == RejectReason::outside_fov);
  CHECK(proj.project(5.0f * direction_deg(60.0, 0.0)).accepted());
  CHECK(proj.project(5.0f * direction_deg(-60.0, 0.0)).accepted());
  CHECK(proj.project(5.0f * direction_deg(60.02, 0.0)).reason == RejectReason::outside_fov);
  // NaN, inf and the origin: the projection contract above
  // 3D range, not horizontal distance: (0.3, 0, 0.3) has range 0.42 < 0.5
  CHECK(proj.project(Eigen::Vector3f(0.3f, 0.0f, 0.3f)).reason == RejectReason::too_close);
  CHECK(proj.project(Eigen::Vector3f(0.3f, 0.0f, 0.45f)).accepted());
  const CylindricalProjection full{{}};
  REQUIRE(full.wraps_horizontally());
  CHECK(full.project(Eigen::Vector3f(-5.0f, 0.0f, 0.0f)).u == 0.0f);
  CHECK(full.project(Eigen::Vector3f(-5.0f, -0.0f, 0.0f)).u == 0.0f);
  CHECK(full.project(Eigen::Vector3f(0.0f, 0.0f, 2.0f)).accepted());  // straight up, inside the band
  const CylindricalProjection no_min{{-180.0f, 180.0f, -3.0f, 3.0f, 0.0f, 10.0f}};
  CHECK(no_min.project(Eigen::Vector3f(0.0f, 0.0f, 0.0f)).reason == RejectReason::too_close);
}

TEST_CASE("CylindricalProjection: invalid Params throw std::invalid_argument naming the parameter") {
  using P = CylindricalProjection::Params;
  const auto msg = [](const P& p) { return invalid_argument_message([&] { CylindricalProjection{p}; }); };
  CHECK(msg(P{}).empty());
  CHECK(msg(P{0.0f, 0.0f, -3.0f, 3.0f, 0.1f, 10.0f}).find("azimuth") != std::string::npos);
  CHECK(msg(P{-180.0f, 180.0f, 3.0f, 3.0f, 0.1f, 10.0f}).find("z_max") != std::string::npos);
  CHECK(msg(P{-180.0f, 180.0f, kNaN, 3.0f, 0.1f, 10.0f}).find("z_min") != std::string::npos);
  CHECK(msg(P{-180.0f, 180.0f, -3.0f, 3.0f, -1.0f, 10.0f}).find("min_range") != std::string::npos);
  CHECK(msg(P{-180.0f, 180.0f, -3.0f, 3.0f, 0.1f, 0.0f}).find("reference_range") != std::string::npos);
  CHECK(msg(P{-180.0f, 180.0f, -3.0f, 3.0f, 0.1f, kInf}).find("reference_range") != std::string::npos);
}

TEST_CASE("the projections' polynomial atan2 stays within 3.5e-7 rad of the exact angle, zeros and seam included") {
  // Angles over the whole circle, at magnitudes from 1e-6 to 1e6 and with
  // tiny components (near the axes, near the seam at +-180 degrees).
  double worst = 0.0;
  for (int k = 0; k < 200000; ++k) {
    const double angle = -3.14159265358979 + 6.28318530717958 * (k + 0.5) / 200000.0;
    for (const double scale : {1e-6, 1.0, 37.0, 1e6}) {
      const auto x = static_cast<float>(scale * std::cos(angle));
      const auto y = static_cast<float>(scale * std::sin(angle));
      const double exact = std::atan2(static_cast<double>(y), static_cast<double>(x));
      worst = std::max(worst, std::fabs(static_cast<double>(streamclust::detail::fast_atan2(y, x)) - exact));
    }
  }
  for (const float tiny : {1e-30f, 1e-8f, 1e-3f}) {
    for (const float big : {-5.0f, 5.0f}) {
      for (const float sign : {-1.0f, 1.0f}) {
        const float y = sign * tiny;
        worst = std::max(worst, std::fabs(static_cast<double>(streamclust::detail::fast_atan2(y, big)) -
                                          std::atan2(static_cast<double>(y), static_cast<double>(big))));
        worst = std::max(worst, std::fabs(static_cast<double>(streamclust::detail::fast_atan2(big, y)) -
                                          std::atan2(static_cast<double>(big), static_cast<double>(y))));
      }
    }
  }
  CHECK(worst < 3.5e-7);
  // Signed zeros as std::atan2: the seam's two sides, the axes, the origin.
  CHECK(streamclust::detail::fast_atan2(0.0f, -1.0f) == std::atan2(0.0f, -1.0f));
  CHECK(streamclust::detail::fast_atan2(-0.0f, -1.0f) == std::atan2(-0.0f, -1.0f));
  CHECK(std::signbit(streamclust::detail::fast_atan2(-0.0f, 1.0f)));
  CHECK(streamclust::detail::fast_atan2(0.0f, 1.0f) == 0.0f);
  CHECK(streamclust::detail::fast_atan2(1.0f, 0.0f) == doctest::Approx(1.5707963267948966));
  CHECK(streamclust::detail::fast_atan2(0.0f, 0.0f) == std::atan2(0.0f, 0.0f));
  CHECK(std::isnan(streamclust::detail::fast_atan2(std::nanf(""), 1.0f)));
  CHECK(std::isnan(streamclust::detail::fast_atan2(1.0f, std::nanf(""))));
}
