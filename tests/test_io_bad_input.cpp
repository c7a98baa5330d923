// SPDX-License-Identifier: MIT
// Input that a reader once accepted silently: bytes after the declared data,
// more records than declared, elements after the vertices, duplicate names;
// and the messages: header errors name their line, file content is escaped,
// a UTF-8 byte-order mark is no part of the first column.

#include <doctest/doctest.h>

#include "support/bad_files.hpp"
#include "support/temp_dir.hpp"

#include <streamclust/io/reader.hpp>
#include <streamclust/io/writers.hpp>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace io = streamclust::io;

namespace {

struct BadInputDir : streamclust::test::TempDir {
  explicit BadInputDir(const std::string& name) : TempDir("io_bad_input", name) {}
};

using streamclust::test::append_bytes;
using streamclust::test::expect_error;
using streamclust::test::file_bytes;
using streamclust::test::some_records;
using streamclust::test::with_rate;

/// All records of `path`; throws what the reader throws.
std::vector<io::Record> read_all_with_rate(const std::string& path) {
  auto r = io::open_reader(path, with_rate());
  std::vector<io::Record> out;
  while (r->read(out, 2) > 0) {
  }
  return out;
}

// Lines 1-6; WIDTH, HEIGHT, POINTS, DATA follow on lines 7-10.
const std::string pcd_head =
    "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\n"
    "COUNT 1 1 1 1\n";

// Lines 1-8: a vertex element of 3 (x y z t); data from line 9.
const std::string ply_ascii_head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                   "property float z\nproperty double t\nend_header\n";

}  // namespace

TEST_CASE("PCD ascii: blank lines may follow the POINTS records, a further record or other text may not") {
  BadInputDir tmp("pcd_ascii_end");
  const std::string h = pcd_head + "WIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA ascii\n";
  const std::string data = "1 2 3 4\n1 2 3 4\n1 2 3 4";
  for (const std::string& tail : {std::string(), std::string("\n"), std::string("\r\n"), std::string("\n\n  \t\n"),
                                  std::string("\n \r\n")}) {
    CHECK(read_all_with_rate(tmp.file("ok.pcd", h + data + tail)).size() == 3);
  }
  expect_error(tmp.file("extra.pcd", h + data + "\n5 6 7 8\n"), "line 14",
               "expected end of file after the 3 points POINTS declares, found \"5 6 7 8\"");
  expect_error(tmp.file("junk.pcd", h + data + "\n\n\x01garbage\n"), "line 15",
               "expected end of file after the 3 points POINTS declares, found \"\\x01garbage\"");
}

TEST_CASE("PCD binary and binary_compressed: no byte may follow the declared data") {
  BadInputDir tmp("pcd_binary_end");
  std::string s = pcd_head + "WIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA binary\n";
  const std::size_t start = s.size();
  for (int i = 0; i < 8; ++i) append_bytes(s, 1.0f);
  CHECK(read_all_with_rate(tmp.file("ok.pcd", s)).size() == 2);
  expect_error(tmp.file("nl.pcd", s + "\n"), "byte " + std::to_string(start + 32),
               "1 byte after the declared data (POINTS 2 x 16 bytes): expected end of file");
  // Misaligned: a record too many would read as garbage coordinates.
  std::string more = s;
  for (int i = 0; i < 5; ++i) append_bytes(more, 2.0f);
  expect_error(tmp.file("more.pcd", more), "byte " + std::to_string(start + 32),
               "20 bytes after the declared data (POINTS 2 x 16 bytes): expected end of file");

  const auto good_path = tmp.path("good.pcd");
  io::write_pcd(good_path, some_records(100), {}, "binary_compressed");
  const std::string good = file_bytes(good_path);
  CHECK(read_all_with_rate(good_path).size() == 100);
  expect_error(tmp.file("compressed.pcd", good + "abc"), "byte " + std::to_string(good.size()),
               "3 bytes after the LZF block of ");
}

TEST_CASE("PCD: a field or keyword given twice is an error on its line; `_` padding may repeat") {
  BadInputDir tmp("pcd_duplicates");
  const std::string tail = "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3 4 5\n";
  expect_error(tmp.file("dup.pcd", "VERSION 0.7\nFIELDS x y z x t\nSIZE 4 4 4 4 4\nTYPE F F F F F\n" + tail), "line 2",
               "field \"x\" appears twice in FIELDS (fields 1 and 4)");
  expect_error(tmp.file("dupcase.pcd", "VERSION 0.7\nFIELDS x y z T t\nSIZE 4 4 4 4 4\nTYPE F F F F F\n" + tail),
               "line 2", "field \"t\" appears twice in FIELDS (fields 4 and 5)");
  CHECK(read_all_with_rate(tmp.file("pad.pcd", "VERSION 0.7\nFIELDS x _ y _ z\nSIZE 4 4 4 4 4\nTYPE F F F F F\n" + tail))
            .size() == 1);
  expect_error(tmp.file("twice.pcd", pcd_head + "WIDTH 1\nHEIGHT 1\nPOINTS 1\nPOINTS 1\nDATA ascii\n1 2 3 4\n"),
               "line 10", "second POINTS line (the first is line 9)");
}

TEST_CASE("PCD header consistency errors name their line") {
  BadInputDir tmp("pcd_lines");
  const std::string tail = "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3 4\n";
  expect_error(tmp.file("count.pcd", "VERSION 0.7\nFIELDS x y z i\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1\n" + tail),
               "line 5", "COUNT has 2 entries, expected 4");
  expect_error(tmp.file("nosize.pcd", "VERSION 0.7\nFIELDS x y z i\nTYPE F F F F\n" + tail), "line 7",
               "the header ends without SIZE");
  expect_error(tmp.file("notype.pcd", "VERSION 0.7\nFIELDS x y z i\nSIZE 4 4 4 4\n" + tail), "line 7",
               "the header ends without TYPE");
  expect_error(tmp.file("nofields.pcd", "VERSION 0.7\nSIZE 4 4 4 4\nTYPE F F F F\n" + tail), "line 7",
               "the header ends without FIELDS");
  expect_error(tmp.file("size.pcd", "VERSION 0.7\nFIELDS x y z i\nSIZE 4 4 4 3\nTYPE F F F F\n" + tail), "line 3",
               "SIZE of field i is \"3\"");
  expect_error(tmp.file("wh.pcd", pcd_head + "WIDTH 2\nHEIGHT 2\nPOINTS 3\nDATA ascii\n"), "line 9",
               "WIDTH 2 x HEIGHT 2 = 4 does not match POINTS 3");
  expect_error(tmp.file("nopoints.pcd", pcd_head + "WIDTH 0\nDATA ascii\n"), "line 8", "the header ends without POINTS");
}

TEST_CASE("PLY ascii: elements after the vertices are read and checked, then only blank lines") {
  BadInputDir tmp("ply_ascii_elements");
  const std::string v = "1 2 3 0.1\n4 5 6 0.2\n7 8 9 0.3\n";
  CHECK(read_all_with_rate(tmp.file("ok.ply", ply_ascii_head + v + "\n \n")).size() == 3);
  expect_error(tmp.file("extra.ply", ply_ascii_head + v + "1 2 3 0.4\n"), "line 12",
               "expected end of file after the last element (vertex, 3 items), found \"1 2 3 0.4\"");

  const std::string h = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                        "property float z\nproperty double t\nelement face 2\nproperty list uchar int vertex_indices\n"
                        "end_header\n";  // data from line 11
  CHECK(read_all_with_rate(tmp.file("faces.ply", h + v + "3 0 1 2\n3 2 1 0\n")).size() == 3);
  expect_error(tmp.file("cut.ply", h + v + "3 0 1 2\n4 2 1 0\n"), "line 15, column 1 (vertex_indices)",
               "list of 4 items cut short: the line ends after 3");
  expect_error(tmp.file("short.ply", h + v + "3 0 1 2\n"), "line 15",
               "truncated ascii data: element \"face\" expects 2 items, file ends after 1 items");
  expect_error(tmp.file("long.ply", h + v + "3 0 1 2\n3 2 1 0 9\n"), "line 15",
               "expected 4 values for the face properties (vertex_indices; lists as long as their lengths say), found 5");
  expect_error(tmp.file("more.ply", h + v + "3 0 1 2\n3 2 1 0\n3 0 0 0\n"), "line 16",
               "expected end of file after the last element (face, 2 items)");
  expect_error(tmp.file("nonnum.ply", h + v + "3 0 1 2\n3 2 x 0\n"), "line 15, column 3 (vertex_indices)",
               "expected a number in the list, found \"x\"");
  // An element before the vertices is checked the same way.
  const std::string before = "ply\nformat ascii 1.0\nelement camera 1\nproperty float f\nelement vertex 1\n"
                             "property float x\nproperty float y\nproperty float z\nend_header\n";
  CHECK(read_all_with_rate(tmp.file("before.ply", before + "0.5\n1 2 3\n")).size() == 1);
  expect_error(tmp.file("before_bad.ply", before + "0.5 7\n1 2 3\n"), "line 10",
               "expected 1 camera properties (f), found 2 values");
}

TEST_CASE("PLY binary: every element up to its last byte, nothing after it") {
  BadInputDir tmp("ply_binary_elements");
  const std::string h = "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  std::string s = h;
  for (int i = 0; i < 6; ++i) append_bytes(s, 1.0f);
  const std::size_t faces = s.size();
  std::string face;
  append_bytes(face, std::uint8_t{3});
  for (std::int32_t k : {0, 1, 0}) append_bytes(face, k);
  CHECK(read_all_with_rate(tmp.file("ok.ply", s + face + face)).size() == 2);
  // A face list cut short: the byte where the file ends.
  const std::string cut = s + face + face.substr(0, 7);
  expect_error(tmp.file("cut.ply", cut), "byte " + std::to_string(cut.size()),
               "truncated binary data: element \"face\" expects 2 items, file ends after 1 items");
  expect_error(tmp.file("trail.ply", s + face + face + "\n"), "byte " + std::to_string(faces + 2 * face.size()),
               "1 byte after the last element (face, 2 items): expected end of file");

  // Fixed-size elements: checked against the file size at open.
  const std::string hf = "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                         "property float z\nelement edge 3\nproperty int a\nproperty int b\nend_header\n";
  std::string f = hf;
  const std::size_t fstart = f.size();
  for (int i = 0; i < 6; ++i) append_bytes(f, 1.0f);
  for (int i = 0; i < 6; ++i) append_bytes(f, std::int32_t{1});
  CHECK(read_all_with_rate(tmp.file("edges.ply", f)).size() == 2);
  expect_error(tmp.file("edges_short.ply", f.substr(0, f.size() - 3)), "byte " + std::to_string(fstart + 24 + 16),
               "truncated binary data: element \"edge\" expects 3 items of 8 bytes, file ends after 2 items");
  expect_error(tmp.file("edges_long.ply", f + "xyz"), "byte " + std::to_string(f.size()),
               "3 bytes after the last element (edge, 3 items): expected end of file");
  std::string v = "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                  "property float z\nend_header\n";
  for (int i = 0; i < 6; ++i) append_bytes(v, 1.0f);
  expect_error(tmp.file("vertex_long.ply", v + std::string(4, '\0')), "byte " + std::to_string(v.size()),
               "4 bytes after the last element (vertex, 2 items)");
  // A list element before the vertices (once unsupported in binary) is read past.
  std::string lb = "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
                   "element vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  lb += face;
  for (int i = 0; i < 6; ++i) append_bytes(lb, 2.0f);
  const auto records = read_all_with_rate(tmp.file("list_before.ply", lb));
  REQUIRE(records.size() == 2);
  CHECK(records[1].z == 2.0f);
}

TEST_CASE("PLY: an element or a property given twice is an error on its line") {
  BadInputDir tmp("ply_duplicates");
  expect_error(tmp.file("prop.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                    "property float z\nproperty float X\nend_header\n1 2 3 4\n"),
               "line 7", "property \"X\" appears twice in element \"vertex\" (the first on line 4)");
  expect_error(tmp.file("elem.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                    "property float z\nelement vertex 1\nproperty float x\nend_header\n1 2 3\n1\n"),
               "line 7", "element \"vertex\" declared twice (the first on line 3)");
}

TEST_CASE("CSV: a UTF-8 byte-order mark is skipped; a role column twice is an error; names are escaped") {
  BadInputDir tmp("csv_header");
  const auto path = tmp.file("bom.csv", "\xEF\xBB\xBFx,y,z,t\n1,2,3,0.5\n");
  auto r = io::open_reader(path, {});
  REQUIRE(r->info().fields.size() == 4);
  CHECK(r->info().fields[0] == "x");
  CHECK(r->info().has_time);
  std::vector<io::Record> out;
  CHECK(r->read(out, 10) == 1);
  CHECK(out[0].x == 1.0f);

  expect_error(tmp.file("dup.csv", "x,y,z,t,X\n1,2,3,0,4\n"), "line 1",
               "column \"X\" appears twice (columns 1 and 5)");
  expect_error(tmp.file("dup_time.csv", "x,y,z,time,time\n1,2,3,0,4\n"), "line 1",
               "column \"time\" appears twice (columns 4 and 5)");
  CHECK(read_all_with_rate(tmp.file("dup_other.csv", "x,y,z,t,note,note\n1,2,3,0,a,b\n")).size() == 1);

  // Raw non-UTF-8 and control bytes in a header never reach the message.
  const auto bad = tmp.file("latin1.csv", "\xff\xfe" "a,b\x01,c\x1b[31m\n1,2,3\n");
  try {
    read_all_with_rate(bad);
    FAIL("expected an InputError");
  } catch (const io::InputError& e) {
    const std::string m = e.what();
    INFO(m);
    CHECK(e.where() == "line 1");
    CHECK(m.find("found: \"\\xff\\xfea\", \"b\\x01\", \"c\\x1b[31m\"") != std::string::npos);
    for (const char c : m) {
      const auto u = static_cast<unsigned char>(c);
      CHECK((u >= 32 && u < 127));
    }
  }
}
