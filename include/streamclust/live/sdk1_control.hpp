// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The control frames of the Livox SDK1 protocol (discovery broadcast,
/// handshake, heartbeat, sampling and the few settings a host needs), both
/// sides: what a host sends and a device answers, and what a device sends
/// and a host (or the emulator's device side) reads. Pure codecs of bytes,
/// no sockets. Little-endian, packed:
///
///     off size field
///       0   1  sof = 0xAA
///       1   1  version = 1
///       2   2  length of the whole frame = data bytes + 15
///       4   1  packet_type: 0 CMD, 1 ACK, 2 MSG
///       5   2  seq_num (an ACK echoes its command's)
///       7   2  crc16_livox_sdk1 of bytes [0, 7)
///       9   1  cmd_set: 0 general, 1 LiDAR, 2 Hub
///      10   1  cmd_id
///      11   n  data
///    11+n   4  crc32_livox_sdk1 of bytes [0, 11 + n)
///
/// Sources: `Livox-SDK/Livox-SDK:sdk_core/src/comm/sdk_protocol.h` and `.cpp`
/// (`SdkPacket`, `SdkPreamble`, `Pack`, `CheckPreamble`), `command_impl.h`
/// (command sets and ids), `sdk_core/include/livox_def.h` (payload structs
/// `BroadcastDeviceInfo`, `HandshakeRequest`, `HeartbeatResponse`, the return
/// modes, coordinate systems and IMU frequencies), `device_discovery.cpp`
/// (the handshake sent with packet type ACK).
///
/// Decoding never reads outside the datagram, never throws and never
/// allocates; a frame's `data` points into the datagram. All functions are
/// pure and thread-safe.

#include <streamclust/io/livox_packet.hpp>
#include <streamclust/live/livox_crc.hpp>
#include <streamclust/live/sdk1_packets.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::live {

/// Bytes of a frame around its data: the 11-byte head and the 4-byte CRC-32.
inline constexpr std::size_t sdk1_frame_overhead_bytes = 15;

/// A frame's packet_type.
enum class Sdk1PacketType : std::uint8_t { cmd = 0, ack = 1, msg = 2 };

/// A command: its set and id.
struct Sdk1Command {
  std::uint8_t set = 0;
  std::uint8_t id = 0;
};

constexpr bool operator==(Sdk1Command a, Sdk1Command b) noexcept { return a.set == b.set && a.id == b.id; }
constexpr bool operator!=(Sdk1Command a, Sdk1Command b) noexcept { return !(a == b); }

/// The commands a host uses while connected (payloads in the comments: CMD / ACK).
inline constexpr Sdk1Command sdk1_broadcast{0, 0x00};          ///< MSG from the device: Sdk1Broadcast
inline constexpr Sdk1Command sdk1_handshake{0, 0x01};          ///< Sdk1Handshake / u8 ret_code
inline constexpr Sdk1Command sdk1_heartbeat{0, 0x03};          ///< none / Sdk1HeartbeatAck
inline constexpr Sdk1Command sdk1_sampling{0, 0x04};           ///< u8 1 start, 0 stop / u8 ret_code
inline constexpr Sdk1Command sdk1_coordinate_system{0, 0x05};  ///< u8 Sdk1Coordinates / u8 ret_code
inline constexpr Sdk1Command sdk1_disconnect{0, 0x06};         ///< none / u8 ret_code
inline constexpr Sdk1Command sdk1_return_mode{1, 0x06};        ///< u8 Sdk1ReturnMode / u8 ret_code
inline constexpr Sdk1Command sdk1_imu_push_frequency{1, 0x08}; ///< u8 Sdk1ImuFrequency / u8 ret_code

/// The ret_code of a successful command.
inline constexpr std::uint8_t sdk1_success = 0;

/// Values of the return mode command (`PointCloudReturnMode`).
enum class Sdk1ReturnMode : std::uint8_t { first = 0, strongest = 1, dual = 2, triple = 3 };

/// Values of the coordinate system command (`CoordinateType`): the point
/// data types 0/2/4/7 (Cartesian) or 1/3/5/8 (spherical).
enum class Sdk1Coordinates : std::uint8_t { cartesian = 0, spherical = 1 };

/// Values of the IMU push frequency command (`ImuFreq`).
enum class Sdk1ImuFrequency : std::uint8_t { off = 0, hz200 = 1 };

/// The device's broadcast MSG (19 data bytes: code, type, u16 reserved).
/// The device's address is the datagram's source.
struct Sdk1Broadcast {
  std::array<char, 16> broadcast_code{};  ///< the serial number, NUL-padded
  std::uint8_t device_type = 0;           ///< see sdk1_device_name

  /// The broadcast code up to its first NUL (at most 16 characters).
  std::string code() const {
    std::size_t n = 0;
    while (n < broadcast_code.size() && broadcast_code[n] != '\0') ++n;
    return std::string(broadcast_code.data(), n);
  }
};

/// The host's handshake (10 data bytes): where the device is to send.
struct Sdk1Handshake {
  std::array<std::uint8_t, 4> host_ip{};  ///< in dotted order: {192, 168, 1, 50}
  std::uint16_t data_port = 0;
  std::uint16_t command_port = 0;
  std::uint16_t sensor_port = 0;          ///< IMU
};

/// The device's heartbeat ACK (7 data bytes).
struct Sdk1HeartbeatAck {
  std::uint8_t ret_code = 0;
  std::uint8_t state = 0;     ///< `LidarState`: 0 init, 1 normal, 2 power saving, 3 standby, 4 error
  std::uint8_t feature = 0;   ///< `LidarFeature`
  std::uint32_t status = 0;   ///< `ErrorMessage` bits
};

/// The name of SDK1 device type `value` ("Avia", "Mid-40", ...; Hub 0,
/// Mid-40 1, Tele-15 2, Horizon 3, Mid-70 6, Avia 7), or "unknown".
inline const char* sdk1_device_name(std::uint8_t value) noexcept {
  const io::LivoxDeviceType* type = io::find_sdk1_device_type(value);
  return type ? type->name : "unknown";
}

/// One decoded frame; `data` points into the datagram it came from.
struct Sdk1Frame {
  Sdk1PacketType packet_type = Sdk1PacketType::cmd;
  std::uint16_t seq = 0;
  Sdk1Command command;
  const std::uint8_t* data = nullptr;
  std::size_t data_size = 0;
};

/// What became of a datagram given to decode_sdk1_frame.
enum class Sdk1FrameStatus : std::uint8_t {
  ok,
  truncated,        ///< shorter than the preamble (9 bytes) or than its length field
  bad_sof,          ///< the first byte is not 0xAA
  bad_version,      ///< the version byte is not 1
  bad_header_crc,   ///< the CRC-16 of the preamble does not check
  bad_length,       ///< a length field below 15, or a datagram longer than it
  bad_crc,          ///< the CRC-32 of the frame does not check
  bad_packet_type,  ///< a packet type other than CMD, ACK, MSG
};

/// Short text for a status, e.g. "bad header CRC".
inline const char* describe(Sdk1FrameStatus status) noexcept {
  switch (status) {
    case Sdk1FrameStatus::ok: return "ok";
    case Sdk1FrameStatus::truncated: return "truncated";
    case Sdk1FrameStatus::bad_sof: return "bad start of frame";
    case Sdk1FrameStatus::bad_version: return "bad version";
    case Sdk1FrameStatus::bad_header_crc: return "bad header CRC";
    case Sdk1FrameStatus::bad_length: return "bad length";
    case Sdk1FrameStatus::bad_crc: return "bad CRC";
    case Sdk1FrameStatus::bad_packet_type: return "bad packet type";
  }
  return "unknown";
}

/// Decodes the datagram of `size` bytes at `data` into `frame` (written
/// only on `ok`). The checks, in order: preamble present, sof, version,
/// preamble CRC-16 (over the 9 bytes with the stored CRC it gives 0), length
/// field, datagram length, CRC-32, packet type. O(size); noexcept.
inline Sdk1FrameStatus decode_sdk1_frame(const std::uint8_t* data, std::size_t size, Sdk1Frame& frame) noexcept {
  using io::detail::load_le;
  if (size < 9) return Sdk1FrameStatus::truncated;
  if (data[0] != 0xAA) return Sdk1FrameStatus::bad_sof;
  if (data[1] != 1) return Sdk1FrameStatus::bad_version;
  if (crc16_livox_sdk1(data, 9) != 0) return Sdk1FrameStatus::bad_header_crc;
  const std::size_t length = load_le<std::uint16_t>(data + 2);
  if (length < sdk1_frame_overhead_bytes) return Sdk1FrameStatus::bad_length;
  if (size < length) return Sdk1FrameStatus::truncated;
  if (size > length) return Sdk1FrameStatus::bad_length;
  if (crc32_livox_sdk1(data, length - 4) != load_le<std::uint32_t>(data + length - 4)) return Sdk1FrameStatus::bad_crc;
  if (data[4] > 2) return Sdk1FrameStatus::bad_packet_type;
  frame.packet_type = static_cast<Sdk1PacketType>(data[4]);
  frame.seq = load_le<std::uint16_t>(data + 5);
  frame.command = Sdk1Command{data[9], data[10]};
  frame.data = data + 11;
  frame.data_size = length - sdk1_frame_overhead_bytes;
  return Sdk1FrameStatus::ok;
}

/// Writes into `out` (cleared; capacity kept) the frame of `packet_type`,
/// `seq` and `command` with the `size` data bytes at `data`. Throws
/// std::invalid_argument when the frame would not fit the u16 length
/// (more than 65,520 data bytes). O(size).
inline void encode_sdk1_frame(Sdk1PacketType packet_type, std::uint16_t seq, Sdk1Command command,
                              const std::uint8_t* data, std::size_t size, std::vector<std::uint8_t>& out) {
  if (size > 0xFFFFu - sdk1_frame_overhead_bytes)
    throw std::invalid_argument("SDK1 control frame: " + std::to_string(size) +
                                " data bytes do not fit its 16-bit length");
  const std::size_t length = size + sdk1_frame_overhead_bytes;
  out.assign(length, 0);
  std::uint8_t* p = out.data();
  p[0] = 0xAA;
  p[1] = 1;
  detail::store_le(p + 2, static_cast<std::uint16_t>(length));
  p[4] = static_cast<std::uint8_t>(packet_type);
  detail::store_le(p + 5, seq);
  detail::store_le(p + 7, crc16_livox_sdk1(p, 7));
  p[9] = command.set;
  p[10] = command.id;
  if (size > 0) std::memcpy(p + 11, data, size);
  detail::store_le(p + 11 + size, crc32_livox_sdk1(p, 11 + size));
}

/// A command without data (heartbeat, disconnect) from the host.
inline void encode_sdk1_request(std::uint16_t seq, Sdk1Command command, std::vector<std::uint8_t>& out) {
  encode_sdk1_frame(Sdk1PacketType::cmd, seq, command, nullptr, 0, out);
}

/// A command with one byte of data (sampling, coordinate system, return
/// mode, IMU push frequency) from the host.
inline void encode_sdk1_request(std::uint16_t seq, Sdk1Command command, std::uint8_t value,
                                std::vector<std::uint8_t>& out) {
  encode_sdk1_frame(Sdk1PacketType::cmd, seq, command, &value, 1, out);
}

/// The device's ACK of `command` with `ret_code` (sdk1_success or 1) only.
inline void encode_sdk1_ack(std::uint16_t seq, Sdk1Command command, std::uint8_t ret_code,
                            std::vector<std::uint8_t>& out) {
  encode_sdk1_frame(Sdk1PacketType::ack, seq, command, &ret_code, 1, out);
}

/// The device's broadcast MSG.
inline void encode_sdk1_broadcast(std::uint16_t seq, const Sdk1Broadcast& message, std::vector<std::uint8_t>& out) {
  std::uint8_t d[19] = {};
  std::memcpy(d, message.broadcast_code.data(), 16);
  d[16] = message.device_type;  // then u16 reserved, zero
  encode_sdk1_frame(Sdk1PacketType::msg, seq, sdk1_broadcast, d, sizeof d, out);
}

/// The host's handshake. The Livox SDK sends it with packet type ACK (the
/// default here, what devices are known to accept); decoders take both.
inline void encode_sdk1_handshake(std::uint16_t seq, const Sdk1Handshake& message, std::vector<std::uint8_t>& out,
                                  Sdk1PacketType packet_type = Sdk1PacketType::ack) {
  std::uint8_t d[10];
  std::memcpy(d, message.host_ip.data(), 4);
  detail::store_le(d + 4, message.data_port);
  detail::store_le(d + 6, message.command_port);
  detail::store_le(d + 8, message.sensor_port);
  encode_sdk1_frame(packet_type, seq, sdk1_handshake, d, sizeof d, out);
}

/// The device's ACK of a heartbeat.
inline void encode_sdk1_heartbeat_ack(std::uint16_t seq, const Sdk1HeartbeatAck& message,
                                      std::vector<std::uint8_t>& out) {
  std::uint8_t d[7] = {message.ret_code, message.state, message.feature};
  detail::store_le(d + 3, message.status);
  encode_sdk1_frame(Sdk1PacketType::ack, seq, sdk1_heartbeat, d, sizeof d, out);
}

// Readers of decoded frames: true when `frame` is that message with at least
// its data bytes (later firmware may append fields: extra bytes are ignored).

/// A broadcast MSG.
inline bool parse_sdk1_broadcast(const Sdk1Frame& frame, Sdk1Broadcast& message) noexcept {
  if (frame.packet_type != Sdk1PacketType::msg || frame.command != sdk1_broadcast || frame.data_size < 19)
    return false;
  std::memcpy(message.broadcast_code.data(), frame.data, 16);
  message.device_type = frame.data[16];
  return true;
}

/// A handshake, sent as CMD or (as the Livox SDK does) as ACK. The device
/// side reads it; a host never receives one (a device's handshake ACK has
/// one data byte).
inline bool parse_sdk1_handshake(const Sdk1Frame& frame, Sdk1Handshake& message) noexcept {
  using io::detail::load_le;
  if (frame.packet_type == Sdk1PacketType::msg || frame.command != sdk1_handshake || frame.data_size < 10)
    return false;
  std::memcpy(message.host_ip.data(), frame.data, 4);
  message.data_port = load_le<std::uint16_t>(frame.data + 4);
  message.command_port = load_le<std::uint16_t>(frame.data + 6);
  message.sensor_port = load_le<std::uint16_t>(frame.data + 8);
  return true;
}

/// A heartbeat ACK.
inline bool parse_sdk1_heartbeat_ack(const Sdk1Frame& frame, Sdk1HeartbeatAck& message) noexcept {
  if (frame.packet_type != Sdk1PacketType::ack || frame.command != sdk1_heartbeat || frame.data_size < 7)
    return false;
  message.ret_code = frame.data[0];
  message.state = frame.data[1];
  message.feature = frame.data[2];
  message.status = io::detail::load_le<std::uint32_t>(frame.data + 3);
  return true;
}

/// An ACK of `command`: its ret_code (the first data byte).
inline bool parse_sdk1_ack(const Sdk1Frame& frame, Sdk1Command command, std::uint8_t& ret_code) noexcept {
  if (frame.packet_type != Sdk1PacketType::ack || frame.command != command || frame.data_size < 1) return false;
  ret_code = frame.data[0];
  return true;
}

/// A CMD of `command` (any data: heartbeat, disconnect).
inline bool is_sdk1_request(const Sdk1Frame& frame, Sdk1Command command) noexcept {
  return frame.packet_type == Sdk1PacketType::cmd && frame.command == command;
}

/// A CMD of `command` with its one-byte value (sampling, coordinate system,
/// return mode, IMU push frequency).
inline bool parse_sdk1_request(const Sdk1Frame& frame, Sdk1Command command, std::uint8_t& value) noexcept {
  if (!is_sdk1_request(frame, command) || frame.data_size < 1) return false;
  value = frame.data[0];
  return true;
}

}  // namespace streamclust::live
