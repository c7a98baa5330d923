// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Livox SDK2 point and IMU packets (Mid-360, Mid-360S, HAP) as pure codecs:
/// `decode_sdk2_packet` turns one UDP datagram into returns in metres with
/// their device times, or one IMU sample; `encode_sdk2_point_packet` and
/// `encode_sdk2_imu_packet` write the datagram a device would send (for the
/// emulator and tests).
///
/// The 36-byte header (little-endian, packed; `LivoxLidarEthernetPacket` in
/// `Livox-SDK/Livox-SDK2:include/livox_lidar_def.h`, wiki "Point Cloud & IMU
/// Data Protocol"):
///
/// | offset | bytes | field         | meaning |
/// |--------|-------|---------------|---------|
/// | 0      | 1     | version       | 0 |
/// | 1      | 2     | length        | the whole datagram [bytes] |
/// | 3      | 2     | time_interval | last point's time - first point's [0.1 us] |
/// | 5      | 2     | dot_num       | point slots (firings; 96 on a Mid-360), 1 for IMU |
/// | 7      | 2     | udp_cnt       | packet counter, wraps at 65535 |
/// | 9      | 1     | frame_cnt     | 0 on non-repetitive scans |
/// | 10     | 1     | data_type     | see `Sdk2DataType` |
/// | 11     | 1     | time_type     | 0 none, 1 PTP / gPTP, 2 GPS; always ns |
/// | 12     | 12    | reserved      | zeros |
/// | 24     | 4     | crc32         | CRC-32 of bytes [28, length); 0: not computed |
/// | 28     | 8     | timestamp     | the first point's time [ns] |
///
/// Data types (bytes per slot): 1 int32 x, y, z [mm] + reflectivity + tag (14);
/// 2 int16 x, y, z [cm] + reflectivity + tag (8); 3 uint32 depth [mm], uint16
/// zenith theta and azimuth phi [0.01 deg] + reflectivity + tag (10), with
/// x = r sin(theta) cos(phi), y = r sin(theta) sin(phi), z = r cos(theta);
/// 0x11 dual echo, two type-1 echoes per slot (28); 0 IMU, float gyro x, y, z
/// [rad/s] and acceleration x, y, z [g] (24).
///
/// Slot i of n is at timestamp + round(i x time_interval x 100 / (n - 1)) ns:
/// the wiki spaces the points equally over time_interval, which spans first to
/// last point (a Mid-360 sends 4750 = 95 x 5 us for 96 points). Both echoes
/// of a dual-echo slot share its time.

#include <streamclust/live/livox_crc.hpp>
#include <streamclust/live/livox_returns.hpp>
#include <streamclust/io/livox_packet.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::live {

/// The data_type byte of an SDK2 packet.
enum class Sdk2DataType : std::uint8_t {
  imu = 0,                 ///< one IMU sample
  cartesian_mm = 1,        ///< int32 x, y, z [mm]
  cartesian_cm = 2,        ///< int16 x, y, z [cm]
  spherical = 3,           ///< uint32 depth [mm], uint16 theta, phi [0.01 deg]
  dual_cartesian_mm = 0x11 ///< two type-1 echoes per slot
};

/// Size of the packet header [bytes].
inline constexpr std::size_t sdk2_header_bytes = 36;

/// The largest dot_num a packet may declare: ten times a Mid-360's 96 (a
/// dual-echo packet of this many slots still fits a UDP datagram).
inline constexpr std::uint16_t sdk2_max_dot_num = 960;

/// The header of an SDK2 data packet, field by field.
struct Sdk2PacketHeader {
  std::uint8_t version = 0;
  std::uint16_t length = 0;         ///< the whole datagram [bytes]
  std::uint16_t time_interval = 0;  ///< last point's time - first point's [0.1 us]
  std::uint16_t dot_num = 0;        ///< point slots (1 for IMU)
  std::uint16_t udp_cnt = 0;        ///< packet counter
  std::uint8_t frame_cnt = 0;
  std::uint8_t data_type = 0;       ///< `Sdk2DataType` value
  std::uint8_t time_type = 0;       ///< 0 none, 1 PTP, 2 GPS
  std::uint32_t crc32 = 0;          ///< CRC-32 of bytes [28, length); 0: absent
  std::uint64_t timestamp = 0;      ///< first point's time [ns]
};

namespace detail {

/// The layout of one slot of `data_type` in io's vocabulary (the LVX2 and
/// SDK1 structs are the same bytes), or nullptr for an undefined type.
inline const io::LivoxDataType* sdk2_layout(std::uint8_t data_type) noexcept {
  using C = io::LivoxCoordinates;
  static constexpr io::LivoxDataType layouts[] = {
      {0, "IMU", C::none, 0, 24, 1, false},
      {1, "cartesian (mm)", C::cartesian_mm, 1, 14, 0, true},
      {2, "cartesian (cm)", C::cartesian_cm, 1, 8, 0, true},
      {3, "spherical", C::spherical_mm, 1, 10, 0, true},
      {0x11, "dual cartesian (mm)", C::cartesian_mm, 2, 28, 0, true},
  };
  for (const auto& t : layouts)
    if (t.value == data_type) return &t;
  return nullptr;
}

using io::detail::store_le;

/// True when echo `k` of the slot at `p` holds no return: its coordinates
/// are (0, 0, 0), or its depth is 0 (spherical).
inline bool sdk2_echo_is_empty(const io::LivoxDataType& layout, const std::uint8_t* p, std::size_t k) noexcept {
  static constexpr std::uint8_t zeros[12] = {};
  switch (layout.coordinates) {
    case io::LivoxCoordinates::cartesian_mm: return std::memcmp(p + 14 * k, zeros, 12) == 0;
    case io::LivoxCoordinates::cartesian_cm: return std::memcmp(p, zeros, 6) == 0;
    case io::LivoxCoordinates::spherical_mm: return std::memcmp(p, zeros, 4) == 0;
    default: return false;
  }
}

}  // namespace detail

/// The bytes of one point slot of `data_type` (14, 8, 10, 28; 24 for IMU),
/// or 0 for a data type SDK2 does not define. O(1).
inline std::size_t sdk2_slot_bytes(std::uint8_t data_type) noexcept {
  const io::LivoxDataType* layout = detail::sdk2_layout(data_type);
  return layout ? layout->struct_bytes : 0;
}

/// The device time of slot `i` of a packet of `dot_num` slots [ns]: the
/// timestamp plus i / (dot_num - 1) of time_interval, rounded half up to
/// the nanosecond. Exact integer arithmetic; O(1).
inline std::uint64_t sdk2_slot_time(std::uint64_t timestamp, std::uint16_t time_interval, std::uint16_t dot_num,
                                    std::uint32_t i) noexcept {
  if (dot_num < 2) return timestamp;
  const std::uint64_t gaps = dot_num - 1u;
  return timestamp + (std::uint64_t{i} * time_interval * 100u + gaps / 2) / gaps;
}

/// Reads the header fields of the first 36 bytes at `p` (no check). O(1).
inline Sdk2PacketHeader read_sdk2_header(const std::uint8_t* p) noexcept {
  using io::detail::load_le;
  Sdk2PacketHeader h;
  h.version = p[0];
  h.length = load_le<std::uint16_t>(p + 1);
  h.time_interval = load_le<std::uint16_t>(p + 3);
  h.dot_num = load_le<std::uint16_t>(p + 5);
  h.udp_cnt = load_le<std::uint16_t>(p + 7);
  h.frame_cnt = p[9];
  h.data_type = p[10];
  h.time_type = p[11];
  h.crc32 = load_le<std::uint32_t>(p + 24);
  h.timestamp = load_le<std::uint64_t>(p + 28);
  return h;
}

/// Writes `h` as the 36 header bytes at `p` (reserved bytes zero). O(1).
inline void write_sdk2_header(const Sdk2PacketHeader& h, std::uint8_t* p) noexcept {
  std::memset(p, 0, sdk2_header_bytes);
  p[0] = h.version;
  detail::store_le(p + 1, h.length);
  detail::store_le(p + 3, h.time_interval);
  detail::store_le(p + 5, h.dot_num);
  detail::store_le(p + 7, h.udp_cnt);
  p[9] = h.frame_cnt;
  p[10] = h.data_type;
  p[11] = h.time_type;
  detail::store_le(p + 24, h.crc32);
  detail::store_le(p + 28, h.timestamp);
}

/// Decodes the datagram of `size` bytes at `data`. A point packet appends
/// its returns to `out.returns` (metres, reflectivity, tag, device time;
/// slots without a return are counted in `empty_slots`, not appended); an
/// IMU packet writes `out.imu`. The status says what the datagram was:
///
/// - `truncated`: fewer than 36 bytes, or fewer than its length field says;
/// - `bad_version`: version not 0; `unknown_data_type`: not 0, 1, 2, 3, 0x11;
/// - `bad_length`: a datagram longer than its length field, a length field
///   other than 36 + dot_num x slot bytes, or dot_num 0, above
///   `sdk2_max_dot_num`, or not 1 for IMU;
/// - `bad_time`: time_type above 2;
/// - `bad_crc`: a non-zero crc32 field that is not the CRC-32 of bytes
///   [28, length). A crc32 of 0 means "not computed" (real Mid-360 point
///   packets send 0) and is never rejected.
///
/// On any status but `points` nothing is appended. Every byte pattern is
/// safe: reads stay within [data, data + size); nothing is allocated but
/// the returns appended (none once `out.returns` has the capacity), and the
/// only exception is std::bad_alloc from appending. O(size); thread-safe
/// for distinct `out`.
inline LivoxPacketSummary decode_sdk2_packet(const std::uint8_t* data, std::size_t size, LivoxPacketContents& out) {
  LivoxPacketSummary s;
  if (size < sdk2_header_bytes) return s;  // truncated
  const Sdk2PacketHeader h = read_sdk2_header(data);
  s.data_type = h.data_type;
  s.has_counter = true;
  s.counter = h.udp_cnt;
  if (h.version != 0) {
    s.status = LivoxPacketStatus::bad_version;
    return s;
  }
  const io::LivoxDataType* layout = detail::sdk2_layout(h.data_type);
  if (!layout) {
    s.status = LivoxPacketStatus::unknown_data_type;
    return s;
  }
  if (h.length > size) return s;  // truncated
  const bool imu = layout->coordinates == io::LivoxCoordinates::none;
  if (h.length < size || h.dot_num == 0 || h.dot_num > sdk2_max_dot_num || (imu && h.dot_num != 1) ||
      h.length != sdk2_header_bytes + std::size_t{h.dot_num} * layout->struct_bytes) {
    s.status = LivoxPacketStatus::bad_length;
    return s;
  }
  if (h.time_type > 2) {
    s.status = LivoxPacketStatus::bad_time;
    return s;
  }
  if (h.crc32 != 0 && crc32_iso_hdlc(data + 28, h.length - 28u) != h.crc32) {
    s.status = LivoxPacketStatus::bad_crc;
    return s;
  }
  s.sync = static_cast<LivoxTimeSync>(h.time_type);  // none, ptp, gps in this order
  s.first_time_ns = h.timestamp;
  s.last_time_ns = sdk2_slot_time(h.timestamp, h.time_interval, h.dot_num, h.dot_num - 1u);
  const std::uint8_t* body = data + sdk2_header_bytes;
  using io::detail::load_le;
  if (imu) {
    out.imu.time_ns = h.timestamp;
    for (std::size_t a = 0; a < 3; ++a) {
      out.imu.gyro[a] = load_le<float>(body + 4 * a);
      out.imu.acceleration[a] = load_le<float>(body + 12 + 4 * a);
    }
    s.status = LivoxPacketStatus::imu;
    return s;
  }
  s.status = LivoxPacketStatus::points;
  s.slots = std::uint32_t{h.dot_num} * layout->returns;
  io::LivoxReturn echoes[io::max_livox_returns];
  for (std::uint32_t i = 0; i < h.dot_num; ++i) {
    const std::uint8_t* slot = body + std::size_t{i} * layout->struct_bytes;
    const std::size_t n = io::decode_livox_struct(*layout, slot, echoes);
    const std::uint64_t t = sdk2_slot_time(h.timestamp, h.time_interval, h.dot_num, i);
    for (std::size_t k = 0; k < n; ++k) {
      if (detail::sdk2_echo_is_empty(*layout, slot, k)) {
        ++s.empty_slots;
        continue;
      }
      const io::LivoxReturn& e = echoes[k];
      out.returns.push_back(LivoxReturn{e.x, e.y, e.z, e.reflectivity, e.tag, t});
      ++s.returns;
    }
  }
  return s;
}

/// The header fields an encoder takes from its caller.
struct Sdk2PacketFields {
  std::uint16_t udp_cnt = 0;                  ///< packet counter
  std::uint64_t timestamp_ns = 0;             ///< the first slot's time [ns]
  std::uint16_t time_interval = 0;            ///< last slot's time - first slot's [0.1 us] (IMU: 0)
  LivoxTimeSync time_sync = LivoxTimeSync::none;  ///< none, ptp or gps
  bool fill_crc = false;                      ///< write the CRC-32, or 0 as a Mid-360's point packets do
};

namespace detail {

inline void sdk2_check_sync(LivoxTimeSync sync) {
  if (sync == LivoxTimeSync::pps)
    throw std::invalid_argument("SDK2 packet time_sync: PPS has no SDK2 time_type (expected none, PTP or GPS)");
}

/// Starts a packet in `out`: header (CRC 0) for `dot_num` slots of `data_type`, then zeros.
inline std::uint8_t* sdk2_start_packet(const Sdk2PacketFields& f, Sdk2DataType data_type, std::size_t dot_num,
                                       std::vector<std::uint8_t>& out) {
  sdk2_check_sync(f.time_sync);
  const std::size_t slot = sdk2_slot_bytes(static_cast<std::uint8_t>(data_type));
  if (slot == 0) {
    throw std::invalid_argument("SDK2 packet data type " + std::to_string(static_cast<int>(data_type)) +
                                ": expected 0 (IMU), 1, 2, 3 or 0x11");
  }
  if (dot_num == 0 || dot_num > sdk2_max_dot_num) {
    throw std::invalid_argument("SDK2 packet dot_num " + std::to_string(dot_num) + ": expected 1 to " +
                                std::to_string(sdk2_max_dot_num));
  }
  Sdk2PacketHeader h;
  h.length = static_cast<std::uint16_t>(sdk2_header_bytes + dot_num * slot);
  h.time_interval = f.time_interval;
  h.dot_num = static_cast<std::uint16_t>(dot_num);
  h.udp_cnt = f.udp_cnt;
  h.data_type = static_cast<std::uint8_t>(data_type);
  h.time_type = static_cast<std::uint8_t>(f.time_sync);
  h.timestamp = f.timestamp_ns;
  out.assign(h.length, 0);
  write_sdk2_header(h, out.data());
  return out.data() + sdk2_header_bytes;
}

inline void sdk2_finish_packet(const Sdk2PacketFields& f, std::vector<std::uint8_t>& out) noexcept {
  if (f.fill_crc) store_le(out.data() + 24, crc32_iso_hdlc(out.data() + 28, out.size() - 28));
}

/// `metres` in `per_metre` units, rounded to nearest (half away from zero),
/// as an integer in [lo, hi]; throws naming `what` when out of range or not finite.
inline std::int64_t sdk2_quantise(double metres, double per_metre, double lo, double hi, const char* what) {
  return quantise_metres("SDK2 point packet", metres, per_metre, lo, hi, what);
}

/// Writes `r` as x, y, z of type `Int` in 1 / `per_metre` m, reflectivity, tag.
template <class Int>
void sdk2_encode_cartesian(const LivoxReturn& r, double per_metre, std::uint8_t* p) {
  constexpr double lo = std::numeric_limits<Int>::min(), hi = std::numeric_limits<Int>::max();
  const float xyz[3] = {r.x, r.y, r.z};
  const char* const names[3] = {"x", "y", "z"};
  for (std::size_t a = 0; a < 3; ++a)
    store_le(p + a * sizeof(Int), static_cast<Int>(sdk2_quantise(xyz[a], per_metre, lo, hi, names[a])));
  p[3 * sizeof(Int)] = r.reflectivity;
  p[3 * sizeof(Int) + 1] = r.tag;
}

/// Writes `r` as one echo of `type` at `p` (type 1: 14 bytes, 2: 8, 3: 10).
inline void sdk2_encode_echo(Sdk2DataType type, const LivoxReturn& r, std::uint8_t* p) {
  switch (type) {
    case Sdk2DataType::cartesian_mm:
    case Sdk2DataType::dual_cartesian_mm: sdk2_encode_cartesian<std::int32_t>(r, 1000.0, p); return;
    case Sdk2DataType::cartesian_cm: sdk2_encode_cartesian<std::int16_t>(r, 100.0, p); return;
    case Sdk2DataType::spherical: {
      constexpr double hundredths_per_radian = 18000.0 / 3.14159265358979323846;
      const double x = r.x, y = r.y, z = r.z;
      const double range = std::sqrt(x * x + y * y + z * z);
      constexpr double max_depth = std::numeric_limits<std::uint32_t>::max();
      const auto depth = static_cast<std::uint32_t>(sdk2_quantise(range, 1000.0, 0, max_depth, "range"));
      std::uint16_t theta = 0, phi = 0;
      if (range > 0) {
        const double zenith = std::acos(std::clamp(z / range, -1.0, 1.0));  // [0, pi]
        theta = static_cast<std::uint16_t>(std::lround(zenith * hundredths_per_radian));
        long a = std::lround(std::atan2(y, x) * hundredths_per_radian);  // -18000 to 18000
        if (a < 0) a += 36000;
        phi = static_cast<std::uint16_t>(a == 36000 ? 0 : a);
      }
      store_le(p, depth);
      store_le(p + 4, theta);
      store_le(p + 6, phi);
      p[8] = r.reflectivity;
      p[9] = r.tag;
      return;
    }
    case Sdk2DataType::imu: return;
  }
}

}  // namespace detail

/// Writes the point packet of `count` returns in `type` (1, 2, 3 or 0x11)
/// into `out` (its contents replaced, its capacity kept). For 0x11, returns
/// 2k and 2k + 1 are the two echoes of slot k, so `count` is even. The
/// returns' `time_ns` are not encoded: the slots' times follow from
/// `fields.timestamp_ns` and `fields.time_interval` (`sdk2_slot_time`).
///
/// Quantisation, and so the round trip's error: types 1 and 0x11 round each
/// coordinate to the millimetre (at most 0.5 mm per axis), type 2 to the
/// centimetre (at most 5 mm per axis), type 3 the range to the millimetre
/// and each angle to 0.01 deg (at most 0.5 mm + 1.235e-4 x range in
/// distance: 0.005 deg on two angles). A return within half a unit of the
/// origin becomes an empty slot ((0, 0, 0) or depth 0), which is how empty
/// slots are encoded. The decoded floats add at most half a float ulp.
///
/// Throws std::invalid_argument for another type, for 0 or more than
/// `sdk2_max_dot_num` slots, an odd count for 0x11, a PPS time sync, and a
/// coordinate that is not finite or does not fit its integer (type 2:
/// beyond +-327.67 m). O(count).
inline void encode_sdk2_point_packet(const Sdk2PacketFields& fields, Sdk2DataType type, const LivoxReturn* returns,
                                     std::size_t count, std::vector<std::uint8_t>& out) {
  if (type == Sdk2DataType::imu)
    throw std::invalid_argument("SDK2 point packet: data type 0 is IMU (use encode_sdk2_imu_packet)");
  const bool dual = type == Sdk2DataType::dual_cartesian_mm;
  if (dual && count % 2 != 0)
    throw std::invalid_argument("SDK2 dual-echo packet: " + std::to_string(count) +
                                " returns (expected an even count)");
  const std::size_t dot_num = dual ? count / 2 : count;
  std::uint8_t* p = detail::sdk2_start_packet(fields, type, dot_num, out);
  const std::size_t echo_bytes = dual ? 14 : sdk2_slot_bytes(static_cast<std::uint8_t>(type));
  for (std::size_t i = 0; i < count; ++i) detail::sdk2_encode_echo(type, returns[i], p + i * echo_bytes);
  detail::sdk2_finish_packet(fields, out);
}

/// Writes the IMU packet of `sample` into `out` (contents replaced); the
/// packet's timestamp is `fields.timestamp_ns` (the sample's time_ns is not
/// read). Floats are copied bit for bit: the round trip is exact. Throws
/// std::invalid_argument for a PPS time sync. O(1).
inline void encode_sdk2_imu_packet(const Sdk2PacketFields& fields, const LivoxImuSample& sample,
                                   std::vector<std::uint8_t>& out) {
  std::uint8_t* p = detail::sdk2_start_packet(fields, Sdk2DataType::imu, 1, out);
  for (std::size_t a = 0; a < 3; ++a) {
    detail::store_le(p + 4 * a, sample.gyro[a]);
    detail::store_le(p + 12 + 4 * a, sample.acceleration[a]);
  }
  detail::sdk2_finish_packet(fields, out);
}

}  // namespace streamclust::live
