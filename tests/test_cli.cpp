// SPDX-License-Identifier: MIT
// The `streamclust` tool, run in-process: end-to-end clustering checked
// against the batch clusterer, outputs, and the exit-code contract.

#include <doctest/doctest.h>

#include "cli/engine_config.hpp"
#include "cli/main.hpp"
#include "cli/options.hpp"
#include "cli/replay.hpp"

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/io/reader.hpp>
#include <streamclust/sim/synthetic_stream.hpp>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"
#include "support/partition.hpp"
#include "support/temp_dir.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace sc = streamclust;
namespace fs = std::filesystem;

namespace {

using streamclust::test::run_cli;
using streamclust::test::RunResult;
using streamclust::test::slurp;

/// Writes `seconds` of the synthetic stream as CSV; every 50th record gets a
/// NaN coordinate (it must come back with label -1).
std::vector<sc::SyntheticPoint> write_stream_csv(const fs::path& path, double seconds) {
  sc::SyntheticStream::Params p;
  p.point_rate = 40000.0;
  sc::SyntheticStream stream(p);
  std::vector<sc::SyntheticPoint> points;
  std::ofstream f(path);
  f.precision(9);
  f << "x,y,z,intensity,t\n";
  while (stream.time() < seconds) {
    sc::SyntheticPoint q = stream.next();
    if (points.size() % 50 == 49) q.x = std::numeric_limits<float>::quiet_NaN();
    points.push_back(q);
    f << q.x << ',' << q.y << ',' << q.z << ',' << q.intensity << ',' << q.t << '\n';
  }
  return points;
}

struct LabelRow {
  std::uint64_t cycle;
  double time;
  std::uint64_t index;
  std::int64_t label;
};

std::vector<LabelRow> read_labels(const fs::path& path) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  REQUIRE(line == "cycle,time,index,label");
  std::vector<LabelRow> rows;
  while (std::getline(f, line)) {
    LabelRow r{};
    char c1, c2, c3;
    std::istringstream s(line);
    s >> r.cycle >> c1 >> r.time >> c2 >> r.index >> c3 >> r.label;
    REQUIRE(!s.fail());
    rows.push_back(r);
  }
  return rows;
}

std::pair<std::uint32_t, std::uint32_t> report_grid(const std::string& json) {
  const auto doc = nlohmann::json::parse(json);
  return {doc.at("grid").at("rows").get<std::uint32_t>(), doc.at("grid").at("cols").get<std::uint32_t>()};
}

}  // namespace

TEST_CASE("cluster --verify on a synthesized stream; the labels file matches the batch clusterer") {
  const sc::test::TempDir tmp("cli", "e2e");
  const fs::path& dir = tmp.dir;
  const auto points = write_stream_csv(dir / "stream.csv", 0.35);
  const auto result = run_cli({"cluster", (dir / "stream.csv").string(), "--preset", "carc", "--theta", "30", "--window-time",
                           "0.1", "--rate", "20", "--labels", (dir / "labels.csv").string(), "--cycles", "all", "--report",
                           (dir / "report.json").string(), "--verify", "--ply", (dir / "last.ply").string(), "--pcd",
                           (dir / "last.pcd").string()});
  INFO(result.err);
  REQUIRE(result.code == 0);
  CHECK(result.out.find("streamclust: ") != std::string::npos);

  const auto rows = read_labels(dir / "labels.csv");
  const std::string report = slurp(dir / "report.json");
  const auto [grid_rows, grid_cols] = report_grid(report);
  CHECK(report.find("\"cycles\": [") != std::string::npos);
  CHECK(report.find("\"retrieval\"") != std::string::npos);
  CHECK(report.find("\"non_finite\": ") != std::string::npos);

  // Group the rows by cycle and re-cluster each window with the library's batch clusterer.
  std::map<std::uint64_t, std::vector<LabelRow>> cycles;
  for (const auto& r : rows) cycles[r.cycle].push_back(r);
  CHECK(cycles.size() >= 6);
  auto options = sc::cli::parse_cluster_options({"x", "--preset", "carc", "--theta", "30", "--window-time", "0.1"});
  using Config = sc::cli::CliConfig<sc::SphericalProjection, sc::BucketGrid, sc::AngularLinkage, sc::TimeWindow>;
  sc::BatchClusterer<Config> batch(sc::cli::make_params<Config>(options));
  batch.set_grid({grid_rows, grid_cols});
  for (const auto& entry : cycles) {
    const std::uint64_t cycle = entry.first;  // not a structured binding: clang 14 cannot capture those in INFO
    const std::vector<LabelRow>& cycle_rows = entry.second;
    std::vector<sc::SyntheticPoint> window;
    std::vector<std::int64_t> labels;
    for (const auto& r : cycle_rows) {
      REQUIRE(r.index < points.size());
      const bool nan = std::isnan(points[r.index].x);
      CHECK((r.label == -1) == nan);
      if (nan) continue;
      window.push_back(points[r.index]);
      labels.push_back(r.label);
    }
    INFO("cycle " << cycle);
    const auto& reference = batch.cluster(window);
    CHECK(sc::test::partition_mismatch(labels, reference.labels) == "");
  }

  // The point clouds of the last cycle carry its labels.
  auto reader = sc::io::open_reader((dir / "last.pcd").string(), {});
  std::vector<sc::io::Record> cloud;
  while (reader->read(cloud, 4096) > 0) {
  }
  const auto& last = cycles.rbegin()->second;
  std::size_t labelled = 0;
  for (const auto& r : last) labelled += r.label >= 0;
  CHECK(cloud.size() == labelled);
  CHECK(fs::file_size(dir / "last.ply") > 0);
}

TEST_CASE("cluster --connectivity forest: the partition of lazy-bfs in every cycle, verified; not in frame mode") {
  const sc::test::TempDir tmp("cli", "connectivity");
  const fs::path& dir = tmp.dir;
  write_stream_csv(dir / "stream.csv", 0.35);
  std::map<std::string, std::vector<LabelRow>> rows;
  for (const std::string connectivity : {"lazy-bfs", "forest"}) {
    const auto result = run_cli({"cluster", (dir / "stream.csv").string(), "--preset", "carc", "--theta", "30",
                                 "--window-time", "0.1", "--index", "capped", "--connectivity", connectivity, "--verify",
                                 "--labels", (dir / (connectivity + ".csv")).string(), "--cycles", "all", "--report",
                                 (dir / (connectivity + ".json")).string()});
    INFO(result.err);
    REQUIRE(result.code == 0);  // --verify: every cycle equals the batch clusterer's partition
    rows[connectivity] = read_labels(dir / (connectivity + ".csv"));
    CHECK(slurp(dir / (connectivity + ".json")).find("\"connectivity\": \"" + connectivity + "\"") !=
          std::string::npos);
  }
  const auto& lazy = rows["lazy-bfs"];
  const auto& forest = rows["forest"];
  REQUIRE(forest.size() == lazy.size());
  std::map<std::uint64_t, std::pair<std::vector<std::int64_t>, std::vector<std::int64_t>>> cycles;
  for (std::size_t i = 0; i < lazy.size(); ++i) {
    REQUIRE(forest[i].cycle == lazy[i].cycle);
    REQUIRE(forest[i].index == lazy[i].index);
    CHECK((forest[i].label == -1) == (lazy[i].label == -1));
    cycles[lazy[i].cycle].first.push_back(lazy[i].label);
    cycles[lazy[i].cycle].second.push_back(forest[i].label);
  }
  CHECK(cycles.size() >= 6);
  for (const auto& entry : cycles) {
    INFO("cycle " << entry.first);
    CHECK(sc::test::partition_mismatch(entry.second.second, entry.second.first) == "");
  }
  const auto frame = run_cli({"cluster", (dir / "stream.csv").string(), "--preset", "baseline", "--connectivity", "forest"});
  CHECK(frame.code == 2);
  CHECK(frame.err.find("--connectivity") != std::string::npos);
  const auto bad = run_cli({"cluster", (dir / "stream.csv").string(), "--connectivity", "bfs"});
  CHECK(bad.code == 2);
  CHECK(bad.err.find("--connectivity: expected lazy-bfs|forest") != std::string::npos);
}

TEST_CASE("frame mode with the baseline preset leaves overwritten points unlabelled") {
  const sc::test::TempDir tmp("cli", "frame");
  const fs::path& dir = tmp.dir;
  write_stream_csv(dir / "stream.csv", 0.2);
  const auto result = run_cli({"cluster", (dir / "stream.csv").string(), "--preset", "baseline", "--grid", "16x64",
                           "--labels", (dir / "labels.csv").string(), "--quiet"});
  INFO(result.err);
  REQUIRE(result.code == 0);
  CHECK(result.out.empty());
  const auto rows = read_labels(dir / "labels.csv");
  std::size_t unlabelled = 0;
  for (const auto& r : rows) unlabelled += r.label < 0;
  CHECK(unlabelled > rows.size() / 2);  // 16 x 64 cells cannot hold a 0.1 s window
  CHECK(unlabelled < rows.size());
}

TEST_CASE("info reports format, count and time span") {
  const sc::test::TempDir tmp("cli", "info");
  const fs::path& dir = tmp.dir;
  const auto points = write_stream_csv(dir / "stream.csv", 0.05);
  const auto result = run_cli({"info", (dir / "stream.csv").string()});
  INFO(result.err);
  REQUIRE(result.code == 0);
  CHECK(result.out.find("csv") != std::string::npos);
  CHECK(result.out.find(std::to_string(points.size())) != std::string::npos);
  CHECK(result.out.find("time:") != std::string::npos);
}

TEST_CASE("exit codes: help 0, usage 2, input 4") {
  CHECK(run_cli({"--help"}).code == 0);
  CHECK(run_cli({}).code == 2);
  const auto help = run_cli({"cluster", "--help"});
  CHECK(help.code == 0);
  CHECK(help.out.find("examples:") != std::string::npos);
  CHECK(run_cli({"info", "--help"}).out.find("examples:") != std::string::npos);
  CHECK(run_cli({"bogus"}).code == 2);
  CHECK(run_cli({"cluster"}).code == 2);
  CHECK(run_cli({"cluster", "a.csv", "--theta", "abc"}).err.find("--theta: expected a number") != std::string::npos);
  CHECK(run_cli({"cluster", "a.csv", "--mask", "4"}).code == 2);
  CHECK(run_cli({"cluster", "a.csv", "--index", "kd-tree"}).code == 2);
  CHECK(run_cli({"cluster", "a.csv", "--window-time", "0.1", "--window-count", "5"}).code == 2);
  CHECK(run_cli({"cluster", "a.csv", "--frobnicate"}).code == 2);
  CHECK(run_cli({"cluster", "a.csv", "--mode", "frame", "--verify"}).code == 2);

  const sc::test::TempDir tmp("cli", "codes");
  const fs::path& dir = tmp.dir;
  const auto missing = run_cli({"cluster", (dir / "missing.csv").string()});
  CHECK(missing.code == 4);
  CHECK(missing.err.find("missing.csv") != std::string::npos);
  { std::ofstream(dir / "empty.csv"); }
  CHECK(run_cli({"cluster", (dir / "empty.csv").string()}).code == 4);
  {
    std::ofstream f(dir / "untimed.csv");
    f << "x,y,z\n1,2,3\n4,5,6\n";
  }
  const auto untimed = run_cli({"cluster", (dir / "untimed.csv").string()});
  CHECK(untimed.code == 4);
  CHECK(untimed.err.find("point-rate") != std::string::npos);
  CHECK(run_cli({"cluster", (dir / "untimed.csv").string(), "--point-rate", "1000", "--quiet"}).code == 0);
  {
    std::ofstream f(dir / "bad.csv");
    f << "x,y,z,t\n1,2,3,0\n4,five,6,0.1\n";
  }
  const auto bad = run_cli({"cluster", (dir / "bad.csv").string()});
  CHECK(bad.code == 4);
  CHECK(bad.err.find("line 3") != std::string::npos);
}

TEST_CASE("one absurd time in a CSV costs that record, not the rest of the stream; no usable time is exit 4") {
  const sc::test::TempDir tmp("cli", "absurd_time");
  const fs::path& dir = tmp.dir;
  const auto points = write_stream_csv(dir / "clean.csv", 0.35);
  {
    std::ifstream in(dir / "clean.csv");
    std::ofstream out(dir / "spiked.csv");
    std::string line;
    for (std::size_t row = 0; std::getline(in, line); ++row) {
      if (row == 2001) line = line.substr(0, line.rfind(',') + 1) + "1e300";  // record 2000
      out << line << '\n';
    }
  }
  auto run = [&](const char* name) {
    const auto r = run_cli({"cluster", (dir / name).string(), "--labels", (dir / (std::string(name) + ".labels")).string(),
                            "--cycles", "all", "--report", (dir / (std::string(name) + ".json")).string(), "--quiet"});
    INFO(r.err);
    REQUIRE(r.code == 0);
    return nlohmann::json::parse(slurp(dir / (std::string(name) + ".json")));
  };
  const auto clean = run("clean.csv");
  const auto spiked = run("spiked.csv");
  const auto& rejected = spiked.at("totals").at("rejected");
  CHECK(rejected.at("time_jump").get<int>() == 1);
  CHECK(rejected.at("time_backwards").get<int>() == 0);
  CHECK(spiked.at("totals").at("inserted").get<int>() == clean.at("totals").at("inserted").get<int>() - 1);
  CHECK(spiked.at("cycles").size() == clean.at("cycles").size());
  const auto rows = read_labels(dir / "spiked.csv.labels");
  std::size_t spike_rows = 0;
  for (const auto& r : rows) {
    if (r.index != 2000) continue;
    ++spike_rows;
    CHECK(r.label == -1);
  }
  CHECK(spike_rows > 0);
  CHECK(points.size() > 2000);

  {
    std::ofstream f(dir / "no_time.csv");
    f << "x,y,z,t\n1,2,3,nan\n4,5,6,1e300\n7,8,9,inf\n";
  }
  const auto none = run_cli({"cluster", (dir / "no_time.csv").string()});
  CHECK(none.code == 4);
  CHECK(none.err.find("no_time.csv") != std::string::npos);
  CHECK(none.err.find("no record has a usable time") != std::string::npos);
}

TEST_CASE("info describes an input without a time field, and times it with --point-rate") {
  const sc::test::TempDir tmp("cli", "info_untimed");
  const fs::path& dir = tmp.dir;
  {
    std::ofstream f(dir / "untimed.csv");
    f << "x,y,z\n1,2,3\n4,5,6\n7,8,9\n";
  }
  const auto plain = run_cli({"info", (dir / "untimed.csv").string()});
  INFO(plain.err);
  REQUIRE(plain.code == 0);
  CHECK(plain.out.find("points:    3") != std::string::npos);
  CHECK(plain.out.find("no time field (cluster needs --point-rate)") != std::string::npos);
  CHECK(plain.out.find("x [1, 7]") != std::string::npos);
  const auto timed = run_cli({"info", (dir / "untimed.csv").string(), "--point-rate", "10"});
  REQUIRE(timed.code == 0);
  CHECK(timed.out.find("span 0.2 s") != std::string::npos);
  // The same input options as cluster, with the same messages.
  CHECK(run_cli({"info", (dir / "untimed.csv").string(), "--format", "xyz"}).err.find("--format: expected") !=
        std::string::npos);
  CHECK(run_cli({"info", (dir / "untimed.csv").string(), "--point-rate", "-1"}).code == 2);
  CHECK(run_cli({"info", (dir / "untimed.csv").string(), "--window-time", "1"}).code == 2);
}

/// <repo>/../shared/data/livox/frames/mid100_campus, or under $STREAMCLUST_LIVOX_DATA.
fs::path mid100_frames() {
  if (const char* env = std::getenv("STREAMCLUST_LIVOX_DATA")) return fs::path(env) / "frames" / "mid100_campus";
  return fs::path(__FILE__).parent_path() / ".." / ".." / "shared" / "data" / "livox" / "frames" / "mid100_campus";
}

bool have_mid100_frames() {
  std::error_code ec;
  return fs::is_directory(mid100_frames(), ec);
}

TEST_CASE("info reads the Mid-100 PCDs of the shared data, which have no time field" *
          doctest::skip(!have_mid100_frames())) {
  const fs::path frames = mid100_frames();
  std::size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(frames)) {
    if (entry.path().extension() != ".pcd" || files >= 3) continue;
    ++files;
    const auto r = run_cli({"info", entry.path().string()});
    INFO(entry.path().string() << ": " << r.err);
    CHECK(r.code == 0);
    CHECK(r.out.find("no time field (cluster needs --point-rate)") != std::string::npos);
    CHECK(r.out.find("bounds:") != std::string::npos);
  }
  CHECK(files > 0);
}

TEST_CASE("--point-rate is the rate of a stream without its own timing in every subcommand") {
  const sc::test::TempDir tmp("cli", "point_rate");
  const fs::path& dir = tmp.dir;
  const auto model = run_cli({"simulate", "--sensor", "mid360", "--point-rate", "1000", "--out", (dir / "s.csv").string()});
  CHECK(model.code == 2);
  CHECK(model.err.find("--point-rate") != std::string::npos);
  CHECK(run_cli({"evaluate", "--sensor", "mid40", "--point-rate", "1000"}).code == 2);
  // A file with a time field keeps its times whatever the rate.
  const auto points = write_stream_csv(dir / "stream.csv", 0.05);
  const auto info = run_cli({"info", (dir / "stream.csv").string(), "--point-rate", "1"});
  REQUIRE(info.code == 0);
  CHECK(info.out.find("field 't'") != std::string::npos);
  CHECK(info.out.find("span 0.0") != std::string::npos);
}

TEST_CASE("frame mode calibrates its grid on the first complete window, as the engine does") {
  const sc::test::TempDir tmp("cli", "frame_grid");
  const fs::path& dir = tmp.dir;
  write_stream_csv(dir / "stream.csv", 0.35);
  std::map<std::string, std::pair<std::uint32_t, std::uint32_t>> grids;
  for (const std::string mode : {"continuous", "frame"}) {
    const auto r = run_cli({"cluster", (dir / "stream.csv").string(), "--mode", mode, "--window-time", "0.1", "--report",
                            (dir / (mode + ".json")).string(), "--quiet"});
    INFO(r.err);
    REQUIRE(r.code == 0);
    grids[mode] = report_grid(slurp(dir / (mode + ".json")));
  }
  CHECK(grids["frame"] == grids["continuous"]);
}

TEST_CASE("simulate writes a stream with ground truth that cluster reads back") {
  const sc::test::TempDir tmp("cli", "simulate");
  const fs::path& dir = tmp.dir;
  const auto sim = run_cli({"simulate", "--sensor", "synthetic", "--scene", "room", "--seconds", "0.1", "--point-rate",
                        "20000", "--out", (dir / "s.csv").string()});
  INFO(sim.err);
  REQUIRE(sim.code == 0);
  auto reader = sc::io::open_reader((dir / "s.csv").string(), {});
  std::vector<sc::io::Record> records;
  while (reader->read(records, 1000) > 0) {
  }
  CHECK(records.size() == 2000);
  CHECK(reader->info().has_label);
  std::size_t objects = 0;
  for (const auto& r : records) objects += r.label > 0;
  CHECK(objects > 0);
  for (const char* sensor : {"mid360", "mid40", "mid70", "avia", "spinning32"}) {
    for (const char* scene : {"office", "forest", "street"}) {
      INFO(sensor << " in " << scene);
      const auto r = run_cli({"simulate", "--sensor", sensor, "--scene", scene, "--seconds", "0.05", "--speed", "1",
                          "--out", (dir / "m.pcd").string(), "--quiet"});
      REQUIRE(r.code == 0);
      auto pcd = sc::io::open_reader((dir / "m.pcd").string(), {});
      std::vector<sc::io::Record> cloud;
      while (pcd->read(cloud, 4096) > 0) {
      }
      CHECK(cloud.size() > 100);
      std::size_t labelled = 0;
      for (const auto& r2 : cloud) labelled += r2.label > 0;
      CHECK(labelled > 0);
    }
  }
  CHECK(run_cli({"cluster", (dir / "m.pcd").string(), "--quiet"}).code == 0);
  CHECK(run_cli({"simulate", "--sensor", "synthetic", "--out", (dir / "s.csv").string()}).code == 2);
  CHECK(run_cli({"simulate", "--out", (dir / "s.txt").string()}).code == 2);
  CHECK(run_cli({"simulate", "--scene", "mars", "--out", (dir / "s.csv").string()}).code == 2);
  CHECK(run_cli({"simulate", "--dropout", "2", "--out", (dir / "s.csv").string()}).code == 2);
  CHECK(run_cli({"simulate", "--help"}).out.find("examples:") != std::string::npos);
}

TEST_CASE("the retrieval schedule never runs the same retrieval twice when floor() rounds down") {
  // At 10 Hz from t0 = 0.3 s the 4th retrieval is at 0.3 + 4 * 0.1 = 0.7 s
  // (the same double as the literal 0.7), but (0.7 - 0.3) / 0.1 is
  // 3.9999999999999996 in double: floor() + 1 schedules 0.7 s again, and the
  // record at 0.72 s would trigger a second retrieval at 0.7 s.
  const sc::test::TempDir tmp("cli", "schedule");
  const fs::path& dir = tmp.dir;
  {
    std::ofstream f(dir / "stream.csv");
    f.precision(17);
    f << "x,y,z,intensity,t\n";
    const double times[] = {0.3, 0.45, 0.65, 0.7, 0.72, 0.75};
    int k = 0;
    for (const double t : times) {
      f << 5.0 << ',' << 0.1 * k << ',' << 0.05 * k << ",1," << t << '\n';
      ++k;
    }
  }
  const auto result = run_cli({"cluster", (dir / "stream.csv").string(), "--grid", "8x32", "--rate", "10",
                           "--window-time", "0.2", "--labels", (dir / "labels.csv").string(), "--cycles", "all",
                           "--quiet"});
  INFO(result.err);
  REQUIRE(result.code == 0);
  std::map<std::uint64_t, double> cycle_time;
  for (const LabelRow& r : read_labels(dir / "labels.csv")) cycle_time[r.cycle] = r.time;
  // Scheduled retrievals at 0.4, 0.5 (after 0.45 and 0.65: the pause skips 0.6), 0.7, then the final one at 0.75.
  std::vector<double> times;
  for (const auto& kv : cycle_time) times.push_back(kv.second);
  REQUIRE(times.size() == 4);
  CHECK(times[0] == doctest::Approx(0.4));
  CHECK(times[1] == doctest::Approx(0.5));
  CHECK(times[2] == doctest::Approx(0.7));
  CHECK(times[3] == doctest::Approx(0.75));
  for (std::size_t i = 1; i < times.size(); ++i) CHECK(times[i] > times[i - 1]);
}

TEST_CASE("replay --simulate: --speed is the replay's rate wherever it stands; --ego-speed moves the sensor") {
  using streamclust::cli::parse_replay_options;
  for (const auto& args : {std::vector<std::string>{"--simulate", "--speed", "4", "--ego-speed", "1.5", "--to", "livox-sdk2://"},
                           std::vector<std::string>{"--speed", "4", "--simulate", "--to", "livox-sdk2://", "--ego-speed", "1.5"}}) {
    const auto o = parse_replay_options(args);
    CHECK(o.emulator.speed == 4.0);
    CHECK(o.simulation.speed == doctest::Approx(1.5));
  }
  CHECK(run_cli({"replay", "in.csv", "--ego-speed", "1", "--to", "livox-sdk2://"}).code == 2);  // needs --simulate
}
