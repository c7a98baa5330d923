// SPDX-License-Identifier: MIT
// ScanAdaptiveLinkage and its ScanSpacing table: the table of a known
// synthetic pattern, the radius at given directions, ranges and mounts,
// symmetry and link_many bit for bit, the laws of the test kit, parameter
// errors, the tool's fit, and the oracle: the objects engine with this
// linkage equals the batch partition (level, pitched, with poses), on the
// Mid-360 and Avia models.

#include <doctest/doctest.h>

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/linkage/scan_adaptive.hpp>
#include <streamclust/objects_presets.hpp>
#include <streamclust/rebind_params.hpp>
#include <streamclust/sensor_fit.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/avia_model.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/simulator.hpp>
#include <streamclust/stream_clusterer.hpp>
#include <streamclust/testing/candidate_pairs.hpp>
#include <streamclust/testing/linkage_laws.hpp>
#include <streamclust/testing/livox_streams.hpp>

#include "support/constants.hpp"
#include "support/directions.hpp"
#include "support/invalid_argument.hpp"
#include "support/oracle_input.hpp"
#include "support/streams.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace sc = streamclust;
namespace st = streamclust::test;

namespace {

using st::direction_deg;
using st::invalid_argument_message;
using st::kDeg;

/// A synthetic pattern: a square lattice of directions, `fine_deg` apart
/// within 20 deg of the axis (azimuth and elevation), `coarse_deg` apart
/// from 24 to 60 deg of azimuth; elevation within +-20 deg.
std::vector<Eigen::Vector3f> two_density_pattern(double fine_deg, double coarse_deg) {
  std::vector<Eigen::Vector3f> out;
  for (double el = -20.0; el <= 20.0 + 1e-9; el += fine_deg) {
    for (double az = -20.0; az <= 20.0 + 1e-9; az += fine_deg) out.push_back(direction_deg(az, el));
  }
  for (double el = -20.0; el <= 20.0 + 1e-9; el += coarse_deg) {
    for (double az = 24.0; az <= 60.0 + 1e-9; az += coarse_deg) out.push_back(direction_deg(az, el));
  }
  return out;
}

sc::Sample sample_at(const Eigen::Vector3f& direction, float range, double time = 0.0) {
  return sc::make_sample(direction * range, direction * range, range, 0.0f, time);
}

std::shared_ptr<const sc::ScanSpacing> lattice_table() {
  static const auto table = sc::ScanSpacing::from_directions(two_density_pattern(0.2, 0.6));
  return table;
}

sc::ScanAdaptiveLinkage::Params lattice_params(float factor = 4.0f) {
  sc::ScanAdaptiveLinkage::Params p;
  p.spacing = lattice_table();
  p.spacing_factor = factor;
  return p;
}

}  // namespace

TEST_CASE("ScanSpacing: a lattice's spacing where it is fine, where it is coarse, and filled beyond") {
  const sc::ScanSpacing& table = *lattice_table();
  CHECK(table.rows() == 90);
  CHECK(table.cols() == 180);
  // Inside each region, away from its edges: the lattice step (the 3 x 3
  // smoothing of equal cells changes nothing).
  CHECK(table.at(direction_deg(0.0, 0.0)) / kDeg == doctest::Approx(0.2).epsilon(0.03));
  CHECK(table.at(direction_deg(-10.0, 8.0)) / kDeg == doctest::Approx(0.2).epsilon(0.03));
  CHECK(table.at(direction_deg(42.0, 0.0)) / kDeg == doctest::Approx(0.6).epsilon(0.03));
  CHECK(table.at(direction_deg(40.0, -10.0)) / kDeg == doctest::Approx(0.6).epsilon(0.03));
  // Continuous across the border (bilinear), between the two values.
  const float border = table.at(direction_deg(22.0, 0.0));
  CHECK(border > 0.2 * kDeg);
  CHECK(border < 0.6 * kDeg);
  // No direction behind the sensor: filled from the nearest filled cells.
  const float behind = table.at(direction_deg(180.0, 60.0));
  CHECK(behind >= 0.19 * kDeg);
  CHECK(behind <= 0.61 * kDeg);
  // Every direction but those of the few border cells with fewer than
  // min_samples has a cell of its own.
  CHECK(table.directions_used() > 9 * two_density_pattern(0.2, 0.6).size() / 10);
  CHECK(table.directions_used() <= two_density_pattern(0.2, 0.6).size());
  // The length of a direction does not matter; azimuth wraps.
  CHECK(table.at(direction_deg(42.0, 0.0) * 7.0f) == table.at(direction_deg(42.0, 0.0)));
  CHECK(table.at_angles(190.0, 5.0) == table.at_angles(-170.0, 5.0));
}

TEST_CASE("ScanSpacing: the median spanning-tree edge of a lattice is its step whatever the quantile") {
  sc::ScanSpacing::Params median;
  median.quantile = 0.5f;
  const auto table = sc::ScanSpacing::from_directions(two_density_pattern(0.2, 0.6), median);
  CHECK(table->at(direction_deg(0.0, 0.0)) / kDeg == doctest::Approx(0.2).epsilon(0.03));
  CHECK(table->at(direction_deg(42.0, 0.0)) / kDeg == doctest::Approx(0.6).epsilon(0.03));
}

TEST_CASE("ScanSpacing: traces side by side: the high quantile sees the gap between them, the median the step along") {
  // Pairs of traces along azimuth, 0.05 deg steps, 0.05 deg apart, the
  // pairs 1 deg apart in elevation: the nearest neighbours are 0.05 deg
  // away, what keeps a surface connected is the 0.95 deg gap.
  std::vector<Eigen::Vector3f> traces;
  for (double el = -10.0; el <= 10.0; el += 1.0) {
    for (double az = -10.0; az <= 10.0; az += 0.05) {
      traces.push_back(direction_deg(az, el));
      traces.push_back(direction_deg(az, el + 0.05));
    }
  }
  sc::ScanSpacing::Params median, widest;
  median.quantile = 0.5f;
  widest.quantile = 1.0f;
  const float at_median = sc::ScanSpacing::from_directions(traces, median)->at(direction_deg(0.0, 0.5));
  const float at_widest = sc::ScanSpacing::from_directions(traces, widest)->at(direction_deg(0.0, 0.5));
  CHECK(at_median / kDeg == doctest::Approx(0.05).epsilon(0.05));
  CHECK(at_widest / kDeg == doctest::Approx(0.95).epsilon(0.05));
}

TEST_CASE("ScanSpacing: a higher quantile and a shorter window give a wider spacing") {
  sc::sim::AviaModel avia_a, avia_b, avia_c;
  const auto half_second = sc::ScanSpacing::from_sensor_model(avia_a, 0.5);
  const auto tenth = sc::ScanSpacing::from_sensor_model(avia_b, 0.1);
  sc::ScanSpacing::Params median;
  median.quantile = 0.5f;
  const auto half_second_median = sc::ScanSpacing::from_sensor_model(avia_c, 0.5, median);
  const Eigen::Vector3f centre = direction_deg(0.0, 0.0), rim = direction_deg(30.0, 0.0);
  CHECK(tenth->at(centre) > 1.5f * half_second->at(centre));
  CHECK(half_second->at(centre) > 1.2f * half_second_median->at(centre));  // default quantile 0.9
  // The Avia fires denser near its axis than 30 deg off it.
  CHECK(half_second->at(rim) > 1.5f * half_second->at(centre));
}

TEST_CASE("ScanSpacing: invalid Params and too few directions throw naming the parameter") {
  const auto pattern = two_density_pattern(1.0, 2.0);
  sc::ScanSpacing::Params p;
  p.cell_deg = 0.1f;
  CHECK(invalid_argument_message([&] { sc::ScanSpacing::from_directions(pattern, p); }).find("ScanSpacing: parameter cell_deg = 0.1") == 0);
  p = {};
  p.quantile = 1.5f;
  CHECK(invalid_argument_message([&] { sc::ScanSpacing::from_directions(pattern, p); }).find("parameter quantile") != std::string::npos);
  p = {};
  p.min_samples = 0;
  CHECK(invalid_argument_message([&] { sc::ScanSpacing::from_directions(pattern, p); }).find("parameter min_samples") != std::string::npos);
  p = {};
  p.max_spacing_deg = std::nanf("");
  CHECK(invalid_argument_message([&] { sc::ScanSpacing::from_directions(pattern, p); }).find("parameter max_spacing_deg") != std::string::npos);
  CHECK(invalid_argument_message([&] { sc::ScanSpacing::from_directions({}); }).find("parameter directions = 0") != std::string::npos);
  // Two directions: no cell with min_samples of them.
  CHECK(!invalid_argument_message([&] {
           sc::ScanSpacing::from_directions({direction_deg(0, 0), direction_deg(10, 0)});
         }).empty());
  sc::sim::AviaModel avia;
  CHECK(invalid_argument_message([&] { sc::ScanSpacing::from_sensor_model(avia, 0.0); }).find("window_seconds") != std::string::npos);
}

TEST_CASE("ScanAdaptiveLinkage: radius = max(min_distance, factor x spacing at the sensor direction x range)") {
  const sc::ScanAdaptiveLinkage link{lattice_params(4.0f)};
  const sc::ScanSpacing& table = *lattice_table();
  const Eigen::Vector3f fine = direction_deg(0.0, 0.0), coarse = direction_deg(42.0, 0.0);
  CHECK(link.radius(sample_at(fine, 50.0f)) == doctest::Approx(4.0 * table.at(fine) * 50.0));
  CHECK(link.radius(sample_at(coarse, 50.0f)) == doctest::Approx(4.0 * table.at(coarse) * 50.0));
  CHECK(link.radius(sample_at(coarse, 50.0f)) > 2.5f * link.radius(sample_at(fine, 50.0f)));
  CHECK(link.radius(sample_at(fine, 2.0f)) == link.params().min_distance);  // 4 x 0.2 deg x 2 m = 2.8 cm: the floor
  // Linked iff within the smaller radius: two points at 50 m, the fine
  // one's radius (0.70 m, above the floor) decides.
  const sc::Sample a = sample_at(fine, 50.0f);
  const float r_fine = link.radius(a);
  sc::Sample b = sample_at(coarse, 50.0f);
  b.position = a.position + Eigen::Vector3f(0.0f, 0.0f, 0.9f * r_fine);
  CHECK(link(a, b));
  b.position = a.position + Eigen::Vector3f(0.0f, 0.0f, 1.1f * r_fine);
  CHECK(!link(a, b));
  CHECK(link.radius(b) > 1.1f * r_fine);  // b alone would reach a
}

TEST_CASE("ScanAdaptiveLinkage: the spacing is read in the sensor frame (mount, poses)") {
  // Mounted turned 42 deg to the left: a world ray along +x is the sensor's
  // azimuth -42 deg (no return there: filled), a world ray at 84 deg its
  // coarse 42 deg, a world ray at 42 deg its fine axis.
  sc::ScanAdaptiveLinkage::Params p = lattice_params();
  p.mount = sc::mount_from_roll_pitch_yaw_deg(0.0, 0.0, 42.0);
  const sc::ScanAdaptiveLinkage turned{p};
  const sc::ScanAdaptiveLinkage level{lattice_params()};
  CHECK(turned.radius(sample_at(direction_deg(42.0, 0.0), 50.0f)) ==
        doctest::Approx(level.radius(sample_at(direction_deg(0.0, 0.0), 50.0f))).epsilon(1e-4));
  CHECK(turned.radius(sample_at(direction_deg(84.0, 0.0), 50.0f)) ==
        doctest::Approx(level.radius(sample_at(direction_deg(42.0, 0.0), 50.0f))).epsilon(1e-4));
  CHECK((turned.sensor_direction(sample_at(direction_deg(42.0, 0.0), 5.0f)) - direction_deg(0.0, 0.0)).norm() < 1e-6f);
  // With poses: the vehicle turns 42 deg between t = 0 and t = 1; the
  // sensor (level mount) sees a world ray at 42 deg along its axis at t = 1.
  std::vector<sc::StampedPose> poses(2);
  poses[0].time = 0.0;
  poses[1].time = 1.0;
  poses[1].pose = sc::mount_from_roll_pitch_yaw_deg(0.0, 0.0, 42.0);
  p = lattice_params();
  p.trajectory = std::make_shared<const sc::PoseTrajectory>(poses);
  const sc::ScanAdaptiveLinkage driven{p};
  CHECK((driven.sensor_direction(sample_at(direction_deg(42.0, 0.0), 5.0f, 1.0)) - direction_deg(0.0, 0.0)).norm() <
        1e-6f);
  CHECK((driven.sensor_direction(sample_at(direction_deg(21.0, 0.0), 5.0f, 0.5)) - direction_deg(0.0, 0.0)).norm() <
        1e-6f);
  CHECK((driven.sensor_direction(sample_at(direction_deg(0.0, 0.0), 5.0f, -3.0)) - direction_deg(0.0, 0.0)).norm() <
        1e-6f);  // before the first pose: the first pose
}

TEST_CASE("ScanAdaptiveLinkage: symmetric, payload and link_many bit for bit (the test kit's laws)") {
  sc::sim::Mid360Model mid360;
  sc::ScanAdaptiveLinkage::Params p;
  p.spacing = sc::ScanSpacing::from_sensor_model(mid360, 0.5);
  std::vector<sc::ScanAdaptiveLinkage::Params> sets;
  for (float factor : {1.0f, 6.0f, 40.0f}) {
    for (float floor : {0.05f, 0.2f}) {
      p.spacing_factor = factor;
      p.min_distance = floor;
      p.mount = sc::mount_from_roll_pitch_yaw_deg(factor > 10.0f ? 180.0 : 0.0, 20.0, 5.0);
      sets.push_back(p);
    }
  }
  std::vector<std::pair<sc::Sample, sc::Sample>> pairs = sc::testing::random_candidate_pairs(7, 6000);
  for (auto& q : sc::testing::livox_candidate_pairs(3000, 7)) pairs.push_back(q);
  std::mt19937 rng(11);
  std::size_t total_linked = 0, total = 0;
  for (const auto& params : sets) {
    const sc::ScanAdaptiveLinkage link{params};
    std::vector<std::pair<sc::Sample, sc::Sample>> all = pairs;
    for (auto& q : sc::testing::boundary_pairs(link, pairs, 1500)) all.push_back(q);
    std::size_t linked = 0;
    const std::string failure = sc::testing::internal::linkage_laws_on(link, params, all, linked, rng);
    INFO("factor " << params.spacing_factor << ", floor " << params.min_distance);
    CHECK(failure == "");
    total_linked += linked;
    total += all.size();
  }
  CHECK(total_linked > total / 20);  // not vacuous: linked and split pairs
  CHECK(total_linked < total - total / 20);
}

TEST_CASE("ScanAdaptiveLinkage::link_many decides as the pairwise operator a few ulps either side of the radius") {
  const sc::ScanAdaptiveLinkage link{lattice_params()};
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<sc::ScanAdaptiveLinkage::Payload> ring;
  const sc::ScanAdaptiveLinkage::Payload a = link.make_payload(sample_at(direction_deg(3.0, 1.0), 30.0f));
  for (int i = 0; i < 400; ++i) {
    Eigen::Vector3f offset(unit(rng), unit(rng), unit(rng));
    offset.normalize();
    sc::ScanAdaptiveLinkage::Payload b = a;
    b.radius = a.radius * (i % 2 == 0 ? 0.5f : 2.0f);
    const float r = std::min(a.radius, b.radius);
    float scale = r;
    for (int k = 0; k < i % 7; ++k) scale = std::nextafter(scale, i % 3 == 0 ? 0.0f : 10.0f);
    for (int c = 0; c < 3; ++c) b.position[c] = a.position[c] + offset[c] * scale;
    ring.push_back(b);
  }
  std::vector<std::uint32_t> slots(ring.size());
  for (std::uint32_t k = 0; k < slots.size(); ++k) slots[k] = k;
  std::vector<std::uint8_t> many(slots.size() + 1, 7);
  link.link_many(a, ring.data(), slots.data(), slots.size(), many.data());
  std::size_t linked = 0;
  for (std::size_t k = 0; k < slots.size(); ++k) {
    CHECK(many[k] == (link(a, ring[k]) ? 1 : 0));
    CHECK(link(a, ring[k]) == link(ring[k], a));
    linked += many[k];
  }
  CHECK(many.back() == 7);
  CHECK(linked > 20);
  CHECK(linked < ring.size() - 20);
}

TEST_CASE("ScanAdaptiveLinkage: invalid Params throw naming the parameter, the value and the range") {
  using P = sc::ScanAdaptiveLinkage::Params;
  const auto msg = [](const P& p) { return invalid_argument_message([&] { sc::ScanAdaptiveLinkage{p}; }); };
  CHECK(msg(P{}).find("ScanAdaptiveLinkage: parameter spacing is null") == 0);
  P p = lattice_params();
  CHECK(msg(p).empty());
  p.min_distance = 0.0f;
  CHECK(msg(p).find("ScanAdaptiveLinkage: parameter min_distance = 0 is invalid; allowed: finite, in (0, 100] m") == 0);
  p = lattice_params();
  p.min_distance = std::nanf("");
  CHECK(msg(p).find("parameter min_distance = nan") != std::string::npos);
  p = lattice_params();
  p.spacing_factor = -1.0f;
  CHECK(msg(p).find("ScanAdaptiveLinkage: parameter spacing_factor = -1 is invalid") == 0);
  p = lattice_params();
  p.spacing_factor = 2000.0f;
  CHECK(msg(p).find("parameter spacing_factor = 2000") != std::string::npos);
  p = lattice_params();
  p.mount.rotation.coeffs().setZero();
  CHECK(msg(p).find("parameter mount.rotation norm = 0") != std::string::npos);
}

TEST_CASE("ScanAdaptiveLinkage::fit_to_sensor builds the table from the first window and takes the placement") {
  sc::SensorFit fit;
  fit.first_window = two_density_pattern(0.2, 0.6);
  for (auto& d : fit.first_window) d *= 12.0f;  // points, not directions: the length does not matter
  fit.mount = sc::mount_from_roll_pitch_yaw_deg(0.0, 15.0, 0.0);
  std::vector<sc::StampedPose> poses(1);
  fit.trajectory = std::make_shared<const sc::PoseTrajectory>(poses);
  sc::ScanAdaptiveLinkage::Params p;
  p.spacing_factor = 3.0f;
  const auto fitted = sc::ScanAdaptiveLinkage::fit_to_sensor(p, fit);
  REQUIRE(fitted.spacing);
  CHECK(fitted.spacing->at(direction_deg(0.0, 0.0)) == doctest::Approx(lattice_table()->at(direction_deg(0.0, 0.0))));
  CHECK(fitted.mount.rotation.isApprox(fit.mount.rotation));
  CHECK(fitted.trajectory == fit.trajectory);
  CHECK(fitted.spacing_factor == 3.0f);
  // A table given is kept.
  p.spacing = sc::ScanSpacing::from_directions(two_density_pattern(0.5, 1.0));
  CHECK(sc::ScanAdaptiveLinkage::fit_to_sensor(p, fit).spacing == p.spacing);
  static_assert(sc::has_sensor_fit_v<sc::ScanAdaptiveLinkage>);
  static_assert(!sc::has_sensor_fit_v<sc::RangeAdaptiveLinkage>);
}

namespace {

struct ObjectsScanConfig : sc::ObjectsConfig {
  using linkage = sc::ScanAdaptiveLinkage;
};

/// The objects engine with ScanAdaptiveLinkage (its table from the sensor
/// model) on `seconds` of a simulated scene, retrieved in random stretches,
/// each retrieval against the batch clusterer. Returns the retrievals
/// compared with points.
template <class Sensor>
int run_objects_oracle(Sensor sensor, const sc::SphericalProjection::Params& fov, const sc::sim::Scene& scene,
                       bool pitched, bool moving, std::uint64_t seed) {
  namespace sim = sc::sim;
  typename sim::Simulator<Sensor>::Params sp;
  sp.seed = seed;
  sp.mount = pitched ? sc::mount_from_roll_pitch_yaw_deg(0.0, 20.0, 0.0) : sc::Pose{};
  sp.velocity = {moving ? 1.5f : 0.0f, 0.0f, 0.0f};
  sp.yaw_rate = moving ? 0.6f : 0.0f;
  Sensor table_model = sensor;
  sim::Simulator<Sensor> simulator(std::move(sensor), scene, sp);
  std::vector<sim::SimPoint> stream;
  while (simulator.time() < 0.6) stream.push_back(simulator.next());
  sc::ObjectsSetup setup;
  setup.mount = sp.mount;
  setup.sensor_height = 1.0f;
  setup.window_seconds = 0.2;
  if (moving) {
    // The vehicle's poses: the simulator's sensor poses without the mount.
    std::vector<sc::StampedPose> vehicle;
    for (const sc::StampedPose& p : simulator.trajectory(0.0, 0.61, 100.0)) {
      vehicle.push_back(sc::StampedPose{p.time, p.pose * sp.mount.inverse()});
    }
    setup.trajectory = std::make_shared<const sc::PoseTrajectory>(std::move(vehicle));
  }
  sc::ScanAdaptiveLinkage::Params lp;
  lp.spacing = sc::ScanSpacing::from_sensor_model(table_model, setup.window_seconds);
  lp.mount = setup.mount;
  lp.trajectory = setup.trajectory;
  const auto params = sc::rebind_params<ObjectsScanConfig>(sc::objects_params(fov, setup), lp);
  sc::StreamClusterer<ObjectsScanConfig> engine(params);
  sc::BatchClusterer<ObjectsScanConfig> batch(params);
  std::mt19937_64 rng(seed);
  int compared = 0;
  for (std::size_t offered = 0; offered < stream.size();) {
    const std::size_t stop = std::min(stream.size(), offered + 1 + static_cast<std::size_t>(rng() % 20000));
    engine.insert_batch(stream.begin() + static_cast<std::ptrdiff_t>(offered), stream.begin() + static_cast<std::ptrdiff_t>(stop));
    offered = stop;
    engine.retrieve();
    const std::string mismatch = st::compare_with_batch_on_input(engine, batch, stream);
    INFO("after point " << offered - 1 << ", window " << engine.size() << " objects + " << engine.structure_size()
                        << " structure");
    REQUIRE(mismatch == "");
    compared += engine.size() > 0 ? 1 : 0;
  }
  return compared;
}

}  // namespace

TEST_CASE("ScanAdaptiveLinkage in the objects engine on random and adversarial streams equals the batch") {
  // The Mid-360 model's table (read in any direction: the streams cover the
  // sphere), a mount upside down or pitched, and poses over most of the
  // stream (points outside are rejected); a short window, random stretches.
  sc::sim::Mid360Model model;
  const auto table = sc::ScanSpacing::from_sensor_model(model, 0.05);
  for (std::uint64_t seed = 0; seed < 16; ++seed) {
    std::mt19937_64 rng(seed * 13 + 5);
    const auto kind = static_cast<st::StreamKind>(seed % static_cast<std::uint64_t>(st::StreamKind::count_));
    const auto stream = st::make_stream(kind, 400 + seed % 300, seed);
    double t_end = 0.0;
    for (const auto& p : stream) {
      if (std::isfinite(p.t) && p.t < 1e6) t_end = std::max(t_end, p.t);
    }
    std::vector<sc::StampedPose> poses;
    for (double t = -0.1; t <= t_end + 1.0; t += 0.01) {
      sc::Pose pose = sc::mount_from_roll_pitch_yaw_deg(3.0 * std::sin(t), 2.0 * std::cos(2.0 * t), 60.0 * t);
      pose.translation = Eigen::Vector3d(1.5 * t, 0.2 * t, 0.0);
      poses.push_back(sc::StampedPose{t, pose});
    }
    sc::ObjectsSetup setup;
    setup.mount = sc::mount_from_roll_pitch_yaw_deg(seed % 2 ? 180.0 : 0.0, 15.0 * static_cast<double>(seed % 3), 0.0);
    if (seed % 4 != 0) setup.trajectory = std::make_shared<const sc::PoseTrajectory>(std::move(poses));
    setup.sensor_height = seed % 3 == 0 ? 0.0f : 1.2f;
    setup.window_seconds = 0.05;
    sc::ScanAdaptiveLinkage::Params lp;
    lp.spacing = table;
    lp.spacing_factor = 2.0f + static_cast<float>(seed % 5) * 6.0f;
    lp.min_distance = seed % 2 ? 0.1f : 0.4f;
    lp.mount = setup.mount;
    lp.trajectory = setup.trajectory;
    auto params = sc::rebind_params<ObjectsScanConfig>(sc::objects_params(sc::SphericalProjection::Params{}, setup), lp);
    params.resolution.initial_rows = 8;
    params.resolution.initial_cols = 32;
    sc::StreamClusterer<ObjectsScanConfig> engine(params);
    sc::BatchClusterer<ObjectsScanConfig> batch(params);
    for (std::size_t offered = 0; offered < stream.size();) {
      const std::size_t stop = std::min(stream.size(), offered + 1 + static_cast<std::size_t>(rng() % 90));
      if (rng() % 2) {
        engine.insert_batch(stream.begin() + static_cast<std::ptrdiff_t>(offered),
                            stream.begin() + static_cast<std::ptrdiff_t>(stop));
      } else {
        for (std::size_t i = offered; i < stop; ++i) engine.insert(stream[i]);
      }
      offered = stop;
      engine.retrieve();
      const std::string mismatch = st::compare_with_batch_on_input(engine, batch, stream);
      INFO("seed " << seed << ", stream " << st::to_string(kind) << ", after point " << offered - 1);
      REQUIRE(mismatch == "");
    }
  }
}

TEST_CASE("ScanAdaptiveLinkage in the objects engine: the partition equals the batch partition") {
  namespace sim = sc::sim;
  const sc::SphericalProjection::Params mid360_fov = sc::field_of_view_of(sc::livox_mid360);
  const sc::SphericalProjection::Params avia_fov = sc::field_of_view_of(sc::livox_avia);
  SUBCASE("Mid-360 office, level, at rest") {
    CHECK(run_objects_oracle(sim::Mid360Model{}, mid360_fov, sim::office_scene(3), false, false, 1) > 3);
  }
  SUBCASE("Mid-360 street, pitched 20 deg, moving with poses") {
    CHECK(run_objects_oracle(sim::Mid360Model{}, mid360_fov, sim::street_scene(4), true, true, 2) > 3);
  }
  SUBCASE("Avia forest, pitched 20 deg, at rest") {
    CHECK(run_objects_oracle(sim::AviaModel{}, avia_fov, sim::forest_scene(5), true, false, 3) > 3);
  }
  SUBCASE("Avia office, level, moving with poses") {
    CHECK(run_objects_oracle(sim::AviaModel{}, avia_fov, sim::office_scene(6), false, true, 4) > 3);
  }
}
