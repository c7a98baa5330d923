// SPDX-License-Identifier: MIT
// Every reader against broken input: each gives a precise InputError (file,
// place, what was expected), never a crash, a hang or a huge allocation.

#include <doctest/doctest.h>

#include "support/bad_files.hpp"
#include "support/temp_dir.hpp"

#include <streamclust/io/reader.hpp>
#include <streamclust/io/writers.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace io = streamclust::io;
namespace fs = std::filesystem;

namespace {

/// A per-test temporary directory (tests/support/temp_dir.hpp).
struct ErrorTempDir : streamclust::test::TempDir {
  explicit ErrorTempDir(const std::string& name) : TempDir("io_errors", name) {}
};

using streamclust::test::append_bytes;
using streamclust::test::expect_error;
using streamclust::test::file_bytes;
using streamclust::test::some_records;
using streamclust::test::with_rate;

const char* pcd_header_xyz =
    "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\n"
    "COUNT 1 1 1 1\n";

}  // namespace

TEST_CASE("any format: missing file, directory, empty file, unknown format") {
  ErrorTempDir tmp("generic");
  for (const char* ext : {".csv", ".pcd", ".ply", ".bin", ""}) {
    expect_error(tmp.path(std::string("missing") + ext), "byte 0", "cannot open");
    expect_error(tmp.file(std::string("empty") + ext, ""), "byte 0", "empty file");
  }
  // A directory is read as a rosbag2 bag folder: without metadata.yaml it is none.
  expect_error(tmp.dir.string(), "directory", "a directory is read as a rosbag2 bag folder: expected metadata.yaml");
  expect_error(tmp.file("mystery.xyz", std::string("\x7f" "ELF\x01\x02", 6)), "header", "unknown format");
  io::ReadOptions forced = with_rate();
  forced.format = io::Format::pcd;
  expect_error(tmp.file("empty.dat", ""), "byte 0", "empty file", forced);
}

TEST_CASE("no time field and no point rate: a header error saying what to pass") {
  ErrorTempDir tmp("notime");
  const std::string msg = "no time field (t, time, timestamp or offset_time); pass a point rate (--point-rate HZ)";
  io::ReadOptions none;
  expect_error(tmp.file("a.csv", "x,y,z\n1,2,3\n"), "header", msg, none);
  expect_error(tmp.file("h.csv", "1,2,3\n"), "header", msg, none);
  expect_error(tmp.file("a.pcd", std::string(pcd_header_xyz) + "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3 4\n"),
               "header", msg, none);
  expect_error(tmp.file("a.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                 "property float z\nend_header\n1 2 3\n"),
               "header", msg, none);
  expect_error(tmp.file("a.bin", std::string(16, '\0')), "header", msg, none);
  io::ReadOptions bad_rate;
  bad_rate.point_rate = 0.0;
  CHECK_THROWS_AS(io::open_reader(tmp.file("b.csv", "x,y,z\n1,2,3\n"), bad_rate), std::invalid_argument);
}

TEST_CASE("CSV errors name line and column") {
  ErrorTempDir tmp("csv");
  expect_error(tmp.file("nonnum.csv", "x,y,z,t\n1,2,3,0\n1,2,abc,0\n"), "line 3, column 3 (z)",
               "expected a number, found \"abc\"");
  expect_error(tmp.file("empty_value.csv", "x,y,z,t\n1,,3,0\n"), "line 2, column 2 (y)",
               "expected a number, found \"\"");
  expect_error(tmp.file("label.csv", "x,y,z,t,label\n1,2,3,0,1.5\n"), "line 2, column 5 (label)",
               "expected an integer label");
  expect_error(tmp.file("count.csv", "x,y,z,t\n1,2,3,0\n\n1,2,3\n"), "line 4", "expected 4 fields (as in the first line), found 3");
  expect_error(tmp.file("toomany.csv", "x,y,z,t\n1,2,3,0,5,6\n"), "line 2", "expected 4 fields");
  expect_error(tmp.file("headerless.csv", "1,2,3,4\n1,2,3\n"), "line 2", "expected 4 fields");
  expect_error(tmp.file("magic.csv", "a,b,c\n1,2,3\n"), "line 1", "expected a header with columns named x, y and z");
  expect_error(tmp.file("short.csv", "1,2\n"), "line 1", "at least 3 numeric columns");
  // Truncated mid-line: the last line has too few fields.
  expect_error(tmp.file("trunc.csv", "x,y,z,t\n1,2,3,0\n4,5"), "line 3", "expected 4 fields");
  // A binary file with no newline: bounded, then a clear error.
  std::string blob(3u << 20, 'a');
  blob[0] = 'x';
  blob[1] = ',';
  expect_error(tmp.file("long.csv", blob), "line 1", "line longer than 1048576 bytes");
  expect_error(tmp.file("range.csv", "x,y,z,t\n1e39,2,3,0\n"), "line 2, column 1 (x)", "expected a number");
}

TEST_CASE("PCD header errors") {
  ErrorTempDir tmp("pcd_header");
  const std::string tail = "WIDTH 1\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\nDATA ascii\n1 2 3 4\n";
  expect_error(tmp.file("magic.pcd", "hello world\n" + tail), "line 1", "expected a PCD header");
  expect_error(tmp.file("magic2.pcd", "ply\nformat ascii 1.0\n"), "line 1", "expected a PCD header");
  expect_error(tmp.file("bincomment.pcd", std::string("#\x01\x02\x03 junk\n", 10)), "line 1", "expected a PCD header");
  expect_error(tmp.file("nodata.pcd", std::string(pcd_header_xyz) + "WIDTH 1\nHEIGHT 1\nPOINTS 1\n"), "line 10",
               "file ends inside the header: expected a DATA line");
  expect_error(tmp.file("sizes.pcd",
                        "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n" + tail),
               "line 3", "SIZE has 3 entries, expected 4 (one per field in FIELDS, line 2)");
  expect_error(tmp.file("types.pcd",
                        "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F\nCOUNT 1 1 1 1\n" + tail),
               "line 4", "TYPE has 3 entries, expected 4");
  expect_error(tmp.file("badtype.pcd",
                        "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 2\nTYPE F F F F\nCOUNT 1 1 1 1\n" + tail),
               "line 4", "field intensity has TYPE \"F\" and SIZE 2");
  expect_error(tmp.file("noxyz.pcd",
                        "VERSION 0.7\nFIELDS x y intensity\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n" + tail),
               "line 2", "expected fields x, y and z with COUNT 1, found FIELDS x y intensity");
  expect_error(tmp.file("points.pcd", std::string(pcd_header_xyz) +
                                          "WIDTH 1\nHEIGHT 1\nPOINTS lots\nDATA ascii\n1 2 3 4\n"),
               "line 9", "expected POINTS followed by one non-negative integer, found \"lots\"");
  expect_error(tmp.file("wh.pcd", std::string(pcd_header_xyz) + "WIDTH 10\nHEIGHT 2\nPOINTS 30\nDATA ascii\n"),
               "line 9", "WIDTH 10 x HEIGHT 2 = 20 does not match POINTS 30");
  expect_error(tmp.file("enc.pcd", std::string(pcd_header_xyz) + "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA lzma\n"), "line 10",
               "expected DATA ascii, binary or binary_compressed, found \"lzma\"");
  expect_error(tmp.file("kw.pcd", std::string(pcd_header_xyz) + "COLOUR 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n"),
               "line 7", "unknown PCD header keyword \"COLOUR\"");
}

TEST_CASE("PCD ascii data errors") {
  ErrorTempDir tmp("pcd_ascii");
  const std::string h = std::string(pcd_header_xyz) + "WIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA ascii\n";
  expect_error(tmp.file("count.pcd", h + "1 2 3 4\n1 2 3\n1 2 3 4\n"), "line 13",
               "expected 4 values (x y z intensity), found 3");
  expect_error(tmp.file("nonnum.pcd", h + "1 2 3 4\n1 2 3 4\n1 two 3 4\n"), "line 14, column 2 (y)",
               "expected a number, found \"two\"");
  expect_error(tmp.file("trunc.pcd", h + "1 2 3 4\n1 2 3 4\n"), "line 14",
               "truncated ascii data: expected 3 points, file ends after 2 points");
  const std::string absurd =
      std::string(pcd_header_xyz) + "WIDTH 0\nHEIGHT 0\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3000000000\nDATA ascii\n1 2 3 4\n";
  expect_error(tmp.file("absurd.pcd", absurd), "line 10", "POINTS 3000000000 cannot fit in the 8 bytes of ascii data");
}

TEST_CASE("PCD binary data errors: truncation and absurd POINTS, checked against the file size") {
  ErrorTempDir tmp("pcd_binary");
  std::string h = std::string(pcd_header_xyz) + "WIDTH 0\nHEIGHT 0\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 10\nDATA binary\n";
  const std::size_t data_start = h.size();
  std::string s = h;
  for (int i = 0; i < 7 * 4 + 2; ++i) append_bytes(s, 1.0f);  // 7.5 points
  const std::string where = "byte " + std::to_string(data_start + 7 * 16);
  expect_error(tmp.file("trunc.pcd", s), where,
               "truncated binary data: expected 10 points of 16 bytes, file ends after 7 points");
  std::string absurd = std::string(pcd_header_xyz) +
                       "WIDTH 3000000000\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3000000000\nDATA binary\n";
  const std::size_t absurd_start = absurd.size();
  append_bytes(absurd, 1.0f);
  expect_error(tmp.file("absurd.pcd", absurd), "byte " + std::to_string(absurd_start),
               "expected 3000000000 points of 16 bytes, file ends after 0 points");
  std::string huge = std::string(pcd_header_xyz) + "POINTS 18446744073709551615\nDATA binary\n";
  expect_error(tmp.file("huge.pcd", huge), "byte " + std::to_string(huge.size()), "file ends after 0 points");
  expect_error(tmp.file("overflow.pcd", std::string(pcd_header_xyz) + "POINTS 99999999999999999999999\nDATA binary\n"),
               "line 7", "expected POINTS followed by one non-negative integer");
}

TEST_CASE("PCD binary_compressed errors: sizes, truncation, corrupt LZF, absurd POINTS") {
  ErrorTempDir tmp("pcd_compressed");
  const auto good_path = tmp.path("good.pcd");
  io::write_pcd(good_path, some_records(1000), {}, "binary_compressed");
  const std::string good = file_bytes(good_path);
  const std::size_t data = good.find("DATA binary_compressed\n") + std::strlen("DATA binary_compressed\n");
  // Truncated compressed block.
  expect_error(tmp.file("trunc.pcd", good.substr(0, good.size() - 10)), "byte " + std::to_string(data + 8),
               "truncated binary_compressed data: expected");
  // Truncated before the two sizes.
  expect_error(tmp.file("trunc_sizes.pcd", good.substr(0, data + 5)), "byte " + std::to_string(data),
               "expected 8 bytes (compressed and uncompressed sizes)");
  // Uncompressed size disagreeing with POINTS x point size.
  std::string s = good;
  const std::uint32_t wrong = 12345;
  std::memcpy(&s[data + 4], &wrong, 4);
  expect_error(tmp.file("usize.pcd", s), "byte " + std::to_string(data + 4),
               "uncompressed size is 12345 bytes, expected POINTS 1000 x 28 bytes = 28000");
  // Corrupt LZF stream (a back reference before the start).
  s = good;
  s[data + 8] = static_cast<char>(0xe0);
  expect_error(tmp.file("corrupt.pcd", s), "byte " + std::to_string(data + 8), "corrupt binary_compressed data: LZF");
  // Absurd POINTS: beyond the 4 GiB block, and a small file claiming a large block.
  std::string absurd = std::string(pcd_header_xyz) + "WIDTH 3000000000\nHEIGHT 1\nPOINTS 3000000000\nDATA binary_compressed\n";
  append_bytes(absurd, std::uint32_t{10});
  append_bytes(absurd, std::uint32_t{0});
  absurd += std::string(10, '\0');
  expect_error(tmp.file("absurd.pcd", absurd), "line 9", "exceeds the 4 GiB limit of a binary_compressed block");
  std::string lying = std::string(pcd_header_xyz) + "POINTS 200000000\nDATA binary_compressed\n";
  const std::size_t lying_data = lying.size();
  append_bytes(lying, std::uint32_t{10});
  append_bytes(lying, std::uint32_t{3200000000u});
  lying += std::string(10, '\0');
  expect_error(tmp.file("lying.pcd", lying), "byte " + std::to_string(lying_data),
               "10 bytes of LZF data cannot expand to 3200000000 bytes");
  std::string lying2 = std::string(pcd_header_xyz) + "POINTS 200000000\nDATA binary_compressed\n";
  append_bytes(lying2, std::uint32_t{4000000000u});
  append_bytes(lying2, std::uint32_t{3200000000u});
  lying2 += std::string(10, '\0');
  expect_error(tmp.file("lying2.pcd", lying2), "byte " + std::to_string(lying_data + 8),
               "expected 4000000000 bytes of LZF data, file has 10");
}

TEST_CASE("PLY errors") {
  ErrorTempDir tmp("ply");
  const std::string h3 = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty double t\nend_header\n";
  expect_error(tmp.file("magic.ply", "plx\nformat ascii 1.0\n" + h3), "line 1", "expected the PLY magic line \"ply\"");
  expect_error(tmp.file("be.ply", "ply\nformat binary_big_endian 1.0\n" + h3), "line 2",
               "unsupported PLY format binary_big_endian");
  expect_error(tmp.file("nofmt.ply", "ply\n" + h3 + "1 2 3 4\n"), "line 7", "the header ends without a format line");
  expect_error(tmp.file("noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"), "line 4",
               "file ends inside the header: expected end_header");
  expect_error(tmp.file("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n"),
               "line 4", "unknown property type \"float128\"");
  expect_error(tmp.file("noxyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float t\nend_header\n1 2\n"),
               "line 3", "expected vertex properties x, y and z, found: x t");
  expect_error(tmp.file("novertex.ply", "ply\nformat ascii 1.0\nelement face 1\nproperty float x\nend_header\n1\n"),
               "line 5", "the header ends without \"element vertex N\"");
  expect_error(tmp.file("count.ply", "ply\nformat ascii 1.0\n" + h3 + "1 2 3 4\n1 2 3\n1 2 3 4\n"), "line 10",
               "expected 4 vertex properties (x y z t), found 3 values");
  expect_error(tmp.file("count2.ply", "ply\nformat ascii 1.0\n" + h3 + "1 2 3 4 5\n"), "line 9",
               "expected 4 vertex properties");
  expect_error(tmp.file("nonnum.ply", "ply\nformat ascii 1.0\n" + h3 + "1 2 3 4\n1 2 3 x4\n1 2 3 4\n"),
               "line 10, column 4 (t)", "expected a number, found \"x4\"");
  expect_error(tmp.file("trunc.ply", "ply\nformat ascii 1.0\n" + h3 + "1 2 3 4\n"), "line 10",
               "truncated ascii data: expected 3 vertices, file ends after 1 vertices");
  expect_error(tmp.file("count_nan.ply", "ply\nformat ascii 1.0\nelement vertex abc\n"), "line 3",
               "expected \"element NAME COUNT\"");
  expect_error(tmp.file("absurd.ply", "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\n"
                                      "property float y\nproperty float z\nproperty double t\nend_header\n1 2 3 4\n"),
               "line 3", "element vertex 4000000000 cannot fit");
  // binary
  std::string b = "ply\nformat binary_little_endian 1.0\n" + h3;
  const std::size_t start = b.size();
  for (int i = 0; i < 2; ++i) {
    for (float f : {1.f, 2.f, 3.f}) append_bytes(b, f);
    append_bytes(b, 0.5);
  }
  append_bytes(b, 1.f);
  expect_error(tmp.file("trunc_b.ply", b), "byte " + std::to_string(start + 2 * 20),
               "truncated binary data: expected 3 vertices of 20 bytes, file ends after 2 vertices");
  std::string ab = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
                   "property float z\nproperty double t\nend_header\n";
  const std::size_t ab_start = ab.size();
  ab += std::string(20, '\0');
  expect_error(tmp.file("absurd_b.ply", ab), "byte " + std::to_string(ab_start + 20),
               "expected 4000000000 vertices of 20 bytes, file ends after 1 vertices");
  // binary with a list property: truncated inside the list.
  std::string l = "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                  "property float z\nproperty double t\nproperty list uchar int idx\nend_header\n";
  for (float f : {1.f, 2.f, 3.f}) append_bytes(l, f);
  append_bytes(l, 0.5);
  append_bytes(l, std::uint8_t{200});
  append_bytes(l, std::int32_t{1});
  for (float f : {1.f, 2.f, 3.f}) append_bytes(l, f);
  append_bytes(l, 0.5);
  expect_error(tmp.file("trunc_list.ply", l), "byte " + std::to_string(l.size()), "truncated binary data: expected 2 vertices");
}

TEST_CASE("KITTI errors: partial record names its byte offset") {
  ErrorTempDir tmp("kitti");
  std::string s(16 * 3 + 5, '\0');
  expect_error(tmp.file("partial.bin", s), "byte 48",
               "file size 53 is not a multiple of 16 bytes (float32 x y z reflectance); the record starting at byte 48 "
               "has only 5 bytes");
  expect_error(tmp.file("tiny.bin", "abc"), "byte 0", "not a multiple of 16 bytes");
}
