// SPDX-License-Identifier: MIT
// The real Livox frames of ../shared/data/livox/frames load with the point
// counts their README and headers state. Each case is skipped when its data
// is absent (a fresh clone does not have it); support/shared_data.hpp says
// where the data is looked up (STREAMCLUST_SHARED_DIR, STREAMCLUST_LIVOX_DATA).

#include <doctest/doctest.h>

#include "support/shared_data.hpp"

#include <streamclust/io/reader.hpp>
#include <streamclust/sensors.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace io = streamclust::io;
namespace fs = std::filesystem;

namespace {

using streamclust::test::livox_data_dir;
using streamclust::test::needs_livox_data;

std::vector<io::Record> load(const fs::path& p, const io::ReadOptions& o = {}) {
  auto r = io::open_reader(p.string(), o);
  std::vector<io::Record> out;
  while (r->read(out, 10000) > 0) {
  }
  if (r->info().declared_points) CHECK(*r->info().declared_points == out.size());
  return out;
}

io::ReadOptions rate(double hz) {
  io::ReadOptions o;
  o.point_rate = hz;
  return o;
}

}  // namespace

TEST_CASE("real frames: horizon_highway CSV has 20,900 slots, 6,832 of them the no-return point" *
          needs_livox_data("frames/horizon_highway")) {
  const fs::path p = livox_data_dir() / "frames" / "horizon_highway" / "test_data.csv";
  auto r = io::open_reader(p.string(), rate(streamclust::livox_horizon.point_rate_hz));
  CHECK(r->info().format == io::Format::csv);
  CHECK(r->info().has_intensity);
  CHECK_FALSE(r->info().has_time);
  const auto v = load(p, rate(streamclust::livox_horizon.point_rate_hz));
  CHECK(v.size() == 20900);
  std::size_t no_return = 0;
  for (const auto& rec : v)
    if (std::fabs(rec.x + 0.089f) < 1e-3f && std::fabs(rec.y - 0.433f) < 1e-3f && std::fabs(rec.z - 0.150f) < 1e-3f)
      ++no_return;
  CHECK(no_return == 6832);
  CHECK(v.back().t == doctest::Approx(20899.0 / streamclust::livox_horizon.point_rate_hz));
}

TEST_CASE("real frames: lane_detection ascii PCDs (VERSION .7), about 24,000 slots each" *
          needs_livox_data("frames/lane_detection")) {
  const std::uint64_t expected[] = {23986, 23953, 23955, 23960, 23995, 24037};  // the files' POINTS
  for (int id = 1; id <= 6; ++id) {
    const fs::path p = livox_data_dir() / "frames" / "lane_detection" / "lidar" / std::to_string(id) / "1589168946_0.pcd";
    INFO(p.string());
    auto r = io::open_reader(p.string(), rate(streamclust::livox_horizon.point_rate_hz));
    CHECK(r->info().encoding == "ascii");
    const auto v = load(p, rate(streamclust::livox_horizon.point_rate_hz));
    CHECK(v.size() == expected[id - 1]);
  }
}

TEST_CASE("real frames: mid100_campus binary PCDs with WIDTH 0 HEIGHT 0 load POINTS records" *
          needs_livox_data("frames/mid100_campus")) {
  const std::pair<const char*, std::size_t> files[] = {{"1/10.pcd", 240887}, {"2/12.pcd", 246427}, {"2/13.pcd", 253311}};
  for (const auto& [name, count] : files) {
    const fs::path p = livox_data_dir() / "frames" / "mid100_campus" / name;
    INFO(p.string());
    auto r = io::open_reader(p.string(), rate(streamclust::livox_mid40.point_rate_hz));
    CHECK(r->info().encoding == "binary");
    CHECK(r->info().declared_points == count);
    const auto v = load(p, rate(streamclust::livox_mid40.point_rate_hz));
    CHECK(v.size() == count);
    std::size_t nonzero_intensity = 0;
    for (const auto& rec : v) nonzero_intensity += rec.intensity != 0.f;
    CHECK(nonzero_intensity == 0);  // README: intensity all 0
  }
}

TEST_CASE("real frames: horizon_submaps binary PCDs, about 40k points" *
          needs_livox_data("frames/horizon_submaps")) {
  const std::pair<const char*, std::size_t> files[] = {{"source.pcd", 41657}, {"target.pcd", 39783}};
  for (const auto& [name, count] : files) {
    const fs::path p = livox_data_dir() / "frames" / "horizon_submaps" / name;
    INFO(p.string());
    CHECK(load(p, rate(streamclust::livox_horizon.point_rate_hz)).size() == count);
  }
}
