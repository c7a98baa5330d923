// SPDX-License-Identifier: MIT
// Sensor models of the scan simulator: the contract (unit directions,
// non-decreasing time, point rate, determinism, parameter checks), each
// model's field of view and TableReplay's file handling. The agreement of
// the analytic Livox models with the real tables is test_sim_sensor_tables.cpp.

#include <doctest/doctest.h>

#include <streamclust/sensors.hpp>
#include <streamclust/sim/sensors/avia_model.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/sensors/pattern_stats.hpp>
#include <streamclust/sim/sensors/risley_pair_model.hpp>
#include <streamclust/sim/sensors/spinning_model.hpp>
#include <streamclust/sim/sensors/table_replay.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/sensor_checks.hpp"
#include "support/temp_dir.hpp"

namespace sim = streamclust::sim;
namespace fs = std::filesystem;

namespace {

using streamclust::test::azimuth_full_every_100ms;

/// Unit directions, non-decreasing time, exactly point_rate firings in 1 s.
template <class Sensor>
void check_contract(Sensor& s, double expected_rate) {
  CHECK(s.point_rate() == doctest::Approx(expected_rate));
  sim::Ray r = s.next();
  const double t0 = r.time;
  double prev = t0;
  std::size_t count = 0;
  std::size_t bad_norm = 0;
  std::size_t bad_time = 0;
  while (r.time - t0 < 1.0) {
    ++count;
    if (std::fabs(r.direction.norm() - 1.0f) > 1e-5f) ++bad_norm;
    if (r.time < prev) ++bad_time;
    prev = r.time;
    r = s.next();
  }
  CHECK(bad_norm == 0);
  CHECK(bad_time == 0);
  CHECK(static_cast<double>(count) == doctest::Approx(expected_rate).epsilon(1e-5));
}

/// The first n rays of two fresh instances are identical.
template <class Make>
void check_deterministic(Make make, int n = 5000) {
  auto a = make();
  auto b = make();
  int differ = 0;
  for (int i = 0; i < n; ++i) {
    const sim::Ray x = a.next();
    const sim::Ray y = b.next();
    if (x.direction != y.direction || x.time != y.time || x.laser != y.laser) ++differ;
  }
  CHECK(differ == 0);
}

/// Runs f, which must throw E with a message containing `needle`.
template <class E, class F>
void check_throws_naming(F f, const std::string& needle) {
  bool thrown = false;
  try {
    f();
  } catch (const E& e) {
    thrown = true;
    INFO(e.what());
    CHECK(std::string(e.what()).find(needle) != std::string::npos);
  }
  CHECK_MESSAGE(thrown, "expected an exception naming " << needle);
}

/// A file in this process's own temp directory (the C++17 and C++20 builds
/// of this test run side by side), removed at exit.
fs::path temp_file(const char* name, const std::vector<unsigned char>& bytes) {
  static const streamclust::test::TempDir dir("sim_sensors", "files");
  const fs::path p = dir.dir / name;
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return p;
}

}  // namespace

TEST_CASE("sensor models: unit directions, non-decreasing time, point rate over 1 s") {
  SUBCASE("Mid-360") {
    sim::Mid360Model m;
    check_contract(m, streamclust::livox_mid360.point_rate_hz);
  }
  SUBCASE("Mid-40") {
    auto m = sim::RisleyPairModel::mid40();
    check_contract(m, streamclust::livox_mid40.point_rate_hz);
  }
  SUBCASE("Mid-70") {
    auto m = sim::RisleyPairModel::mid70();
    check_contract(m, streamclust::livox_mid70.point_rate_hz);
  }
  SUBCASE("Mid-70, pure tangent-plane profile") {
    sim::RisleyPairModel::Params p = sim::RisleyPairModel::mid70().params();
    p.radial_poly = {{0.0, 0.0, 0.0, 0.0}};
    sim::RisleyPairModel m(p);
    check_contract(m, streamclust::livox_mid70.point_rate_hz);
  }
  SUBCASE("Avia") {
    sim::AviaModel m;
    check_contract(m, streamclust::livox_avia.point_rate_hz);
  }
  SUBCASE("spinning 32 x 1800 x 10 Hz") {
    sim::SpinningModel m;
    check_contract(m, 576000.0);
  }
  SUBCASE("start_time shifts the stream") {
    sim::Mid360Model::Params p;
    p.start_time = 2.5;
    sim::Mid360Model m(p);
    CHECK(m.next().time == 2.5);
    check_contract(m, streamclust::livox_mid360.point_rate_hz);
  }
}

TEST_CASE("sensor models: deterministic") {
  check_deterministic([] { return sim::Mid360Model{}; });
  check_deterministic([] { return sim::RisleyPairModel::mid40(); });
  check_deterministic([] { return sim::RisleyPairModel::mid70(); });
  check_deterministic([] { return sim::AviaModel{}; });
  check_deterministic([] { return sim::SpinningModel{}; });
}

TEST_CASE("sensor models: lasers interleave in firing order") {
  sim::Mid360Model mid;
  sim::AviaModel avia;
  sim::SpinningModel spin;
  for (int i = 0; i < 64; ++i) {
    CHECK(mid.next().laser == i % 4);
    CHECK(avia.next().laser == i % 6);
    CHECK(spin.next().laser == i % 32);
  }
}

TEST_CASE("Mid-360 model: full azimuth every 0.1 s, elevation about -7 .. 52 deg") {
  sim::Mid360Model m;
  const std::vector<sim::Ray> rays = sim::collect(m, 0.5);
  CHECK(azimuth_full_every_100ms(rays));
  double lo = 90.0;
  double hi = -90.0;
  for (const sim::Ray& r : rays) {
    lo = std::min(lo, sim::elevation_deg(r.direction));
    hi = std::max(hi, sim::elevation_deg(r.direction));
  }
  CHECK(std::fabs(lo - -7.2) < 1.0);
  CHECK(std::fabs(hi - 52.2) < 1.0);
}

TEST_CASE("Mid-40 / Mid-70 models: circular FOV of 38.4 / 70.4 deg") {
  for (int k = 0; k < 2; ++k) {
    auto m = k == 0 ? sim::RisleyPairModel::mid40() : sim::RisleyPairModel::mid70();
    const double half = (k == 0 ? streamclust::livox_mid40 : streamclust::livox_mid70).horizontal_fov_deg / 2.0;
    const std::vector<sim::Ray> rays = sim::collect(m, 0.5);
    double off = 0.0;
    for (const sim::Ray& r : rays) off = std::max(off, sim::off_axis_deg(r.direction));
    INFO("half FOV " << half << ", reached " << off);
    CHECK(off <= half + 0.1);
    CHECK(off >= half - 0.5);
    // The circle is filled in every direction: all 36 10-degree sectors reach 95 % of the radius.
    std::vector<double> reach(36, 0.0);
    for (const sim::Ray& r : rays) {
      const double psi = std::atan2(static_cast<double>(r.direction.z()), static_cast<double>(r.direction.y())) * 180.0 / 3.14159265358979323846 + 180.0;
      auto& v = reach[static_cast<std::size_t>(std::min(35.0, psi / 10.0))];
      v = std::max(v, sim::off_axis_deg(r.direction));
    }
    for (double v : reach) CHECK(v >= 0.95 * half);
  }
}

TEST_CASE("Avia model: within 70.4 x 77.2 deg, dense centre") {
  sim::AviaModel m;
  const std::vector<sim::Ray> rays = sim::collect(m, 0.5);
  double az = 0.0;
  double el = 0.0;
  for (const sim::Ray& r : rays) {
    az = std::max(az, std::fabs(sim::azimuth_deg(r.direction)));
    el = std::max(el, std::fabs(sim::elevation_deg(r.direction)));
  }
  INFO("reached |azimuth| " << az << ", |elevation| " << el);
  CHECK(az <= streamclust::livox_avia.horizontal_fov_deg / 2.0 + 0.1);
  CHECK(az >= 34.5);
  CHECK(el <= streamclust::livox_avia.vertical_fov_max_deg + 0.1);
  CHECK(el >= 37.5);
  const sim::DensityContrast d =
      sim::density_contrast(rays, {sim::AngularCoordinate::off_axis, 0.0, 11.0}, {{sim::AngularCoordinate::off_axis, 28.0, 34.0}});
  MESSAGE("Avia centre / periphery density ratio " << d.ratio);
  CHECK(d.ratio > 2.0);
}

TEST_CASE("spinning model: beams spread over the vertical FOV, same directions every turn") {
  sim::SpinningModel m;
  const std::vector<sim::Ray> turn = sim::collect(m, 0.1);
  REQUIRE(turn.size() == 57600);
  CHECK(sim::elevation_deg(turn[0].direction) == doctest::Approx(-25.0).epsilon(1e-4));
  CHECK(sim::elevation_deg(turn[31].direction) == doctest::Approx(15.0).epsilon(1e-4));
  CHECK(azimuth_full_every_100ms(sim::collect(m, 0.5)));
  sim::SpinningModel again;
  for (int i = 0; i < 57600; ++i) again.next();  // one turn later
  for (int i = 0; i < 1000; ++i) CHECK(again.next().direction == turn[static_cast<std::size_t>(i)].direction);
}

TEST_CASE("sensor models: invalid Params throw std::invalid_argument naming the parameter") {
  using IA = std::invalid_argument;
  check_throws_naming<IA>([] { sim::Mid360Model{sim::Mid360Model::Params{0.0, 0.0}}; }, "point_rate");
  check_throws_naming<IA>([] { sim::Mid360Model{sim::Mid360Model::Params{200000.0, -1.0}}; }, "start_time");
  check_throws_naming<IA>(
      [] {
        sim::RisleyPairModel::Params p;
        p.amplitude2 = -0.1;
        sim::RisleyPairModel m(p);
      },
      "amplitude2");
  check_throws_naming<IA>(
      [] {
        sim::RisleyPairModel::Params p;
        p.prism1_hz = 0.0;
        sim::RisleyPairModel m(p);
      },
      "prism1_hz");
  check_throws_naming<IA>(
      [] {
        sim::RisleyPairModel::Params p;
        p.radial_poly = {{-1.0, 0.0, 0.0, 0.0}};
        sim::RisleyPairModel m(p);
      },
      "radial_poly");
  check_throws_naming<IA>(
      [] {
        sim::RisleyPairModel::Params p;
        p.point_rate = std::nan("");
        sim::RisleyPairModel m(p);
      },
      "point_rate");
  check_throws_naming<IA>(
      [] {
        sim::AviaModel::Params p;
        p.refractive_index = 1.0;
        sim::AviaModel m(p);
      },
      "refractive_index");
  check_throws_naming<IA>(
      [] {
        sim::AviaModel::Params p;
        p.wedge_deg[1] = 90.0;
        sim::AviaModel m(p);
      },
      "wedge_deg[1]");
  check_throws_naming<IA>(
      [] {
        sim::AviaModel::Params p;
        p.beam_offset_deg[5] = 45.0;
        sim::AviaModel m(p);
      },
      "beam_offset_deg[5]");
  check_throws_naming<IA>(
      [] {
        sim::SpinningModel::Params p;
        p.beams = 0;
        sim::SpinningModel m(p);
      },
      "beams");
  check_throws_naming<IA>(
      [] {
        sim::SpinningModel::Params p;
        p.elevation_max_deg = -30.0;
        sim::SpinningModel m(p);
      },
      "elevation_max_deg");
  check_throws_naming<IA>(
      [] {
        sim::SpinningModel::Params p;
        p.rotation_hz = -10.0;
        sim::SpinningModel m(p);
      },
      "rotation_hz");
  check_throws_naming<IA>(
      [] {
        sim::SpinningModel::Params p;
        p.columns = 0;
        sim::SpinningModel m(p);
      },
      "columns");
  check_throws_naming<IA>([] { sim::TableReplay::risley_f32("x.bin", 0.0); }, "point_rate");
  check_throws_naming<IA>([] { sim::TableReplay{sim::TableReplay::Params{"", sim::TableReplay::Layout::mid360_u16, 1.0, 4}}; },
                          "path");
  check_throws_naming<IA>([] { sim::TableReplay{sim::TableReplay::Params{"x.bin", sim::TableReplay::Layout::mid360_u16, 1.0, 0}}; },
                          "lasers");
}

TEST_CASE("TableReplay: replays in order, repeats with time continuing") {
  // Three Mid-360 rows: (0 deg, 0 deg), (90 deg, 0 deg), (0 deg, 90 deg) as u16: az*100, (el+10)*100.
  const fs::path p = temp_file("three.bin", {0x00, 0x00, 0xE8, 0x03, 0x28, 0x23, 0xE8, 0x03, 0x00, 0x00, 0x10, 0x27});
  auto t = sim::TableReplay::mid360(p.string());
  CHECK(t.rows() == 3);
  CHECK(t.period() == doctest::Approx(3.0 / 200000.0));
  const Eigen::Vector3f expect[3] = {Eigen::Vector3f::UnitX(), Eigen::Vector3f::UnitY(), Eigen::Vector3f::UnitZ()};
  double prev = -1.0;
  for (int i = 0; i < 8; ++i) {
    const sim::Ray r = t.next();
    CHECK(r.time == doctest::Approx(i / 200000.0));
    CHECK(r.time > prev);
    prev = r.time;
    CHECK(r.laser == i % 4);
    CHECK((r.direction - expect[i % 3]).norm() < 1e-6f);
  }
  // f32 layout: one row (az 0.1 rad, el -0.2 rad).
  std::vector<unsigned char> bytes(8);
  const float row[2] = {0.1f, -0.2f};
  std::memcpy(bytes.data(), row, 8);
  const fs::path q = temp_file("one.bin", bytes);
  auto u = sim::TableReplay::risley_f32(q.string());
  const sim::Ray r = u.next();
  CHECK(sim::azimuth_deg(r.direction) == doctest::Approx(0.1 * 180.0 / 3.14159265358979323846).epsilon(1e-5));
  CHECK(sim::elevation_deg(r.direction) == doctest::Approx(-0.2 * 180.0 / 3.14159265358979323846).epsilon(1e-5));
  CHECK(u.next().time == doctest::Approx(1e-5));
  fs::remove(p);
  fs::remove(q);
}

TEST_CASE("TableReplay: short, odd-sized, empty, missing or out-of-range files throw naming the file and offset") {
  using RE = std::runtime_error;
  const fs::path odd = temp_file("odd.bin", {0, 0, 0, 0, 1, 2, 3});
  check_throws_naming<RE>([&] { sim::TableReplay::mid360(odd.string()); }, odd.string());
  check_throws_naming<RE>([&] { sim::TableReplay::mid360(odd.string()); }, "byte offset 4");
  check_throws_naming<RE>([&] { sim::TableReplay::risley_f32(odd.string()); }, "byte offset 0");
  const fs::path empty = temp_file("empty.bin", {});
  check_throws_naming<RE>([&] { sim::TableReplay::mid360(empty.string()); }, empty.string());
  check_throws_naming<RE>([&] { sim::TableReplay::mid360(empty.string()); }, "byte offset 0");
  const fs::path range = temp_file("range.bin", {0, 0, 0, 0, 0xA0, 0x8C, 0, 0});  // azimuth code 36000
  check_throws_naming<RE>([&] { sim::TableReplay::mid360(range.string()); }, "byte offset 4");
  const fs::path missing = odd.parent_path() / "missing.bin";
  fs::remove(missing);
  check_throws_naming<RE>([&] { sim::TableReplay::mid360(missing.string()); }, missing.string());
  fs::remove(odd);
  fs::remove(empty);
  fs::remove(range);
}

TEST_CASE("pattern statistics: hand-checked values") {
  std::vector<sim::Ray> rays(4);
  rays[0].direction = Eigen::Vector3f::UnitX();
  rays[1].direction = Eigen::Vector3f::UnitY();
  rays[2].direction = Eigen::Vector3f::UnitZ();
  rays[3].direction = Eigen::Vector3f(0.0f, 0.0f, -1.0f);
  for (int i = 0; i < 4; ++i) rays[static_cast<std::size_t>(i)].time = 0.1 * i;
  const sim::FovExtents f = sim::fov_extents(rays, 0.0, 100.0);
  CHECK(f.azimuth_min == doctest::Approx(0.0));
  CHECK(f.azimuth_max == doctest::Approx(90.0));
  CHECK(f.elevation_min == doctest::Approx(-90.0));
  CHECK(f.elevation_max == doctest::Approx(90.0));
  CHECK(f.off_axis_max == doctest::Approx(90.0));
  CHECK(sim::solid_angle_sq_deg({sim::AngularCoordinate::elevation, -90.0, 90.0}) == doctest::Approx(41252.96).epsilon(1e-4));
  CHECK(sim::solid_angle_sq_deg({sim::AngularCoordinate::off_axis, 0.0, 180.0}) == doctest::Approx(41252.96).epsilon(1e-4));
  sim::CoverageGrid g;
  g.azimuth_min_deg = -1.0;
  g.azimuth_max_deg = 1.0;
  g.elevation_min_deg = -1.0;
  g.elevation_max_deg = 1.0;  // 4 x 4 cells of 0.5 deg; only ray 0 lands (on the corner of 4 cells: one of them)
  const std::vector<double> cov = sim::coverage_growth(rays, g, {0.05, 1.0});
  CHECK(cov[0] == doctest::Approx(1.0 / 16.0));
  CHECK(cov[1] == doctest::Approx(1.0 / 16.0));
  CHECK_THROWS_AS(sim::fov_extents({}), std::invalid_argument);
}
