// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Livox SDK2 control frames as pure codecs: the 24-byte frame around every
/// command, and the messages a host and a device exchange to start a stream
/// (discovery, the parameter write 0x0100 and its ACK; the status push 0x0102
/// recognised). The host side encodes requests and parses ACKs; the device
/// side (the emulator) parses requests and encodes ACKs.
///
/// The frame (little-endian, packed; `SdkPacket` in
/// `Livox-SDK/Livox-SDK2:sdk_core/comm/sdk_protocol.h`, wiki "Command Format"):
///
/// | offset | bytes | field       | meaning |
/// |--------|-------|-------------|---------|
/// | 0      | 1     | sof         | 0xAA |
/// | 1      | 1     | version     | 0 |
/// | 2      | 2     | length      | the whole frame [bytes], at most 1400 |
/// | 4      | 4     | seq_num     | the ACK echoes the request's |
/// | 8      | 2     | cmd_id      | 0x0000 discovery, 0x0100 set parameters, ... |
/// | 10     | 1     | cmd_type    | 0 REQ, 1 ACK |
/// | 11     | 1     | sender_type | 0 host, 1 LiDAR |
/// | 12     | 6     | reserved    | zeros |
/// | 18     | 2     | crc16       | CRC-16/CCITT-FALSE of bytes [0, 18) |
/// | 20     | 4     | crc32       | CRC-32 of the data (0 for none: the CRC of no bytes) |
/// | 24     | n     | data        | |
///
/// Payloads (wiki "Command ID", key table; `define.h` `HostIpInfoValue`):
/// - discovery 0x0000: REQ empty; ACK u8 ret_code, u8 dev_type, u8 sn[16],
///   u8 lidar_ip[4], u16 cmd_port (24 bytes).
/// - set parameters 0x0100: REQ u16 key_num, u16 reserved, then key_num
///   {u16 key, u16 length, value[length]}; ACK u8 ret_code, u16 error_key.
/// - status push 0x0102: LiDAR to host, no ACK (its content is not decoded here).
///
/// Decoders never read outside their input, never throw and never allocate
/// (except `parse_sdk2_parameters`, into the caller's vector); encoders
/// throw std::invalid_argument for what cannot be encoded. All thread-safe.

#include <streamclust/live/livox_crc.hpp>
#include <streamclust/live/sdk2_device.hpp>
#include <streamclust/io/input_stream.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::live {

/// Size of the control frame header [bytes].
inline constexpr std::size_t sdk2_control_header_bytes = 24;

/// Command ids.
inline constexpr std::uint16_t sdk2_cmd_discovery = 0x0000;
inline constexpr std::uint16_t sdk2_cmd_set_parameters = 0x0100;
inline constexpr std::uint16_t sdk2_cmd_inquire_parameters = 0x0101;
inline constexpr std::uint16_t sdk2_cmd_status_push = 0x0102;
inline constexpr std::uint16_t sdk2_cmd_reboot = 0x0200;

/// Parameter keys of 0x0100 for streaming.
inline constexpr std::uint16_t sdk2_key_point_data_type = 0x0000;  ///< u8: 1, 2 or 3
inline constexpr std::uint16_t sdk2_key_push_destination = 0x0005;   ///< Sdk2HostIpInfo of the status push
inline constexpr std::uint16_t sdk2_key_point_destination = 0x0006;  ///< Sdk2HostIpInfo of the point packets
inline constexpr std::uint16_t sdk2_key_imu_destination = 0x0007;    ///< Sdk2HostIpInfo of the IMU packets
inline constexpr std::uint16_t sdk2_key_work_mode = 0x001A;          ///< u8 `Sdk2WorkMode`
inline constexpr std::uint16_t sdk2_key_imu_enabled = 0x001C;        ///< u8: 0 off, 1 on

/// Values of key 0x001A (work_tgt_mode).
enum class Sdk2WorkMode : std::uint8_t { sampling = 0x01, idle = 0x02, ready = 0x09 };

/// Return codes of ACKs.
inline constexpr std::uint8_t sdk2_ret_success = 0x00;
inline constexpr std::uint8_t sdk2_ret_unsupported_parameter = 0x20;
inline constexpr std::uint8_t sdk2_ret_needs_reboot = 0x21;

/// The cmd_type byte.
enum class Sdk2CommandType : std::uint8_t { request = 0, ack = 1 };
/// The sender_type byte.
enum class Sdk2Sender : std::uint8_t { host = 0, lidar = 1 };

/// One control frame; `data` points into the decoded datagram (or the
/// caller's payload when encoding).
struct Sdk2ControlFrame {
  std::uint32_t seq = 0;
  std::uint16_t cmd_id = 0;
  Sdk2CommandType cmd_type = Sdk2CommandType::request;
  Sdk2Sender sender = Sdk2Sender::host;
  const std::uint8_t* data = nullptr;
  std::size_t data_size = 0;
};

/// What `decode_sdk2_control` found.
enum class Sdk2ControlStatus : std::uint8_t {
  ok,
  truncated,       ///< shorter than 24 bytes, or than its length field
  bad_sof,         ///< first byte not 0xAA
  bad_version,     ///< version not 0
  bad_header_crc,  ///< crc16 is not the CRC of bytes [0, 18)
  bad_length,      ///< length below 24, above 1400, or below the datagram's size
  bad_type,        ///< cmd_type or sender_type not 0 or 1
  bad_data_crc,    ///< crc32 is not the CRC of the data
};

/// Short text for a status, e.g. "bad header CRC".
inline const char* describe(Sdk2ControlStatus status) noexcept {
  switch (status) {
    case Sdk2ControlStatus::ok: return "ok";
    case Sdk2ControlStatus::truncated: return "truncated";
    case Sdk2ControlStatus::bad_sof: return "bad start of frame";
    case Sdk2ControlStatus::bad_version: return "bad version";
    case Sdk2ControlStatus::bad_header_crc: return "bad header CRC";
    case Sdk2ControlStatus::bad_length: return "bad length";
    case Sdk2ControlStatus::bad_type: return "bad command or sender type";
    case Sdk2ControlStatus::bad_data_crc: return "bad data CRC";
  }
  return "unknown";
}

/// Decodes the datagram of `size` bytes at `bytes` into `frame` (its data
/// a view into `bytes`). Checks in order: size, sof, version, header CRC,
/// length, types, data CRC. `frame` is written only when the status is ok.
/// O(size).
inline Sdk2ControlStatus decode_sdk2_control(const std::uint8_t* bytes, std::size_t size,
                                             Sdk2ControlFrame& frame) noexcept {
  using io::detail::load_le;
  if (size < sdk2_control_header_bytes) return Sdk2ControlStatus::truncated;
  if (bytes[0] != 0xAA) return Sdk2ControlStatus::bad_sof;
  if (bytes[1] != 0) return Sdk2ControlStatus::bad_version;
  if (crc16_ccitt_false(bytes, 18) != load_le<std::uint16_t>(bytes + 18)) return Sdk2ControlStatus::bad_header_crc;
  const std::uint16_t length = load_le<std::uint16_t>(bytes + 2);
  if (length < sdk2_control_header_bytes || length > sdk2_max_control_bytes || length < size)
    return Sdk2ControlStatus::bad_length;
  if (length > size) return Sdk2ControlStatus::truncated;
  if (bytes[10] > 1 || bytes[11] > 1) return Sdk2ControlStatus::bad_type;
  const std::size_t data_size = length - sdk2_control_header_bytes;
  if (crc32_iso_hdlc(bytes + 24, data_size) != load_le<std::uint32_t>(bytes + 20))
    return Sdk2ControlStatus::bad_data_crc;
  frame.seq = load_le<std::uint32_t>(bytes + 4);
  frame.cmd_id = load_le<std::uint16_t>(bytes + 8);
  frame.cmd_type = static_cast<Sdk2CommandType>(bytes[10]);
  frame.sender = static_cast<Sdk2Sender>(bytes[11]);
  frame.data = bytes + 24;
  frame.data_size = data_size;
  return Sdk2ControlStatus::ok;
}

namespace detail {

template <class T>
void put_le(std::vector<std::uint8_t>& out, std::size_t at, T value) noexcept {
  std::memcpy(out.data() + at, &value, sizeof value);  // little-endian targets, as io's load_le
}

}  // namespace detail

/// Writes `frame` (with its `data_size` bytes of data) into `out` (contents
/// replaced, capacity kept), CRCs filled. Throws std::invalid_argument when
/// the frame would exceed 1400 bytes. O(data_size).
inline void encode_sdk2_control(const Sdk2ControlFrame& frame, std::vector<std::uint8_t>& out) {
  if (frame.data_size > sdk2_max_control_bytes - sdk2_control_header_bytes) {
    throw std::invalid_argument("SDK2 control frame: " + std::to_string(frame.data_size) +
                                " bytes of data (expected at most " +
                                std::to_string(sdk2_max_control_bytes - sdk2_control_header_bytes) + ")");
  }
  const auto length = static_cast<std::uint16_t>(sdk2_control_header_bytes + frame.data_size);
  out.assign(length, 0);
  out[0] = 0xAA;
  detail::put_le(out, 2, length);
  detail::put_le(out, 4, frame.seq);
  detail::put_le(out, 8, frame.cmd_id);
  out[10] = static_cast<std::uint8_t>(frame.cmd_type);
  out[11] = static_cast<std::uint8_t>(frame.sender);
  if (frame.data_size > 0) std::memcpy(out.data() + 24, frame.data, frame.data_size);
  detail::put_le(out, 18, crc16_ccitt_false(out.data(), 18));
  detail::put_le(out, 20, crc32_iso_hdlc(out.data() + 24, frame.data_size));
}

/// True for a frame of the status push 0x0102 (the LiDAR's periodic state).
inline bool is_sdk2_status_push(const Sdk2ControlFrame& frame) noexcept {
  return frame.cmd_id == sdk2_cmd_status_push && frame.sender == Sdk2Sender::lidar;
}

// ------------------------------------------------------------------ discovery

/// The discovery request: the host's empty 0x0000 REQ (broadcast to 56000).
inline void encode_sdk2_discovery_request(std::uint32_t seq, std::vector<std::uint8_t>& out) {
  encode_sdk2_control({seq, sdk2_cmd_discovery, Sdk2CommandType::request, Sdk2Sender::host, nullptr, 0}, out);
}

/// The device's answer to discovery (24 bytes of data).
struct Sdk2DiscoveryAck {
  std::uint8_t ret_code = sdk2_ret_success;
  std::uint8_t dev_type = 0;                ///< `sdk2_device_name`
  std::array<std::uint8_t, 16> serial{};    ///< ASCII, NUL-padded
  std::array<std::uint8_t, 4> lidar_ip{};   ///< a.b.c.d in this order
  std::uint16_t cmd_port = 0;               ///< the LiDAR's control port
};

inline constexpr std::size_t sdk2_discovery_ack_bytes = 24;

/// The serial number as text: the bytes up to the first NUL.
inline std::string sdk2_serial(const Sdk2DiscoveryAck& ack) {
  std::size_t n = 0;
  while (n < ack.serial.size() && ack.serial[n] != 0) ++n;
  return std::string(reinterpret_cast<const char*>(ack.serial.data()), n);
}

/// Writes the discovery ACK frame (sender LiDAR, `seq` of the request) into `out`.
inline void encode_sdk2_discovery_ack(std::uint32_t seq, const Sdk2DiscoveryAck& ack, std::vector<std::uint8_t>& out) {
  std::array<std::uint8_t, sdk2_discovery_ack_bytes> data{};
  data[0] = ack.ret_code;
  data[1] = ack.dev_type;
  std::memcpy(data.data() + 2, ack.serial.data(), 16);
  std::memcpy(data.data() + 18, ack.lidar_ip.data(), 4);
  std::memcpy(data.data() + 22, &ack.cmd_port, 2);
  encode_sdk2_control({seq, sdk2_cmd_discovery, Sdk2CommandType::ack, Sdk2Sender::lidar, data.data(), data.size()},
                      out);
}

/// Reads a discovery ACK from a decoded frame; false unless it is a 0x0000
/// ACK with exactly 24 bytes of data. O(1).
inline bool parse_sdk2_discovery_ack(const Sdk2ControlFrame& frame, Sdk2DiscoveryAck& ack) noexcept {
  if (frame.cmd_id != sdk2_cmd_discovery || frame.cmd_type != Sdk2CommandType::ack ||
      frame.data_size != sdk2_discovery_ack_bytes)
    return false;
  const std::uint8_t* d = frame.data;
  ack.ret_code = d[0];
  ack.dev_type = d[1];
  std::memcpy(ack.serial.data(), d + 2, 16);
  std::memcpy(ack.lidar_ip.data(), d + 18, 4);
  ack.cmd_port = io::detail::load_le<std::uint16_t>(d + 22);
  return true;
}

// ------------------------------------------------------------- set parameters

/// A destination of a stream (`HostIpInfoValue`, 8 bytes): where the LiDAR
/// sends, and from which of its ports.
struct Sdk2HostIpInfo {
  std::array<std::uint8_t, 4> host_ip{};  ///< a.b.c.d in this order
  std::uint16_t host_port = 0;
  std::uint16_t lidar_port = 0;
};

inline constexpr std::size_t sdk2_host_ip_info_bytes = 8;

/// One key-value pair of a 0x0100 request; `value` points into the frame.
struct Sdk2KeyValue {
  std::uint16_t key = 0;
  const std::uint8_t* value = nullptr;
  std::uint16_t size = 0;  ///< [bytes]
};

/// The most key-value pairs a request can carry: each costs at least 4
/// bytes, and a 1400-byte frame leaves 1376 for key_num, reserved and pairs.
inline constexpr std::uint16_t sdk2_max_parameters = (sdk2_max_control_bytes - sdk2_control_header_bytes - 4) / 4;

/// The payload of a 0x0100 request, built key by key: u16 key_num, u16
/// reserved, then the pairs in the order added. Not thread-safe.
class Sdk2ParameterList {
 public:
  Sdk2ParameterList() : bytes_(4, 0) {}

  /// Appends a pair; throws std::invalid_argument when the payload would no
  /// longer fit a control frame.
  void add(std::uint16_t key, const std::uint8_t* value, std::uint16_t size) {
    if (bytes_.size() + 4 + size > sdk2_max_control_bytes - sdk2_control_header_bytes) {
      throw std::invalid_argument("SDK2 set parameters: key 0x" + hex(key) + " with " + std::to_string(size) +
                                  " bytes does not fit one control frame");
    }
    const std::size_t at = bytes_.size();
    bytes_.resize(at + 4 + size);
    detail::put_le(bytes_, at, key);
    detail::put_le(bytes_, at + 2, size);
    if (size > 0) std::memcpy(bytes_.data() + at + 4, value, size);
    ++count_;
    detail::put_le(bytes_, 0, count_);
  }

  /// A byte-valued key (0x0000 point data type, 0x001C IMU on/off).
  void add_u8(std::uint16_t key, std::uint8_t value) { add(key, &value, 1); }
  /// Key 0x001A, the target work mode.
  void add_work_mode(Sdk2WorkMode mode) { add_u8(sdk2_key_work_mode, static_cast<std::uint8_t>(mode)); }
  /// Keys 0x0005, 0x0006, 0x0007: a stream's destination.
  void add_destination(std::uint16_t key, const Sdk2HostIpInfo& info) {
    std::uint8_t v[sdk2_host_ip_info_bytes];
    std::memcpy(v, info.host_ip.data(), 4);
    std::memcpy(v + 4, &info.host_port, 2);
    std::memcpy(v + 6, &info.lidar_port, 2);
    add(key, v, sizeof v);
  }

  std::uint16_t count() const noexcept { return count_; }
  /// The payload: key_num, reserved, the pairs.
  const std::vector<std::uint8_t>& bytes() const noexcept { return bytes_; }

 private:
  static std::string hex(std::uint16_t v) {
    static const char digits[] = "0123456789ABCDEF";
    std::string s(4, '0');
    for (std::size_t i = 4; i-- > 0; v = static_cast<std::uint16_t>(v >> 4)) s[i] = digits[v & 15];
    return s;
  }

  std::vector<std::uint8_t> bytes_;
  std::uint16_t count_ = 0;
};

/// Writes the 0x0100 request (sender host) carrying `parameters` into `out`.
inline void encode_sdk2_set_parameters(std::uint32_t seq, const Sdk2ParameterList& parameters,
                                       std::vector<std::uint8_t>& out) {
  const auto& b = parameters.bytes();
  encode_sdk2_control({seq, sdk2_cmd_set_parameters, Sdk2CommandType::request, Sdk2Sender::host, b.data(), b.size()},
                      out);
}

/// What `parse_sdk2_parameters` found.
enum class Sdk2ParameterStatus : std::uint8_t {
  ok,
  truncated,       ///< fewer than the 4 bytes of key_num and reserved
  too_many,        ///< key_num above `sdk2_max_parameters`
  overrun,         ///< a pair's header or value runs past the payload
  trailing_bytes,  ///< bytes left after key_num pairs
};

/// Short text for a status, e.g. "overrun".
inline const char* describe(Sdk2ParameterStatus status) noexcept {
  switch (status) {
    case Sdk2ParameterStatus::ok: return "ok";
    case Sdk2ParameterStatus::truncated: return "truncated";
    case Sdk2ParameterStatus::too_many: return "too many keys";
    case Sdk2ParameterStatus::overrun: return "key-value pair overruns the payload";
    case Sdk2ParameterStatus::trailing_bytes: return "trailing bytes";
  }
  return "unknown";
}

/// Splits the payload of a 0x0100 request (the device side) into its pairs,
/// which replace the contents of `pairs` (views into `data`). Every pair
/// must lie within the payload and the last must end it. O(size).
inline Sdk2ParameterStatus parse_sdk2_parameters(const std::uint8_t* data, std::size_t size,
                                                 std::vector<Sdk2KeyValue>& pairs) {
  using io::detail::load_le;
  pairs.clear();
  if (size < 4) return Sdk2ParameterStatus::truncated;
  const std::uint16_t count = load_le<std::uint16_t>(data);
  if (count > sdk2_max_parameters) return Sdk2ParameterStatus::too_many;
  std::size_t at = 4;
  for (std::uint16_t i = 0; i < count; ++i) {
    if (size - at < 4) return Sdk2ParameterStatus::overrun;
    Sdk2KeyValue kv{load_le<std::uint16_t>(data + at), data + at + 4, load_le<std::uint16_t>(data + at + 2)};
    if (size - at - 4 < kv.size) return Sdk2ParameterStatus::overrun;
    pairs.push_back(kv);
    at += 4u + kv.size;
  }
  return at == size ? Sdk2ParameterStatus::ok : Sdk2ParameterStatus::trailing_bytes;
}

/// Reads a destination value (keys 0x0005-0x0007); false unless 8 bytes.
inline bool parse_sdk2_destination(const Sdk2KeyValue& kv, Sdk2HostIpInfo& info) noexcept {
  if (kv.size != sdk2_host_ip_info_bytes) return false;
  std::memcpy(info.host_ip.data(), kv.value, 4);
  info.host_port = io::detail::load_le<std::uint16_t>(kv.value + 4);
  info.lidar_port = io::detail::load_le<std::uint16_t>(kv.value + 6);
  return true;
}

/// Reads a byte value (keys 0x0000, 0x001A, 0x001C); false unless 1 byte.
inline bool parse_sdk2_u8(const Sdk2KeyValue& kv, std::uint8_t& value) noexcept {
  if (kv.size != 1) return false;
  value = kv.value[0];
  return true;
}

/// The device's answer to 0x0100: ret_code and, on failure, the first key
/// it refused (3 bytes of data).
struct Sdk2SetParametersAck {
  std::uint8_t ret_code = sdk2_ret_success;
  std::uint16_t error_key = 0;
};

inline constexpr std::size_t sdk2_set_parameters_ack_bytes = 3;

/// Writes the 0x0100 ACK frame (sender LiDAR, `seq` of the request) into `out`.
inline void encode_sdk2_set_parameters_ack(std::uint32_t seq, const Sdk2SetParametersAck& ack,
                                           std::vector<std::uint8_t>& out) {
  std::uint8_t data[sdk2_set_parameters_ack_bytes] = {ack.ret_code};
  std::memcpy(data + 1, &ack.error_key, 2);
  encode_sdk2_control({seq, sdk2_cmd_set_parameters, Sdk2CommandType::ack, Sdk2Sender::lidar, data, sizeof data}, out);
}

/// Reads a 0x0100 ACK from a decoded frame; false unless it is a 0x0100 ACK
/// with exactly 3 bytes of data. O(1).
inline bool parse_sdk2_set_parameters_ack(const Sdk2ControlFrame& frame, Sdk2SetParametersAck& ack) noexcept {
  if (frame.cmd_id != sdk2_cmd_set_parameters || frame.cmd_type != Sdk2CommandType::ack ||
      frame.data_size != sdk2_set_parameters_ack_bytes)
    return false;
  ack.ret_code = frame.data[0];
  ack.error_key = io::detail::load_le<std::uint16_t>(frame.data + 1);
  return true;
}

}  // namespace streamclust::live
