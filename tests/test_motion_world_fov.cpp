// SPDX-License-Identifier: MIT
// The projection bounds in world orientation (world_field_of_view) and the
// run-time forwarders RuntimeMotion and RuntimeGround.

#include <doctest/doctest.h>

#include <streamclust/ground/height_map_ground.hpp>
#include <streamclust/ground/runtime_ground.hpp>
#include <streamclust/motion/no_motion.hpp>
#include <streamclust/motion/posed_motion.hpp>
#include <streamclust/motion/runtime_motion.hpp>
#include <streamclust/motion/world_field_of_view.hpp>
#include <streamclust/presets.hpp>

#include "support/constants.hpp"

#include <cmath>
#include <random>
#include <vector>

namespace sc = streamclust;

namespace {

using streamclust::test::kDeg;

/// Random directions of `fov` (sensor frame), turned by a random one of
/// `rotations`, must all be accepted by a projection with `world` bounds.
void check_all_inside(const sc::SphericalProjection::Params& fov, const std::vector<Eigen::Quaterniond>& rotations,
                      const sc::SphericalProjection::Params& world) {
  const sc::SphericalProjection projection(world);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    const double az = (fov.azimuth_min_deg + u(rng) * (fov.azimuth_max_deg - fov.azimuth_min_deg)) * kDeg;
    const double el = (fov.elevation_min_deg + u(rng) * (fov.elevation_max_deg - fov.elevation_min_deg)) * kDeg;
    const Eigen::Vector3d d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    const Eigen::Quaterniond& q = rotations[static_cast<std::size_t>(rng() % rotations.size())];
    const Eigen::Vector3f ray = (5.0 * (q * d)).cast<float>();
    const sc::Projected p = projection.project(ray);
    INFO("direction " << i << " az " << az / kDeg << " el " << el / kDeg);
    REQUIRE(p.accepted());
  }
}

}  // namespace

TEST_CASE("world_field_of_view: a level sensor keeps its bounds, widened by the margin") {
  const auto mid360 = sc::field_of_view_of(sc::livox_mid360);
  const auto w = sc::world_field_of_view(mid360, {Eigen::Quaterniond::Identity()});
  CHECK(w.elevation_min_deg == doctest::Approx(mid360.elevation_min_deg - 1.0f).epsilon(0.002));
  CHECK(w.elevation_max_deg == doctest::Approx(mid360.elevation_max_deg + 1.0f).epsilon(0.002));
  CHECK(w.azimuth_max_deg - w.azimuth_min_deg == doctest::Approx(360.0f));
  const auto avia = sc::field_of_view_of(sc::livox_avia);
  const auto a = sc::world_field_of_view(avia, {Eigen::Quaterniond::Identity()});
  CHECK(a.azimuth_min_deg == doctest::Approx(avia.azimuth_min_deg - 1.0f).epsilon(0.02));
  CHECK(a.azimuth_max_deg == doctest::Approx(avia.azimuth_max_deg + 1.0f).epsilon(0.02));
}

TEST_CASE("world_field_of_view: tilted, upside-down and turning sensors see inside their bounds") {
  const auto mid360 = sc::field_of_view_of(sc::livox_mid360);
  const auto avia = sc::field_of_view_of(sc::livox_avia);
  SUBCASE("Mid-360 upside down: elevation mirrored") {
    const std::vector<Eigen::Quaterniond> r{sc::mount_from_roll_pitch_yaw_deg(180.0, 0.0, 0.0).rotation};
    const auto w = sc::world_field_of_view(mid360, r);
    CHECK(w.elevation_min_deg == doctest::Approx(-mid360.elevation_max_deg - 1.0f).epsilon(0.01));
    CHECK(w.elevation_max_deg == doctest::Approx(-mid360.elevation_min_deg + 1.0f).epsilon(0.01));
    check_all_inside(mid360, r, w);
  }
  SUBCASE("Avia pitched 30 degrees down") {
    const std::vector<Eigen::Quaterniond> r{sc::mount_from_roll_pitch_yaw_deg(0.0, 30.0, 0.0).rotation};
    const auto w = sc::world_field_of_view(avia, r);
    CHECK(w.elevation_min_deg < avia.elevation_min_deg - 25.0f);
    CHECK(w.azimuth_max_deg - w.azimuth_min_deg < 180.0f);
    check_all_inside(avia, r, w);
  }
  SUBCASE("Avia turning through 120 degrees of yaw") {
    std::vector<Eigen::Quaterniond> r;
    for (int k = 0; k <= 1000; ++k) r.push_back(sc::mount_from_roll_pitch_yaw_deg(0.0, 0.0, 0.12 * k).rotation);
    const auto w = sc::world_field_of_view(avia, r);
    CHECK(w.azimuth_max_deg - w.azimuth_min_deg > 190.0f);
    CHECK(w.azimuth_max_deg - w.azimuth_min_deg < 200.0f);
    check_all_inside(avia, r, w);
  }
  SUBCASE("Mid-360 rolled 10 and pitched 20 degrees") {
    const std::vector<Eigen::Quaterniond> r{sc::mount_from_roll_pitch_yaw_deg(10.0, 20.0, 0.0).rotation};
    check_all_inside(mid360, r, sc::world_field_of_view(mid360, r));
  }
}

TEST_CASE("RuntimeMotion forwards to PosedMotion, or leaves points in the sensor frame") {
  sc::RuntimeMotion::Params off;
  sc::RuntimeMotion none(off);
  CHECK_FALSE(none.enabled());
  sc::RuntimeMotion::Params on;
  on.enabled = true;
  on.posed.mount = sc::mount_from_roll_pitch_yaw_deg(180.0, 0.0, 0.0);
  sc::RuntimeMotion flipped(on);
  sc::PosedMotion reference(on.posed);
  sc::NoMotion identity;
  const Eigen::Vector3f p(3.0f, -1.0f, 0.5f);
  sc::PlacedPoint a, b;
  REQUIRE(none.place(p, 0.1, a) == sc::RejectReason::accepted);
  REQUIRE(identity.place(p, 0.1, b) == sc::RejectReason::accepted);
  CHECK(a.world == b.world);
  CHECK(a.ray == b.ray);
  REQUIRE(flipped.place(p, 0.1, a) == sc::RejectReason::accepted);
  REQUIRE(reference.place(p, 0.1, b) == sc::RejectReason::accepted);
  CHECK(a.world == b.world);
  CHECK(a.world.z() == doctest::Approx(-0.5f));
}

TEST_CASE("RuntimeGround forwards to HeightMapGround, or classes every point as an object") {
  sc::RuntimeGround off(sc::RuntimeGround::Params{});
  sc::RuntimeGround::Params params;
  params.use_height_map = true;
  sc::RuntimeGround on(params);
  sc::HeightMapGround reference(params.height_map);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  int ground = 0;
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector3f w(u(rng), u(rng), i % 3 == 0 ? 0.3f * u(rng) : -1.0f);
    CHECK(off.classify(w, w) == sc::SurfaceClass::object);
    const sc::SurfaceClass c = on.classify(w, w);
    REQUIRE(c == reference.classify(w, w));
    ground += c == sc::SurfaceClass::ground;
  }
  CHECK(ground > 1000);
  CHECK(on.heap_bytes() > 0);
  CHECK(off.heap_bytes() == 0);
}
