// SPDX-License-Identifier: MIT
// Unit tests of the I/O readers: column mapping, time rules, encodings, streaming.

#include <doctest/doctest.h>

#include "support/bad_files.hpp"
#include "support/temp_dir.hpp"

#include <streamclust/io/lzf.hpp>
#include <streamclust/io/reader.hpp>
#include <streamclust/point_traits.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace io = streamclust::io;
namespace fs = std::filesystem;

namespace {

/// A per-test temporary directory (tests/support/temp_dir.hpp).
struct ReaderTempDir : streamclust::test::TempDir {
  explicit ReaderTempDir(const std::string& name) : TempDir("io_readers", name) {}
};

std::vector<io::Record> read_all(io::PointReader& r, std::size_t chunk = 1000) {
  std::vector<io::Record> out;
  while (r.read(out, chunk) > 0) {
  }
  return out;
}

std::vector<io::Record> read_all(const std::string& path, const io::ReadOptions& o = {}) {
  auto r = io::open_reader(path, o);
  return read_all(*r);
}

using streamclust::test::append_bytes;

}  // namespace

static_assert(streamclust::is_point_v<io::Record>, "io::Record must model the point concept");

TEST_CASE("io::Record works with point_traits: position, stamp and intensity") {
  io::Record r{1.f, 2.f, 3.f, 7.f, 0.25, 4};
  CHECK(streamclust::position(r).x() == 1.f);
  CHECK(streamclust::position(r).z() == 3.f);
  CHECK(streamclust::stamp(r) == 0.25);
  CHECK(streamclust::intensity(r) == 7.f);
}

TEST_CASE("format and time unit names parse and print") {
  CHECK(io::parse_format("pcd") == io::Format::pcd);
  CHECK(io::parse_format("kitti") == io::Format::kitti);
  CHECK_FALSE(io::parse_format("las"));
  CHECK(std::string(io::to_string(io::Format::ply)) == "ply");
  CHECK(io::parse_time_unit("us") == io::TimeUnit::us);
  CHECK_FALSE(io::parse_time_unit("min"));
}

TEST_CASE("CSV: named columns in any order, extra columns ignored, whitespace, trailing comma, label") {
  ReaderTempDir tmp("csv_named");
  const auto p = tmp.file("a.csv",
                          " Tag , Z,reflectivity, x ,y,time, gt ,\n"
                          "0, 3, 9, 1, 2, 0.5, 7,\n"
                          "\n"
                          "1,6,10,4,5,0.75,-1,\n"
                          "2,nan,11,7,8,1.0,3\n");
  auto r = io::open_reader(p);
  CHECK(r->info().format == io::Format::csv);
  CHECK(r->info().has_time);
  CHECK(r->info().time_field == "time");
  CHECK(r->info().has_intensity);
  CHECK(r->info().has_label);
  CHECK(r->info().fields.size() == 7);
  const auto v = read_all(*r);
  REQUIRE(v.size() == 3);
  CHECK(v[0].x == 1.f);
  CHECK(v[0].y == 2.f);
  CHECK(v[0].z == 3.f);
  CHECK(v[0].intensity == 9.f);
  CHECK(v[0].t == 0.5);
  CHECK(v[0].label == 7);
  CHECK(v[1].label == -1);
  CHECK(std::isnan(v[2].z));  // NaN records are returned, not dropped
  CHECK(v[2].label == 3);
}

TEST_CASE("CSV: time field preference t > time > timestamp > offset_time, units") {
  ReaderTempDir tmp("csv_time");
  const auto p = tmp.file("a.csv", "offset_time,x,y,z,timestamp\n1000,1,2,3,5\n");
  auto first = io::open_reader(p);
  auto v = read_all(*first);
  REQUIRE(v.size() == 1);
  // timestamp wins over offset_time; seconds by default; counted from the whole second
  CHECK(first->time_origin() == io::TimeOrigin{5});
  CHECK(v[0].t == 0.0);
  const auto q = tmp.file("b.csv", "offset_time,x,y,z\n1500000000,1,2,3\n");
  auto r = io::open_reader(q);
  CHECK(r->info().time_unit == io::TimeUnit::ns);
  v = read_all(*r);
  CHECK(r->time_origin() == io::TimeOrigin{1});
  CHECK(v[0].t == doctest::Approx(0.5));
  io::ReadOptions o;
  o.time_unit = io::TimeUnit::ms;
  v = read_all(p, o);
  CHECK(v[0].t == doctest::Approx(0.005));
}

TEST_CASE("CSV: Livox Viewer export (Timestamp in ns, X Y Z Reflectivity)") {
  ReaderTempDir tmp("csv_livox");
  const auto p = tmp.file(
      "viewer.csv",
      "Version,Slot ID,LiDAR Index,Rsvd,Error Code,Timestamp Type,Data Type,Timestamp,X,Y,Z,Reflectivity,Tag,"
      "Ori_x,Ori_y,Ori_z,Ori_radius,Ori_theta,Ori_phi\n"
      "5,1,1,0,0x00000000,0,0,2444124311890,4.971,-0.365,0.411,51,0,4971,-365,411,0,0,0\n");
  auto r = io::open_reader(p);
  CHECK(r->info().time_unit == io::TimeUnit::ns);
  const auto v = read_all(*r);
  REQUIRE(v.size() == 1);
  CHECK(v[0].x == doctest::Approx(4.971));
  CHECK(v[0].intensity == 51.f);
  CHECK(r->time_origin() == io::TimeOrigin{2444});
  CHECK(v[0].t == doctest::Approx(0.124311890));
}

TEST_CASE("CSV: headerless x,y,z[,intensity] with a point rate; whitespace-separated text") {
  ReaderTempDir tmp("csv_headerless");
  const auto p = tmp.file("h.csv", "1,2,3,4,\n5,6,7,8,\n9,10,11,12,\n");
  io::ReadOptions o;
  o.point_rate = 10.0;
  auto r = io::open_reader(p, o);
  CHECK_FALSE(r->info().has_time);
  CHECK(r->info().has_intensity);
  const auto v = read_all(*r);
  REQUIRE(v.size() == 3);
  CHECK(v[2].x == 9.f);
  CHECK(v[2].intensity == 12.f);
  CHECK(v[2].t == doctest::Approx(0.2));
  const auto q = tmp.file("w.txt", "x y z t\n1 2 3 0.1\n4\t5\t6\t0.2\n");
  const auto w = read_all(q);
  REQUIRE(w.size() == 2);
  CHECK(w[1].z == 6.f);
  CHECK(w[1].t == doctest::Approx(0.2));
}

TEST_CASE("readers stream in chunks and keep file order; t = index / rate counts every record") {
  ReaderTempDir tmp("chunks");
  std::string s = "x,y,z\n";
  for (int i = 0; i < 100; ++i) s += std::to_string(i) + (i % 7 == 0 ? ",nan,0\n" : ",0,0\n");
  const auto p = tmp.file("c.csv", s);
  io::ReadOptions o;
  o.point_rate = 100.0;
  auto r = io::open_reader(p, o);
  std::vector<io::Record> out;
  std::size_t calls = 0;
  std::size_t got = 0;
  while ((got = r->read(out, 7)) > 0) {
    CHECK(got <= 7);
    ++calls;
  }
  CHECK(calls == 15);
  REQUIRE(out.size() == 100);
  for (int i = 0; i < 100; ++i) {
    CHECK(out[static_cast<std::size_t>(i)].x == static_cast<float>(i));
    CHECK(out[static_cast<std::size_t>(i)].t == doctest::Approx(i / 100.0));
  }
  CHECK(r->read(out, 7) == 0);
  CHECK(r->records_read() == 100);
}

TEST_CASE("PCD ascii: COUNT > 1 fields skipped, integer types, offset_time in ns, VERSION .7") {
  ReaderTempDir tmp("pcd_ascii");
  const auto p = tmp.file("a.pcd",
                          "# .PCD v.7 - Point Cloud Data file format\n"
                          "VERSION .7\n"
                          "FIELDS x normal y z intensity offset_time label\n"
                          "SIZE 4 4 8 4 1 4 2\n"
                          "TYPE F F F F U U I\n"
                          "COUNT 1 3 1 1 1 1 1\n"
                          "WIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n"
                          "1 0 0 1 2 3 200 1000 5\n"
                          "4 0 0 1 5 nan 201 2000 -1\n");
  auto r = io::open_reader(p);
  CHECK(r->info().encoding == "ascii");
  CHECK(r->info().declared_points == 2u);
  CHECK(r->info().time_field == "offset_time");
  CHECK(r->info().time_unit == io::TimeUnit::ns);
  const auto v = read_all(*r);
  REQUIRE(v.size() == 2);
  CHECK(v[0].y == 2.f);
  CHECK(v[0].z == 3.f);
  CHECK(v[0].intensity == 200.f);
  CHECK(v[0].t == doctest::Approx(1e-6));
  CHECK(v[0].label == 5);
  CHECK(std::isnan(v[1].z));
  CHECK(v[1].label == -1);
}

TEST_CASE("PCD binary with WIDTH 0 HEIGHT 0 and a correct POINTS; mixed scalar types") {
  ReaderTempDir tmp("pcd_binary");
  std::string s =
      "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z _ t label\nSIZE 4 4 8 2 8 4\nTYPE F F F U F U\nCOUNT 1 1 1 1 1 1\n"
      "WIDTH 0\nHEIGHT 0\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 300\nDATA binary\n";
  for (int i = 0; i < 300; ++i) {
    append_bytes(s, static_cast<float>(i));
    append_bytes(s, -static_cast<float>(i));
    append_bytes(s, 0.5 * i);
    append_bytes(s, std::uint16_t{0});
    append_bytes(s, 0.001 * i);
    append_bytes(s, static_cast<std::uint32_t>(i % 5));
  }
  const auto p = tmp.file("b.pcd", s);
  auto r = io::open_reader(p);
  CHECK(r->info().encoding == "binary");
  CHECK_FALSE(r->info().has_intensity);
  const auto v = read_all(*r, 64);
  REQUIRE(v.size() == 300);
  CHECK(v[299].x == 299.f);
  CHECK(v[299].y == -299.f);
  CHECK(v[299].z == 149.5f);
  CHECK(v[299].t == doctest::Approx(0.299));
  CHECK(v[299].label == 4);
}

TEST_CASE("PLY ascii: elements before the vertex, list property skipped, comments") {
  ReaderTempDir tmp("ply_ascii");
  const auto p = tmp.file("a.ply",
                          "ply\nformat ascii 1.0\ncomment hi\nelement camera 1\nproperty float fx\n"
                          "element vertex 2\nproperty double x\nproperty float y\nproperty list uchar int idx\n"
                          "property float z\nproperty uint timestamp\nproperty int instance\n"
                          "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                          "500\n"
                          "1 2 3 7 8 9 3 10 4\n"
                          "5 6 0 7 11 -1\n"
                          "3 0 1 1\n");
  auto r = io::open_reader(p);
  CHECK(r->info().encoding == "ascii");
  CHECK(r->info().time_field == "timestamp");
  const auto v = read_all(*r);
  REQUIRE(v.size() == 2);
  CHECK(v[0].x == 1.f);
  CHECK(v[0].y == 2.f);
  CHECK(v[0].z == 3.f);
  CHECK(r->time_origin() == io::TimeOrigin{10});
  CHECK(v[0].t == 0.0);
  CHECK(v[0].label == 4);
  CHECK(v[1].z == 7.f);
  CHECK(v[1].label == -1);
}

TEST_CASE("PLY binary little endian: all scalar types, a list in the vertex element") {
  ReaderTempDir tmp("ply_binary");
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty char a\nproperty float32 x\n"
      "property int16 y\nproperty list uint8 int32 l\nproperty float64 z\nproperty uchar intensity\n"
      "property ushort b\nproperty uint t\nend_header\n";
  for (int i = 0; i < 3; ++i) {
    append_bytes(s, std::int8_t{-1});
    append_bytes(s, 1.5f * static_cast<float>(i));
    append_bytes(s, static_cast<std::int16_t>(-i));
    append_bytes(s, static_cast<std::uint8_t>(i));
    for (int k = 0; k < i; ++k) append_bytes(s, std::int32_t{k});
    append_bytes(s, 2.0 * i);
    append_bytes(s, static_cast<std::uint8_t>(200 + i));
    append_bytes(s, std::uint16_t{7});
    append_bytes(s, static_cast<std::uint32_t>(10 * i));
  }
  const auto p = tmp.file("b.ply", s);
  const auto v = read_all(p);
  REQUIRE(v.size() == 3);
  CHECK(v[2].x == 3.f);
  CHECK(v[2].y == -2.f);
  CHECK(v[2].z == 4.f);
  CHECK(v[2].intensity == 202.f);
  CHECK(v[2].t == 20.0);
}

TEST_CASE("KITTI .bin needs a point rate; reflectance is the intensity") {
  ReaderTempDir tmp("kitti");
  std::string s;
  for (int i = 0; i < 5; ++i)
    for (float f : {1.f * static_cast<float>(i), 2.f, 3.f, 0.5f}) append_bytes(s, f);
  const auto p = tmp.file("k.bin", s);
  io::ReadOptions o;
  o.point_rate = 2.0;
  auto r = io::open_reader(p, o);
  CHECK(r->info().format == io::Format::kitti);
  CHECK(r->info().declared_points == 5u);
  const auto v = read_all(*r, 2);
  REQUIRE(v.size() == 5);
  CHECK(v[4].x == 4.f);
  CHECK(v[4].intensity == 0.5f);
  CHECK(v[4].t == 2.0);
}

TEST_CASE("detect_format: by extension, then by content") {
  ReaderTempDir tmp("detect");
  CHECK(io::detect_format(tmp.file("a.CSV", "x,y,z\n")) == io::Format::csv);
  CHECK(io::detect_format(tmp.file("a.Pcd", "x")) == io::Format::pcd);
  CHECK(io::detect_format(tmp.file("a.ply", "x")) == io::Format::ply);
  CHECK(io::detect_format(tmp.file("a.bin", "x")) == io::Format::kitti);
  CHECK(io::detect_format(tmp.file("noext1", "ply\nformat ascii 1.0\n")) == io::Format::ply);
  CHECK(io::detect_format(tmp.file("noext2", "# .PCD v0.7\n")) == io::Format::pcd);
  CHECK(io::detect_format(tmp.file("noext3", "VERSION 0.7\n")) == io::Format::pcd);
  CHECK(io::detect_format(tmp.file("noext4", "x,y,z\n1,2,3\n")) == io::Format::csv);
  CHECK_THROWS_AS(io::detect_format(tmp.file("noext5", std::string("\x01\x02\x03", 3))), io::InputError);
  // An explicit format wins over the extension.
  io::ReadOptions o;
  o.format = io::Format::csv;
  CHECK(read_all(tmp.file("pts.dat", "x,y,z,t\n1,2,3,4\n"), o).size() == 1);
}

TEST_CASE("LZF: round trips of random, repetitive and tiny data; corrupt data is reported") {
  std::mt19937 rng(42);
  for (std::size_t n : {0u, 1u, 2u, 3u, 31u, 32u, 33u, 1000u, 70000u}) {
    for (int kind = 0; kind < 3; ++kind) {
      std::vector<unsigned char> data(n);
      for (std::size_t i = 0; i < n; ++i) {
        data[i] = kind == 0   ? static_cast<unsigned char>(rng())
                  : kind == 1 ? static_cast<unsigned char>(i % 7)
                              : static_cast<unsigned char>((rng() % 16 == 0) ? rng() : 0);
      }
      const auto c = io::lzf_compress(data.data(), data.size());
      CHECK(c.size() <= n + n / 32 + 1);
      std::vector<unsigned char> back(n);
      CHECK(io::lzf_decompress(c.data(), c.size(), back.data(), back.size()) == "");
      CHECK(back == data);
      if (kind == 1 && n >= 1000) CHECK(c.size() < n / 10);
    }
  }
  // A back reference before the start of the output.
  const unsigned char bad[] = {0x20, 0x05};
  unsigned char out[16];
  CHECK(io::lzf_decompress(bad, sizeof bad, out, sizeof out).find("before the start") != std::string::npos);
  // A literal run past the end of the input.
  const unsigned char trunc[] = {0x05, 'a'};
  CHECK(io::lzf_decompress(trunc, sizeof trunc, out, sizeof out).find("past the end") != std::string::npos);
  // Output larger than declared.
  const unsigned char lit[] = {0x02, 'a', 'b', 'c'};
  CHECK(io::lzf_decompress(lit, sizeof lit, out, 2).find("overflows") != std::string::npos);
  CHECK(io::lzf_decompress(lit, sizeof lit, out, 5).find("declares 5") != std::string::npos);
}
