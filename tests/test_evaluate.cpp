// SPDX-License-Identifier: MIT
// `streamclust evaluate`, run in-process: its metrics against the library
// computing them directly on the same simulated stream (the oracle), the
// baseline's coverage loss on a coarse grid, the ego-motion burst's merge and
// recovery, and the usage errors. The helpers QualityAverage and
// recovery_after are checked on hand-made input.

#include <doctest/doctest.h>

#include "cli/main.hpp"

#include <streamclust/eval/average.hpp>
#include <streamclust/eval/labelled_subset.hpp>
#include <streamclust/eval/recovery.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/sensors/risley_pair_model.hpp>
#include <streamclust/sim/simulator.hpp>
#include <streamclust/streamclust.hpp>

#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace sc = streamclust;

namespace {

using streamclust::test::run_cli;
using streamclust::test::RunResult;
using streamclust::test::slurp;

/// One retrieval of the JSON output: its time and metrics by name.
struct JsonCycle {
  double time = 0.0;
  std::size_t window = 0;
  std::map<std::string, double> q;
  double ari_labelled = -2.0, pq_labelled = -2.0;  ///< -2 when absent or null
};

/// What the tests read back from `evaluate --json` (one member of a method and one cycle per line by contract).
struct JsonEvaluation {
  std::uint32_t rows = 0, cols = 0;
  std::map<std::string, std::map<std::string, double>> mean;  ///< method -> metric -> value
  std::map<std::string, std::map<std::string, double>> mean_labelled;  ///< method -> metric on the baseline-labelled points
  std::map<std::string, std::vector<JsonCycle>> cycles;       ///< method -> retrievals
  std::map<std::string, std::string> recovery_line;           ///< method -> its "recovery" JSON
};

std::map<std::string, double> parse_metrics(const std::string& text) {
  std::map<std::string, double> m;
  static const std::regex kv("\"([a-z_]+)\": (-?[0-9.eE+-]+)");
  for (std::sregex_iterator it(text.begin(), text.end(), kv), end; it != end; ++it) {
    m[(*it)[1].str()] = std::stod((*it)[2].str());
  }
  return m;
}

JsonEvaluation parse_evaluation(const std::string& json) {
  JsonEvaluation e;
  std::smatch m;
  REQUIRE(std::regex_search(json, m, std::regex("\"grid\": \\{\"rows\": ([0-9]+), \"cols\": ([0-9]+)")));
  e.rows = static_cast<std::uint32_t>(std::stoul(m[1].str()));
  e.cols = static_cast<std::uint32_t>(std::stoul(m[2].str()));
  std::istringstream lines(json);
  std::string line, method;
  static const std::regex name_re("\"name\": \"([a-z]+)\"");
  static const std::regex mean_re("\"mean\": \\{(.*)\\}");
  static const std::regex labelled_re("\"ari_labelled\": ([-0-9.eE+]+), \"pq_labelled\": ([-0-9.eE+]+)");
  static const std::regex mean_labelled_re("\"mean_on_baseline_labelled\": \\{(.*)\\}");
  static const std::regex cycle_re("\\{\"time\": ([-0-9.eE+]+), \"window\": ([0-9]+), .*\"quality\": \\{(.*)\\}\\}");
  while (std::getline(lines, line)) {
    if (std::regex_search(line, m, name_re)) method = m[1].str();
    if (line.find("\"recovery\"") != std::string::npos) e.recovery_line[method] = line;
    if (std::regex_search(line, m, cycle_re)) {
      JsonCycle c;
      c.time = std::stod(m[1].str());
      c.window = std::stoul(m[2].str());
      c.q = parse_metrics(m[3].str());
      if (std::regex_search(line, m, labelled_re)) {
        c.ari_labelled = std::stod(m[1].str());
        c.pq_labelled = std::stod(m[2].str());
      }
      e.cycles[method].push_back(c);
    } else if (std::regex_search(line, m, mean_labelled_re)) {
      e.mean_labelled[method] = parse_metrics(m[1].str());
    } else if (std::regex_search(line, m, mean_re)) {
      e.mean[method] = parse_metrics(m[1].str());
    }
  }
  return e;
}

/// C-ARC through the library's own types, on a fixed grid (the continuous
/// engine), for the oracle.
struct OracleConfig : sc::CArcFixedConfig {};

}  // namespace

TEST_CASE("evaluate: JSON metrics equal the library's on the same simulated stream") {
  const sc::test::TempDir dir("evaluate", "evaluate_oracle");
  const std::string json = dir.path("e.json");
  const auto r = run_cli({"evaluate", "--sensor", "mid40", "--scene", "office", "--duration", "0.45", "--seed", "3",
                      "--theta", "10", "--mask", "3", "--window-time", "0.1", "--json", json});
  REQUIRE_MESSAGE(r.code == 0, r.err);
  CHECK(r.out.find("ARI (object points)") != std::string::npos);
  const JsonEvaluation e = parse_evaluation(slurp(json));

  // The same stream, straight from the simulator.
  sc::sim::Simulator<sc::sim::RisleyPairModel>::Params sp;  // defaults = evaluate's: noise 0.02, max range 40
  sp.seed = 3;
  sc::sim::Simulator<sc::sim::RisleyPairModel> simulator(sc::sim::RisleyPairModel::mid40(), sc::sim::office_scene(3), sp);
  std::vector<sc::sim::SimPoint> stream;
  while (simulator.time() < 0.45) stream.push_back(simulator.next());

  sc::SphericalProjection::Params fov;  // evaluate's Mid-40 FOV
  fov.azimuth_min_deg = sc::livox_mid40.projection_azimuth_min_deg();
  fov.azimuth_max_deg = sc::livox_mid40.projection_azimuth_max_deg();
  fov.elevation_min_deg = sc::livox_mid40.projection_elevation_min_deg();
  fov.elevation_max_deg = sc::livox_mid40.projection_elevation_max_deg();

  // The grid is the adaptive loop's choice on the first window.
  sc::ClustererParams<sc::CArcConfig> adaptive;
  adaptive.projection = fov;
  adaptive.mask_size = 3;
  adaptive.window.duration = 0.1;
  sc::StreamClusterer<sc::CArcConfig> calibrating(adaptive);
  for (const auto& p : stream) {
    calibrating.insert(p, p.t);
    if (!calibrating.calibrating()) break;
  }
  REQUIRE_FALSE(calibrating.calibrating());
  CHECK(calibrating.grid().rows == e.rows);
  CHECK(calibrating.grid().cols == e.cols);

  // Every retrieval (20 Hz, the first window skipped), scored directly.
  sc::ClustererParams<OracleConfig> fixed;
  fixed.projection = fov;
  fixed.mask_size = 3;
  fixed.window.duration = 0.1;
  fixed.resolution = {e.rows, e.cols};
  sc::StreamClusterer<OracleConfig> engine(fixed);
  sc::ClustererParams<sc::FrameBaselineConfig> base;
  base.projection = fov;
  base.mask_size = 3;
  sc::BatchClusterer<sc::FrameBaselineConfig> baseline(base, sc::BatchMode::range_image);
  baseline.set_grid({e.rows, e.cols});
  sc::eval::MetricOptions options;
  options.min_points = 10;  // evaluate's default

  std::vector<sc::eval::MeanQuality> carc, frame, carc_labelled, frame_labelled;
  std::vector<double> times;
  const double first = stream.front().t;
  const double period = 0.05;
  double k = 1.0;
  for (const auto& p : stream) {
    if (p.t >= first + k * period) {
      const double t = first + k * period;
      k += 1.0;
      engine.advance_to(t);
      const sc::Clustering& c = engine.retrieve();
      if (t - first < 0.1 - 1e-9) {
        engine.insert(p, p.t);
        continue;
      }
      std::vector<std::int64_t> truth, predicted;
      std::vector<sc::Sample> window;
      for (const sc::PointLabel& pl : c.points) {
        truth.push_back(stream[pl.stream_index].instance);
        predicted.push_back(static_cast<std::int64_t>(pl.label));
      }
      engine.for_each_point([&](const sc::Sample& s, std::uint64_t) { window.push_back(s); });
      times.push_back(t);
      const std::vector<std::int64_t> base_labels = baseline.cluster(window).labels;
      carc.push_back(sc::eval::to_mean_quality(sc::eval::evaluate(truth, predicted, options)));
      frame.push_back(sc::eval::to_mean_quality(sc::eval::evaluate(truth, base_labels, options)));
      // Both on the points the baseline labelled (same window, same order).
      carc_labelled.push_back(sc::eval::to_mean_quality(sc::eval::evaluate_on_labelled(truth, predicted, base_labels, options)));
      frame_labelled.push_back(sc::eval::to_mean_quality(sc::eval::evaluate_on_labelled(truth, base_labels, base_labels, options)));
    }
    engine.insert(p, p.t);
  }
  REQUIRE(e.cycles.count("carc") == 1);
  REQUIRE(e.cycles.count("baseline") == 1);
  REQUIRE(e.cycles.at("carc").size() == carc.size());
  REQUIRE(e.cycles.at("baseline").size() == frame.size());
  REQUIRE(carc.size() >= 6);
  const char* names[] = {"ari", "ose", "use", "pq", "precision", "recall", "coverage", "object_coverage",
                         "correct", "over_segmented", "under_segmented", "missed"};
  double const sc::eval::MeanQuality::*fields[] = {
      &sc::eval::MeanQuality::ari,          &sc::eval::MeanQuality::ose,
      &sc::eval::MeanQuality::use,          &sc::eval::MeanQuality::pq,
      &sc::eval::MeanQuality::precision,    &sc::eval::MeanQuality::recall,
      &sc::eval::MeanQuality::coverage,     &sc::eval::MeanQuality::object_coverage,
      &sc::eval::MeanQuality::correct,      &sc::eval::MeanQuality::over_segmented,
      &sc::eval::MeanQuality::under_segmented, &sc::eval::MeanQuality::missed};
  sc::eval::QualityAverage carc_mean, carc_labelled_mean, frame_labelled_mean;
  for (std::size_t i = 0; i < carc.size(); ++i) {
    const JsonCycle& jc = e.cycles.at("carc")[i];
    const JsonCycle& jb = e.cycles.at("baseline")[i];
    CHECK(jc.time == doctest::Approx(times[i]).epsilon(1e-9));
    CHECK(jc.window == static_cast<std::size_t>(carc[i].points));
    for (std::size_t f = 0; f < 12; ++f) {
      CAPTURE(i);
      CAPTURE(names[f]);
      CHECK(jc.q.at(names[f]) == doctest::Approx(carc[i].*fields[f]).epsilon(1e-7));
      CHECK(jb.q.at(names[f]) == doctest::Approx(frame[i].*fields[f]).epsilon(1e-7));
    }
    CAPTURE(i);
    CHECK(jc.ari_labelled == doctest::Approx(carc_labelled[i].ari).epsilon(1e-7));
    CHECK(jc.pq_labelled == doctest::Approx(carc_labelled[i].pq).epsilon(1e-7));
    CHECK(jb.ari_labelled == doctest::Approx(frame_labelled[i].ari).epsilon(1e-7));
    CHECK(jb.pq_labelled == doctest::Approx(frame_labelled[i].pq).epsilon(1e-7));
    // The same subset for both methods, smaller than the window when the baseline lost points.
    CHECK(carc_labelled[i].points == frame_labelled[i].points);
    CHECK(frame_labelled[i].points == doctest::Approx(frame[i].coverage * frame[i].points));
    CHECK(frame_labelled[i].coverage == 1.0);
    carc_mean.add(carc[i]);
    carc_labelled_mean.add(carc_labelled[i]);
    frame_labelled_mean.add(frame_labelled[i]);
  }
  // The subset is a real restriction: the overwrite grid lost points.
  std::size_t restricted = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) restricted += frame_labelled[i].points < frame[i].points ? 1u : 0u;
  CHECK(restricted > 0);
  REQUIRE(e.mean_labelled.count("carc") == 1);
  REQUIRE(e.mean_labelled.count("baseline") == 1);
  CHECK(e.mean_labelled.at("carc").at("ari") == doctest::Approx(carc_labelled_mean.mean().ari).epsilon(1e-7));
  CHECK(e.mean_labelled.at("carc").at("pq") == doctest::Approx(carc_labelled_mean.mean().pq).epsilon(1e-7));
  CHECK(e.mean_labelled.at("carc").at("points") == doctest::Approx(carc_labelled_mean.mean().points).epsilon(1e-7));
  CHECK(e.mean_labelled.at("baseline").at("ari") == doctest::Approx(frame_labelled_mean.mean().ari).epsilon(1e-7));
  CHECK(e.mean_labelled.at("baseline").at("pq") == doctest::Approx(frame_labelled_mean.mean().pq).epsilon(1e-7));
  CHECK(e.mean_labelled.at("baseline").at("under_segmented") ==
        doctest::Approx(frame_labelled_mean.mean().under_segmented).epsilon(1e-7));
  for (std::size_t f = 0; f < 12; ++f) {
    CAPTURE(names[f]);
    CHECK(e.mean.at("carc").at(names[f]) == doctest::Approx(carc_mean.mean().*fields[f]).epsilon(1e-7));
  }
}

TEST_CASE("evaluate: on a coarse grid the overwrite baseline loses points, C-ARC none") {
  const sc::test::TempDir dir("evaluate", "evaluate_coverage");
  const std::string json = dir.path("e.json");
  const auto r = run_cli({"evaluate", "--sensor", "avia", "--scene", "forest", "--duration", "0.3", "--multiplicity", "2",
                      "--theta", "80", "--json", json, "--quiet"});
  REQUIRE_MESSAGE(r.code == 0, r.err);
  CHECK(r.out.empty());
  const JsonEvaluation e = parse_evaluation(slurp(json));
  const std::string text = slurp(json);
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex("\"mean_multiplicity\": ([0-9.]+)")));
  const double multiplicity = std::stod(m[1].str());
  CHECK(multiplicity > 1.5);
  REQUIRE(!e.cycles.at("carc").empty());
  for (const JsonCycle& c : e.cycles.at("carc")) CHECK(c.q.at("coverage") == 1.0);
  for (const JsonCycle& c : e.cycles.at("baseline")) {
    // One point per occupied cell survives: about 1 / M_mu of the window.
    CHECK(c.q.at("coverage") < 0.8);
    CHECK(c.q.at("coverage") == doctest::Approx(1.0 / multiplicity).epsilon(0.25));
  }
  CHECK(e.mean.at("carc").at("coverage") == 1.0);
  CHECK(e.mean.at("baseline").at("coverage") < 0.8);
}

TEST_CASE("evaluate: an ego-motion burst merges objects until its points leave the window") {
  const sc::test::TempDir dir("evaluate", "evaluate_burst");
  const std::string json = dir.path("e.json");
  const std::string series = dir.path("s.csv");
  const auto r = run_cli({"evaluate", "--sensor", "mid360", "--scene", "forest", "--structure", "drop", "--duration", "1.6",
                      "--burst", "0.5:0.3", "--burst-yaw-rate", "3", "--method", "carc", "--json", json, "--series",
                      series});
  REQUIRE_MESSAGE(r.code == 0, r.err);
  CHECK(r.out.find("recovery after the burst") != std::string::npos);
  const JsonEvaluation e = parse_evaluation(slurp(json));
  REQUIRE(e.cycles.count("baseline") == 0);
  double before = 0, during = 0, after = 0;
  int nb = 0, nd = 0, na = 0;
  for (const JsonCycle& c : e.cycles.at("carc")) {
    const double use = c.q.at("use");
    if (c.time < 0.5) {
      before += use;
      ++nb;
    } else if (c.time > 0.62 && c.time < 0.8) {  // the window is full of turning points
      during += use;
      ++nd;
    } else if (c.time > 0.8 + 0.1 + 0.04) {  // the burst's points have left the 0.1 s window
      after += use;
      ++na;
    }
  }
  REQUIRE(nb >= 5);
  REQUIRE(nd >= 3);
  REQUIRE(na >= 8);
  before /= nb;
  during /= nd;
  after /= na;
  CHECK(during > 1.3 * before);
  CHECK(during > 1.3 * after);
  // The recovery is measured, and bounded by about one window after the burst.
  const std::string& rec = e.recovery_line.at("carc");
  std::smatch m;
  REQUIRE(std::regex_search(rec, m, std::regex("\"use\": \\{[^}]*\"time\": ([0-9.eE+-]+)\\}")));
  const double recovery = std::stod(m[1].str());
  CHECK(recovery >= 0.0);
  CHECK(recovery <= 0.1 + 0.05 + 1e-6);
  // The series holds one row per retrieval with the same values.
  const std::string csv = slurp(series);
  CHECK(csv.rfind("method,time,window,", 0) == 0);
  std::size_t rows = 0;
  for (const char ch : csv) rows += ch == '\n' ? 1u : 0u;
  CHECK(rows == e.cycles.at("carc").size() + 1);
}

TEST_CASE("evaluate: --connectivity forest scores every retrieval as lazy-bfs does") {
  // Same partitions, so the same metrics, retrieval for retrieval (the
  // series has no cost column); the JSON names the strategy.
  const sc::test::TempDir dir("evaluate", "evaluate_connectivity");
  std::map<std::string, std::string> series, json;
  for (const std::string connectivity : {"lazy-bfs", "forest"}) {
    const auto r = run_cli({"evaluate", "--sensor", "avia", "--scene", "office", "--duration", "0.3", "--theta", "80",
                            "--method", "carc", "--connectivity", connectivity, "--series",
                            dir.path(connectivity + ".csv"), "--json", dir.path(connectivity + ".json"), "--quiet"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    series[connectivity] = slurp(dir.path(connectivity + ".csv"));
    json[connectivity] = slurp(dir.path(connectivity + ".json"));
  }
  CHECK(std::count(series["forest"].begin(), series["forest"].end(), '\n') >= 4);
  CHECK(series["forest"] == series["lazy-bfs"]);
  CHECK(json["forest"].find("\"connectivity\": \"forest\"") != std::string::npos);
  CHECK(json["lazy-bfs"].find("\"connectivity\": \"lazy-bfs\"") != std::string::npos);
}

TEST_CASE("evaluate: usage errors exit 2 with a clear message") {
  const auto expect = [](const std::vector<std::string>& args, const std::string& says) {
    const auto r = run_cli(args);
    CAPTURE(says);
    CHECK(r.code == 2);
    CHECK(r.err.find(says) != std::string::npos);
  };
  expect({"evaluate", "--method", "dbscan"}, "--method: expected carc|baseline|both");
  expect({"evaluate", "--index", "overwrite"}, "--index");
  expect({"evaluate", "--duration", "0.1"}, "--duration");
  expect({"evaluate", "--sensor", "synthetic", "--scene", "room"}, "simulated sensor");
  expect({"evaluate", "--burst", "1"}, "--burst: expected START:LENGTH");
  expect({"evaluate", "--frames", "x"}, "--frames: expected sliding|tumbling");
  expect({"evaluate", "--connectivity", "bfs"}, "--connectivity: expected lazy-bfs|forest");
  expect({"evaluate", "--structure", "x"}, "--structure: expected keep|drop");
  expect({"evaluate", "--mask", "4"}, "--mask");
  expect({"evaluate", "--theta", "95"}, "theta");
  expect({"evaluate", "--bogus"}, "unknown option '--bogus'");
  expect({"evaluate", "--window-time", "0"}, "--window-time");
  const auto help = run_cli({"evaluate", "--help"});
  CHECK(help.code == 0);
  CHECK(help.out.find("examples:") != std::string::npos);
  CHECK(run_cli({"--help"}).out.find("evaluate") != std::string::npos);
}

TEST_CASE("evaluate: an unwritable --json is an output error (exit 4)") {
  const auto r = run_cli({"evaluate", "--sensor", "mid40", "--duration", "0.2", "--method", "carc", "--json",
                      "/nonexistent-dir/e.json", "--quiet"});
  CHECK(r.code == 4);
  CHECK(r.err.find("--json") != std::string::npos);
}

TEST_CASE("eval helpers: QualityAverage and recovery_after on hand-made series") {
  sc::eval::QualityAverage average;
  CHECK(average.mean().frames == 0);
  sc::eval::QualityReport a, b;
  a.adjusted_rand_index = 1.0;
  a.coverage = 0.5;
  a.panoptic.pq = 0.2;
  b.adjusted_rand_index = 0.0;
  b.coverage = 1.0;
  b.panoptic.pq = 0.6;
  average.add(a);
  average.add(b);
  CHECK(average.frames() == 2);
  CHECK(average.mean().ari == doctest::Approx(0.5));
  CHECK(average.mean().coverage == doctest::Approx(0.75));
  CHECK(average.mean().pq == doctest::Approx(0.4));

  // Level 1 before, 5 during an event over [1, 2), back to 2 from 2.3 on.
  std::vector<double> t, v;
  for (int i = 0; i < 40; ++i) {
    const double time = 0.1 * i;
    t.push_back(time);
    v.push_back(time < 1.0 - 1e-9 ? 1.0 : time < 2.3 - 1e-9 ? 5.0 : 2.0);
  }
  const sc::eval::Recovery r = sc::eval::recovery_after(t, v, 1.0, 2.0, 3.0);
  CHECK(r.before == doctest::Approx(1.0));
  CHECK(r.peak == doctest::Approx(5.0));
  CHECK(r.settled == doctest::Approx(2.0));
  CHECK(r.threshold == doctest::Approx(2.6));
  REQUIRE(r.time.has_value());
  CHECK(*r.time == doctest::Approx(0.3));
  // Never back within the run: no time.
  std::vector<double> stuck = v;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] >= 2.0 && t[i] < 3.0 - 1e-9) stuck[i] = 5.0;
  }
  CHECK_FALSE(sc::eval::recovery_after(t, stuck, 1.0, 2.0, 3.0).time.has_value());
  CHECK_THROWS_AS(sc::eval::recovery_after(t, v, 2.0, 1.0, 3.0), std::invalid_argument);
  CHECK_THROWS_AS(sc::eval::recovery_after(t, v, 1.0, 2.0, 9.0), std::invalid_argument);
  CHECK_THROWS_WITH_AS(sc::eval::recovery_after(t, v, 1.0, 2.0, 3.0, 1.5), doctest::Contains("fraction"),
                       std::invalid_argument);
}
