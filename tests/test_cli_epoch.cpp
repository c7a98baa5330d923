// SPDX-License-Identifier: MIT
// A recording at epoch times (Unix time, about 1.7e9 s) and the same stream
// starting at zero: the tool clusters both into the same partitions, and
// every time it writes differs by exactly the shift.

#include <doctest/doctest.h>

#include <streamclust/io/reader.hpp>

#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;
namespace io = streamclust::io;

namespace {

using streamclust::test::run_cli;
using streamclust::test::slurp;

constexpr long long kShift = 1700000000;  // [s]

/// The rows of a labels file, split into time and the rest.
struct LabelRows {
  std::vector<std::string> times;  ///< as written
  std::vector<std::string> rest;   ///< "cycle,index,label"
};

LabelRows read_label_rows(const fs::path& path) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  REQUIRE(line == "cycle,time,index,label");
  LabelRows rows;
  while (std::getline(f, line)) {
    const auto c1 = line.find(','), c2 = line.find(',', c1 + 1);
    REQUIRE(c2 != std::string::npos);
    rows.times.push_back(line.substr(c1 + 1, c2 - c1 - 1));
    rows.rest.push_back(line.substr(0, c1) + line.substr(c2));
  }
  return rows;
}

/// The cycle times of a report, as written.
std::vector<std::string> report_times(const fs::path& path) {
  const std::string text = slurp(path);
  static const std::regex time_field("\"time\": (-?[0-9.]+)");
  std::vector<std::string> times;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), time_field); it != std::sregex_iterator(); ++it) {
    times.push_back((*it)[1].str());
  }
  return times;
}

/// True when `shifted` is `base` plus kShift seconds, digit for digit.
bool differs_by_shift(const std::string& base, const std::string& shifted) {
  const auto a = base.find('.'), b = shifted.find('.');
  if (a == std::string::npos || b == std::string::npos) return false;
  return base.substr(a) == shifted.substr(b) && std::stoll(shifted.substr(0, b)) - std::stoll(base.substr(0, a)) == kShift;
}

struct Outputs {
  LabelRows labels;
  std::vector<std::string> report;
  std::vector<io::Record> cloud;
  io::TimeOrigin cloud_origin;
};

/// Simulates 1 s of a moving Mid-360 in the street from `start` (whole
/// seconds) and clusters it with `options`, writing labels, report and a PLY.
Outputs run(const fs::path& dir, const std::string& name, long long start, const std::vector<std::string>& options) {
  const fs::path csv = dir / (name + ".csv"), tum = dir / (name + ".tum");
  const auto sim = run_cli({"simulate", "--sensor", "mid360", "--scene", "street", "--speed", "1.5", "--yaw-rate",
                            "0.3", "--duration", "1.0", "--start-time", std::to_string(start), "--out", csv.string(),
                            "--quiet"});
  INFO(sim.err);
  REQUIRE(sim.code == 0);
  std::vector<std::string> args{"cluster", csv.string(), "--labels", (dir / (name + ".labels")).string(), "--cycles",
                                "all", "--report", (dir / (name + ".json")).string(), "--ply",
                                (dir / (name + ".ply")).string(), "--quiet"};
  for (const std::string& o : options) args.push_back(o == "TUM" ? tum.string() : o);
  const auto r = run_cli(args);
  INFO(r.err);
  REQUIRE(r.code == 0);
  Outputs out;
  out.labels = read_label_rows(dir / (name + ".labels"));
  out.report = report_times(dir / (name + ".json"));
  auto reader = io::open_reader((dir / (name + ".ply")).string());
  while (reader->read(out.cloud, 4096) > 0) {
  }
  out.cloud_origin = reader->time_origin();
  return out;
}

void check_shift_invariant(const std::vector<std::string>& options) {
  const streamclust::test::TempDir tmp("cli", "epoch");
  const Outputs zero = run(tmp.dir, "zero", 0, options);
  const Outputs epoch = run(tmp.dir, "epoch", kShift, options);

  // The same partitions: every row's cycle, index and label.
  REQUIRE(zero.labels.rest.size() > 1000);
  CHECK(zero.labels.rest == epoch.labels.rest);
  // Times differ by exactly the shift, and the cycles stay apart.
  REQUIRE(zero.labels.times.size() == epoch.labels.times.size());
  std::size_t off = 0;
  for (std::size_t i = 0; i < zero.labels.times.size(); ++i)
    off += !differs_by_shift(zero.labels.times[i], epoch.labels.times[i]);
  CHECK(off == 0);
  CHECK(epoch.labels.times.front() != epoch.labels.times.back());
  REQUIRE(zero.report.size() >= 5);
  REQUIRE(zero.report.size() == epoch.report.size());
  for (std::size_t i = 0; i < zero.report.size(); ++i) {
    INFO(zero.report[i] << " vs " << epoch.report[i]);
    CHECK(differs_by_shift(zero.report[i], epoch.report[i]));
  }
  // The point cloud stores a double per time: 0.24 us at epoch scale.
  CHECK(epoch.cloud_origin == io::TimeOrigin{kShift});
  REQUIRE(zero.cloud.size() == epoch.cloud.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < zero.cloud.size(); ++i) {
    const double a = io::absolute_seconds(zero.cloud_origin, zero.cloud[i].t);
    const double b = io::absolute_seconds(epoch.cloud_origin, epoch.cloud[i].t);
    worst = std::max(worst, std::fabs((b - static_cast<double>(kShift)) - a));
  }
  CHECK(worst <= 2.4e-7);
}

}  // namespace

TEST_CASE("epoch times: the default preset gives the same partitions, and times shifted exactly") {
  check_shift_invariant({});
}

TEST_CASE("epoch times: the objects preset with the recording's poses, verified, shift-invariant" *
          doctest::test_suite("slow")) {
  check_shift_invariant({"--preset", "objects-mid360", "--sensor-height", "1", "--poses", "TUM", "--verify"});
}

TEST_CASE("epoch times: info shows the span with nanoseconds; --time-origin changes no output time") {
  const streamclust::test::TempDir tmp("cli", "epoch_info");
  const fs::path csv = tmp.dir / "s.csv";
  REQUIRE(run_cli({"simulate", "--duration", "0.2", "--start-time", "1700000000", "--out", csv.string(), "--quiet"})
              .code == 0);
  const auto r = run_cli({"info", csv.string()});
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  CHECK(std::regex_search(r.out, std::regex("time: .*1700000000\\.000[0-9]{6} s to 1700000000\\.19[0-9]{7} s")));
  // --time-origin: another time base gives the same absolute times out.
  const auto own = run_cli({"cluster", csv.string(), "--labels", (tmp.dir / "own.csv").string(), "--quiet"});
  const auto given = run_cli({"cluster", csv.string(), "--time-origin", "1699999000", "--labels",
                              (tmp.dir / "given.csv").string(), "--quiet"});
  REQUIRE(own.code == 0);
  REQUIRE(given.code == 0);
  CHECK(read_label_rows(tmp.dir / "own.csv").times == read_label_rows(tmp.dir / "given.csv").times);
  CHECK(run_cli({"cluster", csv.string(), "--time-origin", "1.5"}).code == 2);
  CHECK(run_cli({"cluster", csv.string(), "--time-origin", "1e12"}).code == 2);
  CHECK(run_cli({"simulate", "--start-time", "1.5", "--out", csv.string()}).code == 2);
  CHECK(run_cli({"simulate", "--start-time", "-3", "--out", csv.string()}).code == 2);
}
