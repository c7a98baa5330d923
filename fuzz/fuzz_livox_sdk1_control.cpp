// SPDX-License-Identifier: MIT
// Fuzz target: the Livox SDK1 control frame decoder (live::decode_sdk1_frame)
// and the message readers on one datagram.
//
// A bug, besides a crash, undefined behaviour or a read outside the datagram:
// - a frame accepted that does not encode back to the same bytes
//   (encode_sdk1_frame of its type, seq, command and data);
// - a frame accepted after one of its bytes changed (the CRC-16 covers the
//   9-byte preamble, the CRC-32 the rest: every change of one byte fails);
// - a status that disagrees with the datagram (too short, sof, version);
// - a message read by a reader that the matching encoder does not write
//   back to the same message (broadcast, handshake, heartbeat ACK, ACK,
//   one-byte request).
// Inputs that start like a frame but fail a CRC are also checked with their
// CRCs made right, so that mutations reach the length checks and readers.

#include "support/expect.hpp"

#include <streamclust/live/sdk1_control.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace {

namespace live = streamclust::live;
using streamclust::fuzz::require;

/// Decodes `bytes`, which must be one frame.
live::Sdk1Frame decode_again(const std::vector<std::uint8_t>& bytes) {
  live::Sdk1Frame f;
  require(live::decode_sdk1_frame(bytes.data(), bytes.size(), f) == live::Sdk1FrameStatus::ok,
          "an encoded frame decodes");
  return f;
}

/// Every reader that accepts `f`, through its encoder and back.
void check_messages(const live::Sdk1Frame& f) {
  std::vector<std::uint8_t> bytes;
  live::Sdk1Broadcast broadcast, broadcast2;
  if (live::parse_sdk1_broadcast(f, broadcast)) {
    live::encode_sdk1_broadcast(f.seq, broadcast, bytes);
    require(live::parse_sdk1_broadcast(decode_again(bytes), broadcast2) &&
                broadcast.broadcast_code == broadcast2.broadcast_code &&
                broadcast.device_type == broadcast2.device_type,
            "a broadcast round trips");
  }
  live::Sdk1Handshake handshake, handshake2;
  if (live::parse_sdk1_handshake(f, handshake)) {
    live::encode_sdk1_handshake(f.seq, handshake, bytes, f.packet_type);
    require(live::parse_sdk1_handshake(decode_again(bytes), handshake2) && handshake.host_ip == handshake2.host_ip &&
                handshake.data_port == handshake2.data_port && handshake.command_port == handshake2.command_port &&
                handshake.sensor_port == handshake2.sensor_port,
            "a handshake round trips");
  }
  live::Sdk1HeartbeatAck heartbeat, heartbeat2;
  if (live::parse_sdk1_heartbeat_ack(f, heartbeat)) {
    live::encode_sdk1_heartbeat_ack(f.seq, heartbeat, bytes);
    require(live::parse_sdk1_heartbeat_ack(decode_again(bytes), heartbeat2) &&
                heartbeat.ret_code == heartbeat2.ret_code && heartbeat.state == heartbeat2.state &&
                heartbeat.feature == heartbeat2.feature && heartbeat.status == heartbeat2.status,
            "a heartbeat ACK round trips");
  }
  std::uint8_t value = 0, value2 = 0;
  if (live::parse_sdk1_ack(f, f.command, value)) {
    live::encode_sdk1_ack(f.seq, f.command, value, bytes);
    require(live::parse_sdk1_ack(decode_again(bytes), f.command, value2) && value == value2, "an ACK round trips");
  }
  if (live::parse_sdk1_request(f, f.command, value)) {
    live::encode_sdk1_request(f.seq, f.command, value, bytes);
    require(live::parse_sdk1_request(decode_again(bytes), f.command, value2) && value == value2,
            "a one-byte request round trips");
  }
}

/// The properties of a frame that decodes: its bytes again, one byte changed, its messages.
void check_frame(const std::uint8_t* data, std::size_t size, const live::Sdk1Frame& f) {
  require(size >= live::sdk1_frame_overhead_bytes && f.data == data + 11 &&
              f.data_size == size - live::sdk1_frame_overhead_bytes,
          "a frame's data lies between its head and its CRC");
  std::vector<std::uint8_t> bytes;
  live::encode_sdk1_frame(f.packet_type, f.seq, f.command, f.data, f.data_size, bytes);
  require(bytes.size() == size && std::memcmp(bytes.data(), data, size) == 0, "a frame encodes byte for byte");
  check_messages(f);

  // One byte changed, at a place and by a value the frame itself chooses.
  const std::size_t at = f.seq % size;
  bytes[at] = static_cast<std::uint8_t>(bytes[at] ^ ((f.seq >> 8) | 1u));
  live::Sdk1Frame g;
  require(live::decode_sdk1_frame(bytes.data(), bytes.size(), g) != live::Sdk1FrameStatus::ok,
          "a frame with one byte changed is refused");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  live::Sdk1Frame f;
  const live::Sdk1FrameStatus status = live::decode_sdk1_frame(data, size, f);
  if (status == live::Sdk1FrameStatus::ok) {
    check_frame(data, size, f);
    return 0;
  }
  if (size < 9) {
    require(status == live::Sdk1FrameStatus::truncated, "a datagram without a preamble is truncated");
    return 0;
  }
  if (data[0] != 0xAA) require(status == live::Sdk1FrameStatus::bad_sof, "the first check is the sof");
  else if (data[1] != 1) require(status == live::Sdk1FrameStatus::bad_version, "the second check is the version");
  // Mutations rarely keep both CRCs right: the same bytes with the CRCs made
  // right reach the length checks and the message readers.
  std::vector<std::uint8_t> sealed(data, data + size);
  sealed[0] = 0xAA;
  sealed[1] = 1;
  const std::uint16_t crc16 = live::crc16_livox_sdk1(sealed.data(), 7);
  sealed[7] = static_cast<std::uint8_t>(crc16);
  sealed[8] = static_cast<std::uint8_t>(crc16 >> 8);
  if (size >= live::sdk1_frame_overhead_bytes && size == (data[2] | std::size_t{data[3]} << 8)) {
    const std::uint32_t crc32 = live::crc32_livox_sdk1(sealed.data(), size - 4);
    for (int k = 0; k < 4; ++k) sealed[size - 4 + k] = static_cast<std::uint8_t>(crc32 >> (8 * k));
  }
  if (live::decode_sdk1_frame(sealed.data(), size, f) == live::Sdk1FrameStatus::ok) check_frame(sealed.data(), size, f);
  return 0;
}
