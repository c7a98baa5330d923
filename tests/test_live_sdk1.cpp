// SPDX-License-Identifier: MIT
// The Livox SDK1 codecs (live/sdk1_packets.hpp, live/sdk1_control.hpp): the
// CRCs' check values; data packets of every type built here byte by byte and
// decoded (coordinates, reflectivity, tags, per-firing times, empty slots);
// GPS time; every malformed class and every truncation; encode -> decode
// round trips within each type's quantisation; control frames against bytes
// computed independently (a heartbeat and a handshake), their round trips and
// their malformed classes.

#include <doctest/doctest.h>

#include <streamclust/live/livox_crc.hpp>
#include <streamclust/live/sdk1_control.hpp>
#include <streamclust/live/sdk1_packets.hpp>
#include <streamclust/live/sdk1_ports.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace live = streamclust::live;
using Bytes = std::vector<std::uint8_t>;
using TypeList = std::initializer_list<std::uint8_t>;

namespace {

/// Appends `v` little-endian, byte by byte (independent of the codecs).
template <class T>
void put(Bytes& b, T v) {
  std::uint64_t u = 0;
  std::memcpy(&u, &v, sizeof v);
  for (std::size_t k = 0; k < sizeof v; ++k) b.push_back(static_cast<std::uint8_t>(u >> (8 * k)));
}

/// The 18-byte header: version 5, slot 0, id 1, rsvd, err_code, timestamp type, data type, timestamp.
Bytes header(std::uint8_t data_type, std::uint8_t timestamp_type, std::uint64_t timestamp) {
  Bytes b = {5, 0, 1, 0};
  put<std::uint32_t>(b, 0x01020304u);
  b.push_back(timestamp_type);
  b.push_back(data_type);
  put(b, timestamp);
  return b;
}

/// Pads `b` with zero structs (empty slots) up to `bytes`.
Bytes& pad(Bytes& b, std::size_t bytes) {
  REQUIRE(b.size() <= bytes);
  b.resize(bytes, 0);
  return b;
}

live::LivoxPacketSummary decode_sdk1(const Bytes& b, live::LivoxPacketContents& out, std::uint32_t interval = 4167) {
  return live::decode_sdk1_packet(b.data(), b.size(), interval, out);
}

constexpr std::uint64_t kPacketTime = 1000000000123ull;  // a packet time [ns]

/// A Cartesian return: i32 x, y, z [mm], reflectivity, optional tag.
void cartesian(Bytes& b, std::int32_t x, std::int32_t y, std::int32_t z, std::uint8_t refl, int tag = -1) {
  put(b, x);
  put(b, y);
  put(b, z);
  b.push_back(refl);
  if (tag >= 0) b.push_back(static_cast<std::uint8_t>(tag));
}

void check_return(const live::LivoxReturn& r, float x, float y, float z, std::uint8_t refl, std::uint8_t tag,
                  std::uint64_t t, float tolerance = 0.0f) {
  CHECK(std::abs(r.x - x) <= tolerance);
  CHECK(std::abs(r.y - y) <= tolerance);
  CHECK(std::abs(r.z - z) <= tolerance);
  CHECK(r.reflectivity == refl);
  CHECK(r.tag == tag);
  CHECK(r.time_ns == t);
}

}  // namespace

TEST_CASE("SDK1 CRCs: check values, the seeded empty CRC, a preamble with its CRC gives 0") {
  const std::uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  CHECK(live::crc16_livox_sdk1(check, 9) == 0xAB4E);
  CHECK(live::crc32_livox_sdk1(check, 9) == 0xB08DB5B1u);
  CHECK(live::crc32_livox_sdk1(check, 0) == 0x564F580Au);
  std::uint8_t preamble[9] = {0xAA, 1, 0x0F, 0, 0, 0x34, 0x12};
  const std::uint16_t crc = live::crc16_livox_sdk1(preamble, 7);
  preamble[7] = static_cast<std::uint8_t>(crc);
  preamble[8] = static_cast<std::uint8_t>(crc >> 8);
  CHECK(live::crc16_livox_sdk1(preamble, 9) == 0);
  preamble[5] ^= 1;
  CHECK(live::crc16_livox_sdk1(preamble, 9) != 0);
}

TEST_CASE("SDK1 Cartesian packets (types 0, 2), hand-built: metres, reflectivity, tags, firing times, empty slots") {
  live::LivoxPacketContents out;
  SUBCASE("type 0: 100 structs of 13 bytes, no tag, Mid-40 interval") {
    Bytes b = header(0, 0, kPacketTime);
    cartesian(b, 1234, -5678, 90, 77);
    cartesian(b, 0, 0, 0, 60);  // empty (whatever its reflectivity)
    cartesian(b, -1, 0, 0, 255);
    REQUIRE(pad(b, 18 + 100 * 13).size() == 1318);
    b[18 + 99 * 13 + 11] = 0x10;  // the last struct: z = 0x10000000 mm
    const auto s = decode_sdk1(b, out, 10000);
    REQUIRE(s.status == live::LivoxPacketStatus::points);
    CHECK_FALSE(s.has_counter);
    CHECK(s.sync == live::LivoxTimeSync::none);
    CHECK(s.data_type == 0);
    CHECK(s.slots == 100);
    CHECK(s.returns == 3);
    CHECK(s.empty_slots == 97);
    CHECK(s.first_time_ns == kPacketTime);
    CHECK(s.last_time_ns == kPacketTime + 99 * 10000);
    REQUIRE(out.returns.size() == 3);
    check_return(out.returns[0], 1.234f, -5.678f, 0.09f, 77, 0, kPacketTime);
    check_return(out.returns[1], -0.001f, 0.0f, 0.0f, 255, 0, kPacketTime + 2 * 10000);
    check_return(out.returns[2], 0.0f, 0.0f, 268435.456f, 0, 0, kPacketTime + 99 * 10000);
  }
  SUBCASE("type 2: 96 structs of 14 bytes with a tag; appended after what `returns` held") {
    out.returns.resize(2);
    Bytes b = header(2, 1, kPacketTime);
    cartesian(b, 0, 0, 0, 0, 0);
    cartesian(b, 450000, 2, -3, 9, 0x35);
    REQUIRE(pad(b, 1362).size() == 18 + 96 * 14);
    const auto s = decode_sdk1(b, out);
    REQUIRE(s.status == live::LivoxPacketStatus::points);
    CHECK(s.sync == live::LivoxTimeSync::ptp);
    CHECK(s.slots == 96);
    CHECK(s.returns == 1);
    CHECK(s.empty_slots == 95);
    CHECK(s.last_time_ns == kPacketTime + 95 * 4167);
    REQUIRE(out.returns.size() == 3);
    check_return(out.returns[2], 450.0f, 0.002f, -0.003f, 9, 0x35, kPacketTime + 4167);
  }
}

TEST_CASE("SDK1 spherical packets (types 1, 3), hand-built: depth and angles to metres") {
  live::LivoxPacketContents out;
  auto spherical = [](Bytes& b, std::uint32_t depth, std::uint16_t theta, std::uint16_t phi, std::uint8_t refl,
                      int tag) {
    put(b, depth);
    put(b, theta);
    put(b, phi);
    b.push_back(refl);
    if (tag >= 0) b.push_back(static_cast<std::uint8_t>(tag));
  };
  for (const int tag : {-1, 7}) {
    CAPTURE(tag);
    out.returns.clear();
    const std::uint8_t type = tag < 0 ? 1 : 3;
    Bytes b = header(type, 4, kPacketTime);
    spherical(b, 10000, 9000, 0, 1, tag);      // 10 m along x
    spherical(b, 0, 4500, 4500, 50, tag);      // no return
    spherical(b, 2000, 0, 12345, 2, tag);      // 2 m up: the azimuth does not matter
    spherical(b, 5000, 9000, 27000, 3, tag);   // 5 m along -y
    spherical(b, 4000, 6000, 4500, 4, tag);    // theta 60 deg, phi 45 deg
    pad(b, type == 1 ? 918 : 978);
    const auto s = decode_sdk1(b, out);
    REQUIRE(s.status == live::LivoxPacketStatus::points);
    CHECK(s.sync == live::LivoxTimeSync::pps);
    CHECK(s.slots == (type == 1 ? 100u : 96u));
    CHECK(s.returns == 4);
    CHECK(s.empty_slots == s.slots - 4);
    REQUIRE(out.returns.size() == 4);
    const auto t = static_cast<std::uint8_t>(tag < 0 ? 0 : tag);
    check_return(out.returns[0], 10.0f, 0.0f, 0.0f, 1, t, kPacketTime, 1e-6f);
    check_return(out.returns[1], 0.0f, 0.0f, 2.0f, 2, t, kPacketTime + 2 * 4167, 1e-6f);
    check_return(out.returns[2], 0.0f, -5.0f, 0.0f, 3, t, kPacketTime + 3 * 4167, 1e-6f);
    const float h = 4.0f * std::sqrt(3.0f) / 2.0f / std::sqrt(2.0f);
    check_return(out.returns[3], h, h, 2.0f, 4, t, kPacketTime + 4 * 4167, 1e-5f);
  }
}

TEST_CASE("SDK1 dual and triple packets (types 4, 5, 7, 8): returns of one firing share its time") {
  live::LivoxPacketContents out;
  SUBCASE("type 4: 48 firings of 2 x 14 bytes; an empty first return") {
    Bytes b = header(4, 0, kPacketTime);
    cartesian(b, 1000, 0, 0, 10, 0x10);
    cartesian(b, 2000, 0, 0, 20, 0x20);
    cartesian(b, 0, 0, 0, 0, 0);
    cartesian(b, 0, 3000, 0, 30, 0x20);
    pad(b, 18 + 48 * 28);
    const auto s = decode_sdk1(b, out);
    REQUIRE(s.status == live::LivoxPacketStatus::points);
    CHECK(s.slots == 96);
    CHECK(s.returns == 3);
    CHECK(s.empty_slots == 93);
    CHECK(s.last_time_ns == kPacketTime + 47 * 4167);
    REQUIRE(out.returns.size() == 3);
    check_return(out.returns[0], 1.0f, 0.0f, 0.0f, 10, 0x10, kPacketTime);
    check_return(out.returns[1], 2.0f, 0.0f, 0.0f, 20, 0x20, kPacketTime);
    check_return(out.returns[2], 0.0f, 3.0f, 0.0f, 30, 0x20, kPacketTime + 4167);
  }
  SUBCASE("type 5: 48 firings of theta, phi, 2 x (depth, reflectivity, tag)") {
    Bytes b = header(5, 0, kPacketTime);
    put<std::uint16_t>(b, 9000);
    put<std::uint16_t>(b, 9000);  // along +y
    put<std::uint32_t>(b, 1500);
    b.insert(b.end(), {11, 0x10});
    put<std::uint32_t>(b, 2500);
    b.insert(b.end(), {22, 0x20});
    REQUIRE(pad(b, 18 + 48 * 16).size() == 786);
    const auto s = decode_sdk1(b, out);
    REQUIRE(s.status == live::LivoxPacketStatus::points);
    CHECK(s.returns == 2);
    CHECK(s.empty_slots == 94);
    REQUIRE(out.returns.size() == 2);
    check_return(out.returns[0], 0.0f, 1.5f, 0.0f, 11, 0x10, kPacketTime, 1e-6f);
    check_return(out.returns[1], 0.0f, 2.5f, 0.0f, 22, 0x20, kPacketTime, 1e-6f);
  }
  SUBCASE("types 7 and 8: 30 firings of 3 returns") {
    Bytes b = header(7, 0, kPacketTime);
    pad(b, 18 + 29 * 42);
    cartesian(b, 1, 2, 3, 1, 1);
    cartesian(b, 4, 5, 6, 2, 2);
    cartesian(b, 7, 8, 9, 3, 3);
    auto s = decode_sdk1(b, out);
    REQUIRE(s.status == live::LivoxPacketStatus::points);
    CHECK(s.slots == 90);
    CHECK(s.returns == 3);
    REQUIRE(out.returns.size() == 3);
    for (int k = 0; k < 3; ++k)
      check_return(out.returns[k], 0.001f * float(3 * k + 1), 0.001f * float(3 * k + 2), 0.001f * float(3 * k + 3),
                   static_cast<std::uint8_t>(k + 1), static_cast<std::uint8_t>(k + 1), kPacketTime + 29 * 4167, 1e-7f);
    out.returns.clear();
    b = header(8, 0, kPacketTime);
    put<std::uint16_t>(b, 0);
    put<std::uint16_t>(b, 0);  // straight up
    for (std::uint32_t depth : {1000u, 0u, 3000u}) {
      put(b, depth);
      b.insert(b.end(), {5, 6});
    }
    REQUIRE(pad(b, 18 + 30 * 22).size() == 678);
    s = decode_sdk1(b, out);
    REQUIRE(s.status == live::LivoxPacketStatus::points);
    CHECK(s.returns == 2);
    CHECK(s.empty_slots == 88);
    REQUIRE(out.returns.size() == 2);
    check_return(out.returns[0], 0.0f, 0.0f, 1.0f, 5, 6, kPacketTime);
    check_return(out.returns[1], 0.0f, 0.0f, 3.0f, 5, 6, kPacketTime);
  }
}

TEST_CASE("SDK1 IMU packets (type 6): gyro [rad/s] and acceleration [g]") {
  Bytes b = header(6, 1, kPacketTime);
  for (float v : {0.01f, -0.02f, 0.03f, 0.0f, 0.5f, -1.0f}) put(b, v);
  REQUIRE(b.size() == 42);
  live::LivoxPacketContents out;
  const auto s = decode_sdk1(b, out);
  REQUIRE(s.status == live::LivoxPacketStatus::imu);
  CHECK(s.first_time_ns == kPacketTime);
  CHECK(out.returns.empty());
  CHECK(out.imu.time_ns == kPacketTime);
  CHECK(out.imu.gyro == std::array<float, 3>{0.01f, -0.02f, 0.03f});
  CHECK(out.imu.acceleration == std::array<float, 3>{0.0f, 0.5f, -1.0f});
  // The encoder writes the same bytes.
  live::Sdk1PacketHeader h;
  REQUIRE(live::read_sdk1_packet_header(b.data(), b.size(), h));
  CHECK(h.error_code == 0x01020304u);
  Bytes again;
  live::encode_sdk1_imu_packet(h, out.imu, again);
  CHECK(again == b);
}

TEST_CASE("SDK1 time: GPS UTC fields to ns since 1970, impossible dates, reserved and unknown types") {
  auto gps = [](std::uint8_t year, std::uint8_t month, std::uint8_t day, std::uint8_t hour, std::uint32_t us) {
    Bytes b = {5, 0, 1, 0, 0, 0, 0, 0, 3, 6, year, month, day, hour};
    put(b, us);
    return pad(b, 42);
  };
  live::LivoxPacketContents out;
  auto s = decode_sdk1(gps(26, 11, 29, 13, 1234567890u), out);
  REQUIRE(s.status == live::LivoxPacketStatus::imu);
  CHECK(s.sync == live::LivoxTimeSync::gps);
  CHECK(out.imu.time_ns == 1795958434567890000ull);  // 2026-11-29 13:20:34.567890 UTC
  s = decode_sdk1(gps(24, 2, 29, 23, 3599999999u), out);    // a leap day, the hour's last microsecond
  REQUIRE(s.status == live::LivoxPacketStatus::imu);
  CHECK(out.imu.time_ns == 1709251199999999000ull);
  out.imu.time_ns = 42;
  for (const Bytes& bad : {gps(25, 2, 29, 0, 0), gps(26, 0, 1, 0, 0), gps(26, 13, 1, 0, 0), gps(26, 4, 31, 0, 0),
                           gps(26, 1, 0, 0, 0), gps(26, 1, 1, 24, 0), gps(26, 1, 1, 0, 3600000000u)}) {
    CHECK(decode_sdk1(bad, out).status == live::LivoxPacketStatus::bad_time);
    CHECK(out.imu.time_ns == 42);
  }
  for (const std::uint8_t type : TypeList{2, 5, 255}) {
    Bytes b = header(6, type, kPacketTime);
    CHECK(decode_sdk1(pad(b, 42), out).status == live::LivoxPacketStatus::bad_time);
  }
  // The encoder's side: UTC to the microsecond, and only years 2000-2255.
  live::Sdk1PacketHeader h;
  REQUIRE(live::set_sdk1_packet_time(h, 3, 1795958434567890999ull));
  std::uint64_t ns = 0;
  live::LivoxTimeSync sync = live::LivoxTimeSync::none;
  REQUIRE(live::sdk1_packet_time(h, ns, sync));
  CHECK(ns == 1795958434567890000ull);
  CHECK(sync == live::LivoxTimeSync::gps);
  CHECK_FALSE(live::set_sdk1_packet_time(h, 3, 946684799999999999ull));  // 1999-12-31
  CHECK_FALSE(live::set_sdk1_packet_time(h, 2, 0));
  CHECK(live::set_sdk1_packet_time(h, 1, 7));
  CHECK((h.timestamp_type == 1 && h.timestamp == 7));
}

TEST_CASE("SDK1 malformed packets: every truncation, extra bytes, unknown data types; nothing appended") {
  live::LivoxPacketContents out;
  for (std::uint8_t type = 0; type <= 8; ++type) {
    CAPTURE(int(type));
    Bytes whole = header(type, 0, kPacketTime);
    pad(whole, live::sdk1_packet_bytes(*streamclust::io::find_sdk1_data_type(type)));
    std::memset(whole.data() + 18, 0x11, whole.size() - 18);  // every slot a return
    for (std::size_t n = 0; n < whole.size(); ++n) {
      // A vector of exactly n bytes: ASan sees a read past them.
      const Bytes cut(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(n));
      if (decode_sdk1(cut, out).status != live::LivoxPacketStatus::truncated) FAIL_CHECK("not truncated at " << n);
    }
    Bytes longer = whole;
    longer.push_back(0);
    CHECK(decode_sdk1(longer, out).status == live::LivoxPacketStatus::bad_length);
    CHECK(out.returns.empty());
    const auto s = decode_sdk1(whole, out);
    CHECK(s.returns == s.slots);
    CHECK(out.returns.size() == s.returns);
    out.returns.clear();
  }
  for (const std::uint8_t type : TypeList{9, 17, 255}) {
    Bytes b = header(type, 0, kPacketTime);
    const auto s = decode_sdk1(pad(b, 1362), out);
    CHECK(s.status == live::LivoxPacketStatus::unknown_data_type);
    CHECK(s.data_type == type);
  }
  CHECK(out.returns.empty());
  CHECK(live::decode_sdk1_packet(nullptr, 0, 4167, out).status == live::LivoxPacketStatus::truncated);
}

TEST_CASE("SDK1 encode -> decode round trips of every point type within its quantisation") {
  std::mt19937 rng(20261129);
  std::uniform_real_distribution<float> coordinate(-200.0f, 200.0f);
  std::uniform_int_distribution<int> byte(0, 255);
  for (const std::uint8_t type_value : TypeList{0, 1, 2, 3, 4, 5, 7, 8}) {
    CAPTURE(int(type_value));
    const auto& type = *streamclust::io::find_sdk1_data_type(type_value);
    const std::uint32_t interval = live::sdk1_nominal_firing_interval_ns(type_value);
    live::Sdk1PacketHeader h;
    h.data_type = type_value;
    REQUIRE(live::set_sdk1_packet_time(h, 3, 1795958434567890000ull));
    const std::uint64_t t = 1795958434567890000ull;
    // Every firing but a few holds its returns; spherical firings share a direction.
    std::vector<live::LivoxReturn> in;
    for (std::uint32_t k = 0; k < type.structs_per_package; ++k) {
      if (k % 7 == 3) continue;
      const float x = coordinate(rng), y = coordinate(rng), z = coordinate(rng);
      for (std::uint32_t r = 0; r < type.returns; ++r) {
        const float scale = 1.0f + 0.25f * float(r);
        in.push_back(live::LivoxReturn{x * scale, y * scale, z * scale, static_cast<std::uint8_t>(byte(rng)),
                                       type.has_tag ? static_cast<std::uint8_t>(byte(rng)) : std::uint8_t{0},
                                       t + k * std::uint64_t{interval}});
      }
    }
    Bytes packet;
    live::encode_sdk1_data_packet(h, interval, in.data(), in.size(), packet);
    CHECK(packet.size() == live::sdk1_packet_bytes(type));
    live::LivoxPacketContents out;
    const auto s = live::decode_sdk1_packet(packet.data(), packet.size(), interval, out);
    REQUIRE(s.status == live::LivoxPacketStatus::points);
    CHECK(s.sync == live::LivoxTimeSync::gps);
    CHECK(s.empty_slots == s.slots - in.size());
    REQUIRE(out.returns.size() == in.size());
    const bool spherical = type.coordinates == streamclust::io::LivoxCoordinates::spherical_mm;
    double worst = 0;
    for (std::size_t i = 0; i < in.size(); ++i) {
      const auto& a = in[i];
      const auto& b = out.returns[i];
      const double range = std::sqrt(double(a.x) * a.x + double(a.y) * a.y + double(a.z) * a.z);
      // 0.5 mm per coordinate; spherical: 0.5 mm in depth plus 0.005 deg in each angle.
      const double bound = spherical ? 0.0005 + range * 2 * 0.005 * 3.14159265358979 / 180 + 1e-4 : 0.0005 + 2e-5;
      const double error = std::max({std::abs(double(a.x) - b.x), std::abs(double(a.y) - b.y),
                                     std::abs(double(a.z) - b.z)});
      worst = std::max(worst, error / bound);
      CHECK(b.reflectivity == a.reflectivity);
      CHECK(b.tag == a.tag);
      CHECK(b.time_ns == a.time_ns);
    }
    CHECK(worst <= 1.0);
    CHECK(worst > 0.05);  // the quantisation shows: the comparison is not vacuous
  }
}

TEST_CASE("SDK1 packet encoder refuses what it cannot write") {
  live::Sdk1PacketHeader h;
  h.data_type = 2;
  h.timestamp = kPacketTime;
  Bytes out;
  auto encode = [&](std::vector<live::LivoxReturn> in, std::uint32_t interval = 4167) {
    live::encode_sdk1_data_packet(h, interval, in.data(), in.size(), out);
  };
  const live::LivoxReturn ok{1, 2, 3, 0, 0, kPacketTime};
  CHECK_NOTHROW(encode({ok}));
  CHECK_THROWS_AS(encode({live::LivoxReturn{NAN, 0, 0, 0, 0, kPacketTime}}), std::invalid_argument);
  CHECK_THROWS_AS(encode({live::LivoxReturn{3e6f, 0, 0, 0, 0, kPacketTime}}), std::invalid_argument);
  CHECK_THROWS_AS(encode({live::LivoxReturn{1, 0, 0, 0, 0, kPacketTime - 1000}}), std::invalid_argument);
  CHECK_THROWS_AS(encode({live::LivoxReturn{1, 0, 0, 0, 0, kPacketTime + 96 * 4167}}), std::invalid_argument);
  CHECK_THROWS_AS(encode({ok, ok}), std::invalid_argument);  // two returns in a single-return firing
  CHECK_THROWS_AS(encode({live::LivoxReturn{1, 0, 0, 0, 0, kPacketTime + 4167}, ok}),
                  std::invalid_argument);  // out of order
  CHECK_THROWS_AS(encode({ok}, 0), std::invalid_argument);
  h.data_type = 6;
  CHECK_THROWS_AS(encode({ok}), std::invalid_argument);
  h.data_type = 9;
  CHECK_THROWS_AS(encode({ok}), std::invalid_argument);
  h.data_type = 0;
  h.timestamp_type = 2;
  CHECK_THROWS_AS(encode({ok}), std::invalid_argument);
}

TEST_CASE("SDK1 rates, periods, ports and timing") {
  CHECK(live::sdk1_nominal_firing_interval_ns(0) == 10000);
  CHECK(live::sdk1_nominal_firing_interval_ns(1) == 10000);
  for (const std::uint8_t t : TypeList{2, 3, 4, 5, 7, 8}) CHECK(live::sdk1_nominal_firing_interval_ns(t) == 4167);
  CHECK(live::sdk1_nominal_firing_interval_ns(6) == 0);
  CHECK(live::sdk1_nominal_firing_interval_ns(9) == 0);
  CHECK(live::expected_sdk1_packet_period_ns(0, 10000) == 1000000);  // 1,000 packets/s at 100 k points/s
  CHECK(live::expected_sdk1_packet_period_ns(2, 4167) == 400032);     // 2,500 packets/s at 240 k points/s
  CHECK(live::expected_sdk1_packet_period_ns(4, 4167) == 200016);     // dual: 48 firings
  CHECK(live::expected_sdk1_packet_period_ns(7, 4167) == 125010);     // triple: 30 firings
  CHECK(live::expected_sdk1_packet_period_ns(6, 4167) == 5000000);    // IMU 200 Hz
  CHECK(live::expected_sdk1_packet_period_ns(9, 4167) == 0);
  CHECK(live::sdk1_broadcast_listen_port == 55000);
  CHECK(live::sdk1_lidar_command_port == 65000);
  CHECK(live::sdk1_host_command_port(2) == 55502);
  CHECK(live::sdk1_host_data_port(2) == 56002);
  CHECK(live::sdk1_host_sensor_port(2) == 56002);
  CHECK(live::sdk1_heartbeat_period < live::sdk1_heartbeat_max_period);
  CHECK(live::sdk1_heartbeat_max_period.count() == 1000);
  CHECK(live::sdk1_disconnect_timeout.count() == 3000);
}

TEST_CASE("SDK1 control frames: a heartbeat and a handshake byte for byte, decoded back") {
  // Computed by an independent bitwise implementation of the two seeded CRCs;
  // the heartbeat of seq 0 is also the frame other SDK1 clients send.
  const Bytes heartbeat = {0xAA, 0x01, 0x0F, 0x00, 0x00, 0x00, 0x00, 0x04, 0xD7, 0x00, 0x03, 0x38, 0xBA, 0x8D, 0x0C};
  const Bytes handshake = {0xAA, 0x01, 0x19, 0x00, 0x01, 0x01, 0x00, 0xD8, 0x1B, 0x00, 0x01, 0xC0, 0xA8,
                           0x01, 0x32, 0xC0, 0xDA, 0xCC, 0xD8, 0xC0, 0xDA, 0x97, 0x4B, 0x53, 0xA8};
  Bytes out;
  live::encode_sdk1_request(0, live::sdk1_heartbeat, out);
  CHECK(out == heartbeat);
  live::encode_sdk1_handshake(1, live::Sdk1Handshake{{192, 168, 1, 50}, 56000, 55500, 56000}, out);
  CHECK(out == handshake);

  live::Sdk1Frame f;
  REQUIRE(live::decode_sdk1_frame(heartbeat.data(), heartbeat.size(), f) == live::Sdk1FrameStatus::ok);
  CHECK(live::is_sdk1_request(f, live::sdk1_heartbeat));
  CHECK_FALSE(live::is_sdk1_request(f, live::sdk1_disconnect));
  CHECK(f.data_size == 0);
  REQUIRE(live::decode_sdk1_frame(handshake.data(), handshake.size(), f) == live::Sdk1FrameStatus::ok);
  CHECK(f.packet_type == live::Sdk1PacketType::ack);
  CHECK(f.seq == 1);
  live::Sdk1Handshake hs;
  REQUIRE(live::parse_sdk1_handshake(f, hs));
  CHECK(hs.host_ip == std::array<std::uint8_t, 4>{192, 168, 1, 50});
  CHECK((hs.data_port == 56000 && hs.command_port == 55500 && hs.sensor_port == 56000));
  // Sent as CMD it reads the same; as MSG it is no handshake.
  live::encode_sdk1_handshake(9, hs, out, live::Sdk1PacketType::cmd);
  REQUIRE(live::decode_sdk1_frame(out.data(), out.size(), f) == live::Sdk1FrameStatus::ok);
  CHECK(live::parse_sdk1_handshake(f, hs));
  live::encode_sdk1_handshake(9, hs, out, live::Sdk1PacketType::msg);
  REQUIRE(live::decode_sdk1_frame(out.data(), out.size(), f) == live::Sdk1FrameStatus::ok);
  CHECK_FALSE(live::parse_sdk1_handshake(f, hs));
}

TEST_CASE("SDK1 control messages round trip, both sides") {
  Bytes out;
  live::Sdk1Frame f;
  auto decoded = [&]() -> const live::Sdk1Frame& {
    REQUIRE(live::decode_sdk1_frame(out.data(), out.size(), f) == live::Sdk1FrameStatus::ok);
    return f;
  };
  live::Sdk1Broadcast b;
  std::memcpy(b.broadcast_code.data(), "3GGDJ6K00200101", 15);
  b.device_type = 7;
  live::encode_sdk1_broadcast(3, b, out);
  CHECK(out.size() == 15 + 19);
  live::Sdk1Broadcast b2;
  REQUIRE(live::parse_sdk1_broadcast(decoded(), b2));
  CHECK(f.seq == 3);
  CHECK(b2.code() == "3GGDJ6K00200101");
  CHECK(std::string(live::sdk1_device_name(b2.device_type)) == "Avia");
  CHECK(std::string(live::sdk1_device_name(1)) == "Mid-40");
  CHECK(std::string(live::sdk1_device_name(6)) == "Mid-70");
  CHECK(std::string(live::sdk1_device_name(4)) == "unknown");

  live::encode_sdk1_heartbeat_ack(65535, live::Sdk1HeartbeatAck{0, 1, 2, 0xDEADBEEFu}, out);
  live::Sdk1HeartbeatAck hb;
  REQUIRE(live::parse_sdk1_heartbeat_ack(decoded(), hb));
  CHECK(f.seq == 65535);
  CHECK((hb.ret_code == 0 && hb.state == 1 && hb.feature == 2 && hb.status == 0xDEADBEEFu));

  struct OneByte {
    live::Sdk1Command command;
    std::uint8_t value;
  };
  for (const OneByte c : {OneByte{live::sdk1_sampling, 1}, OneByte{live::sdk1_sampling, 0},
                          OneByte{live::sdk1_coordinate_system, std::uint8_t(live::Sdk1Coordinates::spherical)},
                          OneByte{live::sdk1_return_mode, std::uint8_t(live::Sdk1ReturnMode::dual)},
                          OneByte{live::sdk1_imu_push_frequency, std::uint8_t(live::Sdk1ImuFrequency::hz200)}}) {
    std::uint8_t value = 99, ret = 99;
    live::encode_sdk1_request(12, c.command, c.value, out);
    REQUIRE(live::parse_sdk1_request(decoded(), c.command, value));
    CHECK(value == c.value);
    CHECK_FALSE(live::parse_sdk1_ack(f, c.command, ret));
    live::encode_sdk1_ack(12, c.command, 1, out);
    REQUIRE(live::parse_sdk1_ack(decoded(), c.command, ret));
    CHECK(ret == 1);
    CHECK_FALSE(live::parse_sdk1_ack(f, live::sdk1_disconnect, ret));
  }
  live::encode_sdk1_request(4, live::sdk1_disconnect, out);
  CHECK(live::is_sdk1_request(decoded(), live::sdk1_disconnect));
  std::uint8_t value = 0;
  CHECK_FALSE(live::parse_sdk1_request(f, live::sdk1_disconnect, value));  // no data byte
}

TEST_CASE("SDK1 malformed control frames: each check names its class") {
  Bytes good;
  live::encode_sdk1_request(5, live::sdk1_sampling, 1, good);
  live::Sdk1Frame f;
  auto status = [&](const Bytes& b) { return live::decode_sdk1_frame(b.data(), b.size(), f); };
  auto with_header_crc = [](Bytes b) {  // re-seal the preamble after an edit
    const std::uint16_t crc = live::crc16_livox_sdk1(b.data(), 7);
    b[7] = static_cast<std::uint8_t>(crc);
    b[8] = static_cast<std::uint8_t>(crc >> 8);
    return b;
  };
  REQUIRE(status(good) == live::Sdk1FrameStatus::ok);
  for (std::size_t n = 0; n < good.size(); ++n) {
    const Bytes cut(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n));
    if (status(cut) != live::Sdk1FrameStatus::truncated) FAIL_CHECK("not truncated at " << n);
  }
  Bytes b = good;
  b[0] = 0x55;
  CHECK(status(b) == live::Sdk1FrameStatus::bad_sof);
  b = good;
  b[1] = 0;
  CHECK(status(with_header_crc(b)) == live::Sdk1FrameStatus::bad_version);
  b = good;
  b[5] ^= 0x80;  // seq: the preamble CRC
  CHECK(status(b) == live::Sdk1FrameStatus::bad_header_crc);
  b = good;
  b[2] = 14;
  CHECK(status(with_header_crc(b)) == live::Sdk1FrameStatus::bad_length);
  b = good;
  b.push_back(0);
  CHECK(status(b) == live::Sdk1FrameStatus::bad_length);
  b = good;
  b[11] ^= 1;  // the data byte
  CHECK(status(b) == live::Sdk1FrameStatus::bad_crc);
  b = good;
  b.back() ^= 0x80;  // the CRC-32 itself
  CHECK(status(b) == live::Sdk1FrameStatus::bad_crc);
  live::encode_sdk1_frame(static_cast<live::Sdk1PacketType>(3), 5, live::sdk1_sampling, nullptr, 0, b);
  CHECK(status(b) == live::Sdk1FrameStatus::bad_packet_type);
  CHECK(std::string(live::describe(live::Sdk1FrameStatus::bad_header_crc)) == "bad header CRC");
  const Bytes big(0xFFFF - 14, 0);
  CHECK_THROWS_AS(live::encode_sdk1_frame(live::Sdk1PacketType::cmd, 0, live::sdk1_sampling, big.data(), big.size(), b),
                  std::invalid_argument);
}
