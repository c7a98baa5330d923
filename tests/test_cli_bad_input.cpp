// SPDX-License-Identifier: MIT
// The tool on bad input: an input error (exit 4) naming file and place; a
// header without points (info describes it, cluster refuses it); running
// out of memory (exit 5, naming command, input and stage).

#include <doctest/doctest.h>

#include "cli/main.hpp"
#include "cli/memory_context.hpp"
#include "cli/options.hpp"

#include "support/cli_run.hpp"
#include "support/temp_dir.hpp"

#include <new>
#include <sstream>
#include <string>

namespace sc = streamclust;

namespace {

using streamclust::test::run_cli;

const std::string pcd_head_xyzt =
    "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z t\nSIZE 4 4 4 8\nTYPE F F F F\n"
    "COUNT 1 1 1 1\n";

}  // namespace

TEST_CASE("a header without points: info reports 0 points (exit 0), cluster exits 4 'no points'") {
  const sc::test::TempDir tmp("cli_bad_input", "header_only");
  const std::string files[] = {
      tmp.file("empty.csv", "x,y,z,t\n"),
      tmp.file("empty.pcd", pcd_head_xyzt + "WIDTH 0\nHEIGHT 1\nPOINTS 0\nDATA ascii\n"),
      tmp.file("empty_binary.pcd", pcd_head_xyzt + "WIDTH 0\nHEIGHT 1\nPOINTS 0\nDATA binary\n"),
      tmp.file("empty.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
                            "property float y\nproperty float z\nproperty double t\nend_header\n"),
  };
  for (const std::string& f : files) {
    INFO(f);
    const auto info = run_cli({"info", f});
    INFO(info.err);
    CHECK(info.code == 0);
    CHECK(info.out.find("points:    0 (0 with finite coordinates)") != std::string::npos);
    const auto cluster = run_cli({"cluster", f, "--quiet"});
    CHECK(cluster.code == 4);
    CHECK(cluster.err == "streamclust: input error: " + f + ": header: no points: nothing to cluster (info describes such an input)\n");
  }
}

TEST_CASE("bytes after the declared data: info and cluster exit 4 naming the byte") {
  const sc::test::TempDir tmp("cli_bad_input", "trailing");
  std::string s = pcd_head_xyzt + "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA binary\n";
  const std::size_t end = s.size() + 20;
  s += std::string(20 + 7, '\0');
  const std::string f = tmp.file("trailing.pcd", s);
  const std::string expected = "streamclust: input error: " + f + ": byte " + std::to_string(end) +
                               ": 7 bytes after the declared data (POINTS 1 x 20 bytes): expected end of file\n";
  const auto info = run_cli({"info", f});
  CHECK(info.code == 4);
  CHECK(info.err == expected);
  const auto cluster = run_cli({"cluster", f, "--quiet"});
  CHECK(cluster.code == 4);
  CHECK(cluster.err == expected);
}

TEST_CASE("out of memory: the command, the input and the stage, exit 5") {
  using sc::cli::Stage;
  try {
    sc::cli::with_memory_context("cluster", "scan.pcd", [](Stage& stage) -> int {
      stage = Stage::clustering;
      throw std::bad_alloc();
    });
    FAIL("expected OutOfMemory");
  } catch (const sc::cli::OutOfMemory& e) {
    CHECK(std::string(e.what()) == "cluster scan.pcd: out of memory while clustering");
    CHECK(e.stage() == Stage::clustering);
    std::ostringstream err;
    CHECK(sc::cli::report_exception("cluster", err) == sc::cli::kOutOfMemory);
    CHECK(err.str() == "streamclust: cluster scan.pcd: out of memory while clustering\n");
  }
  // Without context (simulate, evaluate): the command.
  try {
    throw std::bad_alloc();
  } catch (...) {
    std::ostringstream err;
    CHECK(sc::cli::report_exception("simulate", err) == 5);
    CHECK(err.str() == "streamclust: simulate: out of memory\n");
  }
  // A value computed without running out passes through.
  CHECK(sc::cli::with_memory_context("info", "a.csv", [](Stage&) { return 7; }) == 7);
}
