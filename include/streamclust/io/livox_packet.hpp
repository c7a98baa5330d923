// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The Livox point-packet vocabulary that LVX and LVX2 files share with the
/// Livox SDKs: the point data types and how one point struct decodes into
/// returns in metres, the device types with the interval between their
/// firings, and package timestamps. Pure functions of bytes, no I/O.
///
/// Sources (little-endian, packed structs):
/// - SDK 1 data types 0-8 and their structs: `Livox-SDK/Livox-SDK:sdk_core/include/livox_def.h`
///   (`PointDataType`, `LivoxRawPoint` ... `LivoxTripleExtendSpherPoint`); points per
///   packet and returns per firing: `Livox-SDK/livox_ros_driver:livox_ros_driver/livox_ros_driver/lds.h`
///   (`data_type_info_pair_table`).
/// - LVX 1.0 packages hold 100 `LivoxPoint` (float x, y, z in m, u8 reflectivity):
///   `livox_ros_driver/lvx_file.h` (`LvxFilePacketV0`).
/// - LVX2 data types 1 (i32 mm) and 2 (i16 cm): "LVX2 Specifications" v1.0 (Livox, 2023).
/// - Firing intervals: see `LivoxDeviceType`.
/// - Timestamps: `livox_def.h` (`TimestampType`), `livox_ros_driver/lds.cpp`
///   (`GetStoragePacketTimestamp`: types 0, 1, 4 are nanoseconds, type 3 is UTC).

#include <streamclust/io/input_stream.hpp>

#include <cmath>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>

namespace streamclust::io {

/// How the coordinates of one point struct are stored.
enum class LivoxCoordinates : unsigned char {
  none,           ///< IMU data: no point
  cartesian_mm,   ///< int32 x, y, z [mm]
  cartesian_cm,   ///< int16 x, y, z [cm]
  spherical_mm,   ///< uint32 depth [mm], uint16 zenith theta and azimuth phi [0.01 deg]
  cartesian_m32,  ///< float32 x, y, z [m] (LVX 1.0 packages)
};

/// A point data type: the layout of the structs that follow a package header.
/// One struct is one firing; it holds `returns` points (dual and triple return
/// types share one direction, spherical ones also one pair of angles).
struct LivoxDataType {
  std::uint8_t value;                  ///< data_type byte of the package header
  const char* name;                    ///< e.g. "dual extended cartesian"
  LivoxCoordinates coordinates;
  std::uint8_t returns;                ///< points per struct (0 for IMU)
  std::uint8_t struct_bytes;           ///< bytes per struct
  std::uint8_t structs_per_package;    ///< fixed count in an SDK 1 package; 0: the package's length says (LVX2)
  bool has_tag;                        ///< the struct carries a tag byte per return
};

namespace detail {

inline constexpr LivoxDataType sdk1_data_types[] = {
    {0, "cartesian", LivoxCoordinates::cartesian_mm, 1, 13, 100, false},
    {1, "spherical", LivoxCoordinates::spherical_mm, 1, 9, 100, false},
    {2, "extended cartesian", LivoxCoordinates::cartesian_mm, 1, 14, 96, true},
    {3, "extended spherical", LivoxCoordinates::spherical_mm, 1, 10, 96, true},
    {4, "dual extended cartesian", LivoxCoordinates::cartesian_mm, 2, 28, 48, true},
    {5, "dual extended spherical", LivoxCoordinates::spherical_mm, 2, 16, 48, true},
    {6, "IMU", LivoxCoordinates::none, 0, 24, 1, false},
    {7, "triple extended cartesian", LivoxCoordinates::cartesian_mm, 3, 42, 30, true},
    {8, "triple extended spherical", LivoxCoordinates::spherical_mm, 3, 22, 30, true},
};

/// The package body of LVX 1.0: 100 float points, whatever its data_type byte.
inline constexpr LivoxDataType lvx10_points = {0, "float cartesian (LVX 1.0)", LivoxCoordinates::cartesian_m32, 1,
                                               13, 100, false};

inline constexpr LivoxDataType lvx2_data_types[] = {
    {1, "cartesian (mm)", LivoxCoordinates::cartesian_mm, 1, 14, 0, true},
    {2, "cartesian (cm)", LivoxCoordinates::cartesian_cm, 1, 8, 0, true},
};

}  // namespace detail

/// The SDK 1 (LVX 1.1) data type `value`, or nullptr when it is none of 0-8.
inline const LivoxDataType* find_sdk1_data_type(std::uint8_t value) noexcept {
  return value < std::size(detail::sdk1_data_types) ? &detail::sdk1_data_types[value] : nullptr;
}

/// The LVX2 data type `value` (1 or 2), or nullptr.
inline const LivoxDataType* find_lvx2_data_type(std::uint8_t value) noexcept {
  for (const auto& t : detail::lvx2_data_types)
    if (t.value == value) return &t;
  return nullptr;
}

/// One point of a struct: coordinates [m] rounded to float, reflectivity (0-255) and tag.
struct LivoxReturn {
  float x = 0, y = 0, z = 0;
  std::uint8_t reflectivity = 0;
  std::uint8_t tag = 0;
};

namespace detail {

/// Integer millimetres (centimetres) to metres: the double quotient is
/// rounded once more to float, which gives the float nearest to the exact
/// decimal (a quotient of a 32-bit integer by 10^k never lands on a float
/// rounding boundary).
inline float livox_metres(std::int64_t value, double per_metre) noexcept {
  return static_cast<float>(static_cast<double>(value) / per_metre);
}

/// Spherical to Cartesian: theta is the zenith angle, phi the azimuth, both
/// in 0.01 degree (livox_def.h; lds.h `RawPointConvert`), computed in double.
inline void livox_spherical(std::uint32_t depth_mm, std::uint16_t theta, std::uint16_t phi, LivoxReturn& r) noexcept {
  constexpr double radians_per_hundredth = 3.14159265358979323846 / 18000.0;
  const double range = static_cast<double>(depth_mm) / 1000.0;
  const double t = static_cast<double>(theta) * radians_per_hundredth;
  const double p = static_cast<double>(phi) * radians_per_hundredth;
  r.x = static_cast<float>(range * std::sin(t) * std::cos(p));
  r.y = static_cast<float>(range * std::sin(t) * std::sin(p));
  r.z = static_cast<float>(range * std::cos(t));
}

}  // namespace detail

/// Returns per firing of the richest data type (triple return).
inline constexpr std::size_t max_livox_returns = 3;

/// Decodes the struct at `p` (`type.struct_bytes` bytes) into `type.returns`
/// points written to `out` (room for max_livox_returns); returns how many. Every bit pattern
/// decodes (float coordinates may be NaN or infinite). O(1); thread-safe.
inline std::size_t decode_livox_struct(const LivoxDataType& type, const unsigned char* p, LivoxReturn* out) noexcept {
  using detail::load_le;
  const std::size_t n = std::min<std::size_t>(type.returns, max_livox_returns);  // the caller's room
  switch (type.coordinates) {
    case LivoxCoordinates::none: return 0;
    case LivoxCoordinates::cartesian_mm: {
      const std::size_t stride = type.has_tag ? 14 : 13;
      for (std::size_t k = 0; k < n; ++k, p += stride) {
        out[k].x = detail::livox_metres(load_le<std::int32_t>(p), 1000.0);
        out[k].y = detail::livox_metres(load_le<std::int32_t>(p + 4), 1000.0);
        out[k].z = detail::livox_metres(load_le<std::int32_t>(p + 8), 1000.0);
        out[k].reflectivity = p[12];
        out[k].tag = type.has_tag ? p[13] : 0;
      }
      return n;
    }
    case LivoxCoordinates::cartesian_cm:
      out[0].x = detail::livox_metres(load_le<std::int16_t>(p), 100.0);
      out[0].y = detail::livox_metres(load_le<std::int16_t>(p + 2), 100.0);
      out[0].z = detail::livox_metres(load_le<std::int16_t>(p + 4), 100.0);
      out[0].reflectivity = p[6];
      out[0].tag = p[7];
      return 1;
    case LivoxCoordinates::cartesian_m32:
      out[0].x = load_le<float>(p);
      out[0].y = load_le<float>(p + 4);
      out[0].z = load_le<float>(p + 8);
      out[0].reflectivity = p[12];
      out[0].tag = 0;
      return 1;
    case LivoxCoordinates::spherical_mm:
      if (n == 1) {  // depth, theta, phi, reflectivity[, tag]
        detail::livox_spherical(load_le<std::uint32_t>(p), load_le<std::uint16_t>(p + 4),
                                load_le<std::uint16_t>(p + 6), out[0]);
        out[0].reflectivity = p[8];
        out[0].tag = type.has_tag ? p[9] : 0;
        return 1;
      }
      // theta, phi, then per return: depth, reflectivity, tag
      for (std::size_t k = 0; k < n; ++k) {
        const unsigned char* r = p + 4 + 6 * k;
        detail::livox_spherical(load_le<std::uint32_t>(r), load_le<std::uint16_t>(p), load_le<std::uint16_t>(p + 2),
                                out[k]);
        out[k].reflectivity = r[4];
        out[k].tag = r[5];
      }
      return n;
  }
  return 0;
}

/// A device type and the time between two of its firings [ns]. A package's
/// timestamp is the time of its first firing; firing k of the package is at
/// timestamp + k x interval, and the returns of one firing share its time.
///
/// - SDK 1 types: `livox_ros_driver:lds.h` `product_type_info_pair_table`, which the
///   driver uses when it converts LVX files to bags (`lddc.cpp`
///   `FillPointsToCustomMsg`: offset = k / echo_num x point_interval): 10,000 ns
///   (100 kHz) for Hub, Mid-40 and Mid-70; 4,167 ns (240 kHz) for Tele-15, Horizon,
///   Avia. With dual or triple returns these rates count firings: an Avia's
///   480,000 (720,000) points per second are 240,000 firings of 2 (3) returns.
/// - Mid-360: 200,000 points per second (Mid-360 specifications), one return:
///   5,000 ns. (Livox's own sample recording replays as 20,064 points per 100 ms,
///   a 0.3 % difference.)
/// - HAP: 452,000 points per second (HAP user manual, specifications): 2,212 ns.
/// LVX2 packages carry no time_interval (the SDK 2 UDP header does), so these
/// nominal intervals stand in for it.
struct LivoxDeviceType {
  std::uint8_t value;               ///< device_type byte of the device info
  const char* name;                 ///< "Avia", "Mid-360", ...
  std::uint32_t firing_interval_ns; ///< time between two firings [ns]
};

namespace detail {

inline constexpr LivoxDeviceType sdk1_device_types[] = {
    {0, "Hub", 10000},     {1, "Mid-40", 10000}, {2, "Tele-15", 4167},
    {3, "Horizon", 4167},  {6, "Mid-70", 10000}, {7, "Avia", 4167},
};

inline constexpr LivoxDeviceType lvx2_device_types[] = {{9, "Mid-360", 5000}, {10, "HAP", 2212}};

}  // namespace detail

/// The SDK 1 (LVX 1.x) device type `value`, or nullptr.
inline const LivoxDeviceType* find_sdk1_device_type(std::uint8_t value) noexcept {
  for (const auto& t : detail::sdk1_device_types)
    if (t.value == value) return &t;
  return nullptr;
}

/// The LVX2 device type `value` (9 Mid-360, 10 HAP), or nullptr.
inline const LivoxDeviceType* find_lvx2_device_type(std::uint8_t value) noexcept {
  for (const auto& t : detail::lvx2_device_types)
    if (t.value == value) return &t;
  return nullptr;
}

namespace detail {

/// Days from 1970-01-01 to the civil date y-m-d (proleptic Gregorian).
constexpr std::int64_t days_from_civil(std::int64_t y, int m, int d) noexcept {
  y -= m <= 2 ? 1 : 0;
  const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
  const std::int64_t yoe = y - era * 400;
  const std::int64_t doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
  const std::int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

constexpr int days_in_month(std::int64_t y, int m) noexcept {
  constexpr int days[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
  return m == 2 && leap ? 29 : days[m - 1];
}

}  // namespace detail

/// The time [ns since 1970] of an SDK 1 type 3 (PPS + GPS, UTC) timestamp,
/// the 8 bytes at `p`: year - 2000, month, day, hour (one byte each), then
/// uint32 microseconds within the hour. False for fields out of range (an
/// impossible date, hour 24, an hour of more than 3600 s). O(1), noexcept.
inline bool decode_sdk1_utc_timestamp(const unsigned char* p, std::uint64_t& ns) noexcept {
  const std::int64_t year = 2000 + p[0];
  const int month = p[1], day = p[2], hour = p[3];
  const std::uint32_t us = detail::load_le<std::uint32_t>(p + 4);
  if (month < 1 || month > 12 || day < 1 || day > detail::days_in_month(year, month) || hour > 23 ||
      us >= 3600000000u)
    return false;
  const std::int64_t seconds = detail::days_from_civil(year, month, day) * 86400 + hour * 3600;
  ns = static_cast<std::uint64_t>(seconds) * 1000000000u + std::uint64_t{us} * 1000u;
  return true;
}

/// The inverse of decode_sdk1_utc_timestamp: writes the 8 bytes of `ns`
/// [since 1970] at `p`, rounded down to the microsecond. False (and nothing
/// written) for a time outside the years 2000-2255 the format can hold. O(1).
inline bool encode_sdk1_utc_timestamp(std::uint64_t ns, unsigned char* p) noexcept {
  const std::uint64_t seconds = ns / 1000000000u;
  const std::int64_t days = static_cast<std::int64_t>(seconds / 86400);
  // Civil date from days since 1970-01-01 (the inverse of days_from_civil; days >= 0).
  const std::int64_t z = days + 719468;
  const std::int64_t era = z / 146097;
  const std::int64_t doe = z - era * 146097;
  const std::int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const std::int64_t mp = (5 * doy + 2) / 153;
  const int day = static_cast<int>(doy - (153 * mp + 2) / 5 + 1);
  const int month = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
  const std::int64_t year = yoe + era * 400 + (month <= 2 ? 1 : 0);
  if (year < 2000 || year > 2255) return false;
  const std::uint64_t second_of_day = seconds % 86400;
  const auto us = static_cast<std::uint32_t>((second_of_day % 3600) * 1000000u + (ns % 1000000000u) / 1000u);
  p[0] = static_cast<unsigned char>(year - 2000);
  p[1] = static_cast<unsigned char>(month);
  p[2] = static_cast<unsigned char>(day);
  p[3] = static_cast<unsigned char>(second_of_day / 3600);
  for (int k = 0; k < 4; ++k) p[4 + k] = static_cast<unsigned char>(us >> (8 * k));
  return true;
}

/// The time [ns since 1970] of an SDK 1 (LVX 1.x) package timestamp of type
/// `type`, the 8 bytes at `p`. Types 0 (no sync), 1 (PTP) and 4 (PPS) are a
/// uint64 of nanoseconds; type 3 (PPS + GPS) is UTC: year - 2000, month, day,
/// hour (one byte each), then uint32 microseconds within the hour. Returns
/// false and says why in `why` for type 2 (reserved), types above 4 and UTC
/// fields out of range. O(1).
inline bool decode_sdk1_timestamp(std::uint8_t type, const unsigned char* p, std::uint64_t& ns, std::string& why) {
  if (type == 0 || type == 1 || type == 4) {
    ns = detail::load_le<std::uint64_t>(p);
    return true;
  }
  if (type == 3) {
    if (decode_sdk1_utc_timestamp(p, ns)) return true;
    why = "timestamp type 3 (PPS + GPS, UTC): expected year - 2000, month 1-12, a day of that month, hour 0-23 "
          "and microseconds within the hour (below 3600000000), found " +
          std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) + ", " +
          std::to_string(p[3]) + ", " + std::to_string(detail::load_le<std::uint32_t>(p + 4));
    return false;
  }
  why = "unknown timestamp type " + std::to_string(type) +
        ": expected 0 (no sync), 1 (PTP), 3 (PPS + GPS, UTC) or 4 (PPS); type 2 is reserved";
  return false;
}

/// The time [ns] of an LVX2 package timestamp of type `type` (0 LiDAR system
/// time, 1 gPTP / PTP, 2 GPS: always a uint64 of nanoseconds, only the clock
/// differs). Returns false and says why for other types. O(1).
inline bool decode_lvx2_timestamp(std::uint8_t type, const unsigned char* p, std::uint64_t& ns, std::string& why) {
  if (type <= 2) {
    ns = detail::load_le<std::uint64_t>(p);
    return true;
  }
  why = "unknown timestamp type " + std::to_string(type) + ": expected 0 (no sync), 1 (gPTP / PTP) or 2 (GPS)";
  return false;
}

}  // namespace streamclust::io
