// SPDX-License-Identifier: MIT
// The range-adaptive linkage in the `streamclust` tool, run in-process: the
// options reach RangeAdaptiveLinkage's Params, `cluster` runs the compiled
// configuration (verified against the batch clusterer), `evaluate` records
// the choice, and bad values are usage errors naming the parameter.

#include <doctest/doctest.h>

#include "cli/engine_config.hpp"
#include "cli/main.hpp"
#include "cli/options.hpp"

#include <streamclust/linkage/range_adaptive.hpp>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace sc = streamclust;

namespace {

using streamclust::test::run_cli;
using streamclust::test::slurp;

/// The label column of a `--labels` file, row by row.
std::vector<std::string> label_column(const std::string& path) {
  std::istringstream in(slurp(path));
  std::string line;
  std::getline(in, line);  // header
  std::vector<std::string> labels;
  while (std::getline(in, line)) labels.push_back(line.substr(line.rfind(',') + 1));
  return labels;
}

/// Number of distinct labels in a label column.
std::size_t distinct(const std::vector<std::string>& labels) {
  std::map<std::string, int> seen;
  for (const auto& l : labels) seen[l] = 1;
  return seen.size();
}

}  // namespace

TEST_CASE("CLI: --linkage range-adaptive and its parameters reach RangeAdaptiveLinkage::Params") {
  using Config = sc::cli::CliConfig<sc::SphericalProjection, sc::BucketGrid, sc::RangeAdaptiveLinkage, sc::TimeWindow>;
  const sc::cli::ClusterOptions defaults = sc::cli::parse_cluster_options({"in.csv", "--linkage", "range-adaptive"});
  CHECK(defaults.linkage == "range-adaptive");
  const sc::RangeAdaptiveLinkage::Params library{};
  CHECK(sc::cli::make_params<Config>(defaults).linkage.min_distance == library.min_distance);
  CHECK(sc::cli::make_params<Config>(defaults).linkage.range_factor == library.range_factor);
  const sc::cli::ClusterOptions o = sc::cli::parse_cluster_options(
      {"in.csv", "--range-factor", "0.04", "--linkage", "range-adaptive", "--min-distance", "0.35"});
  const auto p = sc::cli::make_params<Config>(o);
  CHECK(p.linkage.min_distance == 0.35f);
  CHECK(p.linkage.range_factor == 0.04f);
  CHECK(sc::cli::parse_cluster_options({"in.csv", "--linkage", "euclidean"}).linkage == "euclidean");
  CHECK(sc::cli::parse_cluster_options({"in.csv", "--linkage", "angular"}).linkage == "angular");
}

TEST_CASE("CLI: cluster --linkage range-adaptive is verified, and its parameters change the partition") {
  const sc::test::TempDir tmp("linkage_cli", "cluster");
  const std::string stream = tmp.path("street.pcd");
  const auto sim =
      run_cli({"simulate", "--sensor", "mid360", "--scene", "street", "--seconds", "0.3", "--out", stream, "--quiet"});
  REQUIRE(sim.code == 0);
  const auto cluster = [&](std::vector<std::string> extra, const std::string& labels) {
    std::vector<std::string> args = {"cluster", stream, "--preset", "carc-mid360", "--window-time", "0.1", "--verify",
                                     "--labels", labels, "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_cli(args);
  };
  for (const char* connectivity : {"forest", "lazy-bfs"}) {
    for (const char* index : {"bucket", "capped"}) {
      INFO(connectivity << ", " << index);
      const auto r = cluster({"--linkage", "range-adaptive", "--connectivity", connectivity, "--index", index},
                             tmp.path("a.csv"));
      INFO(r.err);
      CHECK(r.code == 0);  // 3 would be a retrieval that differs from the batch clusterer
    }
  }
  // range factor 0 is a fixed radius of min_distance: the Euclidean linkage's partition
  REQUIRE(cluster({"--linkage", "range-adaptive", "--range-factor", "0", "--min-distance", "0.3"}, tmp.path("f.csv"))
              .code == 0);
  REQUIRE(cluster({"--linkage", "euclidean", "--distance", "0.3"}, tmp.path("e.csv")).code == 0);
  REQUIRE(cluster({"--linkage", "range-adaptive"}, tmp.path("d.csv")).code == 0);
  const auto fixed = label_column(tmp.path("f.csv"));
  const auto euclidean = label_column(tmp.path("e.csv"));
  const auto adaptive = label_column(tmp.path("d.csv"));
  REQUIRE(fixed.size() > 1000);
  CHECK(fixed == euclidean);
  // the growing radius joins the far street's fragments: fewer components
  CHECK(adaptive.size() == fixed.size());
  CHECK(distinct(adaptive) < distinct(fixed));
}

TEST_CASE("CLI: evaluate --linkage range-adaptive records the linkage; bad values are usage errors") {
  const sc::test::TempDir tmp("linkage_cli", "evaluate");
  const std::string json = tmp.path("e.json");
  const auto r = run_cli({"evaluate", "--sensor", "avia", "--scene", "office", "--duration", "0.3", "--linkage",
                          "range-adaptive", "--min-distance", "0.25", "--range-factor", "0.04", "--json", json});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("linkage range-adaptive max(0.25 m, 0.04 x range)") != std::string::npos);
  const nlohmann::json doc = nlohmann::json::parse(slurp(json));
  CHECK(doc["policy"]["linkage"] == "range-adaptive");
  CHECK(doc["policy"]["min_distance"].get<double>() == doctest::Approx(0.25));
  CHECK(doc["policy"]["range_factor"].get<double>() == doctest::Approx(0.04));
  CHECK(doc["methods"].size() == 2);  // C-ARC and the baseline, both with the linkage
  const auto bad_factor = run_cli({"evaluate", "--duration", "0.3", "--linkage", "range-adaptive", "--range-factor",
                                   "1.5", "--quiet"});
  CHECK(bad_factor.code == 2);
  CHECK(bad_factor.err.find("range_factor = 1.5") != std::string::npos);
  const auto bad_distance = run_cli({"cluster", "in.csv", "--linkage", "range-adaptive", "--min-distance", "0"});
  CHECK(bad_distance.code == 2);
  CHECK(bad_distance.err.find("--min-distance") != std::string::npos);
  const auto bad_name = run_cli({"cluster", "in.csv", "--linkage", "range"});
  CHECK(bad_name.code == 2);
  CHECK(bad_name.err.find("angular|euclidean|range-adaptive") != std::string::npos);
  CHECK(run_cli({"cluster", "--help"}).out.find("--range-factor") != std::string::npos);
}
