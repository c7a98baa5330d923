// SPDX-License-Identifier: MIT
// The table of sensor facts (<streamclust/sensors.hpp>): its projection bounds,
// the presets and sensor models that read it, and that every ray of the
// simulator's models (and of the real Mid-360 table, when
// ../shared/data/livox is present) falls inside the projection bounds.

#include <doctest/doctest.h>

#include <streamclust/presets.hpp>
#include <streamclust/sensors.hpp>
#include <streamclust/sim/sensors/avia_model.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/sensors/risley_pair_model.hpp>
#include <streamclust/sim/sensors/table_replay.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace sc = streamclust;
namespace fs = std::filesystem;

namespace {

/// <repo>/tests/this_file.cpp -> <repo>/../shared/data/livox/patterns/mid360_u16le.bin,
/// or under $STREAMCLUST_LIVOX_DATA.
fs::path mid360_table() {
  const fs::path root = std::getenv("STREAMCLUST_LIVOX_DATA") != nullptr
                            ? fs::path(std::getenv("STREAMCLUST_LIVOX_DATA"))
                            : fs::path(__FILE__).parent_path() / ".." / ".." / "shared" / "data" / "livox";
  return root / "patterns" / "mid360_u16le.bin";
}

bool have_mid360_table() {
  std::error_code ec;
  return fs::is_regular_file(mid360_table(), ec);
}

/// Fires `seconds` of `sensor` at a 10 m sphere and counts the rays the
/// projection rejects.
template <class Sensor>
std::size_t rays_outside(Sensor sensor, const sc::SphericalProjection::Params& fov, double seconds) {
  const sc::SphericalProjection projection(fov);
  std::size_t outside = 0;
  std::size_t fired = 0;
  for (sc::sim::Ray r = sensor.next(); r.time < seconds; r = sensor.next()) {
    ++fired;
    if (!projection.project(r.direction * 10.0f).accepted()) ++outside;
  }
  REQUIRE(fired > 1000);
  return outside;
}

}  // namespace

TEST_CASE("sensor facts: projection bounds are the FOV widened by the margin, clamped") {
  CHECK(sc::kFieldOfViewMarginDeg == 0.5);
  // All around: the azimuth is the full circle whatever the margin.
  CHECK(sc::livox_mid360.all_around());
  CHECK(sc::livox_mid360.projection_azimuth_min_deg() == -180.0f);
  CHECK(sc::livox_mid360.projection_azimuth_max_deg() == 180.0f);
  CHECK(sc::livox_mid360.projection_elevation_min_deg() == -7.5f);
  CHECK(sc::livox_mid360.projection_elevation_max_deg() == 52.5f);
  CHECK(sc::livox_mid360.vertical_fov_deg() == doctest::Approx(59.0));
  // The Avia: 70.4 x 77.2 deg, centred.
  CHECK_FALSE(sc::livox_avia.all_around());
  CHECK(sc::livox_avia.horizontal_fov_deg == 70.4);
  CHECK(sc::livox_avia.vertical_fov_deg() == doctest::Approx(77.2));
  CHECK(sc::livox_avia.projection_azimuth_min_deg() == doctest::Approx(-35.7));
  CHECK(sc::livox_avia.projection_azimuth_max_deg() == doctest::Approx(35.7));
  CHECK(sc::livox_avia.projection_elevation_min_deg() == doctest::Approx(-39.1));
  CHECK(sc::livox_avia.projection_elevation_max_deg() == doctest::Approx(39.1));
  // No margin: the FOV itself. A huge margin: clamped to the sphere.
  CHECK(sc::livox_mid40.projection_azimuth_max_deg(0.0) == doctest::Approx(19.2));
  CHECK(sc::livox_mid40.projection_azimuth_min_deg(500.0) == -180.0f);
  CHECK(sc::livox_mid40.projection_elevation_max_deg(500.0) == 90.0f);
  // Circular FOVs are as tall as they are wide.
  for (const sc::SensorFacts& s : {sc::livox_mid40, sc::livox_mid70}) {
    CHECK(s.circular_fov);
    CHECK(s.vertical_fov_deg() == doctest::Approx(s.horizontal_fov_deg));
  }
}

TEST_CASE("sensor facts: the presets and the sensor models read the table") {
  const sc::CArcParams mid360 = sc::carc_mid360_params();
  CHECK(mid360.field_of_view.azimuth_min_deg == sc::livox_mid360.projection_azimuth_min_deg());
  CHECK(mid360.field_of_view.elevation_min_deg == sc::livox_mid360.projection_elevation_min_deg());
  CHECK(mid360.field_of_view.elevation_max_deg == sc::livox_mid360.projection_elevation_max_deg());
  const sc::CArcParams avia = sc::carc_avia_params();
  CHECK(avia.field_of_view.azimuth_min_deg == sc::livox_avia.projection_azimuth_min_deg());
  CHECK(avia.field_of_view.azimuth_max_deg == sc::livox_avia.projection_azimuth_max_deg());
  CHECK(avia.field_of_view.elevation_min_deg == sc::livox_avia.projection_elevation_min_deg());
  CHECK(avia.field_of_view.elevation_max_deg == sc::livox_avia.projection_elevation_max_deg());

  CHECK(sc::sim::Mid360Model().point_rate() == sc::livox_mid360.point_rate_hz);
  CHECK(sc::sim::Mid360Model::kLasers == sc::livox_mid360.lasers);
  CHECK(sc::sim::AviaModel().point_rate() == sc::livox_avia.point_rate_hz);
  CHECK(sc::sim::AviaModel::kBeams == sc::livox_avia.lasers);
  CHECK(sc::sim::RisleyPairModel::mid40().point_rate() == sc::livox_mid40.point_rate_hz);
  CHECK(sc::sim::RisleyPairModel::mid70().point_rate() == sc::livox_mid70.point_rate_hz);
}

TEST_CASE("sensor facts: every simulated ray falls inside the sensor's projection bounds") {
  CHECK(rays_outside(sc::sim::Mid360Model(), sc::field_of_view_of(sc::livox_mid360), 0.5) == 0);
  CHECK(rays_outside(sc::sim::AviaModel(), sc::field_of_view_of(sc::livox_avia), 0.5) == 0);
  CHECK(rays_outside(sc::sim::RisleyPairModel::mid40(), sc::field_of_view_of(sc::livox_mid40), 0.5) == 0);
  CHECK(rays_outside(sc::sim::RisleyPairModel::mid70(), sc::field_of_view_of(sc::livox_mid70), 0.5) == 0);
  // Without the margin, the spec FOV alone loses rays of the models at its rim:
  // the margin is needed (and this test can fail).
  sc::SphericalProjection::Params tight = sc::field_of_view_of(sc::livox_avia);
  tight.azimuth_min_deg = -static_cast<float>(sc::livox_avia.horizontal_fov_deg / 2.0 - 1.0);
  tight.azimuth_max_deg = static_cast<float>(sc::livox_avia.horizontal_fov_deg / 2.0 - 1.0);
  CHECK(rays_outside(sc::sim::AviaModel(), tight, 0.5) > 0);
}

TEST_CASE("sensor facts: every ray of the real Mid-360 table falls inside its projection bounds" *
          doctest::skip(!have_mid360_table())) {
  auto table = sc::sim::TableReplay::mid360(mid360_table().string());
  CHECK(table.point_rate() == sc::livox_mid360.point_rate_hz);
  CHECK(rays_outside(table, sc::field_of_view_of(sc::livox_mid360), table.period()) == 0);
}
