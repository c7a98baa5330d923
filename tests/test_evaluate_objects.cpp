// SPDX-License-Identifier: MIT
// `streamclust evaluate --objects` and its peers: the hash-grid Euclidean
// clustering against brute-force single linkage, RANSAC's removal of a
// synthetic plane, the frame pipeline's checked ground and ceiling planes
// (a bigger plane at the wrong height or facing sideways rejected, a ceiling
// removed, in any sensor attitude), the option errors, and short end-to-end
// runs whose metrics are in range and whose objects method passes --verify.

#include <doctest/doctest.h>

#include "cli/euclidean_clusters.hpp"
#include "cli/evaluate_objects.hpp"
#include "cli/structure_planes.hpp"

#include "support/cli_run.hpp"
#include "support/partition.hpp"
#include "support/temp_dir.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace cli = streamclust::cli;

namespace {

using streamclust::test::run_cli;
using streamclust::test::RunResult;

/// Single linkage by definition: a BFS over all pairs at most `radius` apart. O(n^2).
std::vector<int> brute_force_single_linkage(const std::vector<Eigen::Vector3f>& points, float radius) {
  const std::size_t n = points.size();
  std::vector<int> label(n, -1);
  int next = 0;
  std::vector<std::size_t> queue;
  for (std::size_t s = 0; s < n; ++s) {
    if (label[s] >= 0) continue;
    label[s] = next;
    queue.assign(1, s);
    while (!queue.empty()) {
      const std::size_t i = queue.back();
      queue.pop_back();
      for (std::size_t j = 0; j < n; ++j) {
        if (label[j] < 0 && (points[i] - points[j]).squaredNorm() <= radius * radius) {
          label[j] = next;
          queue.push_back(j);
        }
      }
    }
    ++next;
  }
  return label;
}

/// Random points: blobs of various spreads, lines of points about the
/// radius apart, uniform background and exact duplicates.
std::vector<Eigen::Vector3f> random_points(std::mt19937_64& rng, std::size_t n) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Eigen::Vector3f> points;
  const float spread = 0.05f + 0.5f * (u(rng) + 1.0f);
  std::vector<Eigen::Vector3f> centres;
  for (int k = 0; k < 6; ++k) centres.emplace_back(4.0f * u(rng), 4.0f * u(rng), 2.0f * u(rng));
  while (points.size() < n) {
    const auto kind = rng() % 10;
    if (kind < 6) {
      const Eigen::Vector3f& c = centres[rng() % centres.size()];
      points.push_back(c + spread * Eigen::Vector3f(u(rng), u(rng), u(rng)));
    } else if (kind < 8) {
      // A chain with steps near the radius: links that hold or just fail.
      Eigen::Vector3f p(4.0f * u(rng), 4.0f * u(rng), 2.0f * u(rng));
      const Eigen::Vector3f step = Eigen::Vector3f(u(rng), u(rng), u(rng)).normalized() * (0.3f + 0.02f * u(rng));
      for (int k = 0; k < 5 && points.size() < n; ++k, p += step) points.push_back(p);
    } else if (kind < 9) {
      points.emplace_back(6.0f * u(rng), 6.0f * u(rng), 3.0f * u(rng));
    } else if (!points.empty()) {
      points.push_back(points[rng() % points.size()]);
    }
  }
  return points;
}

}  // namespace

TEST_CASE("EuclideanClustering equals brute-force single linkage on random points") {
  for (std::uint64_t seed = 0; seed < 12; ++seed) {
    std::mt19937_64 rng(seed + 11);
    const std::size_t n = 200 + static_cast<std::size_t>(rng() % 1200);
    std::vector<Eigen::Vector3f> points = random_points(rng, n);
    const float radius = seed % 3 == 0 ? 0.3f : (seed % 3 == 1 ? 0.15f : 0.7f);
    if (seed == 5) points.emplace_back(1e7f, -1e7f, 3.0f);  // beyond the cell range: clamped, still exact
    cli::EuclideanClustering clustering(radius);
    const std::vector<std::int64_t> labels = clustering.cluster(points);
    const std::vector<int> expected = brute_force_single_linkage(points, radius);
    INFO("seed " << seed << ", " << points.size() << " points, radius " << radius);
    CHECK(streamclust::test::partition_mismatch(labels, expected) == "");
    // Numbered 0, 1, ... in order of each component's first point.
    std::int64_t next = 0;
    for (const std::int64_t l : labels) {
      REQUIRE(l <= next);
      if (l == next) ++next;
    }
    // A second call on other points reuses the buffers and is still exact.
    points.resize(points.size() / 2);
    CHECK(streamclust::test::partition_mismatch(clustering.cluster(points),
                                                brute_force_single_linkage(points, radius)) == "");
  }
}

TEST_CASE("EuclideanClustering: edge cases and parameter errors") {
  cli::EuclideanClustering clustering(0.3f);
  CHECK(clustering.cluster({}).empty());
  // Within the radius links; beyond it does not.
  const std::vector<Eigen::Vector3f> pair{{0.0f, 0.0f, 0.0f}, {0.25f, 0.0f, 0.0f}, {0.6f, 0.0f, 0.0f}};
  const std::vector<std::int64_t> labels = clustering.cluster(pair);
  CHECK(labels == std::vector<std::int64_t>{0, 0, 1});
  const std::vector<Eigen::Vector3f> with_nan{{0.0f, 0.0f, 0.0f}, {std::nanf(""), 0.0f, 0.0f}, {0.1f, 0.0f, 0.0f}};
  CHECK(clustering.cluster(with_nan) == std::vector<std::int64_t>{0, -1, 0});
  CHECK_THROWS_AS(cli::EuclideanClustering{0.0f}, std::invalid_argument);
  CHECK_THROWS_AS(cli::EuclideanClustering{std::nanf("")}, std::invalid_argument);
}

TEST_CASE("ransac_dominant_plane removes a synthetic plane") {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::normal_distribution<float> noise(0.0f, 0.02f);
  // A tilted plane z = 0.2 x - 0.1 y - 1.2 (the ground under a pitched
  // sensor) and, above it, boxes and scattered points.
  const Eigen::Vector3f normal = Eigen::Vector3f(-0.2f, 0.1f, 1.0f).normalized();
  std::vector<Eigen::Vector3f> points;
  std::vector<bool> on_plane;
  for (int i = 0; i < 3000; ++i) {
    const float x = 10.0f * u(rng), y = 10.0f * u(rng);
    points.emplace_back(x, y, 0.2f * x - 0.1f * y - 1.2f + noise(rng));
    on_plane.push_back(true);
  }
  for (int i = 0; i < 1500; ++i) {
    const float x = 10.0f * u(rng), y = 10.0f * u(rng);
    points.emplace_back(x, y, 0.2f * x - 0.1f * y - 1.2f + 0.5f + 1.5f * (u(rng) + 1.0f));
    on_plane.push_back(false);
  }
  const float distance = 0.1f;
  const cli::PlaneFit fit = cli::ransac_dominant_plane(points, distance, 100, 7);
  REQUIRE(fit.found);
  CHECK(std::abs(std::abs(fit.normal.dot(normal)) - 1.0f) < 0.01f);
  std::size_t plane_kept = 0, others_removed = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool removed = std::abs(fit.normal.dot(points[i]) + fit.offset) <= distance;
    plane_kept += on_plane[i] && !removed ? 1u : 0u;
    others_removed += !on_plane[i] && removed ? 1u : 0u;
  }
  CHECK(plane_kept < 30);  // 5 sigma of the noise is 0.1 m: nearly every plane point goes
  CHECK(others_removed == 0);
  CHECK(fit.inliers >= 2970);
  // Deterministic: the same seed gives the same plane.
  const cli::PlaneFit again = cli::ransac_dominant_plane(points, distance, 100, 7);
  CHECK(again.normal == fit.normal);
  CHECK(again.offset == fit.offset);
  // Degenerate input.
  CHECK_FALSE(cli::ransac_dominant_plane({Eigen::Vector3f(0.0f, 0.0f, 0.0f), Eigen::Vector3f(1.0f, 0.0f, 0.0f)}, distance, 10, 1).found);
  CHECK_THROWS_AS(cli::ransac_dominant_plane(points, 0.0f, 10, 1), std::invalid_argument);
  CHECK_THROWS_AS(cli::ransac_dominant_plane(points, 0.1f, 0, 1), std::invalid_argument);
}

TEST_CASE("classify_structure_planes: the ground at the sensor height, not a bigger plane; a ceiling above") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::normal_distribution<float> noise(0.0f, 0.02f);
  // Level sensor frame: ground 1 m below (4000 points), a platform 0.6 m
  // above the ground (2500), a ceiling 2 m above the sensor (1500) and a
  // box on the ground (500).
  enum Kind { kGroundPoint, kPlatform, kCeilingPoint, kBox };
  std::vector<Eigen::Vector3f> level;
  std::vector<Kind> kind;
  const auto add = [&](int n, Kind k, auto&& point) {
    for (int i = 0; i < n; ++i) {
      level.push_back(point());
      kind.push_back(k);
    }
  };
  add(4000, kGroundPoint, [&] { return Eigen::Vector3f(10.0f * u(rng), 10.0f * u(rng), -1.0f + noise(rng)); });
  add(2500, kPlatform, [&] { return Eigen::Vector3f(13.5f + 1.5f * u(rng), 3.0f * u(rng), -0.4f + noise(rng)); });
  add(1500, kCeilingPoint, [&] { return Eigen::Vector3f(8.0f * u(rng), 8.0f * u(rng), 2.0f + noise(rng)); });
  add(500, kBox, [&] { return Eigen::Vector3f(3.0f + 0.3f * u(rng), 2.0f + 0.3f * u(rng), -0.5f + 0.3f * u(rng)); });

  for (const double pitch_deg : {0.0, 30.0, 180.0}) {
    CAPTURE(pitch_deg);
    // The same scene seen by a sensor pitched (or upside down): points and
    // up in its frame.
    const Eigen::Matrix3f sensor_from_level =
        Eigen::AngleAxisf(static_cast<float>(pitch_deg * 3.14159265358979 / 180.0), Eigen::Vector3f::UnitY())
            .toRotationMatrix();
    std::vector<Eigen::Vector3f> points;
    for (const Eigen::Vector3f& p : level) points.push_back(sensor_from_level * p);
    cli::StructurePlaneChecks checks;
    checks.up = sensor_from_level * Eigen::Vector3f::UnitZ();
    checks.sensor_height = 1.0f;
    std::vector<std::int64_t> labels;
    const cli::StructurePlanes planes = cli::classify_structure_planes(points, 0.1f, 100, 7, checks, true, labels);
    REQUIRE(planes.ground.found);
    CHECK(planes.ground.offset == doctest::Approx(1.0f).epsilon(0.02));
    CHECK(planes.ground.normal.dot(checks.up) > 0.999f);
    REQUIRE(planes.ceiling.found);
    CHECK(-planes.ceiling.offset == doctest::Approx(2.0f).epsilon(0.02));
    std::size_t wrong = 0, ground = 0, ceiling = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const std::int64_t expected = kind[i] == kGroundPoint ? cli::kGroundLabel : kind[i] == kCeilingPoint ? cli::kCeilingLabel : -1;
      wrong += labels[i] != expected ? 1u : 0u;
      ground += labels[i] == cli::kGroundLabel ? 1u : 0u;
      ceiling += labels[i] == cli::kCeilingLabel ? 1u : 0u;
    }
    CHECK(wrong < 5);  // 5 sigma of the noise is 0.1 m
    CHECK(ground >= 3995);
    CHECK(ceiling >= 1495);
    // Deterministic for a seed.
    std::vector<std::int64_t> again;
    cli::classify_structure_planes(points, 0.1f, 100, 7, checks, true, again);
    CHECK(again == labels);
    // Outdoors: no ceiling stage, the ceiling points are left to clustering.
    cli::classify_structure_planes(points, 0.1f, 100, 7, checks, false, labels);
    CHECK(std::count(labels.begin(), labels.end(), cli::kCeilingLabel) == 0);
    CHECK(std::count(labels.begin(), labels.end(), cli::kGroundLabel) >= 3995);
  }

  // A sensor height no plane matches (2 m; the ground is 1 m, the platform
  // 0.4 m below the sensor): no ground removed. Candidates that cross the
  // ground at a slant pass the height check but refit onto the ground.
  cli::StructurePlaneChecks wrong_height;
  wrong_height.sensor_height = 2.0f;
  wrong_height.height_tolerance = 0.3f;
  std::vector<std::int64_t> labels;
  const cli::StructurePlanes none = cli::classify_structure_planes(level, 0.1f, 100, 7, wrong_height, false, labels);
  CHECK_FALSE(none.ground.found);
  CHECK(std::count(labels.begin(), labels.end(), cli::kGroundLabel) == 0);
  // The platform's height (0.4 m below the sensor) finds the platform, not
  // the bigger ground.
  wrong_height.sensor_height = 0.4f;
  wrong_height.height_tolerance = 0.1f;
  const cli::StructurePlanes platform = cli::classify_structure_planes(level, 0.1f, 100, 7, wrong_height, false, labels);
  REQUIRE(platform.ground.found);
  // The plane runs through the platform: its centre (13.5, 0, -0.4) on it
  // within the noise. Its offset at the sensor may differ by a few
  // centimetres: the box's top slab can join the inliers and tilt the refit.
  CHECK(std::abs(platform.ground.normal.dot(Eigen::Vector3f(13.5f, 0.0f, -0.4f)) + platform.ground.offset) < 0.05f);
  CHECK(platform.ground.normal.z() > 0.999f);
  CHECK(std::count(labels.begin(), labels.end(), cli::kGroundLabel) >= 2495);
  // A ceiling needs min_ceiling_points inliers.
  cli::StructurePlaneChecks strict;
  strict.min_ceiling_points = 1600;
  CHECK_FALSE(cli::classify_structure_planes(level, 0.1f, 100, 7, strict, true, labels).ceiling.found);

  // A wall (the dominant plane, which the plain RANSAC takes) is no ground.
  std::vector<Eigen::Vector3f> walled(level.begin(), level.begin() + 4000);  // the ground alone
  for (int i = 0; i < 6000; ++i) walled.emplace_back(-11.0f + noise(rng), 10.0f * u(rng), 0.5f + 1.5f * u(rng));
  const cli::PlaneFit dominant = cli::ransac_dominant_plane(walled, 0.1f, 100, 3);
  REQUIRE(dominant.found);
  CHECK(std::abs(dominant.normal.x()) > 0.99f);
  const cli::StructurePlanes checked = cli::classify_structure_planes(walled, 0.1f, 100, 7, {}, true, labels);
  REQUIRE(checked.ground.found);
  CHECK(checked.ground.offset == doctest::Approx(1.0f).epsilon(0.02));
  CHECK_FALSE(checked.ceiling.found);  // the wall's slices are too steep

  cli::StructurePlaneChecks bad;
  bad.up = Eigen::Vector3f(0.0f, 0.0f, 2.0f);
  CHECK_THROWS_AS(cli::classify_structure_planes(level, 0.1f, 100, 7, bad, true, labels), std::invalid_argument);
  bad = cli::StructurePlaneChecks{};
  bad.max_tilt_deg = 90.0f;
  CHECK_THROWS_AS(cli::classify_structure_planes(level, 0.1f, 100, 7, bad, true, labels), std::invalid_argument);
  CHECK_THROWS_AS(cli::classify_structure_planes(level, 0.0f, 100, 7, {}, true, labels), std::invalid_argument);
  CHECK_THROWS_AS(cli::classify_structure_planes(level, 0.1f, 0, 7, {}, true, labels), std::invalid_argument);
}

TEST_CASE("evaluate --objects: option errors and help") {
  const auto code = [](std::vector<std::string> args) {
    args.insert(args.begin(), {"evaluate", "--objects"});
    return run_cli(args).code;
  };
  CHECK(code({"--sensor", "spinning32"}) == 2);
  CHECK(code({"--sensor", "synthetic", "--scene", "room"}) == 2);
  CHECK(code({"--poses", "maybe"}) == 2);
  CHECK(code({"--method", "objects,pcl"}) == 2);
  CHECK(code({"--method", "carc", "--verify"}) == 2);
  CHECK(code({"--duration", "0.5"}) == 2);  // no retrieval after a 0.5 s window
  CHECK(code({"--height", "-1"}) == 2);
  CHECK(code({"--mount", "0,30"}) == 2);
  CHECK(code({"--burst", "1:0.3"}) == 2);
  CHECK(code({"--distance", "0"}) == 2);
  CHECK(code({"--euclidean-distances", "0.3,0"}) == 2);
  CHECK(code({"--frame-distances", ""}) == 2);
  CHECK(code({"--plane-distance", "0.1,20"}) == 2);
  CHECK(code({"--frame-ceiling", "maybe"}) == 2);
  CHECK(code({"--frame-max-tilt", "90"}) == 2);
  CHECK(code({"--frame-height-tolerance", "-0.1"}) == 2);
  CHECK(code({"--no-such-option"}) == 2);
  const RunResult bad = run_cli({"evaluate", "--objects", "--scene", "moon"});
  CHECK(bad.code == 2);
  CHECK(bad.err.find("--scene") != std::string::npos);
  const RunResult help = run_cli({"evaluate", "--objects", "--help"});
  CHECK(help.code == 0);
  CHECK(help.out.find("--poses on|off") != std::string::npos);
  CHECK(run_cli({"evaluate", "--help"}).out.find("--objects") != std::string::npos);

  // The parsed options.
  const cli::EvaluateObjectsOptions o = cli::parse_evaluate_objects_options(
      {"--sensor", "avia", "--mount", "180,0,0", "--velocity", "1.5", "--poses", "off", "--method", "objects,frame"});
  CHECK(o.scenario.speed == doctest::Approx(1.5));
  CHECK_FALSE(o.poses);
  CHECK(o.run_objects);
  CHECK(o.run_frame);
  CHECK_FALSE(o.run_carc);
  CHECK(o.scenario.seconds == doctest::Approx(3.0));
  CHECK(cli::effective_height(o) == doctest::Approx(2.5f));  // upside down: under a ceiling or on a mast
  CHECK(cli::effective_height(cli::parse_evaluate_objects_options({})) == doctest::Approx(1.0f));
  CHECK(cli::effective_height(cli::parse_evaluate_objects_options({"--height", "1.7"})) == doctest::Approx(1.7f));
}

TEST_CASE("evaluate --objects: short runs score in range and the objects method passes --verify" *
          doctest::test_suite("slow")) {
  const streamclust::test::TempDir dir("evaluate_objects", "runs");
  struct Case {
    std::vector<std::string> args;
    bool ceiling, wall;
  };
  const Case cases[] = {
      {{"--sensor", "mid360", "--scene", "office", "--mount", "180,0,0"}, true, true},
      {{"--sensor", "avia", "--scene", "street", "--mount", "0,15,0", "--speed", "1.5", "--yaw-rate", "0.3"}, false, true},
      {{"--sensor", "mid360", "--scene", "hills", "--speed", "1.5", "--yaw-rate", "0.3", "--poses", "off"}, false, false}};
  int k = 0;
  for (const Case& c : cases) {
    const std::string json = dir.path("run" + std::to_string(k++) + ".json");
    std::vector<std::string> args{"evaluate", "--objects", "--duration", "0.75", "--window-time", "0.25", "--verify",
                                  "--json", json};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const RunResult r = run_cli(args);
    INFO(r.out << r.err);
    REQUIRE(r.code == 0);
    CHECK(r.out.find("equals the batch partition") != std::string::npos);
    CHECK((r.out.find("ceiling F1") != std::string::npos) == c.ceiling);
    CHECK((r.out.find("wall recall") != std::string::npos) == c.wall);
    CHECK(r.out.find("coverage >= 30 m") != std::string::npos);
    std::ifstream f(json);
    const nlohmann::json doc = nlohmann::json::parse(f);
    CHECK(doc["verify"]["mismatches"].empty());
    CHECK(doc["verify"]["retrievals"].get<int>() == doc["retrievals"].get<int>());
    CHECK(doc["retrievals"].get<int>() >= 6);  // of the 10 at 20 Hz after the first window (engines calibrate first)
    CHECK(doc["scene_has_ceiling"].get<bool>() == c.ceiling);
    CHECK(doc["scene_has_wall"].get<bool>() == c.wall);
    REQUIRE(doc["methods"].size() == 4);
    for (const auto& m : doc["methods"]) {
      INFO(m["name"].get<std::string>());
      const auto& mean = m["mean"];
      CHECK(mean["objects"].get<double>() > 0.0);
      for (const char* key : {"ari", "correct", "over_segmented", "under_segmented", "missed", "object_point_coverage",
                              "ground_f1", "ceiling_f1", "wall_precision", "wall_recall", "wall_f1"}) {
        INFO(key);
        CHECK(mean[key].get<double>() >= 0.0);
        CHECK(mean[key].get<double>() <= 1.0);
      }
      // Coverage per range band: three bands whose points add up, each kept share in [0, 1].
      const auto& bands = m["object_point_coverage_by_range"];
      REQUIRE(bands.size() == 3);
      CHECK(bands[0]["from_m"].get<double>() == 0.0);
      CHECK(bands[2]["to_m"].is_null());
      double points = 0.0;
      for (const auto& band : bands) {
        CHECK(band["kept"].get<double>() <= band["object_points"].get<double>());
        CHECK(band["coverage"].get<double>() >= 0.0);
        CHECK(band["coverage"].get<double>() <= 1.0);
        points += band["object_points"].get<double>();
      }
      CHECK(points > 0.0);
      CHECK(m["cost_median_ms"].get<double>() > 0.0);
      CHECK(m["cost_p99_ms"].get<double>() >= m["cost_median_ms"].get<double>());
      const std::string name = m["name"].get<std::string>();
      if (name == "carc" || name == "euclidean") {
        // No structure removal: every object point is left to clustering, no point is ground.
        CHECK(mean["object_point_coverage"].get<double>() == 1.0);
        CHECK(mean["ground_f1"].get<double>() == 0.0);
        for (const auto& band : bands) CHECK(band["coverage"].get<double>() == 1.0);
      } else {
        CHECK(mean["ground_f1"].get<double>() > 0.5);
      }
    }
  }
}

TEST_CASE("evaluate --objects: swept peer settings run as one method each, in one run") {
  const streamclust::test::TempDir dir("evaluate_objects", "sweep");
  const std::string json = dir.path("sweep.json");
  const RunResult r =
      run_cli({"evaluate", "--objects", "--scene", "office", "--mount", "0,30,0", "--duration", "0.5",
               "--window-time", "0.2", "--rate", "10", "--method", "euclidean,frame", "--euclidean-distances",
               "0.3,0.5", "--frame-distances", "0.4", "--plane-distance", "0.1,0.2", "--json", json, "-q"});
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  std::ifstream f(json);
  const nlohmann::json doc = nlohmann::json::parse(f);
  std::vector<std::string> names;
  for (const auto& m : doc["methods"]) names.push_back(m["name"].get<std::string>());
  CHECK(names == std::vector<std::string>{"euclidean@0.3", "euclidean@0.5", "frame@0.1/0.4", "frame@0.2/0.4"});
  CHECK(doc["methods"][1]["settings"]["distance"].get<double>() == doctest::Approx(0.5));
  CHECK(doc["methods"][3]["settings"]["plane_distance"].get<double>() == doctest::Approx(0.2));
  // Another radius, another partition; another tolerance, another ground.
  CHECK(doc["methods"][0]["mean"]["ari"] != doc["methods"][1]["mean"]["ari"]);
  CHECK(doc["methods"][2]["mean"]["ground_f1"] != doc["methods"][3]["mean"]["ground_f1"]);
  CHECK(doc["settings"]["plane_distances"].size() == 2);
}

TEST_CASE("evaluate --objects --linkage: the objects preset with another registered linkage") {
  // Parsing: the preset's linkage by default, any registered one by name,
  // its options into its Params; --distance is the peers' radius and the
  // euclidean linkage's.
  const cli::EvaluateObjectsOptions preset = cli::parse_evaluate_objects_options({});
  CHECK(preset.linkage == "range-adaptive");
  const cli::EvaluateObjectsOptions euclidean =
      cli::parse_evaluate_objects_options({"--linkage", "euclidean", "--distance", "0.4", "--min-distance", "0.3"});
  CHECK(euclidean.linkage == "euclidean");
  REQUIRE(euclidean.euclidean_distances.size() == 1);
  CHECK(euclidean.euclidean_distances[0] == doctest::Approx(0.4f));
  CHECK(euclidean.frame_distances == euclidean.euclidean_distances);
  CHECK(euclidean.linkage_params.get<streamclust::EuclideanLinkage>().max_distance == doctest::Approx(0.4f));
  CHECK(euclidean.linkage_params.get<streamclust::RangeAdaptiveLinkage>().min_distance == doctest::Approx(0.3f));
  CHECK(preset.linkage_params.get<streamclust::RangeAdaptiveLinkage>().min_distance ==
        streamclust::objects_mid360_params().linkage.min_distance);

  const RunResult unknown = run_cli({"evaluate", "--objects", "--linkage", "nearest"});
  CHECK(unknown.code == 2);
  CHECK(unknown.err.find("--linkage: expected angular|euclidean|range-adaptive|scan-adaptive, got 'nearest'") != std::string::npos);
  const RunResult bad_value = run_cli({"evaluate", "--objects", "--linkage", "angular", "--theta", "x"});
  CHECK(bad_value.code == 2);
  CHECK(bad_value.err.find("--theta: expected a number, got 'x'") != std::string::npos);
  CHECK(run_cli({"evaluate", "--objects", "--cap", "3"}).code == 2);  // not a linkage's option
  CHECK(run_cli({"evaluate", "--objects", "--help"}).out.find("--linkage angular|euclidean|range-adaptive") !=
        std::string::npos);

  // Runs: each linkage's partition equals the batch partition of the
  // same configuration, and the report names the linkage and its values.
  const streamclust::test::TempDir dir("evaluate_objects", "linkage");
  const auto run = [&](const std::string& name, std::vector<std::string> linkage) {
    const std::string json = dir.path(name + ".json");
    std::vector<std::string> args{"evaluate", "--objects", "--duration", "0.75", "--window-time", "0.25",
                                  "--method",  "objects",   "--verify",   "--json", json};
    args.insert(args.end(), linkage.begin(), linkage.end());
    const RunResult r = run_cli(args);
    INFO(r.out << r.err);
    REQUIRE(r.code == 0);
    CHECK(r.out.find("equals the batch partition") != std::string::npos);
    std::ifstream f(json);
    return nlohmann::json::parse(f);
  };
  const nlohmann::json by_preset = run("preset", {});
  const nlohmann::json by_euclidean = run("euclidean", {"--linkage", "euclidean", "--distance", "0.25"});
  CHECK(by_preset["settings"]["linkage"] == "range-adaptive");
  CHECK(by_preset["settings"]["linkage_parameters"]["min_distance"].get<double>() ==
        doctest::Approx(streamclust::objects_mid360_params().linkage.min_distance));
  CHECK(by_euclidean["settings"]["linkage"] == "euclidean");
  CHECK(by_euclidean["settings"]["linkage_parameters"]["distance"].get<double>() == doctest::Approx(0.25));
  CHECK(by_euclidean["settings"]["linkage_parameters"].size() == 1);
  // The same stream and structure removal, another partition of the objects.
  CHECK(by_euclidean["retrievals"] == by_preset["retrievals"]);
  CHECK(by_euclidean["methods"][0]["mean"]["ground_f1"] == by_preset["methods"][0]["mean"]["ground_f1"]);
  CHECK(by_euclidean["methods"][0]["mean"]["ari"] != by_preset["methods"][0]["mean"]["ari"]);
}
