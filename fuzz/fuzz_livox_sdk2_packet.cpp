// SPDX-License-Identifier: MIT
// Fuzz target: one Livox SDK2 data datagram (live/sdk2_packets.hpp), decoded
// by decode_sdk2_packet, then encoded again and decoded once more.
//
// A bug, besides a crash, undefined behaviour, a leak or an exception: a
// decode that breaks its promises (anything appended for a status other than
// `points`; returns + empty slots not the packet's slots; a return that is
// not finite or whose time is outside [first, last] or earlier than the one
// before); and a round trip that changes what it should keep. The decoded
// returns and sample, encoded with the packet's header fields and decoded
// again, give the same counter, sync, first time, reflectivity and tag, the
// slot times of the new packet, and coordinates within the type's
// quantisation (types 1, 2 and 0x11: exactly the same floats below 8192 m,
// where a float still resolves a millimetre; type 3: 0.5 mm + 1.235e-4 x
// range). An IMU packet, and a Cartesian packet without empty slots, encode
// back to the input's bytes (frame_cnt and reserved bytes aside). Returns
// beyond 1e5 m (only reachable with absurd integers) are not re-encoded.

#include "support/expect.hpp"

#include <streamclust/live/sdk2_packets.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace {

namespace live = streamclust::live;
using streamclust::fuzz::never_throws;
using streamclust::fuzz::require;

/// The input's bytes with frame_cnt and the reserved bytes zeroed (what the encoder writes).
std::vector<std::uint8_t> canonical(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> b(data, data + size);
  b[9] = 0;
  std::memset(b.data() + 12, 0, 12);
  return b;
}

void check_decode(const live::LivoxPacketSummary& s, const live::LivoxPacketContents& out) {
  if (s.status != live::LivoxPacketStatus::points) {
    require(out.returns.size() == 1, "nothing is appended unless the status is points");
    return;
  }
  require(out.returns.size() == 1 + s.returns, "returns counts the returns appended");
  require(s.returns + s.empty_slots == s.slots, "every slot is a return or empty");
  for (std::size_t i = 1; i < out.returns.size(); ++i) {
    const live::LivoxReturn& r = out.returns[i];
    require(std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.z), "returns are finite");
    require(!(r.x == 0 && r.y == 0 && r.z == 0), "an empty slot is never a return");
    if (s.first_time_ns <= s.last_time_ns) {
      require(r.time_ns >= s.first_time_ns && r.time_ns <= s.last_time_ns, "times lie within the packet's");
      require(i == 1 || r.time_ns >= out.returns[i - 1].time_ns, "times do not decrease");
    }
  }
}

void check_round_trip(const std::uint8_t* data, std::size_t size, const live::LivoxPacketSummary& s,
                      const live::LivoxPacketContents& out) {
  const live::Sdk2PacketHeader h = live::read_sdk2_header(data);
  live::Sdk2PacketFields fields;
  fields.udp_cnt = h.udp_cnt;
  fields.timestamp_ns = h.timestamp;
  fields.time_interval = h.time_interval;
  fields.time_sync = s.sync;
  fields.fill_crc = h.crc32 != 0;
  std::vector<std::uint8_t> packet;
  live::LivoxPacketContents again;
  if (s.status == live::LivoxPacketStatus::imu) {
    never_throws([&] { live::encode_sdk2_imu_packet(fields, out.imu, packet); });
    require(packet == canonical(data, size), "an IMU packet encodes back to its bytes");
    return;
  }
  std::vector<live::LivoxReturn> returns(out.returns.begin() + 1, out.returns.end());
  for (const auto& r : returns)
    if (!(std::abs(r.x) < 1e5f && std::abs(r.y) < 1e5f && std::abs(r.z) < 1e5f)) return;
  const auto type = static_cast<live::Sdk2DataType>(h.data_type);
  const bool dual = type == live::Sdk2DataType::dual_cartesian_mm;
  if (dual && returns.size() % 2 == 1) returns.push_back({});  // an empty echo completes the last slot
  if (returns.empty()) return;
  never_throws([&] { live::encode_sdk2_point_packet(fields, type, returns.data(), returns.size(), packet); });
  const live::LivoxPacketSummary t = live::decode_sdk2_packet(packet.data(), packet.size(), again);
  require(t.status == live::LivoxPacketStatus::points, "an encoded packet decodes");
  require(t.counter == s.counter && t.sync == s.sync && t.first_time_ns == s.first_time_ns,
          "the round trip keeps counter, sync and first time");
  require(t.returns == s.returns, "the round trip keeps every return");
  const auto dot_num = static_cast<std::uint16_t>(dual ? returns.size() / 2 : returns.size());
  for (std::size_t i = 0; i < t.returns; ++i) {
    const live::LivoxReturn& a = returns[i];
    const live::LivoxReturn& b = again.returns[i];
    require(a.reflectivity == b.reflectivity && a.tag == b.tag, "the round trip keeps reflectivity and tag");
    const auto slot = static_cast<std::uint32_t>(dual ? i / 2 : i);
    require(b.time_ns == live::sdk2_slot_time(h.timestamp, h.time_interval, dot_num, slot),
            "slot times follow the header");
    if (type == live::Sdk2DataType::spherical) {
      const double dx = double{b.x} - a.x, dy = double{b.y} - a.y, dz = double{b.z} - a.z;
      const double range = std::sqrt(double{a.x} * a.x + double{a.y} * a.y + double{a.z} * a.z);
      require(std::sqrt(dx * dx + dy * dy + dz * dz) <= 0.0005 + 1.235e-4 * range + 1e-7 * range + 1e-9,
              "spherical round trip within 0.5 mm + 1.235e-4 x range");
    } else if (std::abs(a.x) < 8192 && std::abs(a.y) < 8192 && std::abs(a.z) < 8192) {
      require(a.x == b.x && a.y == b.y && a.z == b.z, "Cartesian round trip gives the same floats");
    }
  }
  if (type != live::Sdk2DataType::spherical && s.empty_slots == 0) {
    bool small = true;
    for (const auto& r : returns) small = small && std::abs(r.x) < 8192 && std::abs(r.y) < 8192 && std::abs(r.z) < 8192;
    if (small) require(packet == canonical(data, size), "a Cartesian packet without empty slots encodes back");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The input in its own allocation, so that ASan sees any read past its end.
  const std::vector<std::uint8_t> bytes(data, data + size);
  live::LivoxPacketContents out;
  out.returns.push_back({});  // the decoder appends after what is there
  live::LivoxPacketSummary s;
  never_throws([&] { s = live::decode_sdk2_packet(bytes.data(), bytes.size(), out); });
  check_decode(s, out);
  if (s.status == live::LivoxPacketStatus::points || s.status == live::LivoxPacketStatus::imu)
    check_round_trip(bytes.data(), bytes.size(), s, out);
  return 0;
}
