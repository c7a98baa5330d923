// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// What a Livox data packet holds once decoded, whichever protocol carried it
/// (SDK2: Mid-360, HAP; SDK1: Avia, Mid-40/70, Horizon, Tele-15): the returns
/// in metres with their device times, or one IMU sample, and a summary of the
/// packet (status, time sync, counter, slot counts). The decoders of
/// <streamclust/live/sdk2_packets.hpp> and <streamclust/live/sdk1_packets.hpp>
/// fill these; the live pipeline turns returns into engine points.
///
/// Plain data, no I/O.

#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::live {

/// One return of a Livox data packet, in the sensor frame.
struct LivoxReturn {
  float x = 0.0f;                ///< [m]
  float y = 0.0f;                ///< [m]
  float z = 0.0f;                ///< [m]
  std::uint8_t reflectivity = 0;
  std::uint8_t tag = 0;          ///< the Livox tag byte as sent (0 where the data type has none)
  std::uint64_t time_ns = 0;     ///< the LiDAR's clock [ns]
};

/// One IMU sample.
struct LivoxImuSample {
  std::uint64_t time_ns = 0;                 ///< the LiDAR's clock [ns]
  std::array<float, 3> gyro{};               ///< angular rate [rad/s]
  std::array<float, 3> acceleration{};       ///< [g] (1 g = 9.80665 m/s^2), sensor frame
};

/// How the LiDAR's clock is synchronised (the packet's time type).
enum class LivoxTimeSync : std::uint8_t {
  none,   ///< free-running since power-on
  ptp,    ///< IEEE 1588 / gPTP
  gps,    ///< GPS (with PPS)
  pps,    ///< PPS only (SDK1)
};

/// What became of one datagram given to a decoder.
enum class LivoxPacketStatus : std::uint8_t {
  points,             ///< a point packet: its returns were appended
  imu,                ///< an IMU packet: the sample was written
  truncated,          ///< shorter than its header, or than its header says
  bad_length,         ///< the length field disagrees with the datagram or the data type
  bad_version,        ///< a version byte this protocol does not define
  unknown_data_type,  ///< a data type this protocol does not define
  bad_crc,            ///< a CRC present and wrong
  bad_time,           ///< a timestamp that cannot be a time (e.g. an invalid GPS date)
};

/// Short text for a status, e.g. "truncated".
inline const char* describe(LivoxPacketStatus status) noexcept {
  switch (status) {
    case LivoxPacketStatus::points: return "points";
    case LivoxPacketStatus::imu: return "imu";
    case LivoxPacketStatus::truncated: return "truncated";
    case LivoxPacketStatus::bad_length: return "bad length";
    case LivoxPacketStatus::bad_version: return "bad version";
    case LivoxPacketStatus::unknown_data_type: return "unknown data type";
    case LivoxPacketStatus::bad_crc: return "bad CRC";
    case LivoxPacketStatus::bad_time: return "bad time";
  }
  return "unknown";
}

/// Short text for a time sync, e.g. "PTP".
inline const char* describe(LivoxTimeSync sync) noexcept {
  switch (sync) {
    case LivoxTimeSync::none: return "none";
    case LivoxTimeSync::ptp: return "PTP";
    case LivoxTimeSync::gps: return "GPS";
    case LivoxTimeSync::pps: return "PPS";
  }
  return "unknown";
}

/// The summary of one decoded datagram. Fields past `status` are meaningful
/// only for `points` and `imu`.
struct LivoxPacketSummary {
  LivoxPacketStatus status = LivoxPacketStatus::truncated;
  LivoxTimeSync sync = LivoxTimeSync::none;
  std::uint8_t data_type = 0;        ///< the header's data_type byte
  bool has_counter = false;          ///< the protocol numbers its packets (SDK2 udp_cnt; SDK1 has none)
  std::uint16_t counter = 0;         ///< udp_cnt, wrapping at 65535
  std::uint64_t first_time_ns = 0;   ///< device time of the first slot [ns]
  std::uint64_t last_time_ns = 0;    ///< device time of the last slot [ns]
  std::uint32_t slots = 0;           ///< point slots in the packet (firings x returns)
  std::uint32_t returns = 0;         ///< returns appended
  std::uint32_t empty_slots = 0;     ///< slots without a return ((0,0,0) or depth 0), not appended
};

/// Where a decoder writes what it decodes. `returns` is appended to (the
/// caller clears it and keeps its capacity: no allocation once warm).
struct LivoxPacketContents {
  std::vector<LivoxReturn> returns;
  LivoxImuSample imu;
};

namespace detail {

/// `metres` as the integer count of 1 / `per_metre` m an encoder writes,
/// rounded to nearest; throws std::invalid_argument naming `encoder` and
/// the coordinate `what` when it is not finite or outside [lo, hi] counts.
inline std::int64_t quantise_metres(const char* encoder, double metres, double per_metre, double lo, double hi,
                                    const char* what) {
  const double q = std::round(metres * per_metre);
  if (!(q >= lo && q <= hi)) {
    throw std::invalid_argument(std::string(encoder) + ": " + what + " " + std::to_string(metres) +
                                " m cannot be encoded (expected a finite value within " + std::to_string(lo / per_metre) +
                                " to " + std::to_string(hi / per_metre) + " m)");
  }
  return static_cast<std::int64_t>(q);
}

}  // namespace detail

}  // namespace streamclust::live
