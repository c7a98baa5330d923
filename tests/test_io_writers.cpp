// SPDX-License-Identifier: MIT
// Round trips of every writer through the readers, NaN coordinates and labels included.

#include <doctest/doctest.h>

#include <streamclust/io/reader.hpp>
#include <streamclust/io/writers.hpp>

#include "support/same_float.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace io = streamclust::io;
namespace fs = std::filesystem;
using streamclust::test::same_float;

namespace {

struct WriterTempDir {
  fs::path dir;
  explicit WriterTempDir(const std::string& name) {
    std::random_device rd;
    dir = fs::temp_directory_path() / ("streamclust_io_writers_" + name + "_" + std::to_string(rd()));
    fs::create_directories(dir);
  }
  ~WriterTempDir() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string path(const std::string& name) const { return (dir / name).string(); }
};

/// Records with NaN / inf coordinates, negative and positive labels, fine times.
std::vector<io::Record> sample_records(std::size_t n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-50.f, 50.f);
  std::vector<io::Record> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    v[i].x = u(rng);
    v[i].y = u(rng);
    v[i].z = u(rng) / 10.f;
    v[i].intensity = static_cast<float>(i % 256);
    v[i].t = 1.6e9 + static_cast<double>(i) * 4.1666e-6;
    v[i].label = (i % 5 == 0) ? -1 : static_cast<std::int64_t>(i % 37);
  }
  if (n > 3) {
    v[1].x = std::numeric_limits<float>::quiet_NaN();
    v[2].y = std::numeric_limits<float>::infinity();
    v[3].z = -std::numeric_limits<float>::infinity();
  }
  return v;
}

/// Records read back equal `a`, their times counted from the reader's origin.
struct ReadBack {
  std::vector<io::Record> records;
  io::TimeOrigin origin;
};

void check_same(const std::vector<io::Record>& a, const ReadBack& back, bool has_t, bool has_label,
                const std::vector<std::int64_t>& labels = {}) {
  const std::vector<io::Record>& b = back.records;
  REQUIRE(a.size() == b.size());
  std::size_t bad = 0, first_bad = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const bool ok = same_float(a[i].x, b[i].x) && same_float(a[i].y, b[i].y) && same_float(a[i].z, b[i].z) &&
                    a[i].intensity == b[i].intensity &&
                    (!has_t || a[i].t == io::absolute_seconds(back.origin, b[i].t)) &&
                    (!has_label || b[i].label == (labels.empty() ? a[i].label : labels[i]));
    if (!ok && bad++ == 0) first_bad = i;
  }
  INFO("first mismatching record: " << first_bad);
  CHECK(bad == 0);
}

ReadBack read_back(const std::string& path, const io::ReadOptions& o = {}) {
  auto r = io::open_reader(path, o);
  ReadBack out;
  while (r->read(out.records, 333) > 0) {
  }
  out.origin = r->time_origin();
  return out;
}

}  // namespace

TEST_CASE("CSV round trip is exact, NaN/inf and labels included") {
  WriterTempDir tmp("csv");
  const auto recs = sample_records(500);
  const auto p = tmp.path("pts.csv");
  io::write_csv_points(p, recs);
  auto r = io::open_reader(p);
  CHECK(r->info().has_time);
  CHECK(r->info().has_label);
  check_same(recs, read_back(p), true, true);
  std::vector<std::int64_t> labels(recs.size(), 9);
  io::write_csv_points(p, recs, labels);
  check_same(recs, read_back(p), true, true, labels);
}

TEST_CASE("PCD round trips: ascii, binary, binary_compressed, with given or record labels") {
  WriterTempDir tmp("pcd");
  for (std::size_t n : {0u, 1u, 5u, 20000u}) {
    const auto recs = sample_records(n);
    std::vector<std::int64_t> labels(n);
    for (std::size_t i = 0; i < n; ++i) labels[i] = static_cast<std::int64_t>(i / 100) - 1;
    for (const char* enc : {"ascii", "binary", "binary_compressed"}) {
      INFO(enc << " n=" << n);
      const auto p = tmp.path(std::string("out_") + enc + ".pcd");
      io::write_pcd(p, recs, labels, enc);
      auto r = io::open_reader(p);
      CHECK(r->info().encoding == enc);
      CHECK(r->info().declared_points == n);
      CHECK(r->info().has_label);
      check_same(recs, read_back(p), true, true, labels);
      io::write_pcd(p, recs, {}, enc);
      check_same(recs, read_back(p), true, true);
    }
  }
  const auto big = sample_records(20000);
  io::write_pcd(tmp.path("a.pcd"), big, {}, "binary");
  io::write_pcd(tmp.path("c.pcd"), big, {}, "binary_compressed");
  CHECK(fs::file_size(tmp.path("c.pcd")) < fs::file_size(tmp.path("a.pcd")));
}

TEST_CASE("PLY round trips: ascii and binary, label property and colours") {
  WriterTempDir tmp("ply");
  const auto recs = sample_records(1000);
  for (bool binary : {false, true}) {
    INFO("binary=" << binary);
    const auto p = tmp.path(binary ? "b.ply" : "a.ply");
    io::write_ply(p, recs, {}, binary);
    auto r = io::open_reader(p);
    CHECK(r->info().encoding == (binary ? "binary_little_endian" : "ascii"));
    CHECK(r->info().fields.size() == 9);
    check_same(recs, read_back(p), true, true);
    std::vector<std::int64_t> labels(recs.size(), 3);
    io::write_ply(p, recs, labels, binary);
    check_same(recs, read_back(p), true, true, labels);
  }
}

TEST_CASE("label colours: grey for -1, deterministic and varied otherwise") {
  CHECK(io::label_color(-1) == std::array<std::uint8_t, 3>{128, 128, 128});
  CHECK(io::label_color(5) == io::label_color(5));
  std::set<std::array<std::uint8_t, 3>> colours;
  for (std::int64_t l = 0; l < 50; ++l) {
    const auto c = io::label_color(l);
    CHECK(c != io::label_color(-1));
    colours.insert(c);
  }
  CHECK(colours.size() >= 45);
}

TEST_CASE("KITTI .bin round trip (x y z reflectance; t from the point rate)") {
  WriterTempDir tmp("kitti");
  const auto recs = sample_records(777);
  const auto p = tmp.path("k.bin");
  io::write_kitti_bin(p, recs);
  CHECK(fs::file_size(p) == 777u * 16u);
  io::ReadOptions o;
  o.point_rate = 1000.0;
  const auto back = read_back(p, o);
  check_same(recs, back, false, false);
  CHECK(back.records[10].t == doctest::Approx(0.01));
  CHECK(back.records[10].label == -1);
}

TEST_CASE("SemanticKITTI .label: semantic 0/1 in the low 16 bits, instance = label + 1 (clamped) above") {
  CHECK(io::semantickitti_encode(-1) == 0u);
  CHECK(io::semantickitti_encode(0) == ((1u << 16) | 1u));
  CHECK(io::semantickitti_encode(41) == ((42u << 16) | 1u));
  CHECK(io::semantickitti_encode(1000000) == ((65535u << 16) | 1u));
  WriterTempDir tmp("label");
  const std::vector<std::int64_t> labels{-1, 0, 1, 7, -1, 65533, 70000};
  const auto p = tmp.path("l.label");
  io::write_semantickitti_labels(p, labels);
  CHECK(fs::file_size(p) == labels.size() * 4);
  const auto back = io::read_semantickitti_labels(p);
  CHECK(back == std::vector<std::int64_t>{-1, 0, 1, 7, -1, 65533, 65534});
}

TEST_CASE("writers: bad arguments and unwritable paths throw naming the file") {
  WriterTempDir tmp("bad");
  const auto recs = sample_records(3);
  const std::string nowhere = tmp.path("no/such/dir/x.pcd");
  for (auto f : {+[](const std::string& p, const std::vector<io::Record>& r) { io::write_csv_points(p, r); },
                 +[](const std::string& p, const std::vector<io::Record>& r) { io::write_pcd(p, r, {}, "binary"); },
                 +[](const std::string& p, const std::vector<io::Record>& r) { io::write_ply(p, r, {}, true); },
                 +[](const std::string& p, const std::vector<io::Record>& r) { io::write_kitti_bin(p, r); }}) {
    try {
      f(nowhere, recs);
      FAIL("expected an exception");
    } catch (const std::runtime_error& e) {
      CHECK(std::string(e.what()).find(nowhere) != std::string::npos);
    }
  }
  CHECK_THROWS_AS(io::write_semantickitti_labels(nowhere, {1}), std::runtime_error);
  CHECK_THROWS_AS(io::write_pcd(tmp.path("a.pcd"), recs, {1, 2}, "ascii"), std::invalid_argument);
  CHECK_THROWS_AS(io::write_pcd(tmp.path("a.pcd"), recs, {}, "lzf"), std::invalid_argument);
  CHECK_THROWS_AS(io::write_ply(tmp.path("a.ply"), recs, {1}, false), std::invalid_argument);
  CHECK_THROWS_AS(io::write_pcd(tmp.path("a.pcd"), recs, {1, 2, std::int64_t{1} << 40}, "binary"),
                  std::invalid_argument);
}
