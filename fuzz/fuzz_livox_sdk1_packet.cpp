// SPDX-License-Identifier: MIT
// Fuzz target: the Livox SDK1 data packet decoder (live::decode_sdk1_packet)
// on one datagram, then its encoder on what it decoded. The firing interval
// comes from the version byte (which the decoder does not check): 4,167,
// 10,000, 1 or 0 ns.
//
// A bug, besides a crash, undefined behaviour or a read outside the datagram:
// - a summary that breaks its promises: a status that disagrees with the
//   datagram's length and data type, returns + empty slots other than the
//   slots, returns other than those appended, times off the firing grid,
//   has_counter set, anything appended when the packet is refused;
// - a round trip that fails: the header and returns decoded, encoded again
//   (encode_sdk1_data_packet, encode_sdk1_imu_packet), must decode to the
//   same returns: the same count, times, reflectivity and tags, Cartesian
//   coordinates equal (within 16 km, where a float keeps the millimetre),
//   spherical ones within 0.5 mm in depth and 0.01 deg in angle; an IMU
//   packet must come back byte for byte. The encoder may refuse (with
//   std::invalid_argument) only coordinates beyond 100 km or a time grid
//   that wraps around 2^64 ns.

#include "support/expect.hpp"

#include <streamclust/live/sdk1_packets.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace {

namespace io = streamclust::io;
namespace live = streamclust::live;
using streamclust::fuzz::require;

/// Checks the summary of a refused datagram against its bytes.
void check_refusal(const std::uint8_t* data, std::size_t size, const live::LivoxPacketSummary& s) {
  if (size < live::sdk1_packet_header_bytes) {
    require(s.status == live::LivoxPacketStatus::truncated, "a datagram shorter than the header is truncated");
    return;
  }
  const io::LivoxDataType* type = io::find_sdk1_data_type(data[9]);
  if (!type) {
    require(s.status == live::LivoxPacketStatus::unknown_data_type, "data types above 8 are unknown");
    return;
  }
  const std::size_t expected = live::sdk1_packet_bytes(*type);
  if (size != expected) {
    require(s.status == (size < expected ? live::LivoxPacketStatus::truncated : live::LivoxPacketStatus::bad_length),
            "a datagram of another length than its type's is truncated or too long");
    return;
  }
  require(s.status == live::LivoxPacketStatus::bad_time, "a whole packet is refused only for its time");
}

/// Decodes `packet` again and compares with `first` (the returns of the first decoding).
void check_round_trip(const std::vector<std::uint8_t>& packet, std::uint32_t interval, const io::LivoxDataType& type,
                      const std::vector<live::LivoxReturn>& first) {
  live::LivoxPacketContents again;
  const auto s = live::decode_sdk1_packet(packet.data(), packet.size(), interval, again);
  require(s.status == live::LivoxPacketStatus::points, "an encoded packet decodes");
  require(again.returns.size() == first.size(), "an encoded packet holds the returns it was given");
  const bool spherical = type.coordinates == io::LivoxCoordinates::spherical_mm;
  for (std::size_t i = 0; i < first.size(); ++i) {
    const live::LivoxReturn& a = first[i];
    const live::LivoxReturn& b = again.returns[i];
    require(a.time_ns == b.time_ns && a.reflectivity == b.reflectivity && a.tag == b.tag,
            "times, reflectivity and tags survive a round trip");
    const double ax = a.x, ay = a.y, az = a.z;
    const double range = std::sqrt(ax * ax + ay * ay + az * az);
    const double error = std::max({std::abs(ax - b.x), std::abs(ay - b.y), std::abs(az - b.z)});
    if (spherical) {
      const double bound = 0.0005 + range * (0.01 * 3.14159265358979 / 180 + 1e-6);
      require(error <= bound, "spherical returns survive a round trip within 0.5 mm and 0.01 deg");
    } else if (std::max({std::abs(ax), std::abs(ay), std::abs(az)}) < 16000.0) {
      require(error == 0.0, "Cartesian returns within 16 km survive a round trip exactly");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr std::uint32_t intervals[] = {4167, 10000, 1, 0};
  const std::uint32_t interval = intervals[size > 0 ? data[0] % 4 : 0];
  live::LivoxPacketContents out;
  out.returns.push_back(live::LivoxReturn{1, 2, 3, 4, 5, 6});  // decoders append
  const auto s = live::decode_sdk1_packet(data, size, interval, out);
  require(!s.has_counter, "SDK1 packets have no counter");
  require(out.returns.front().time_ns == 6 && out.returns.front().x == 1.0f, "what `returns` held stays");
  if (s.status != live::LivoxPacketStatus::points && s.status != live::LivoxPacketStatus::imu) {
    require(out.returns.size() == 1, "a refused packet appends nothing");
    check_refusal(data, size, s);
    return 0;
  }
  live::Sdk1PacketHeader header;
  require(live::read_sdk1_packet_header(data, size, header), "a decoded packet has a header");
  const io::LivoxDataType& type = *io::find_sdk1_data_type(header.data_type);
  require(size == live::sdk1_packet_bytes(type), "a decoded packet has its type's length");

  if (s.status == live::LivoxPacketStatus::imu) {
    require(type.returns == 0 && out.returns.size() == 1, "IMU packets append no return");
    require(out.imu.time_ns == s.first_time_ns, "the IMU sample has the packet's time");
    std::vector<std::uint8_t> again;
    live::encode_sdk1_imu_packet(header, out.imu, again);
    require(again.size() == size && std::memcmp(again.data(), data, size) == 0, "an IMU packet encodes byte for byte");
    return 0;
  }

  const std::vector<live::LivoxReturn> returns(out.returns.begin() + 1, out.returns.end());
  require(s.returns == returns.size(), "summary.returns counts the returns appended");
  require(s.slots == std::uint32_t{type.structs_per_package} * type.returns, "slots = firings x returns");
  require(s.returns + s.empty_slots == s.slots, "every slot is a return or empty");
  require(s.last_time_ns - s.first_time_ns == (type.structs_per_package - 1u) * std::uint64_t{interval},
          "the last firing's time");
  bool small = true;
  for (std::size_t i = 0; i < returns.size(); ++i) {
    const live::LivoxReturn& r = returns[i];
    const std::uint64_t after = r.time_ns - s.first_time_ns;
    require(interval == 0 ? after == 0 : after % interval == 0 && after / interval < type.structs_per_package,
            "a return's time is one of the packet's firings");
    require(i == 0 || after >= returns[i - 1].time_ns - s.first_time_ns, "returns come in firing order");
    require(std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.z), "coordinates are finite");
    require(r.x != 0.0f || r.y != 0.0f || r.z != 0.0f, "no return at the origin");
    require(type.has_tag || r.tag == 0, "types without a tag give tag 0");
    small = small && std::max({std::abs(r.x), std::abs(r.y), std::abs(r.z)}) < 1e5f;
  }

  std::vector<std::uint8_t> packet;
  const bool grid_wraps = s.last_time_ns < s.first_time_ns;
  const bool encoded = streamclust::fuzz::only_throws<std::invalid_argument>(
      [&] { live::encode_sdk1_data_packet(header, interval, returns.data(), returns.size(), packet); });
  if (interval > 0 && small && !grid_wraps)
    require(encoded, "the encoder takes what the decoder gives within 100 km");
  if (!encoded) return 0;
  require(std::memcmp(packet.data(), data, live::sdk1_packet_header_bytes) == 0, "the header encodes byte for byte");
  check_round_trip(packet, interval, type, returns);
  return 0;
}
