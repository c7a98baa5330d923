// SPDX-License-Identifier: MIT
// `streamclust evaluate --objects` and its peers: the hash-grid Euclidean
// clustering against brute-force single linkage, RANSAC's removal of a
// synthetic plane, the option errors, and short end-to-end runs whose
// metrics are in range and whose objects method passes --verify.

#include <doctest/doctest.h>

#include "cli/euclidean_clusters.hpp"
#include "cli/evaluate_objects.hpp"

#include "support/cli_run.hpp"
#include "support/partition.hpp"
#include "support/temp_dir.hpp"

#include <nlohmann/json.hpp>

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

TEST_CASE("evaluate --objects: short runs score in range and the objects method passes --verify") {
  const streamclust::test::TempDir dir("evaluate_objects", "runs");
  struct Case {
    std::vector<std::string> args;
    bool ceiling;
  };
  const Case cases[] = {
      {{"--sensor", "mid360", "--scene", "office", "--mount", "180,0,0"}, true},
      {{"--sensor", "avia", "--scene", "street", "--mount", "0,15,0", "--speed", "1.5", "--yaw-rate", "0.3"}, false},
      {{"--sensor", "mid360", "--scene", "hills", "--speed", "1.5", "--yaw-rate", "0.3", "--poses", "off"}, false}};
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
    std::ifstream f(json);
    const nlohmann::json doc = nlohmann::json::parse(f);
    CHECK(doc["verify"]["mismatches"].empty());
    CHECK(doc["verify"]["retrievals"].get<int>() == doc["retrievals"].get<int>());
    CHECK(doc["retrievals"].get<int>() >= 6);  // of the 10 at 20 Hz after the first window (engines calibrate first)
    CHECK(doc["scene_has_ceiling"].get<bool>() == c.ceiling);
    REQUIRE(doc["methods"].size() == 4);
    for (const auto& m : doc["methods"]) {
      INFO(m["name"].get<std::string>());
      const auto& mean = m["mean"];
      CHECK(mean["objects"].get<double>() > 0.0);
      for (const char* key : {"ari", "correct", "over_segmented", "under_segmented", "missed", "object_point_coverage",
                              "ground_f1", "ceiling_f1"}) {
        INFO(key);
        CHECK(mean[key].get<double>() >= 0.0);
        CHECK(mean[key].get<double>() <= 1.0);
      }
      CHECK(m["cost_median_ms"].get<double>() > 0.0);
      CHECK(m["cost_p99_ms"].get<double>() >= m["cost_median_ms"].get<double>());
      const std::string name = m["name"].get<std::string>();
      if (name == "carc" || name == "euclidean") {
        // No structure removal: every object point is left to clustering, no point is ground.
        CHECK(mean["object_point_coverage"].get<double>() == 1.0);
        CHECK(mean["ground_f1"].get<double>() == 0.0);
      } else {
        CHECK(mean["ground_f1"].get<double>() > 0.5);
      }
    }
  }
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
  CHECK(euclidean.euclidean_distance == doctest::Approx(0.4f));
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
