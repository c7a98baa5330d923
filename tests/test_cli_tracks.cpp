// SPDX-License-Identifier: MIT
// `cluster --tracks`: the CSV's layout, its tracks tied to the cycle's
// components, standing objects reported still and walkers moving (the
// simulator's truth: the scene's moving objects), the partition unchanged
// (--verify, labels equal with and without tracks), and its usage errors;
// the simulator's objects truth and `evaluate --tracks`.

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <streamclust/sim/scenes.hpp>

#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace st = streamclust::test;

namespace {

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, sep)) out.push_back(field);
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace

TEST_CASE("cluster --tracks: rows per track and cycle, tied to the cycle's components; standing objects still, "
          "walkers moving; labels unchanged" *
          doctest::test_suite("slow")) {
  const st::TempDir dir("cli_tracks", "office");
  const std::string input = dir.path("office.csv");
  REQUIRE(st::run_cli({"simulate", "--sensor", "mid360", "--scene", "office", "--seconds", "2.5", "--out", input,
                       "-q"})
              .code == 0);
  const std::vector<std::string> common = {"cluster", input, "--preset", "objects-mid360", "--sensor-height", "1.0",
                                           "--cycles", "all", "-q"};
  std::vector<std::string> with = common, without = common;
  with.insert(with.end(), {"--tracks", dir.path("tracks.csv"), "--labels", dir.path("with.csv"), "--verify",
                           "--report", dir.path("report.json")});
  without.insert(without.end(), {"--labels", dir.path("without.csv")});
  const st::RunResult a = st::run_cli(with);
  INFO(a.err);
  REQUIRE(a.code == 0);
  REQUIRE(st::run_cli(without).code == 0);
  // Tracking changes no label.
  CHECK(st::slurp(dir.path("with.csv")) == st::slurp(dir.path("without.csv")));
  CHECK(st::slurp(dir.path("report.json")).find("\"tracking\"") != std::string::npos);

  // The components of each cycle and their sizes, from the labels file.
  std::map<std::uint64_t, std::map<std::int64_t, std::int64_t>> sizes;  // cycle -> label -> points
  for (const std::string& line : lines_of(st::slurp(dir.path("with.csv")))) {
    const auto f = split(line, ',');
    if (f.size() != 4 || f[0] == "cycle") continue;
    const std::int64_t label = std::stoll(f[3]);
    if (label >= 0) ++sizes[std::stoull(f[0])][label];
  }
  REQUIRE(!sizes.empty());

  const std::vector<std::string> rows = lines_of(st::slurp(dir.path("tracks.csv")));
  REQUIRE(!rows.empty());
  CHECK(rows.front() == "cycle,time,track_id,cluster_id,x,y,z,vx,vy,vz,length,width,height,yaw,points,state");
  // The simulator's truth: each record's object instance (0: structure), and
  // the office's walkers (the scene's moving objects; seed 1, simulate's).
  std::vector<std::int64_t> instance;
  for (const std::string& line : lines_of(st::slurp(input))) {
    const auto f = split(line, ',');
    if (f.size() == 6 && f[0] != "x") instance.push_back(std::stoll(f[5]));
  }
  std::set<std::int64_t> walking;
  const streamclust::sim::Scene office = streamclust::sim::make_scene("office", 1);
  for (const auto& info : office.objects()) {
    if (info.moving) walking.insert(info.instance);
  }
  REQUIRE(!walking.empty());
  // Each labelled component of each cycle: its majority instance.
  std::map<std::pair<std::uint64_t, std::int64_t>, std::map<std::int64_t, int>> votes;
  for (const std::string& line : lines_of(st::slurp(dir.path("with.csv")))) {
    const auto f = split(line, ',');
    if (f.size() != 4 || f[0] == "cycle") continue;
    const std::int64_t label = std::stoll(f[3]);
    if (label >= 0) ++votes[{std::stoull(f[0]), label}][instance.at(std::stoull(f[2]))];
  }
  auto majority = [&](std::uint64_t cycle, std::int64_t label) {
    const auto& v = votes.at({cycle, label});
    return std::max_element(v.begin(), v.end(), [](const auto& p, const auto& q) { return p.second < q.second; })->first;
  };

  std::size_t confirmed_static = 0, still = 0;
  std::set<std::int64_t> walkers_moving;
  std::set<std::uint64_t> cycles_with_tracks;
  std::map<std::uint64_t, std::set<std::uint64_t>> ids_per_cycle;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const auto f = split(rows[r], ',');
    REQUIRE(f.size() == 16);
    const std::uint64_t cycle = std::stoull(f[0]);
    const std::uint64_t track = std::stoull(f[2]);
    const std::int64_t cluster = std::stoll(f[3]);
    const std::string& state = f[15];
    CHECK((state == "tentative" || state == "confirmed" || state == "coasting"));
    CHECK(ids_per_cycle[cycle].insert(track).second);  // one row per track and cycle
    cycles_with_tracks.insert(cycle);
    for (std::size_t k = 4; k < 15; ++k) CHECK(std::isfinite(std::stod(f[k])));
    const double length = std::stod(f[10]), width = std::stod(f[11]), height = std::stod(f[12]);
    CHECK(length >= width);
    CHECK(width >= 0.05);
    CHECK(height >= 0.05);
    CHECK(std::abs(std::stod(f[13])) <= 3.1416);
    if (state == "coasting") CHECK(cluster == -1);
    if (cluster == -1) {  // not seen this cycle: coasting, or tentative and missed
      CHECK(state != "confirmed");
      CHECK(f[14] == "0");
      continue;
    }
    // Seen: its component is the cycle's, with the points the labels give it.
    REQUIRE(sizes.count(cycle) == 1);
    const auto it = sizes[cycle].find(cluster);
    REQUIRE(it != sizes[cycle].end());
    CHECK(std::stoll(f[14]) == it->second);
    CHECK(it->second >= 10);
    if (state != "confirmed") continue;
    const std::int64_t truth = majority(cycle, cluster);
    const double speed = std::hypot(std::stod(f[7]), std::stod(f[8]));
    if (walking.count(truth) != 0) {
      if (speed >= 0.4) walkers_moving.insert(truth);
    } else if (truth > 0) {
      ++confirmed_static;
      still += speed < 0.2;
    }
  }
  CHECK(cycles_with_tracks.size() >= 30);
  // Standing objects are reported still; every walker is seen moving.
  CAPTURE(confirmed_static);
  CAPTURE(still);
  CHECK(confirmed_static >= 100);
  CHECK(static_cast<double>(still) >= 0.95 * static_cast<double>(confirmed_static));
  CHECK(walkers_moving == walking);
}

TEST_CASE("cluster --tracks: frame mode and an unwritable file are usage errors (exit 2)") {
  const st::TempDir dir("cli_tracks", "errors");
  const std::string input = dir.path("office.csv");
  REQUIRE(st::run_cli({"simulate", "--sensor", "mid360", "--seconds", "0.3", "--out", input, "-q"}).code == 0);
  const st::RunResult frame = st::run_cli({"cluster", input, "--mode", "frame", "--tracks", dir.path("t.csv")});
  CHECK(frame.code == 2);
  CHECK(frame.err.find("--tracks") != std::string::npos);
  const st::RunResult unwritable =
      st::run_cli({"cluster", input, "--tracks", dir.path("missing/dir/t.csv"), "-q"});
  CHECK(unwritable.code == 2);
  CHECK(unwritable.err.find("--tracks: cannot write") != std::string::npos);
}

TEST_CASE("simulate writes each object's box and velocity over time beside the stream") {
  const st::TempDir dir("cli_tracks", "truth");
  const std::string input = dir.path("office.csv");
  REQUIRE(st::run_cli({"simulate", "--sensor", "mid360", "--scene", "office", "--seconds", "1", "--out", input, "-q"})
              .code == 0);
  std::ifstream file(dir.path("office.objects.csv"));
  REQUIRE(file);
  std::string line;
  REQUIRE(std::getline(file, line));
  CHECK(line == "time,instance,label,moving,x,y,z,vx,vy,vz,length,width,height,yaw");
  const std::vector<streamclust::sim::ObjectInfo> objects = streamclust::sim::make_scene("office", 1).objects();
  std::map<std::string, int> rows_at;
  std::size_t rows = 0, moving_rows = 0;
  while (std::getline(file, line)) {
    const std::vector<std::string> f = split(line, ',');
    REQUIRE(f.size() == 14);
    ++rows;
    ++rows_at[f[0]];
    const int instance = std::stoi(f[1]);
    REQUIRE(instance >= 1);
    REQUIRE(instance <= static_cast<int>(objects.size()));
    const bool moving = f[3] == "1";
    CHECK(moving == objects[static_cast<std::size_t>(instance - 1)].moving);
    CHECK(f[2] == objects[static_cast<std::size_t>(instance - 1)].label);
    const double speed = std::hypot(std::stod(f[7]), std::stod(f[8]));
    if (moving) {
      ++moving_rows;
      CHECK(speed > 0.3);  // the office's walkers: 0.8-1.5 m/s
      CHECK(speed < 2.0);
    } else {
      CHECK(speed == 0.0);
    }
    CHECK(std::stod(f[10]) >= std::stod(f[11]));  // length >= width
    CHECK(std::stod(f[12]) > 0.0);
  }
  // 20 rows per second for every object: about 21 times over 1 s.
  CHECK(rows_at.size() >= 20);
  CHECK(rows_at.size() <= 21);
  for (const auto& [time, count] : rows_at) CHECK(count == static_cast<int>(objects.size()));
  CHECK(moving_rows > 0);
  CHECK(rows == rows_at.size() * objects.size());

  const st::RunResult synthetic = st::run_cli({"simulate", "--sensor", "synthetic", "--scene", "room", "--out",
                                               dir.path("room.csv"), "--objects", dir.path("room.objects.csv")});
  CHECK(synthetic.code == 2);
  CHECK(synthetic.err.find("--objects") != std::string::npos);
}

TEST_CASE("evaluate --tracks: every method scored against the truth; its usage errors") {
  const st::TempDir dir("cli_tracks", "evaluate");
  const std::string json = dir.path("office.json"), tracks = dir.path("tracks.csv");
  const st::RunResult run = st::run_cli({"evaluate", "--tracks", "--sensor", "mid360", "--scene", "office",
                                         "--duration", "2.5", "--json", json, "--tracks-out", tracks, "-q"});
  INFO(run.err);
  REQUIRE(run.code == 0);
  std::ifstream f(json);
  const nlohmann::json doc = nlohmann::json::parse(f);
  REQUIRE(doc["methods"].size() == 3);
  CHECK(doc["methods"][0]["method"] == "objects");
  CHECK(doc["methods"][2]["method"] == "centroid");
  CHECK(doc["moving_objects"].get<int>() > 0);
  for (const auto& m : doc["methods"]) {
    CAPTURE(m.dump());
    CHECK(m["frames"].get<int>() >= 15);
    CHECK(m["objects"].get<int>() > 5);
    CHECK(m["mota"].get<double>() <= 1.0);
    for (const char* rate : {"idf1", "recall", "precision", "still_share", "mean_bev_iou"}) {
      CHECK(m[rate].get<double>() >= 0.0);
      CHECK(m[rate].get<double>() <= 1.0);
    }
    CHECK(m["matches"].get<int>() + m["misses"].get<int>() == m["truth"].get<int>());
    CHECK(m["velocity_samples"].get<int>() > 0);  // the walkers
  }
  // The objects tracker finds most rated objects and keeps the standing ones
  // still (2 s scored: its births wait for three sightings of 30 points
  // standing on the ground, which costs the first retrievals' recall).
  const auto& objects = doc["methods"][0];
  CHECK(objects["recall"].get<double>() > 0.8);
  CHECK(objects["still_share"].get<double>() > 0.8);
  // The tracks CSV: the cluster command's header, a row per track and scored retrieval.
  std::ifstream csv(tracks);
  std::string header;
  REQUIRE(std::getline(csv, header));
  CHECK(header == "cycle,time,track_id,cluster_id,x,y,z,vx,vy,vz,length,width,height,yaw,points,state");
  std::size_t rows = 0;
  for (std::string line; std::getline(csv, line);) rows += line.empty() ? 0 : 1;
  CHECK(rows > 100);

  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"evaluate", "--tracks", "--method", "kalman"},
        std::vector<std::string>{"evaluate", "--tracks", "--duration", "0.5"},
        std::vector<std::string>{"evaluate", "--tracks", "--sensor", "spinning32"},
        std::vector<std::string>{"evaluate", "--tracks", "--match-distance", "0"},
        std::vector<std::string>{"evaluate", "--tracks", "--verify"}}) {
    const st::RunResult r = st::run_cli(bad);
    CAPTURE(bad.back());
    CHECK(r.code == 2);
    CHECK_FALSE(r.err.empty());
  }
  const st::RunResult help = st::run_cli({"evaluate", "--tracks", "--help"});
  CHECK(help.code == 0);
  CHECK(help.out.find("CLEAR MOT") != std::string::npos);
}
