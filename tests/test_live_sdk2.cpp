// SPDX-License-Identifier: MIT
// The Livox SDK2 codecs (live/sdk2_packets.hpp, live/sdk2_control.hpp): the
// CRCs against their catalogue check values and an independent bitwise
// CRC-16; data packets of every type built byte by byte here (not by the
// encoder) and decoded: units, cm scaling, spherical angles, slot times,
// empty slots, tags, the CRC-0 rule and every malformed class; encode ->
// decode round trips within each type's quantisation; control frames with
// hand-checked bytes, every status, the discovery and parameter messages and
// the key-value parser's bounds; the packets through LivoxStream across a
// clock jump.

#include <doctest/doctest.h>

#include <streamclust/live/livox_crc.hpp>
#include <streamclust/live/livox_stream.hpp>
#include <streamclust/live/sdk2_control.hpp>
#include <streamclust/live/sdk2_device.hpp>
#include <streamclust/live/sdk2_packets.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace live = streamclust::live;
using Bytes = std::vector<std::uint8_t>;

namespace {

/// Little-endian appends, written out byte by byte (independent of the codecs).
struct ByteWriter {
  Bytes b;
  ByteWriter& u8(unsigned v) { b.push_back(static_cast<std::uint8_t>(v)); return *this; }
  ByteWriter& u16(unsigned v) { return u8(v & 0xFF).u8((v >> 8) & 0xFF); }
  ByteWriter& u32(std::uint32_t v) { return u16(v & 0xFFFF).u16(v >> 16); }
  ByteWriter& u64(std::uint64_t v) {
    return u32(static_cast<std::uint32_t>(v)).u32(static_cast<std::uint32_t>(v >> 32));
  }
  ByteWriter& i16(int v) { return u16(static_cast<std::uint16_t>(static_cast<std::int16_t>(v))); }
  ByteWriter& i32(std::int32_t v) { return u32(static_cast<std::uint32_t>(v)); }
  ByteWriter& f32(float v) {
    std::uint32_t u;
    std::memcpy(&u, &v, 4);
    return u32(u);
  }
};

/// The reflected CRC-32 (ISO-HDLC), bit by bit.
std::uint32_t bitwise_crc32(const std::uint8_t* p, std::size_t n) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? (c >> 1) ^ 0xEDB88320u : c >> 1;
  }
  return c ^ 0xFFFFFFFFu;
}

/// CRC-16/CCITT-FALSE from its catalogue parameters, bit by bit.
std::uint16_t bitwise_crc16_ccitt_false(const std::uint8_t* p, std::size_t n) {
  std::uint32_t c = 0xFFFF;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= std::uint32_t{p[i]} << 8;
    for (int k = 0; k < 8; ++k) c = (c & 0x8000u) ? ((c << 1) ^ 0x1021u) & 0xFFFFu : (c << 1) & 0xFFFFu;
  }
  return static_cast<std::uint16_t>(c);
}

/// A data packet: header fields as given, then `body`; the length field is
/// the true size unless `length` says otherwise. With `crc`, the crc32 field
/// is the bitwise CRC-32 of bytes [28, end).
Bytes data_packet(unsigned data_type, unsigned dot_num, unsigned time_interval, std::uint64_t timestamp,
                  const Bytes& body, bool crc = false, unsigned time_type = 0, unsigned udp_cnt = 7,
                  long length = -1) {
  ByteWriter w;
  const auto size = static_cast<unsigned>(36 + body.size());
  w.u8(0).u16(length < 0 ? size : static_cast<unsigned>(length)).u16(time_interval).u16(dot_num).u16(udp_cnt)
      .u8(0).u8(data_type).u8(time_type);
  for (int i = 0; i < 12; ++i) w.u8(0);
  w.u32(0).u64(timestamp);
  w.b.insert(w.b.end(), body.begin(), body.end());
  if (crc) {
    const std::uint32_t c = bitwise_crc32(w.b.data() + 28, w.b.size() - 28);
    for (int i = 0; i < 4; ++i) w.b[24 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(c >> (8 * i));
  }
  return w.b;
}

live::LivoxPacketSummary decode(const Bytes& b, live::LivoxPacketContents& out) {
  return live::decode_sdk2_packet(b.data(), b.size(), out);
}

live::LivoxPacketStatus status_of(const Bytes& b) {
  live::LivoxPacketContents out;
  const auto s = decode(b, out);
  if (s.status != live::LivoxPacketStatus::points) CHECK(out.returns.empty());
  return s.status;
}

/// A valid type-1 packet of three slots (the second empty) at t = 1e9 ns.
Bytes three_cartesian_mm(bool crc = false) {
  ByteWriter body;
  body.i32(1000).i32(-2000).i32(3000).u8(10).u8(0x15);
  body.i32(0).i32(0).i32(0).u8(60).u8(0);  // FOV-cropped: empty, reflectivity 60
  body.i32(-1).i32(0).i32(1).u8(255).u8(0x2A);
  return data_packet(1, 3, 200, 1000000000ull, body.b, crc);
}

}  // namespace

TEST_CASE("SDK2 CRCs: catalogue check values and bitwise agreement") {
  const std::string check = "123456789";
  const auto* p = reinterpret_cast<const std::uint8_t*>(check.data());
  CHECK(live::crc16_ccitt_false(p, 9) == 0x29B1);
  CHECK(live::crc32_iso_hdlc(p, 9) == 0xCBF43926u);
  CHECK(bitwise_crc16_ccitt_false(p, 9) == 0x29B1);
  CHECK(bitwise_crc32(p, 9) == 0xCBF43926u);
  CHECK(live::crc32_iso_hdlc(p, 0) == 0u);  // why an empty control payload's crc32 is 0
}

TEST_CASE("SDK2 type 1: int32 mm, tags, empty slots, slot times") {
  live::LivoxPacketContents out;
  out.returns.push_back({});  // decoders append
  const auto s = decode(three_cartesian_mm(), out);
  REQUIRE(s.status == live::LivoxPacketStatus::points);
  CHECK(s.data_type == 1);
  CHECK(s.has_counter);
  CHECK(s.counter == 7);
  CHECK(s.sync == live::LivoxTimeSync::none);
  CHECK(s.slots == 3);
  CHECK(s.returns == 2);
  CHECK(s.empty_slots == 1);
  CHECK(s.first_time_ns == 1000000000ull);
  CHECK(s.last_time_ns == 1000020000ull);  // time_interval 200 x 100 ns
  REQUIRE(out.returns.size() == 3);
  const live::LivoxReturn& a = out.returns[1];
  CHECK(a.x == 1.0f);
  CHECK(a.y == -2.0f);
  CHECK(a.z == 3.0f);
  CHECK(a.reflectivity == 10);
  CHECK(a.tag == 0x15);
  CHECK(a.time_ns == 1000000000ull);
  const live::LivoxReturn& b = out.returns[2];
  CHECK(b.x == -0.001f);
  CHECK(b.y == 0.0f);
  CHECK(b.z == 0.001f);
  CHECK(b.reflectivity == 255);
  CHECK(b.tag == 0x2A);
  CHECK(b.time_ns == 1000020000ull);  // slot 2 of 3: the whole interval
}

TEST_CASE("SDK2 type 2 is centimetres; type 3 spherical; 0x11 dual echo; IMU") {
  live::LivoxPacketContents out;
  SUBCASE("type 2: int16 cm") {
    ByteWriter body;
    body.i16(123).i16(-45).i16(7).u8(1).u8(2);
    body.i16(0).i16(0).i16(0).u8(0).u8(0);
    body.i16(-32768).i16(32767).i16(0).u8(3).u8(4);
    const auto s = decode(data_packet(2, 3, 0, 5, body.b, false, 1), out);
    REQUIRE(s.status == live::LivoxPacketStatus::points);
    CHECK(s.sync == live::LivoxTimeSync::ptp);
    CHECK(s.empty_slots == 1);
    REQUIRE(out.returns.size() == 2);
    CHECK(out.returns[0].x == 1.23f);
    CHECK(out.returns[0].y == -0.45f);
    CHECK(out.returns[0].z == 0.07f);
    CHECK(out.returns[0].tag == 2);
    CHECK(out.returns[1].x == -327.68f);
    CHECK(out.returns[1].y == 327.67f);
    CHECK(out.returns[0].time_ns == 5);  // time_interval 0: every slot at the timestamp
    CHECK(out.returns[1].time_ns == 5);
  }
  SUBCASE("type 3: depth mm, zenith theta and azimuth phi in 0.01 deg") {
    ByteWriter body;
    body.u32(10000).u16(9000).u16(0).u8(9).u8(0x01);      // horizon, straight ahead: (10, 0, 0)
    body.u32(2000).u16(4500).u16(9000).u8(9).u8(0x02);    // 45 deg up, azimuth 90: (0, 1.414, 1.414)
    body.u32(0).u16(4500).u16(100).u8(9).u8(0x03);        // depth 0: empty
    body.u32(5000).u16(0).u16(12345).u8(9).u8(0x04);      // zenith: (0, 0, 5)
    body.u32(3000).u16(18000).u16(27000).u8(9).u8(0x05);  // nadir: (0, 0, -3)
    const auto s = decode(data_packet(3, 5, 400, 0, body.b, false, 2), out);
    REQUIRE(s.status == live::LivoxPacketStatus::points);
    CHECK(s.sync == live::LivoxTimeSync::gps);
    CHECK(s.empty_slots == 1);
    REQUIRE(out.returns.size() == 4);
    const double h = std::sqrt(2.0);
    CHECK(out.returns[0].x == doctest::Approx(10.0).epsilon(1e-6));
    CHECK(std::abs(out.returns[0].y) < 1e-6);
    CHECK(std::abs(out.returns[0].z) < 1e-6);
    CHECK(std::abs(out.returns[1].x) < 1e-6);
    CHECK(out.returns[1].y == doctest::Approx(h).epsilon(1e-6));
    CHECK(out.returns[1].z == doctest::Approx(h).epsilon(1e-6));
    CHECK(out.returns[2].z == doctest::Approx(5.0).epsilon(1e-6));
    CHECK(out.returns[3].z == doctest::Approx(-3.0).epsilon(1e-6));
    CHECK(out.returns[1].tag == 0x02);
    CHECK(out.returns[2].time_ns == 30000);  // slot 3 of 5: 3/4 of 40 us
  }
  SUBCASE("0x11: two type-1 echoes per slot, sharing its time") {
    ByteWriter body;
    body.i32(1000).i32(0).i32(0).u8(1).u8(1).i32(1500).i32(0).i32(0).u8(2).u8(2);
    body.i32(0).i32(2000).i32(0).u8(3).u8(3).i32(0).i32(0).i32(0).u8(0).u8(0);  // second echo empty
    const auto s = decode(data_packet(0x11, 2, 50, 100, body.b), out);
    REQUIRE(s.status == live::LivoxPacketStatus::points);
    CHECK(s.slots == 4);
    CHECK(s.returns == 3);
    CHECK(s.empty_slots == 1);
    REQUIRE(out.returns.size() == 3);
    CHECK(out.returns[1].x == 1.5f);
    CHECK(out.returns[1].tag == 2);
    CHECK(out.returns[0].time_ns == 100);
    CHECK(out.returns[1].time_ns == 100);
    CHECK(out.returns[2].y == 2.0f);
    CHECK(out.returns[2].time_ns == 5100);
  }
  SUBCASE("IMU: gyro rad/s, acceleration g, with a CRC") {
    ByteWriter body;
    body.f32(0.5f).f32(-0.25f).f32(1e-3f).f32(0.01f).f32(-0.02f).f32(1.0f);
    const auto s = decode(data_packet(0, 1, 0, 123456789ull, body.b, true), out);
    REQUIRE(s.status == live::LivoxPacketStatus::imu);
    CHECK(out.returns.empty());
    CHECK(s.slots == 0);
    CHECK(out.imu.time_ns == 123456789ull);
    CHECK(out.imu.gyro[0] == 0.5f);
    CHECK(out.imu.gyro[1] == -0.25f);
    CHECK(out.imu.gyro[2] == 1e-3f);
    CHECK(out.imu.acceleration[0] == 0.01f);
    CHECK(out.imu.acceleration[1] == -0.02f);
    CHECK(out.imu.acceleration[2] == 1.0f);
  }
}

TEST_CASE("SDK2 slot times: equal spacing over time_interval, first to last") {
  // A Mid-360 packet: 96 points, time_interval 4750 (475 us): 5 us apart.
  ByteWriter body;
  for (int i = 0; i < 96; ++i) body.i32(1000 + i).i32(0).i32(0).u8(0).u8(0);
  live::LivoxPacketContents out;
  const std::uint64_t t0 = 1700000000000000000ull;
  REQUIRE(decode(data_packet(1, 96, 4750, t0, body.b), out).status == live::LivoxPacketStatus::points);
  REQUIRE(out.returns.size() == 96);
  for (std::size_t i = 0; i < 96; ++i) CHECK(out.returns[i].time_ns == t0 + 5000 * i);
  // Rounding to the nearest ns: 100 ns over 3 gaps.
  CHECK(live::sdk2_slot_time(0, 1, 4, 1) == 33);
  CHECK(live::sdk2_slot_time(0, 1, 4, 2) == 67);
  CHECK(live::sdk2_slot_time(0, 1, 4, 3) == 100);
  CHECK(live::sdk2_slot_time(9, 65535, 1, 0) == 9);  // one slot: the timestamp
}

TEST_CASE("SDK2 data-packet CRC: 0 is absent, a right one passes, a wrong one is bad_crc") {
  CHECK(status_of(three_cartesian_mm(false)) == live::LivoxPacketStatus::points);
  const Bytes with_crc = three_cartesian_mm(true);
  CHECK(status_of(with_crc) == live::LivoxPacketStatus::points);
  Bytes wrong = with_crc;
  wrong[24] ^= 0x01;
  CHECK(status_of(wrong) == live::LivoxPacketStatus::bad_crc);
  Bytes corrupted = with_crc;
  corrupted[40] ^= 0x80;  // a point byte under a present CRC
  CHECK(status_of(corrupted) == live::LivoxPacketStatus::bad_crc);
  corrupted[24] = corrupted[25] = corrupted[26] = corrupted[27] = 0;  // the same bytes without a CRC pass
  CHECK(status_of(corrupted) == live::LivoxPacketStatus::points);
}

TEST_CASE("SDK2 malformed data packets: each class has its status, nothing is appended") {
  using S = live::LivoxPacketStatus;
  const Bytes good = three_cartesian_mm(true);
  for (std::size_t n = 0; n < good.size(); ++n) {
    const Bytes prefix(good.begin(), good.begin() + static_cast<long>(n));
    CHECK(status_of(prefix) == S::truncated);
  }
  Bytes longer = good;
  longer.push_back(0);
  CHECK(status_of(longer) == S::bad_length);  // the datagram is longer than its length field
  Bytes version = good;
  version[0] = 1;
  CHECK(status_of(version) == S::bad_version);
  for (unsigned type : {4u, 5u, 0x10u, 0x12u, 0xFFu}) {
    Bytes t = good;
    t[10] = static_cast<std::uint8_t>(type);
    CHECK(status_of(t) == S::unknown_data_type);
  }
  const Bytes body14(14, 1), body28(28, 1), imu_body(24, 0);
  CHECK(status_of(data_packet(1, 2, 0, 0, body14)) == S::bad_length);     // dot_num says 2 slots, 1 present
  CHECK(status_of(data_packet(1, 0, 0, 0, {})) == S::bad_length);         // no slot
  CHECK(status_of(data_packet(2, 1, 0, 0, body14)) == S::bad_length);     // 14 bytes are not one type-2 slot
  CHECK(status_of(data_packet(0, 2, 0, 0, Bytes(48, 0))) == S::bad_length);  // IMU packets hold one sample
  CHECK(status_of(data_packet(1, 1, 0, 0, body14, false, 0, 0, 36)) == S::bad_length);  // length below the data
  const Bytes many(std::size_t{14} * (live::sdk2_max_dot_num + 1), 1);
  CHECK(status_of(data_packet(1, live::sdk2_max_dot_num + 1, 0, 0, many)) == S::bad_length);
  CHECK(status_of(data_packet(0x11, 1, 0, 0, body28)) == S::points);
  CHECK(status_of(data_packet(1, 1, 0, 0, body14, false, 3)) == S::bad_time);
  CHECK(status_of(data_packet(1, 1, 0, 0, body14, false, 0xFF)) == S::bad_time);
  CHECK(status_of(data_packet(0, 1, 0, 0, imu_body, false, 2)) == S::imu);
}

TEST_CASE("SDK2 point packets: encode -> decode within each type's quantisation") {
  std::mt19937 rng(20260);
  std::uniform_real_distribution<float> coord(-300.0f, 300.0f);
  std::uniform_int_distribution<int> byte(0, 255);
  struct Case {
    live::Sdk2DataType type;
    double per_axis;       // [m]
    double per_range;      // [m per m of range]
  };
  const Case cases[] = {{live::Sdk2DataType::cartesian_mm, 0.0005, 0},
                        {live::Sdk2DataType::dual_cartesian_mm, 0.0005, 0},
                        {live::Sdk2DataType::cartesian_cm, 0.005, 0},
                        {live::Sdk2DataType::spherical, 0.0005, 1.235e-4}};
  for (const Case& c : cases) {
    CAPTURE(static_cast<int>(c.type));
    std::vector<live::LivoxReturn> in(96);
    for (auto& r : in) {
      r.x = coord(rng);
      r.y = coord(rng);
      r.z = coord(rng) / 10.0f;
      r.reflectivity = static_cast<std::uint8_t>(byte(rng));
      r.tag = static_cast<std::uint8_t>(byte(rng));
    }
    in[5] = live::LivoxReturn{};  // an empty slot
    in[5].reflectivity = 60;
    live::Sdk2PacketFields f;
    f.udp_cnt = 65535;
    f.timestamp_ns = 42;
    f.time_interval = 4750;
    f.time_sync = live::LivoxTimeSync::ptp;
    f.fill_crc = c.type == live::Sdk2DataType::spherical;
    Bytes packet;
    live::encode_sdk2_point_packet(f, c.type, in.data(), in.size(), packet);
    live::LivoxPacketContents out;
    const auto s = decode(packet, out);
    REQUIRE(s.status == live::LivoxPacketStatus::points);
    CHECK(s.counter == 65535);
    CHECK(s.sync == live::LivoxTimeSync::ptp);
    CHECK(s.empty_slots == 1);
    REQUIRE(out.returns.size() == 95);
    const bool dual = c.type == live::Sdk2DataType::dual_cartesian_mm;
    const auto dot_num = static_cast<std::uint16_t>(dual ? 48 : 96);
    std::size_t j = 0;
    for (std::size_t i = 0; i < in.size(); ++i) {
      if (i == 5) continue;
      const live::LivoxReturn& a = in[i];
      const live::LivoxReturn& b = out.returns[j++];
      const double range = std::sqrt(double{a.x} * a.x + double{a.y} * a.y + double{a.z} * a.z);
      const double slack = 1e-4 * 0.001 + range * 6e-8;  // half a float ulp of the decoded value
      const double dx = b.x - double{a.x}, dy = b.y - double{a.y}, dz = b.z - double{a.z};
      if (c.per_range == 0) {
        CHECK(std::abs(dx) <= c.per_axis + slack);
        CHECK(std::abs(dy) <= c.per_axis + slack);
        CHECK(std::abs(dz) <= c.per_axis + slack);
      } else {
        CHECK(std::sqrt(dx * dx + dy * dy + dz * dz) <= c.per_axis + c.per_range * range + slack);
      }
      CHECK(b.reflectivity == a.reflectivity);
      CHECK(b.tag == a.tag);
      CHECK(b.time_ns == live::sdk2_slot_time(42, 4750, dot_num, static_cast<std::uint32_t>(dual ? i / 2 : i)));
    }
  }
  // Quantisation is rounding to nearest, not truncation.
  live::LivoxReturn r{0.0149f, -0.0151f, 0.0004f, 0, 0, 0};
  Bytes packet;
  live::encode_sdk2_point_packet({}, live::Sdk2DataType::cartesian_cm, &r, 1, packet);
  live::LivoxPacketContents out;
  REQUIRE(decode(packet, out).status == live::LivoxPacketStatus::points);
  CHECK(out.returns[0].x == 0.01f);
  CHECK(out.returns[0].y == -0.02f);
  CHECK(out.returns[0].z == 0.0f);
}

TEST_CASE("SDK2 encoders: bytes of a known packet, IMU round trip, refused inputs") {
  live::LivoxReturn r{1.0f, -2.0f, 3.0f, 10, 0x15, 0};
  live::Sdk2PacketFields f;
  f.udp_cnt = 7;
  f.timestamp_ns = 1000000000ull;
  f.time_interval = 200;
  Bytes packet;
  const live::LivoxReturn three[] = {r, {0, 0, 0, 60, 0, 0}, {-0.001f, 0, 0.001f, 255, 0x2A, 0}};
  live::encode_sdk2_point_packet(f, live::Sdk2DataType::cartesian_mm, three, 3, packet);
  CHECK(packet == three_cartesian_mm(false));
  f.fill_crc = true;
  live::encode_sdk2_point_packet(f, live::Sdk2DataType::cartesian_mm, three, 3, packet);
  CHECK(packet == three_cartesian_mm(true));

  live::LivoxImuSample imu;
  imu.gyro = {0.1f, -0.2f, 0.3f};
  imu.acceleration = {0.0f, 0.05f, -0.98f};
  f.time_sync = live::LivoxTimeSync::gps;
  live::encode_sdk2_imu_packet(f, imu, packet);
  CHECK(packet.size() == 60);
  live::LivoxPacketContents out;
  const auto s = decode(packet, out);
  REQUIRE(s.status == live::LivoxPacketStatus::imu);
  CHECK(s.sync == live::LivoxTimeSync::gps);
  CHECK(out.imu.time_ns == 1000000000ull);
  CHECK(out.imu.gyro == imu.gyro);
  CHECK(out.imu.acceleration == imu.acceleration);

  const live::LivoxReturn far{400.0f, 0, 0, 0, 0, 0}, nan{std::nanf(""), 0, 0, 0, 0, 0};
  CHECK_THROWS_AS(live::encode_sdk2_point_packet({}, live::Sdk2DataType::cartesian_cm, &far, 1, packet),
                  std::invalid_argument);
  CHECK_THROWS_AS(live::encode_sdk2_point_packet({}, live::Sdk2DataType::cartesian_mm, &nan, 1, packet),
                  std::invalid_argument);
  CHECK_THROWS_AS(live::encode_sdk2_point_packet({}, live::Sdk2DataType::dual_cartesian_mm, three, 3, packet),
                  std::invalid_argument);
  CHECK_THROWS_AS(live::encode_sdk2_point_packet({}, live::Sdk2DataType::imu, three, 3, packet),
                  std::invalid_argument);
  CHECK_THROWS_AS(live::encode_sdk2_point_packet({}, live::Sdk2DataType::cartesian_mm, three, 0, packet),
                  std::invalid_argument);
  live::Sdk2PacketFields pps;
  pps.time_sync = live::LivoxTimeSync::pps;
  CHECK_THROWS_AS(live::encode_sdk2_imu_packet(pps, imu, packet), std::invalid_argument);
}

TEST_CASE("SDK2 control frames: a discovery request byte by byte, every status") {
  Bytes frame;
  live::encode_sdk2_discovery_request(0x01020304u, frame);
  ByteWriter expected;
  expected.u8(0xAA).u8(0).u16(24).u32(0x01020304u).u16(0).u8(0).u8(0);
  for (int i = 0; i < 6; ++i) expected.u8(0);
  expected.u16(bitwise_crc16_ccitt_false(expected.b.data(), 18)).u32(0);
  CHECK(frame == expected.b);

  using S = live::Sdk2ControlStatus;
  live::Sdk2ControlFrame f;
  REQUIRE(live::decode_sdk2_control(frame.data(), frame.size(), f) == S::ok);
  CHECK(f.seq == 0x01020304u);
  CHECK(f.cmd_id == live::sdk2_cmd_discovery);
  CHECK(f.cmd_type == live::Sdk2CommandType::request);
  CHECK(f.sender == live::Sdk2Sender::host);
  CHECK(f.data_size == 0);

  // A frame with data, to reach every check.
  const std::uint8_t payload[] = {1, 2, 3, 4, 5};
  Bytes good;
  live::encode_sdk2_control({9, 0x0101, live::Sdk2CommandType::ack, live::Sdk2Sender::lidar, payload, 5}, good);
  REQUIRE(live::decode_sdk2_control(good.data(), good.size(), f) == S::ok);
  CHECK(f.data_size == 5);
  CHECK(std::memcmp(f.data, payload, 5) == 0);
  const std::uint32_t crc32_field = good[20] | good[21] << 8 | good[22] << 16 | std::uint32_t{good[23]} << 24;
  CHECK(bitwise_crc32(good.data() + 24, 5) == crc32_field);
  const auto status = [](const Bytes& b) {
    live::Sdk2ControlFrame g;
    return live::decode_sdk2_control(b.data(), b.size(), g);
  };
  /// `b` with its header CRC made right again after an edit.
  const auto resealed = [](Bytes b) {
    const std::uint16_t c = bitwise_crc16_ccitt_false(b.data(), 18);
    b[18] = static_cast<std::uint8_t>(c & 0xFF);
    b[19] = static_cast<std::uint8_t>(c >> 8);
    return b;
  };
  for (std::size_t n = 0; n < good.size(); ++n)
    CHECK(status(Bytes(good.begin(), good.begin() + static_cast<long>(n))) == S::truncated);
  Bytes b = good;
  b[0] = 0xAB;
  CHECK(status(b) == S::bad_sof);
  b = good;
  b[1] = 1;
  CHECK(status(b) == S::bad_version);
  b = good;
  b[5] ^= 1;  // seq changed, CRC not
  CHECK(status(b) == S::bad_header_crc);
  b = good;
  b[2] = 23;
  CHECK(status(resealed(b)) == S::bad_length);
  b = good;
  b[2] = 0x79;  // 1401
  b[3] = 0x05;
  CHECK(status(resealed(b)) == S::bad_length);
  b = good;
  b.push_back(0);
  CHECK(status(b) == S::bad_length);  // datagram longer than the frame
  b = good;
  b[10] = 2;
  CHECK(status(resealed(b)) == S::bad_type);
  b = good;
  b[11] = 7;
  CHECK(status(resealed(b)) == S::bad_type);
  b = good;
  b[26] ^= 0x10;
  CHECK(status(b) == S::bad_data_crc);
  b = frame;
  b[20] = 1;  // an empty payload must carry crc32 0
  CHECK(status(b) == S::bad_data_crc);
  CHECK_THROWS_AS(live::encode_sdk2_control({0, 0, {}, {}, payload, 1377}, b), std::invalid_argument);
  CHECK(std::string(live::describe(S::bad_header_crc)) == "bad header CRC");
}

TEST_CASE("SDK2 discovery ACK, set parameters and its ACK, status push") {
  Bytes frame;
  live::Sdk2ControlFrame f;
  live::Sdk2DiscoveryAck ack;
  ack.dev_type = live::sdk2_device_mid360;
  const std::string serial = "47MDL9A0020123";
  std::memcpy(ack.serial.data(), serial.data(), serial.size());
  ack.lidar_ip = {192, 168, 1, 123};
  ack.cmd_port = live::sdk2_mid360_ports.lidar_command;
  live::encode_sdk2_discovery_ack(77, ack, frame);
  REQUIRE(frame.size() == 48);
  CHECK(frame[24] == 0);        // ret_code
  CHECK(frame[25] == 9);        // dev_type
  CHECK(frame[26] == '4');      // serial
  CHECK(frame[42] == 192);      // lidar_ip
  CHECK(frame[46] == 0x24);     // 56100 = 0xDB24, little-endian
  CHECK(frame[47] == 0xDB);
  REQUIRE(live::decode_sdk2_control(frame.data(), frame.size(), f) == live::Sdk2ControlStatus::ok);
  CHECK(f.seq == 77);
  CHECK(f.sender == live::Sdk2Sender::lidar);
  live::Sdk2DiscoveryAck back;
  REQUIRE(live::parse_sdk2_discovery_ack(f, back));
  CHECK(live::sdk2_serial(back) == serial);
  CHECK(back.lidar_ip == ack.lidar_ip);
  CHECK(back.cmd_port == 56100);
  CHECK(std::string(live::sdk2_device_name(back.dev_type)) == "Mid-360");
  CHECK(live::sdk2_device_name(8) == nullptr);
  live::Sdk2SetParametersAck not_this;
  CHECK_FALSE(live::parse_sdk2_set_parameters_ack(f, not_this));

  // The configure-mode request: three destinations, work mode, data type, IMU on.
  live::Sdk2ParameterList list;
  list.add_destination(live::sdk2_key_push_destination, {{192, 168, 1, 50}, 56201, 56200});
  list.add_destination(live::sdk2_key_point_destination, {{192, 168, 1, 50}, 56301, 56300});
  list.add_destination(live::sdk2_key_imu_destination, {{192, 168, 1, 50}, 56401, 56400});
  list.add_work_mode(live::Sdk2WorkMode::sampling);
  list.add_u8(live::sdk2_key_point_data_type, 1);
  list.add_u8(live::sdk2_key_imu_enabled, 1);
  CHECK(list.count() == 6);
  live::encode_sdk2_set_parameters(5, list, frame);
  REQUIRE(frame.size() == 24 + 4 + 3 * 12 + 3 * 5);
  ByteWriter head;  // key_num, reserved, key 0x0005, length 8, 192.168.1.50, 56201, 56200
  head.u16(6).u16(0).u16(5).u16(8).u8(192).u8(168).u8(1).u8(50).u16(56201).u16(56200);
  CHECK(Bytes(frame.begin() + 24, frame.begin() + 40) == head.b);
  REQUIRE(live::decode_sdk2_control(frame.data(), frame.size(), f) == live::Sdk2ControlStatus::ok);
  CHECK(f.cmd_id == 0x0100);
  std::vector<live::Sdk2KeyValue> pairs;
  REQUIRE(live::parse_sdk2_parameters(f.data, f.data_size, pairs) == live::Sdk2ParameterStatus::ok);
  REQUIRE(pairs.size() == 6);
  live::Sdk2HostIpInfo dest;
  CHECK(pairs[1].key == live::sdk2_key_point_destination);
  REQUIRE(live::parse_sdk2_destination(pairs[1], dest));
  CHECK(dest.host_ip == std::array<std::uint8_t, 4>{192, 168, 1, 50});
  CHECK(dest.host_port == 56301);
  CHECK(dest.lidar_port == 56300);
  std::uint8_t mode = 0;
  CHECK(pairs[3].key == 0x001A);
  REQUIRE(live::parse_sdk2_u8(pairs[3], mode));
  CHECK(mode == 0x01);
  CHECK_FALSE(live::parse_sdk2_destination(pairs[3], dest));
  CHECK_FALSE(live::parse_sdk2_u8(pairs[0], mode));

  live::encode_sdk2_set_parameters_ack(5, {live::sdk2_ret_unsupported_parameter, 0x001C}, frame);
  CHECK(Bytes(frame.begin() + 24, frame.end()) == Bytes{0x20, 0x1C, 0x00});
  REQUIRE(live::decode_sdk2_control(frame.data(), frame.size(), f) == live::Sdk2ControlStatus::ok);
  live::Sdk2SetParametersAck set_ack;
  REQUIRE(live::parse_sdk2_set_parameters_ack(f, set_ack));
  CHECK(set_ack.ret_code == 0x20);
  CHECK(set_ack.error_key == 0x001C);
  CHECK_FALSE(live::parse_sdk2_discovery_ack(f, back));
  CHECK_FALSE(live::is_sdk2_status_push(f));

  const std::uint8_t push[] = {'{', '}'};
  live::encode_sdk2_control({1, 0x0102, live::Sdk2CommandType::request, live::Sdk2Sender::lidar, push, 2}, frame);
  REQUIRE(live::decode_sdk2_control(frame.data(), frame.size(), f) == live::Sdk2ControlStatus::ok);
  CHECK(live::is_sdk2_status_push(f));
}

TEST_CASE("SDK2 key-value parser: bounded, rejects overruns and trailing bytes") {
  using P = live::Sdk2ParameterStatus;
  std::vector<live::Sdk2KeyValue> pairs;
  const auto parse = [&](const Bytes& b) { return live::parse_sdk2_parameters(b.data(), b.size(), pairs); };
  CHECK(parse({}) == P::truncated);
  CHECK(parse({0, 0, 0}) == P::truncated);
  CHECK(parse({0, 0, 0, 0}) == P::ok);
  CHECK(pairs.empty());
  ByteWriter one;
  one.u16(1).u16(0).u16(0x1A).u16(1).u8(1);
  CHECK(parse(one.b) == P::ok);
  REQUIRE(pairs.size() == 1);
  CHECK(pairs[0].size == 1);
  CHECK(pairs[0].key == 0x1A);
  CHECK(pairs[0].value[0] == 1);
  Bytes cut = one.b;
  cut.pop_back();  // the value runs past the end
  CHECK(parse(cut) == P::overrun);
  CHECK(pairs.empty());
  cut.resize(6);  // a pair header cut short
  CHECK(parse(cut) == P::overrun);
  ByteWriter huge;  // a value length of 65535 in a short payload
  huge.u16(1).u16(0).u16(6).u16(0xFFFF).u32(0);
  CHECK(parse(huge.b) == P::overrun);
  ByteWriter two_declared;  // key_num 2, one pair present
  two_declared.u16(2).u16(0).u16(0x1A).u16(1).u8(1);
  CHECK(parse(two_declared.b) == P::overrun);
  Bytes trailing = one.b;
  trailing.push_back(0);
  CHECK(parse(trailing) == P::trailing_bytes);
  ByteWriter too_many;
  too_many.u16(live::sdk2_max_parameters + 1u).u16(0);
  CHECK(parse(too_many.b) == P::too_many);

  live::Sdk2ParameterList list;
  const Bytes value(1000, 0);
  list.add(0x0100, value.data(), 1000);
  CHECK_THROWS_AS(list.add(0x0101, value.data(), 400), std::invalid_argument);  // would pass 1376 bytes
  CHECK(list.count() == 1);
}

TEST_CASE("LivoxStream: a packet sent before a clock jump and reordered after it is late, not two more epochs") {
  live::LivoxPacketFormat format;
  format.decode = [](const std::uint8_t* d, std::size_t n, live::LivoxPacketContents& out) {
    return live::decode_sdk2_packet(d, n, out);
  };
  live::LivoxStream stream(format, live::LivoxStream::Options{8, 1'000'000'000});
  std::vector<live::LivoxReturn> returns;
  std::vector<live::LivoxImuSample> imu;
  std::vector<live::PacketArrival> arrivals;
  const std::int64_t host0 = 1'700'000'000'000'000'000;
  constexpr std::uint64_t hour_ns = 3'600'000'000'000;
  // Packet i (one return) leaves the device at device time 1 s + i x 0.5 ms
  // and arrives i x 0.5 ms after host0; from packet 20 on the clock is an hour ahead.
  auto send = [&](int i, int arrives_as) {
    const live::LivoxReturn r{1.0f, 2.0f, static_cast<float>(i), 10, 0, 0};
    live::Sdk2PacketFields f;
    f.udp_cnt = static_cast<std::uint16_t>(i);
    f.timestamp_ns = 1'000'000'000 + static_cast<std::uint64_t>(i) * 500'000 + (i >= 20 ? hour_ns : 0);
    Bytes bytes;
    live::encode_sdk2_point_packet(f, live::Sdk2DataType::cartesian_mm, &r, 1, bytes);
    live::Datagram d;
    std::copy(bytes.begin(), bytes.end(), d.bytes.begin());
    d.size = static_cast<std::uint16_t>(bytes.size());
    d.arrival_ns = host0 + arrives_as * 500'000;
    stream.consume(d, returns, imu, arrivals);
  };
  for (int i = 0; i < 19; ++i) send(i, i);
  send(20, 19);  // the first packet after the jump overtakes the last one before it
  send(19, 20);
  for (int i = 21; i < 40; ++i) send(i, i);
  stream.flush(returns, arrivals);
  CHECK(stream.counters().epochs == 2);
  CHECK(stream.order().late == 1);  // packet 19: its epoch was flushed when packet 20 began the next
  CHECK(stream.order().lost == 0);
  REQUIRE(returns.size() == 39);
  for (std::size_t k = 1; k < returns.size(); ++k) CHECK(returns[k].time_ns > returns[k - 1].time_ns);
  CHECK(returns[19].z == 20.0f);
}
