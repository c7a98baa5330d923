// SPDX-License-Identifier: MIT
// The scan-adaptive linkage in the `streamclust` tool, run in-process: the
// tool fits it to the input's first window (and the mount) before the run,
// `cluster` and `evaluate --objects` are verified against the batch
// clusterer, `evaluate` runs it, its options change the partition, and bad
// values are usage errors naming the parameter.

#include <doctest/doctest.h>

#include "cli/options.hpp"

#include <streamclust/linkage/scan_adaptive.hpp>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace sc = streamclust;

namespace {

using streamclust::test::run_cli;
using streamclust::test::slurp;

/// Distinct values of the label column of a `--labels` file.
std::size_t distinct_labels(const std::string& path) {
  std::istringstream in(slurp(path));
  std::string line;
  std::getline(in, line);  // header
  std::set<std::string> seen;
  while (std::getline(in, line)) seen.insert(line.substr(line.rfind(',') + 1));
  return seen.size();
}

}  // namespace

TEST_CASE("CLI: --linkage scan-adaptive options reach ScanAdaptiveLinkage::Params") {
  const sc::cli::ClusterOptions o = sc::cli::parse_cluster_options(
      {"in.csv", "--linkage", "scan-adaptive", "--spacing-factor", "5", "--spacing-quantile", "0.8", "--min-distance",
       "0.3"});
  CHECK(o.linkage == "scan-adaptive");
  const auto& p = o.params.get<sc::ScanAdaptiveLinkage>();
  CHECK(p.spacing_factor == doctest::Approx(5.0f));
  CHECK(p.spacing_quantile == doctest::Approx(0.8f));
  CHECK(p.min_distance == doctest::Approx(0.3f));
  CHECK(!p.spacing);  // the table comes from the first window at run time
  CHECK(run_cli({"cluster", "--help"}).out.find("--spacing-factor") != std::string::npos);
}

TEST_CASE("CLI: cluster --linkage scan-adaptive is fitted to the first window and verified") {
  const sc::test::TempDir tmp("linkage_scan_cli", "cluster");
  const std::string stream = tmp.path("street.pcd");
  REQUIRE(run_cli({"simulate", "--sensor", "mid360", "--scene", "street", "--seconds", "0.8", "--out", stream,
                   "--quiet"})
              .code == 0);
  const auto cluster = [&](std::vector<std::string> extra, const std::string& labels) {
    std::vector<std::string> args = {"cluster", stream,     "--preset", "objects-mid360", "--linkage", "scan-adaptive",
                                     "--verify", "--labels", labels,     "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_cli(args);
    INFO(r.err);
    return r.code;  // 3 would be a retrieval that differs from the batch clusterer
  };
  CHECK(cluster({"--spacing-factor", "1", "--min-distance", "0.1"}, tmp.path("tight.csv")) == 0);
  CHECK(cluster({"--spacing-factor", "12", "--min-distance", "0.1"}, tmp.path("wide.csv")) == 0);
  // A wider radius joins fragments: fewer clusters.
  CHECK(distinct_labels(tmp.path("wide.csv")) < distinct_labels(tmp.path("tight.csv")));
  // With a mount the table is read in the sensor frame, the points placed in the world.
  CHECK(cluster({"--mount", "0,10,0", "--sensor-height", "1"}, tmp.path("mounted.csv")) == 0);
}

TEST_CASE("CLI: evaluate --objects and evaluate with --linkage scan-adaptive") {
  const sc::test::TempDir tmp("linkage_scan_cli", "evaluate");
  const std::string json = tmp.path("objects.json");
  const auto objects =
      run_cli({"evaluate", "--objects", "--sensor", "avia", "--scene", "street", "--duration", "0.75", "--window-time",
               "0.25", "--method", "objects", "--speed", "1.5", "--yaw-rate", "0.3", "--poses", "on", "--verify",
               "--linkage", "scan-adaptive", "--spacing-factor", "3", "--json", json});
  INFO(objects.out << objects.err);
  REQUIRE(objects.code == 0);
  CHECK(objects.out.find("equals the batch partition") != std::string::npos);
  CHECK(objects.out.find("linkage scan-adaptive max(0.4 m, 3 x spacing x range)") != std::string::npos);
  const nlohmann::json doc = nlohmann::json::parse(slurp(json));
  CHECK(doc["settings"]["linkage"] == "scan-adaptive");
  CHECK(doc["settings"]["linkage_parameters"]["spacing_factor"].get<double>() == doctest::Approx(3.0));

  const auto carc = run_cli({"evaluate", "--sensor", "mid360", "--scene", "office", "--duration", "0.3", "--linkage",
                             "scan-adaptive", "--quiet"});
  INFO(carc.err);
  CHECK(carc.code == 0);
}

TEST_CASE("CLI: bad scan-adaptive values are usage errors naming the parameter") {
  const sc::test::TempDir tmp("linkage_scan_cli", "errors");
  const std::string stream = tmp.path("office.pcd");
  REQUIRE(run_cli({"simulate", "--sensor", "avia", "--scene", "office", "--seconds", "0.2", "--out", stream, "--quiet"})
              .code == 0);
  const auto factor = run_cli({"cluster", stream, "--linkage", "scan-adaptive", "--spacing-factor", "2000", "--quiet"});
  CHECK(factor.code == 2);
  CHECK(factor.err.find("spacing_factor = 2000") != std::string::npos);
  const auto quantile =
      run_cli({"cluster", stream, "--linkage", "scan-adaptive", "--spacing-quantile", "1.5", "--quiet"});
  CHECK(quantile.code == 2);
  CHECK(quantile.err.find("quantile = 1.5") != std::string::npos);
}
