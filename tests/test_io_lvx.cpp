// SPDX-License-Identifier: MIT
// The LVX / LVX2 reader (io/lvx_reader.hpp): the fixtures of tests/data/lvx,
// written by an independent Python writer (make_lvx.py), read point for point
// (times exact); the choice of a LiDAR; summarize_lvx; and malformed files,
// each an InputError naming its byte: mutated fixtures and every truncation.

#include <doctest/doctest.h>

#include "support/bad_files.hpp"
#include "support/temp_dir.hpp"

#include <streamclust/io/error.hpp>
#include <streamclust/io/input_stream.hpp>
#include <streamclust/io/lvx_reader.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace io = streamclust::io;

namespace {

using streamclust::test::file_bytes;

/// A file of tests/data/lvx.
std::string lvx_data(const std::string& name) {
  // <source>/tests/test_io_lvx.cpp -> <source>/tests/data/lvx/<name>
  return (std::filesystem::path(__FILE__).parent_path() / "data" / "lvx" / name).string();
}

struct ExpectedPoint {
  float x, y, z, intensity;
  std::uint64_t t_ns;
};

/// The rows of an expected CSV (x,y,z,intensity,t with t in integer ns);
/// decimals parse to the nearest float.
std::vector<ExpectedPoint> read_expected(const std::string& path) {
  std::ifstream in(path);
  REQUIRE_MESSAGE(in, "cannot open " << path);
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "x,y,z,intensity,t");
  std::vector<ExpectedPoint> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string field; std::getline(ss, field, ',');) f.push_back(field);
    REQUIRE(f.size() == 5);
    ExpectedPoint p{};
    REQUIRE(io::detail::parse_real(f[0], p.x));
    REQUIRE(io::detail::parse_real(f[1], p.y));
    REQUIRE(io::detail::parse_real(f[2], p.z));
    REQUIRE(io::detail::parse_real(f[3], p.intensity));
    REQUIRE(io::detail::parse_uint64(f[4], p.t_ns));
    rows.push_back(p);
  }
  return rows;
}

struct ReadResult {
  std::vector<io::Record> records;
  io::TimeOrigin origin;
  io::InputInfo info;
};

/// Every record of `path` read through io::LvxReader in chunks of `chunk`.
ReadResult read_lvx(const std::string& path, const io::ReadOptions& options = {}, std::size_t chunk = 7) {
  io::LvxReader reader(path, options);
  ReadResult r;
  std::vector<io::Record> part;
  for (;;) {
    part.clear();
    const std::size_t got = reader.read(part, chunk);
    REQUIRE(got == part.size());
    REQUIRE(got <= chunk);
    if (got == 0) break;
    r.records.insert(r.records.end(), part.begin(), part.end());
  }
  CHECK(reader.read(part, chunk) == 0);
  CHECK(reader.records_read() == r.records.size());
  r.origin = reader.time_origin();
  r.info = reader.info();
  return r;
}

/// Floats `ulps` apart or closer.
bool near_ulps(float a, float b, int ulps) {
  if (a == b) return true;
  float x = a;
  for (int k = 0; k < ulps; ++k) x = std::nextafter(x, b);
  return x == b;
}

/// Reads `file` (with `topic`) and compares it with `expected`, point for
/// point: coordinates exact (within `ulps` for spherical data), intensity
/// exact, time exact to the nanosecond.
void check_fixture(const std::string& file, const std::string& expected, std::optional<std::string> topic = {},
                   int ulps = 0, std::size_t chunk = 7) {
  INFO("fixture " << file << ", topic " << topic.value_or("(none)") << ", chunk " << chunk);
  io::ReadOptions options;
  options.topic = topic;
  const ReadResult r = read_lvx(lvx_data(file), options, chunk);
  const std::vector<ExpectedPoint> want = read_expected(lvx_data(expected));
  REQUIRE(r.records.size() == want.size());
  const auto origin_ns = static_cast<std::uint64_t>(r.origin.seconds) * 1000000000u;
  std::size_t bad = 0;
  for (std::size_t i = 0; i < want.size() && bad < 5; ++i) {
    const io::Record& g = r.records[i];
    const ExpectedPoint& w = want[i];
    const std::uint64_t t_ns = origin_ns + static_cast<std::uint64_t>(std::llround(g.t * 1e9));
    const bool ok = near_ulps(g.x, w.x, ulps) && near_ulps(g.y, w.y, ulps) && near_ulps(g.z, w.z, ulps) &&
                    g.intensity == w.intensity && t_ns == w.t_ns && g.label == -1;
    if (!ok) {
      ++bad;
      FAIL_CHECK("record " << i << ": got " << g.x << " " << g.y << " " << g.z << " " << g.intensity << " t_ns " << t_ns
                           << ", expected " << w.x << " " << w.y << " " << w.z << " " << w.intensity << " " << w.t_ns);
    }
  }
}

// ------------------------------------------------------------ layout offsets
constexpr std::size_t lvx11_devices_at = 29;  // public header 24 + frame_duration 4 + device_count 1
constexpr std::size_t lvx11_frame0(std::size_t devices) { return lvx11_devices_at + 59 * devices; }
constexpr std::size_t lvx10_frame0(std::size_t devices) { return 25 + 58 * devices; }
constexpr std::size_t lvx2_frame0(std::size_t devices) { return 29 + 63 * devices; }

template <class T>
void put(std::string& bytes, std::size_t at, T value) {
  REQUIRE(at + sizeof value <= bytes.size());
  std::memcpy(&bytes[at], &value, sizeof value);
}

template <class T>
T get(const std::string& bytes, std::size_t at) {
  T v;
  std::memcpy(&v, &bytes[at], sizeof v);
  return v;
}

struct LvxDir : streamclust::test::TempDir {
  explicit LvxDir(const std::string& name) : TempDir("io_lvx", name) {}
};

/// Opening and reading `path` throws an InputError naming it, at `where`,
/// whose message contains `expected`.
void expect_lvx_error(const std::string& path, const std::string& where, const std::string& expected,
                      const io::ReadOptions& options = {}) {
  INFO("file " << path);
  try {
    io::LvxReader reader(path, options);
    std::vector<io::Record> out;
    while (reader.read(out, 100) > 0) {
    }
    FAIL("expected an InputError, read " << out.size() << " records");
  } catch (const io::InputError& e) {
    INFO("message: " << std::string(e.what()));
    CHECK(e.file() == path);
    CHECK(e.where() == where);
    CHECK(e.what_expected().find(expected) != std::string::npos);
    CHECK(std::string(e.what()) == path + ": " + where + ": " + e.what_expected());
  }
}

/// The same for summarize_lvx.
void expect_summary_error(const std::string& path, const std::string& where, const std::string& expected) {
  INFO("file " << path);
  try {
    io::summarize_lvx(path);
    FAIL("expected an InputError");
  } catch (const io::InputError& e) {
    INFO("message: " << std::string(e.what()));
    CHECK(e.where() == where);
    CHECK(e.what_expected().find(expected) != std::string::npos);
  }
}

}  // namespace

TEST_CASE("LVX fixtures: every record equals the independent writer's expected point, times to the nanosecond") {
  check_fixture("avia_v11.lvx", "avia_v11.lvx.expected.csv");
  check_fixture("mid40_v10.lvx", "mid40_v10.lvx.expected.csv");
  check_fixture("horizon_v11_returns.lvx", "horizon_v11_returns.lvx.expected.csv");
  check_fixture("tele15_v11_spherical.lvx", "tele15_v11_spherical.lvx.expected.csv", {}, 1);
  check_fixture("two_lidars_v11.lvx", "two_lidars_v11.lvx.index1.expected.csv", "1");
  check_fixture("two_lidars_v11.lvx", "two_lidars_v11.lvx.index3.expected.csv", "3");
  check_fixture("mid360_type1.lvx2", "mid360_type1.lvx2.expected.csv");
  check_fixture("mid360_type2.lvx2", "mid360_type2.lvx2.expected.csv");
  check_fixture("two_lidars.lvx2", "two_lidars.lvx2.index0.expected.csv", "0");
  check_fixture("two_lidars.lvx2", "two_lidars.lvx2.index1.expected.csv", "1");
}

TEST_CASE("LVX: the chunk size does not matter, also when it cuts a firing's returns apart") {
  for (std::size_t chunk : {1, 2, 3, 5, 4096}) {
    check_fixture("horizon_v11_returns.lvx", "horizon_v11_returns.lvx.expected.csv", {}, 0, chunk);
    check_fixture("tele15_v11_spherical.lvx", "tele15_v11_spherical.lvx.expected.csv", {}, 1, chunk);
    check_fixture("two_lidars.lvx2", "two_lidars.lvx2.index1.expected.csv", "1", 0, chunk);
  }
}

TEST_CASE("LVX: what the reader reports; time is nanoseconds whatever the time unit option says") {
  io::ReadOptions options;
  options.time_unit = io::TimeUnit::s;  // ignored: the format fixes the unit
  options.point_rate = 10.0;            // ignored: the file has times
  io::LvxReader v11(lvx_data("avia_v11.lvx"), options);
  CHECK(v11.info().format == io::Format::lvx);
  CHECK(v11.info().encoding == "lvx 1.1");
  CHECK(v11.info().fields == std::vector<std::string>{"x", "y", "z", "reflectivity", "tag", "time"});
  CHECK(v11.info().has_time);
  CHECK(v11.info().time_unit == io::TimeUnit::ns);
  CHECK(v11.info().has_intensity);
  CHECK_FALSE(v11.info().has_label);
  CHECK(v11.device().type_name == "Avia");
  CHECK(v11.firing_interval_ns() == 4167);
  CHECK(io::LvxReader(lvx_data("mid40_v10.lvx"), {}).info().encoding == "lvx 1.0");
  io::LvxReader v2(lvx_data("mid360_type1.lvx2"), {});
  CHECK(v2.info().encoding == "lvx2");
  CHECK(v2.firing_interval_ns() == 5000);
  CHECK(v2.device().serial == "47MDK9DF710030");

  const ReadResult r = read_lvx(lvx_data("avia_v11.lvx"), options);
  CHECK(r.origin.seconds == 1700000000);
  REQUIRE(r.records.size() == 192);
  CHECK(std::llround(r.records[1].t * 1e9) == 123456789 + 4167);
}

TEST_CASE("LVX: several LiDARs: without a topic the error lists them; serial number and index choose one") {
  const std::string v11 = lvx_data("two_lidars_v11.lvx");
  try {
    io::LvxReader reader(v11, {});
    FAIL("expected an InputError");
  } catch (const io::InputError& e) {
    CHECK(e.where() == "header");
    CHECK(e.what_expected() ==
          "2 LiDARs in the file: choose one by serial number or index (--topic): index 1: serial "
          "\"3WEDH7600103381\", Mid-70; index 3: serial \"3JEDHB300100591\", Avia");
  }
  for (const char* topic : {"3", "3JEDHB300100591"}) {
    io::ReadOptions o;
    o.topic = topic;
    io::LvxReader reader(v11, o);
    CHECK(reader.device().index == 3);
    CHECK(reader.device().hub_serial == "13UUG1R00400170");
  }
  check_fixture("two_lidars_v11.lvx", "two_lidars_v11.lvx.index3.expected.csv", "3JEDHB300100591");
  check_fixture("two_lidars.lvx2", "two_lidars.lvx2.index1.expected.csv", "HAP2301TX000731");

  io::ReadOptions none;
  none.topic = "0";  // LVX 1.x: indices are the device_index fields (1 and 3), not positions
  expect_lvx_error(v11, "header", "no LiDAR has the serial number or index \"0\": the file holds index 1: ", none);
  none.topic = "2";
  expect_lvx_error(lvx_data("two_lidars.lvx2"), "header",
                   "no LiDAR has the serial number or index \"2\": the file holds index 0: serial \"47MDK9DF710124\", "
                   "Mid-360, lidar id 2080483520; index 1: serial \"HAP2301TX000731\", HAP, lidar id 1677830336",
                   none);
  none.topic = "1";  // a single LiDAR: a topic still has to name it
  expect_lvx_error(lvx_data("avia_v11.lvx"), "header", "no LiDAR has the serial number or index \"1\"", none);
}

TEST_CASE("summarize_lvx: devices, extrinsics, frames, packages, points and time span") {
  const io::LvxSummary a = io::summarize_lvx(lvx_data("avia_v11.lvx"));
  CHECK(a.version == io::LvxVersion::v1_1);
  CHECK(a.encoding == "lvx 1.1");
  CHECK(a.frame_duration_ms == 50u);
  CHECK(a.frames == 2);
  CHECK(a.packages == 3);
  CHECK(a.points == 192);
  REQUIRE(a.devices.size() == 1);
  const io::LvxDeviceSummary& d = a.devices[0];
  CHECK(d.device.serial == "1PQDH5B00100041");
  CHECK(d.device.hub_serial.empty());
  CHECK(d.device.device_type == 7);
  CHECK(d.device.extrinsic_enabled);
  CHECK(d.device.roll == 0.5f);
  CHECK(d.device.pitch == -1.0f);
  CHECK(d.device.yaw == 90.0f);
  CHECK(d.device.x == 0.1f);
  CHECK(d.device.y == 0.0f);
  CHECK(d.device.z == 1.2f);
  CHECK(d.point_packages == 2);
  CHECK(d.imu_packages == 1);
  CHECK(d.points == 192);
  CHECK(d.first_ns == 1700000000123456789u);
  CHECK(d.last_ns == 1700000000123456789u + 50000000u + 95u * 4167u);
  CHECK(a.first_ns == d.first_ns);
  CHECK(a.last_ns == d.last_ns);

  const io::LvxSummary m = io::summarize_lvx(lvx_data("mid40_v10.lvx"));
  CHECK(m.encoding == "lvx 1.0");
  CHECK_FALSE(m.frame_duration_ms);
  CHECK(m.points == 200);
  CHECK(m.devices[0].device.type_name == "Mid-40");
  CHECK_FALSE(m.devices[0].device.extrinsic_enabled);

  const io::LvxSummary t = io::summarize_lvx(lvx_data("two_lidars.lvx2"));
  CHECK(t.version == io::LvxVersion::v2);
  CHECK(t.frames == 2);
  CHECK(t.packages == 5);
  REQUIRE(t.devices.size() == 2);
  CHECK(t.devices[0].device.index == 0);
  CHECK(t.devices[0].device.lidar_id == 2080483520u);  // 192.168.1.124, bytes in address order
  CHECK(t.devices[1].device.type_name == "HAP");
  CHECK(t.devices[0].points == 64);
  CHECK(t.devices[1].points == 88);
  CHECK(t.points == 152);
  CHECK(t.first_ns == 1700000300500000000u);
  CHECK(t.last_ns == 1700000300500000000u + 50000100u + 31u * 5000u);
}

TEST_CASE("LVX bad input: header (signature, version, magic, device list)") {
  LvxDir tmp("header");
  const std::string good = file_bytes(lvx_data("avia_v11.lvx"));
  std::string b = good;
  b[0] = 'L';
  expect_lvx_error(tmp.file("sig.lvx", b), "byte 0",
                   "not an LVX file: expected the signature \"livox_tech\" and 6 zero bytes, found \"Livox_tech\\x00");
  b = good;
  b[12] = 'x';  // a byte of the zero padding
  expect_lvx_error(tmp.file("sig_pad.lvx", b), "byte 0", "not an LVX file");
  b = good;
  b[16] = 3;
  expect_lvx_error(tmp.file("version.lvx", b), "byte 16", "unsupported LVX version 3.1.0.0: expected 1.0, 1.1 (LVX) or 2.0 (LVX2)");
  b = good;
  b[17] = 2;
  expect_lvx_error(tmp.file("version_12.lvx", b), "byte 16", "unsupported LVX version 1.2.0.0");
  b = good;
  put<std::uint32_t>(b, 20, 0xAC0EA766u);
  expect_lvx_error(tmp.file("magic.lvx", b), "byte 20", "wrong magic code 0xac0ea766: expected 0xac0ea767");
  expect_summary_error(tmp.path("magic.lvx"), "byte 20", "wrong magic code");
  b = good;
  b[28] = 0;
  expect_lvx_error(tmp.file("nodevice.lvx", b), "byte 28", "device count 0: expected at least one LiDAR");
  b = good;
  b[28] = 2;  // a second device record that is really the first frame: its "index" is a 0 byte of a package
  expect_lvx_error(tmp.file("count.lvx", b), "byte 120", "device index 0 appears twice in the header");

  // LVX 1.1 with two devices of one index; an unknown device type.
  std::string two = file_bytes(lvx_data("two_lidars_v11.lvx"));
  b = two;
  b[lvx11_devices_at + 59 + 32] = 1;
  expect_lvx_error(tmp.file("dup.lvx", b), "byte 120",
                   "device index 1 appears twice in the header (devices 0 and 1 from 0): expected each device once");
  b = good;
  b[lvx11_devices_at + 33] = 5;
  expect_lvx_error(tmp.file("type.lvx", b), "byte 62",
                   "unknown device type 5 of LiDAR \"1PQDH5B00100041\": expected 0 (Hub), 1 (Mid-40), 2 (Tele-15), "
                   "3 (Horizon), 6 (Mid-70) or 7 (Avia); without it the time between its firings is not known");
  CHECK(io::summarize_lvx(tmp.path("type.lvx")).devices[0].device.type_name == "unknown");
  std::string v2 = file_bytes(lvx_data("mid360_type1.lvx2"));
  b = v2;
  b[29 + 37] = 35;
  expect_lvx_error(tmp.file("type.lvx2", b), "byte 66", "unknown device type 35 of LiDAR \"47MDK9DF710030\": expected 9 (Mid-360) or 10 (HAP)");

  // Truncated headers; a file with headers and no frame reads nothing.
  expect_lvx_error(tmp.file("empty.lvx", ""), "byte 0", "truncated public header: expected 24 bytes from byte 0, the file ends after 0");
  expect_lvx_error(tmp.file("cut_device.lvx", good.substr(0, 60)), "byte 60",
                   "truncated device info: expected 59 bytes from byte 29, the file ends after 31");
  CHECK(read_lvx(tmp.file("headers_only.lvx", good.substr(0, lvx11_frame0(1)))).records.empty());
  CHECK(io::summarize_lvx(tmp.path("headers_only.lvx")).frames == 0);
}

TEST_CASE("LVX bad input: frame chain (offsets backwards, beyond the file, bytes after the last frame)") {
  LvxDir tmp("frames");
  const std::string good = file_bytes(lvx_data("avia_v11.lvx"));
  const std::size_t f0 = lvx11_frame0(1);
  const auto next0 = get<std::uint64_t>(good, f0 + 8);
  std::string b = good;
  put<std::uint64_t>(b, f0, 5);
  expect_lvx_error(tmp.file("current.lvx", b), "byte " + std::to_string(f0),
                   "frame header: current_offset is 5, expected 88 (the position of the frame)");
  b = good;
  put<std::uint64_t>(b, f0 + 8, f0 + 10);
  expect_lvx_error(tmp.file("back.lvx", b), "byte " + std::to_string(f0 + 8),
                   "frame header: next_offset 98 points back: expected at least 112 (the end of this frame header)");
  b = good;
  put<std::uint64_t>(b, f0 + 8, 3);
  expect_lvx_error(tmp.file("back2.lvx", b), "byte " + std::to_string(f0 + 8), "points back");
  b = good;
  put<std::uint64_t>(b, f0 + 8, good.size() + 1);
  expect_lvx_error(tmp.file("beyond.lvx", b), "byte " + std::to_string(f0 + 8),
                   "frame header: next_offset 2906 is beyond the end of the file (2905 bytes)");
  b = good;
  put<std::uint64_t>(b, f0 + 8, next0 - 1);  // the frame ends one byte into its last package
  expect_lvx_error(tmp.file("short.lvx", b), "byte " + std::to_string(f0 + 24 + 1363),
                   "package of data type 6 (IMU, 1 x 24 bytes) needs 43 bytes, its frame has 42 left");
  b = good;
  put<std::uint64_t>(b, f0 + 8, f0 + 24 + 10);
  expect_lvx_error(tmp.file("tiny.lvx", b), "byte " + std::to_string(f0 + 24),
                   "10 bytes left in the frame (it ends at byte 122, its next_offset): too few for a package header of "
                   "19 bytes");
  // Bytes after the last frame: the format has none (the file ends with the last frame).
  expect_lvx_error(tmp.file("tail.lvx", good + std::string(10, '\0')), "byte 2915",
                   "truncated frame header: expected 24 bytes from byte 2905, the file ends after 10 (all zero: "
                   "padding after the last frame?)");
  expect_lvx_error(tmp.file("tail24.lvx", good + std::string(30, '\0')), "byte 2905",
                   "frame header: current_offset is 0, expected 2905 (the position of the frame); the header is all "
                   "zero bytes: padding after the last frame?");
  expect_summary_error(tmp.path("tail24.lvx"), "byte 2905", "current_offset is 0");
  // An empty frame (next_offset = the end of its header) is fine.
  std::string empty = good.substr(0, f0);
  streamclust::test::append_bytes<std::uint64_t>(empty, f0);
  streamclust::test::append_bytes<std::uint64_t>(empty, f0 + 24);
  streamclust::test::append_bytes<std::uint64_t>(empty, 0);
  CHECK(read_lvx(tmp.file("empty_frame.lvx", empty)).records.empty());
  CHECK(io::summarize_lvx(tmp.path("empty_frame.lvx")).frames == 1);
}

TEST_CASE("LVX bad input: packages (data type, device, timestamp, LVX 1.0 packet count)") {
  LvxDir tmp("packages");
  const std::string good = file_bytes(lvx_data("avia_v11.lvx"));
  const std::size_t p0 = lvx11_frame0(1) + 24;
  std::string b = good;
  b[p0 + 10] = 9;
  expect_lvx_error(tmp.file("type9.lvx", b), "byte " + std::to_string(p0 + 10),
                   "unknown data type 9: expected 0-8 (0 cartesian, 1 spherical, 2 extended cartesian, 3 extended "
                   "spherical, 4/5 dual, 6 IMU, 7/8 triple)");
  b = good;
  b[p0 + 10] = 4;  // 48 x 28 = 1344 bytes, as type 2: the package fits, the points differ
  CHECK(read_lvx(tmp.file("type4.lvx", b)).records.size() == 192);
  b = good;
  b[p0 + 10] = 0;  // 100 x 13 = 1300 bytes: the next "package" starts inside the points
  expect_lvx_error(tmp.file("type0.lvx", b), "byte " + std::to_string(p0 + 1319),
                   "package of device index 45, which the header does not declare (declared: 0)");
  b = good;
  b[p0] = 5;
  expect_lvx_error(tmp.file("device.lvx", b), "byte " + std::to_string(p0),
                   "package of device index 5, which the header does not declare (declared: 0)");
  b = good;
  b[p0 + 9] = 2;
  expect_lvx_error(tmp.file("ts2.lvx", b), "byte " + std::to_string(p0 + 9),
                   "unknown timestamp type 2: expected 0 (no sync), 1 (PTP), 3 (PPS + GPS, UTC) or 4 (PPS); type 2 is "
                   "reserved");
  b = good;
  b[p0 + 9] = 3;  // the ns value read as UTC: month byte out of range
  expect_lvx_error(tmp.file("ts3.lvx", b), "byte " + std::to_string(p0 + 9), "timestamp type 3 (PPS + GPS, UTC)");
  b = good;
  put<std::uint64_t>(b, p0 + 11, ~std::uint64_t{0} - 1000);
  expect_lvx_error(tmp.file("overflow.lvx", b), "byte " + std::to_string(p0 + 11), "overflows 64 bits");

  // LVX 1.0: packet_count must match the frame; data type 0 only.
  const std::string v10 = file_bytes(lvx_data("mid40_v10.lvx"));
  const std::size_t g0 = lvx10_frame0(1);
  b = v10;
  put<std::uint64_t>(b, g0 + 24, 2);
  expect_lvx_error(tmp.file("count.lvx", b), "byte " + std::to_string(g0 + 24),
                   "frame header: packet_count 2 does not match the frame: 1319 bytes of packages (next_offset - "
                   "current_offset - 32) hold 1 packages of 1319 bytes");
  b = v10;
  b[g0 + 32 + 10] = 1;
  expect_lvx_error(tmp.file("v10_type.lvx", b), "byte " + std::to_string(g0 + 32 + 10),
                   "data type 1 in an LVX 1.0 package: expected 0 (LVX 1.0 packages hold 100 float points)");
  b = v10;
  b[g0 + 32 + 11 + 1] = 13;  // UTC month 13
  expect_lvx_error(tmp.file("utc.lvx", b), "byte " + std::to_string(g0 + 32 + 9),
                   "timestamp type 3 (PPS + GPS, UTC): expected year - 2000, month 1-12, a day of that month, hour "
                   "0-23 and microseconds within the hour (below 3600000000), found 24, 13, 29, 13, 1234567890");
  b = v10;
  b[g0 + 32 + 11 + 2] = 30;  // 2024-02-30
  expect_lvx_error(tmp.file("utc_day.lvx", b), "byte " + std::to_string(g0 + 32 + 9), "found 24, 2, 30, 13");
}

TEST_CASE("LVX2 bad input: lying package length, data type, undeclared LiDAR id, timestamp type") {
  LvxDir tmp("lvx2");
  const std::string good = file_bytes(lvx_data("mid360_type1.lvx2"));
  const std::size_t p0 = lvx2_frame0(1) + 24;
  REQUIRE(get<std::uint32_t>(good, p0 + 18) == 1344);
  std::string b = good;
  put<std::uint32_t>(b, p0 + 18, 1345);
  expect_lvx_error(tmp.file("len1.lvx2", b), "byte " + std::to_string(p0 + 18),
                   "package length 1345 is not a whole number of points: data type 1 has 14 bytes per point");
  b = good;
  put<std::uint32_t>(b, p0 + 18, 1344 + 14);
  expect_lvx_error(tmp.file("len_more.lvx2", b), "byte " + std::to_string(p0 + 18),
                   "package length 1358 does not fit its frame: the package would end at byte 1501, the frame ends at "
                   "byte 1487 (its next_offset)");
  b = good;
  put<std::uint32_t>(b, p0 + 18, 14u * 306783377u);  // a huge length allocates nothing
  expect_lvx_error(tmp.file("len_huge.lvx2", b), "byte " + std::to_string(p0 + 18), "does not fit its frame");
  b = good;
  put<std::uint32_t>(b, p0 + 18, 1344 - 14);  // one point less: 14 bytes left over, too few for a package header
  expect_lvx_error(tmp.file("len_less.lvx2", b), "byte " + std::to_string(p0 + 27 + 1330),
                   "14 bytes left in the frame (it ends at byte 1487, its next_offset): too few for a package header of "
                   "27 bytes");
  b = good;
  b[p0 + 17] = 3;
  expect_lvx_error(tmp.file("type.lvx2", b), "byte " + std::to_string(p0 + 17),
                   "unknown data type 3: expected 1 (cartesian, int32 mm, 14 bytes per point) or 2 (cartesian, int16 "
                   "cm, 8 bytes per point)");
  b = good;
  put<std::uint32_t>(b, p0 + 1, 7);
  expect_lvx_error(tmp.file("id.lvx2", b), "byte " + std::to_string(p0 + 1),
                   "package of LiDAR id 7, which the header does not declare (declared: 738306240)");
  b = good;
  b[p0 + 6] = 3;
  expect_lvx_error(tmp.file("ts.lvx2", b), "byte " + std::to_string(p0 + 6),
                   "unknown timestamp type 3: expected 0 (no sync), 1 (gPTP / PTP) or 2 (GPS)");
  b = good;
  b[17] = 1;  // version 2.1
  expect_lvx_error(tmp.file("version.lvx2", b), "byte 16", "unsupported LVX version 2.1.0.0");
  // Two devices with one LiDAR id.
  std::string two = file_bytes(lvx_data("two_lidars.lvx2"));
  put<std::uint32_t>(two, 29 + 63 + 32, get<std::uint32_t>(two, 29 + 32));
  expect_lvx_error(tmp.file("dup.lvx2", two), "byte 124",
                   "LiDAR id 2080483520 appears twice in the header (devices 0 and 1 from 0)");
  // A package of the other LiDAR is validated too.
  two = file_bytes(lvx_data("two_lidars.lvx2"));
  const std::size_t q0 = lvx2_frame0(2) + 24;
  const std::size_t q1 = q0 + 27 + get<std::uint32_t>(two, q0 + 18);
  two[q1 + 17] = 0;
  io::ReadOptions first;
  first.topic = "0";
  expect_lvx_error(tmp.file("other.lvx2", two), "byte " + std::to_string(q1 + 17), "unknown data type 0", first);
}

TEST_CASE("LVX: every truncation of a fixture is an InputError naming a byte, or a clean read of whole frames") {
  LvxDir tmp("truncations");
  struct Case {
    const char* file;
    const char* topic;
  };
  for (const Case c : {Case{"avia_v11.lvx", nullptr}, Case{"mid40_v10.lvx", nullptr}, Case{"two_lidars.lvx2", "1"},
                       Case{"horizon_v11_returns.lvx", nullptr}}) {
    const std::string whole = file_bytes(lvx_data(c.file));
    io::ReadOptions options;
    if (c.topic) options.topic = c.topic;
    const std::string path = tmp.path(std::string("cut_") + c.file);
    const std::size_t all = read_lvx(lvx_data(c.file), options).records.size();
    std::size_t clean = 0;
    for (std::size_t n = 0; n < whole.size(); ++n) {
      {
        std::ofstream(path, std::ios::binary | std::ios::trunc) << whole.substr(0, n);
      }
      try {
        io::LvxReader reader(path, options);
        std::vector<io::Record> out;
        while (reader.read(out, 64) > 0) {
        }
        ++clean;  // only at a frame boundary: then fewer records than the whole file
        CHECK_MESSAGE(out.size() < all, c.file << " cut at " << n);
      } catch (const io::InputError& e) {
        const std::string& where = e.where();
        std::uint64_t byte = 0;
        const bool named = where.rfind("byte ", 0) == 0 && io::detail::parse_uint64(where.substr(5), byte);
        CHECK_MESSAGE((named || where == "header"), c.file << " cut at " << n << ": " << e.what());
        CHECK_MESSAGE(byte <= n, c.file << " cut at " << n << ": " << e.what());
      }
    }
    // Clean cuts: right after the device list and after each frame but the last.
    CHECK_MESSAGE(clean == io::summarize_lvx(lvx_data(c.file)).frames, c.file);
  }
}
