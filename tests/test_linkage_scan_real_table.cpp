// SPDX-License-Identifier: MIT
// ScanSpacing from the real Livox firing tables (shared data; skipped when
// absent): the official Mid-360 table gives the analytic model's spacing,
// and the Mid-70's rosette is denser at its axis than 10 degrees off it.

#include <doctest/doctest.h>

#include <streamclust/linkage/scan_spacing.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/sim/sensors/table_replay.hpp>

#include "support/shared_data.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace sc = streamclust;
using streamclust::test::livox_data_dir;
using streamclust::test::needs_livox_data;

TEST_CASE("ScanSpacing of the real Mid-360 table matches the model's over 0.5 s" *
          needs_livox_data("patterns/mid360_u16le.bin")) {
  auto table = sc::sim::TableReplay::mid360((livox_data_dir() / "patterns" / "mid360_u16le.bin").string());
  sc::sim::Mid360Model model;
  const auto real = sc::ScanSpacing::from_sensor_model(table, 0.5);
  const auto modelled = sc::ScanSpacing::from_sensor_model(model, 0.5);
  std::vector<double> ratios;  // over the field of view, every 2 degrees
  for (double el = -4.0; el <= 50.0; el += 2.0) {
    for (double az = -178.0; az <= 178.0; az += 2.0) ratios.push_back(real->at_angles(az, el) / modelled->at_angles(az, el));
  }
  std::sort(ratios.begin(), ratios.end());
  const double p5 = ratios[ratios.size() / 20], p50 = ratios[ratios.size() / 2], p95 = ratios[ratios.size() * 19 / 20];
  MESSAGE("real / model spacing: p5 " << p5 << ", median " << p50 << ", p95 " << p95);
  CHECK(p5 > 0.8);
  CHECK(p50 == doctest::Approx(1.0).epsilon(0.1));
  CHECK(p95 < 1.25);
}

TEST_CASE("ScanSpacing of the real Mid-70 table: the rosette is denser at its axis" *
          needs_livox_data("patterns/mid70_f32le.bin")) {
  auto table = sc::sim::TableReplay::risley_f32((livox_data_dir() / "patterns" / "mid70_f32le.bin").string());
  const auto spacing = sc::ScanSpacing::from_sensor_model(table, 0.5);
  CHECK(spacing->at_angles(0.0, 0.0) < 0.85f * spacing->at_angles(10.0, 0.0));
  CHECK(spacing->at_angles(0.0, 0.0) < 0.85f * spacing->at_angles(0.0, 10.0));
}
