// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The data packets of the Livox SDK1 protocol (Avia, Mid-40/100, Mid-70,
/// Horizon, Tele-15) as pure codecs of bytes: `decode_sdk1_packet` turns one
/// UDP datagram into returns in metres with device times (or one IMU
/// sample); `encode_sdk1_data_packet` and `encode_sdk1_imu_packet` write the
/// datagram a device would send (for the emulator and the tests). No I/O.
///
/// A datagram is the 18-byte header `LivoxEthPacket` (little-endian, packed)
/// followed by a fixed number of point structs of its data type, no CRC:
///
///     off size field
///       0   1  version       (5 on the devices whose recordings we know; not checked)
///       1   1  slot          (Hub port)
///       2   1  id
///       3   1  reserved
///       4   4  err_code      (the LiDAR's status bits)
///       8   1  timestamp_type  0 none, 1 PTP, 3 PPS + GPS (UTC), 4 PPS; 2 reserved
///       9   1  data_type     0-8 (io::find_sdk1_data_type: structs, returns, bytes)
///      10   8  timestamp     ns (types 0, 1, 4) or UTC fields (type 3)
///      18      data          structs_per_package x struct_bytes
///
/// Sources: `Livox-SDK/Livox-SDK:sdk_core/include/livox_def.h` (`LivoxEthPacket`,
/// point structs, `TimestampType`); `Livox-SDK/livox_ros_driver:livox_ros_driver/
/// livox_ros_driver/lds.h` (header length, points per packet).
///
/// Times: the timestamp is the time of the packet's first firing; firing k is
/// at timestamp + k x the device's firing interval, and the returns of one
/// firing (dual, triple) share its time. The packet does not name its device,
/// so the caller gives the interval (`sdk1_nominal_firing_interval_ns` has
/// the nominal one per data type). SDK1 packets carry no counter: the
/// pipeline counts lost packets from timestamp gaps
/// (`expected_sdk1_packet_period_ns`).
///
/// The decoder never reads outside [data, data + size), never throws and
/// never allocates beyond the growth of `out.returns`. All functions are
/// pure and thread-safe (each call works on its own arguments).

#include <streamclust/io/livox_packet.hpp>
#include <streamclust/live/livox_returns.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::live {

namespace detail {

using io::detail::store_le;

}  // namespace detail

/// Bytes of the data packet header.
inline constexpr std::size_t sdk1_packet_header_bytes = 18;

/// The data type of IMU packets (one sample of 6 floats).
inline constexpr std::uint8_t sdk1_imu_data_type = 6;

/// The IMU push period at the only non-zero push frequency, 200 Hz
/// (`livox_def.h` `ImuFreq`) [ns].
inline constexpr std::uint64_t sdk1_imu_period_ns = 5000000;

/// The header of a data packet, field for field.
struct Sdk1PacketHeader {
  std::uint8_t version = 5;
  std::uint8_t slot = 0;
  std::uint8_t id = 0;
  std::uint8_t reserved = 0;
  std::uint32_t error_code = 0;       ///< the LiDAR's status bits (`LidarErrorCode`)
  std::uint8_t timestamp_type = 0;    ///< 0 none, 1 PTP, 3 PPS + GPS, 4 PPS
  std::uint8_t data_type = 0;         ///< 0-8
  std::uint64_t timestamp = 0;        ///< the 8 timestamp bytes as sent (little-endian), see sdk1_packet_time
};

/// Reads the header of the datagram at `data`; false when it is shorter
/// than the header. O(1), noexcept.
inline bool read_sdk1_packet_header(const std::uint8_t* data, std::size_t size, Sdk1PacketHeader& header) noexcept {
  using io::detail::load_le;
  if (size < sdk1_packet_header_bytes) return false;
  header.version = data[0];
  header.slot = data[1];
  header.id = data[2];
  header.reserved = data[3];
  header.error_code = load_le<std::uint32_t>(data + 4);
  header.timestamp_type = data[8];
  header.data_type = data[9];
  header.timestamp = load_le<std::uint64_t>(data + 10);
  return true;
}

/// Writes `header` to the 18 bytes at `p`. O(1), noexcept.
inline void write_sdk1_packet_header(const Sdk1PacketHeader& header, std::uint8_t* p) noexcept {
  p[0] = header.version;
  p[1] = header.slot;
  p[2] = header.id;
  p[3] = header.reserved;
  detail::store_le(p + 4, header.error_code);
  p[8] = header.timestamp_type;
  p[9] = header.data_type;
  detail::store_le(p + 10, header.timestamp);
}

/// The time of `header` [ns; since 1970 for GPS] and its sync. False for
/// timestamp type 2 (reserved), types above 4 and an impossible UTC date.
/// O(1), noexcept.
inline bool sdk1_packet_time(const Sdk1PacketHeader& header, std::uint64_t& time_ns, LivoxTimeSync& sync) noexcept {
  switch (header.timestamp_type) {
    case 0: sync = LivoxTimeSync::none; break;
    case 1: sync = LivoxTimeSync::ptp; break;
    case 4: sync = LivoxTimeSync::pps; break;
    case 3: {
      std::uint8_t bytes[8];
      detail::store_le(bytes, header.timestamp);
      sync = LivoxTimeSync::gps;
      return io::decode_sdk1_utc_timestamp(bytes, time_ns);
    }
    default: return false;
  }
  time_ns = header.timestamp;
  return true;
}

/// Sets the timestamp type and bytes of `header` to `time_ns` [ns] with
/// `timestamp_type`; for type 3 (UTC) the time is rounded down to the
/// microsecond. False (header unchanged) for types 2 and above 4 and for a
/// UTC time outside the years 2000-2255. O(1), noexcept.
inline bool set_sdk1_packet_time(Sdk1PacketHeader& header, std::uint8_t timestamp_type,
                                 std::uint64_t time_ns) noexcept {
  if (timestamp_type == 3) {
    std::uint8_t bytes[8];
    if (!io::encode_sdk1_utc_timestamp(time_ns, bytes)) return false;
    header.timestamp = io::detail::load_le<std::uint64_t>(bytes);
  } else if (timestamp_type == 0 || timestamp_type == 1 || timestamp_type == 4) {
    header.timestamp = time_ns;
  } else {
    return false;
  }
  header.timestamp_type = timestamp_type;
  return true;
}

/// Bytes of a whole packet of `type`: the header and its fixed number of structs.
constexpr std::size_t sdk1_packet_bytes(const io::LivoxDataType& type) noexcept {
  return sdk1_packet_header_bytes + std::size_t{type.structs_per_package} * type.struct_bytes;
}

/// The nominal time between two firings of the devices that send `data_type`
/// [ns]: 10,000 (100 k firings/s, Mid-40, Mid-70) for types 0 and 1, the
/// types of those devices; 4,167 (240 k firings/s, Avia, Horizon, Tele-15)
/// for the extended types 2-8, dual and triple returns counting firings.
/// 0 for IMU and unknown types. From io::find_sdk1_device_type.
inline std::uint32_t sdk1_nominal_firing_interval_ns(std::uint8_t data_type) noexcept {
  const io::LivoxDataType* type = io::find_sdk1_data_type(data_type);
  if (!type || type->returns == 0) return 0;
  return io::find_sdk1_device_type(data_type <= 1 ? 1 : 7)->firing_interval_ns;  // Mid-40 : Avia
}

/// The time from one packet of `data_type` to the next of an uninterrupted
/// stream [ns]: structs per packet x `firing_interval_ns` for points, the
/// 200 Hz IMU period for IMU, 0 for unknown types. A gap of about k periods
/// between two packet times means k - 1 packets lost (SDK1 has no counter).
inline std::uint64_t expected_sdk1_packet_period_ns(std::uint8_t data_type, std::uint32_t firing_interval_ns) noexcept {
  const io::LivoxDataType* type = io::find_sdk1_data_type(data_type);
  if (!type) return 0;
  if (type->returns == 0) return sdk1_imu_period_ns;
  return std::uint64_t{type->structs_per_package} * firing_interval_ns;
}

/// Decodes the datagram of `size` bytes at `data`. Point packets append
/// their returns to `out.returns` (firing k at the packet time + k x
/// `firing_interval_ns`; slots without a return, (0, 0, 0) or depth 0, are
/// counted in `empty_slots`, not appended); IMU packets write `out.imu`.
/// The status says what became of it:
/// - `truncated`: shorter than the header, or than its data type's packet;
/// - `bad_length`: longer than its data type's packet;
/// - `unknown_data_type`: a data type above 8;
/// - `bad_time`: timestamp type 2 or above 4, or an impossible UTC date.
/// Nothing is appended then. `has_counter` is false. O(size); noexcept.
inline LivoxPacketSummary decode_sdk1_packet(const std::uint8_t* data, std::size_t size,
                                             std::uint32_t firing_interval_ns, LivoxPacketContents& out) noexcept {
  using io::detail::load_le;
  LivoxPacketSummary summary;
  Sdk1PacketHeader header;
  if (!read_sdk1_packet_header(data, size, header)) return summary;  // truncated
  summary.data_type = header.data_type;
  const io::LivoxDataType* type = io::find_sdk1_data_type(header.data_type);
  if (!type) {
    summary.status = LivoxPacketStatus::unknown_data_type;
    return summary;
  }
  const std::size_t expected = sdk1_packet_bytes(*type);
  if (size != expected) {
    summary.status = size < expected ? LivoxPacketStatus::truncated : LivoxPacketStatus::bad_length;
    return summary;
  }
  std::uint64_t time_ns = 0;
  if (!sdk1_packet_time(header, time_ns, summary.sync)) {
    summary.status = LivoxPacketStatus::bad_time;
    return summary;
  }
  summary.first_time_ns = time_ns;
  const std::uint8_t* body = data + sdk1_packet_header_bytes;
  if (type->returns == 0) {  // IMU: gyro x, y, z [rad/s], acceleration x, y, z [g], float32
    out.imu.time_ns = time_ns;
    for (int k = 0; k < 3; ++k) {
      out.imu.gyro[k] = load_le<float>(body + 4 * k);
      out.imu.acceleration[k] = load_le<float>(body + 12 + 4 * k);
    }
    summary.status = LivoxPacketStatus::imu;
    summary.last_time_ns = time_ns;
    return summary;
  }
  io::LivoxReturn firing[io::max_livox_returns];
  for (std::size_t k = 0; k < type->structs_per_package; ++k) {
    const std::uint64_t t = time_ns + k * std::uint64_t{firing_interval_ns};  // wraps, never UB
    const std::size_t n = io::decode_livox_struct(*type, body + k * type->struct_bytes, firing);
    for (std::size_t r = 0; r < n; ++r) {
      const io::LivoxReturn& f = firing[r];
      if (f.x == 0.0f && f.y == 0.0f && f.z == 0.0f) {  // integer zeros, or depth 0
        ++summary.empty_slots;
        continue;
      }
      out.returns.push_back(LivoxReturn{f.x, f.y, f.z, f.reflectivity, f.tag, t});
      ++summary.returns;
    }
  }
  summary.slots = std::uint32_t{type->structs_per_package} * type->returns;
  summary.last_time_ns = time_ns + (type->structs_per_package - 1u) * std::uint64_t{firing_interval_ns};
  summary.status = LivoxPacketStatus::points;
  return summary;
}

namespace detail {

/// `value` [m] in units of 1/`per_metre` m, rounded; throws
/// std::invalid_argument naming `what` when not finite or beyond [lo, hi].
inline std::int64_t sdk1_quantise(double value, double per_metre, double lo, double hi, const char* what) {
  return quantise_metres("SDK1 packet encoder", value, per_metre, lo, hi, what);
}

/// Writes one struct of `type` at `p` from the returns `r[0, n)` of one
/// firing (n <= type.returns; the other slots stay empty: zeros). Spherical
/// types with several returns take the direction of the first return that
/// is not at the origin. Throws std::invalid_argument for a coordinate out
/// of range.
inline void write_sdk1_struct(const io::LivoxDataType& type, const LivoxReturn* const* r, std::size_t n,
                              std::uint8_t* p) {
  std::memset(p, 0, type.struct_bytes);
  if (type.coordinates == io::LivoxCoordinates::cartesian_mm) {
    constexpr double lo = -2147483648.0, hi = 2147483647.0;
    const std::size_t stride = type.has_tag ? 14 : 13;
    for (std::size_t k = 0; k < n; ++k, p += stride) {
      store_le(p, static_cast<std::int32_t>(sdk1_quantise(r[k]->x, 1000.0, lo, hi, "x")));
      store_le(p + 4, static_cast<std::int32_t>(sdk1_quantise(r[k]->y, 1000.0, lo, hi, "y")));
      store_le(p + 8, static_cast<std::int32_t>(sdk1_quantise(r[k]->z, 1000.0, lo, hi, "z")));
      p[12] = r[k]->reflectivity;
      if (type.has_tag) p[13] = r[k]->tag;
    }
    return;
  }
  // spherical_mm: depth [mm], zenith theta in [0, 18000] and azimuth phi in
  // [0, 36000) [0.01 deg]; the inverse of io::detail::livox_spherical.
  constexpr double hundredths_per_radian = 18000.0 / 3.14159265358979323846;
  std::uint16_t theta = 0, phi = 0;
  bool have_direction = false;
  auto depth_of = [&](const LivoxReturn& q) -> std::uint32_t {
    const double x = q.x, y = q.y, z = q.z;
    const double range = std::sqrt(x * x + y * y + z * z);
    const auto depth = static_cast<std::uint32_t>(sdk1_quantise(range, 1000.0, 0.0, 4294967295.0, "range"));
    if (depth != 0 && !have_direction) {
      const double zenith = std::acos(std::clamp(z / range, -1.0, 1.0));
      theta = static_cast<std::uint16_t>(std::lround(zenith * hundredths_per_radian));
      double azimuth = std::atan2(y, x) * hundredths_per_radian;
      if (azimuth < 0) azimuth += 36000.0;
      const long a = std::lround(azimuth);
      phi = static_cast<std::uint16_t>(a >= 36000 ? 0 : a);
      have_direction = true;
    }
    return depth;
  };
  if (type.returns == 1) {
    if (n == 0) return;
    store_le(p, depth_of(*r[0]));
    store_le(p + 4, theta);
    store_le(p + 6, phi);
    p[8] = r[0]->reflectivity;
    if (type.has_tag) p[9] = r[0]->tag;
    return;
  }
  for (std::size_t k = 0; k < n; ++k) {  // theta, phi, then per return: depth, reflectivity, tag
    std::uint8_t* q = p + 4 + 6 * k;
    store_le(q, depth_of(*r[k]));
    q[4] = r[k]->reflectivity;
    q[5] = r[k]->tag;
  }
  store_le(p, theta);
  store_le(p + 2, phi);
}

}  // namespace detail

/// Writes into `out` (cleared; its capacity kept) the point packet a device
/// would send: `header` (its data type, one of 0-5, 7, 8, and its time, see
/// set_sdk1_packet_time), then the structs of the returns `returns[0,
/// count)` [m]. Each return goes to the firing of its `time_ns` (the packet
/// time + k x `firing_interval_ns`, rounded to the nearest k); the returns
/// of one firing fill its return slots in the order given. Firings and
/// slots without a return are written empty (zeros). Quantisation: 1 mm for
/// Cartesian coordinates; 1 mm in depth and 0.01 deg in angle for spherical
/// ones, whose returns of one firing share the direction of its first.
///
/// Throws std::invalid_argument (naming the problem) for an IMU or unknown
/// data type, an undecodable time, a zero interval, a return before the
/// packet or after its last firing, more returns in a firing than the type
/// holds, or a coordinate that is not finite or beyond the type's range.
/// O(count + packet bytes).
inline void encode_sdk1_data_packet(const Sdk1PacketHeader& header, std::uint32_t firing_interval_ns,
                                    const LivoxReturn* returns, std::size_t count, std::vector<std::uint8_t>& out) {
  const io::LivoxDataType* type = io::find_sdk1_data_type(header.data_type);
  if (!type || type->returns == 0)
    throw std::invalid_argument("SDK1 packet encoder: data type " + std::to_string(header.data_type) +
                                " is not a point data type (expected 0-5, 7 or 8)");
  std::uint64_t time_ns = 0;
  LivoxTimeSync sync = LivoxTimeSync::none;
  if (!sdk1_packet_time(header, time_ns, sync))
    throw std::invalid_argument("SDK1 packet encoder: timestamp type " + std::to_string(header.timestamp_type) +
                                " with these timestamp bytes is no time");
  if (firing_interval_ns == 0) throw std::invalid_argument("SDK1 packet encoder: the firing interval is 0 ns");
  out.assign(sdk1_packet_bytes(*type), 0);
  write_sdk1_packet_header(header, out.data());
  std::uint8_t* body = out.data() + sdk1_packet_header_bytes;
  const LivoxReturn* firing[io::max_livox_returns] = {};
  std::size_t in_firing = 0, current = 0;
  auto flush = [&] {
    if (in_firing > 0) detail::write_sdk1_struct(*type, firing, in_firing, body + current * type->struct_bytes);
    in_firing = 0;
  };
  for (std::size_t i = 0; i < count; ++i) {
    const LivoxReturn& r = returns[i];
    const std::uint64_t after = r.time_ns - time_ns;  // wraps for a return before the packet: k too large
    const std::uint64_t k = after / firing_interval_ns + (after % firing_interval_ns >= (firing_interval_ns + 1u) / 2u);
    if (r.time_ns < time_ns || k >= type->structs_per_package)
      throw std::invalid_argument("SDK1 packet encoder: return " + std::to_string(i) + " at " +
                                  std::to_string(r.time_ns) + " ns is outside the packet's " +
                                  std::to_string(type->structs_per_package) + " firings from " +
                                  std::to_string(time_ns) + " ns");
    if (k < current)
      throw std::invalid_argument("SDK1 packet encoder: return " + std::to_string(i) + " comes before the return " +
                                  "ahead of it (returns go in time order)");
    if (k != current) {
      flush();
      current = static_cast<std::size_t>(k);
    }
    if (in_firing == type->returns)
      throw std::invalid_argument("SDK1 packet encoder: more than " + std::to_string(type->returns) +
                                  " returns in firing " + std::to_string(k));
    firing[in_firing++] = &r;
  }
  flush();
}

/// Writes into `out` (cleared) the IMU packet of `sample` (its gyro [rad/s]
/// and acceleration [g]; its time_ns is not used: the time is the header's).
/// The header's data type is written as 6. O(1) but for the vector.
inline void encode_sdk1_imu_packet(const Sdk1PacketHeader& header, const LivoxImuSample& sample,
                                   std::vector<std::uint8_t>& out) {
  Sdk1PacketHeader h = header;
  h.data_type = sdk1_imu_data_type;
  out.assign(sdk1_packet_bytes(*io::find_sdk1_data_type(sdk1_imu_data_type)), 0);
  write_sdk1_packet_header(h, out.data());
  std::uint8_t* body = out.data() + sdk1_packet_header_bytes;
  for (int k = 0; k < 3; ++k) {
    detail::store_le(body + 4 * k, sample.gyro[k]);
    detail::store_le(body + 12 + 4 * k, sample.acceleration[k]);
  }
}

}  // namespace streamclust::live
