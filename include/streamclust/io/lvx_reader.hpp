// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Streaming reader of Livox Viewer recordings: LVX 1.0 and 1.1 (Livox Viewer
/// 1, SDK 1 LiDARs: Mid-40/100, Mid-70, Horizon, Tele-15, Avia) and LVX2
/// (Livox Viewer 2: Mid-360, HAP); and `summarize_lvx`, the whole file in
/// figures for `streamclust info`.
///
/// Layout (little-endian, packed; docs/io.md has the full table):
///
///     public header    24 B   "livox_tech" + 6 zero bytes, version[4], u32 magic 0xAC0EA767
///     private header          LVX 1.1, LVX2: u32 frame_duration [ms], u8 device_count; LVX 1.0: u8 device_count
///     device info x N         LVX 1.0 58 B, LVX 1.1 59 B, LVX2 63 B
///     frames until the end    header: u64 current_offset, u64 next_offset, u64 frame_index
///                             (LVX 1.0: + u64 packet_count), then packages up to next_offset
///     package                 LVX 1.x: 19 B header + a fixed count of point structs per data type
///                             LVX2: 27 B header (with u32 length) + length bytes of points
///
/// Sources: `Livox-SDK/Livox-SDK:sample/lidar_lvx_file/lvx_file.h` (the LVX 1.1
/// writer), `Livox-SDK/livox_ros_driver:livox_ros_driver/livox_ros_driver/lvx_file.h,
/// lvx_file.cpp, lds_lvx.cpp` (the reader of LVX 1.0 and 1.1 that converts them to
/// bags), "LVX2 Specifications" v1.0 (Livox, 2023). Point structs, firing
/// intervals and timestamps: livox_packet.hpp.
///
/// Every record is one return of the chosen LiDAR: x, y, z [m] in that
/// LiDAR's own frame (the header's extrinsics are reported by
/// `summarize_lvx`, not applied), intensity = reflectivity, time = package
/// timestamp + firing index x the device's firing interval [ns]. IMU packages
/// and packages of other LiDARs are skipped; the whole file is validated.

#include <streamclust/io/error.hpp>
#include <streamclust/io/input_stream.hpp>
#include <streamclust/io/livox_packet.hpp>
#include <streamclust/io/point_reader.hpp>
#include <streamclust/io/record.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace streamclust::io {

/// The three layouts.
enum class LvxVersion { v1_0, v1_1, v2 };

/// A LiDAR the header declares.
struct LvxDevice {
  /// What selects it (`ReadOptions::topic`, besides its serial): LVX 1.x its
  /// device_index (the packages name it); LVX2 its position in the header, from 0.
  std::uint32_t index = 0;
  /// LiDAR serial number (broadcast code): the bytes before the first NUL,
  /// as they are (print through `detail::printable`).
  std::string serial;
  /// The hub's serial number, "" without a hub (Livox Viewer 2's own files
  /// hold uninitialised bytes here).
  std::string hub_serial;
  /// LVX2: the id its packages carry (Livox Viewer 2 writes the IPv4 address as a u32).
  std::optional<std::uint32_t> lidar_id;
  std::uint8_t device_type = 0;
  std::string type_name;   ///< "Avia", "Mid-360", ... or "unknown"
  bool extrinsic_enabled = false;    ///< LVX 1.0 has no such flag: false
  float roll = 0, pitch = 0, yaw = 0;  ///< extrinsic rotation [deg], as written (not applied)
  float x = 0, y = 0, z = 0;           ///< extrinsic translation [m by the specification], as written
  std::uint64_t offset = 0;            ///< byte of its device info record
};

/// One device's share of a file (`summarize_lvx`).
struct LvxDeviceSummary {
  LvxDevice device;
  std::uint64_t point_packages = 0;  ///< packages with points
  std::uint64_t imu_packages = 0;    ///< IMU packages (LVX 1.1), skipped by the reader
  std::uint64_t points = 0;          ///< records `LvxReader` returns for this device
  /// Earliest and latest point time [ns] (package timestamp + firing offset;
  /// firing offsets 0 for an unknown device type); none without points.
  std::optional<std::uint64_t> first_ns, last_ns;
};

/// A whole LVX / LVX2 file in figures.
struct LvxSummary {
  LvxVersion version = LvxVersion::v1_1;
  std::string encoding;                         ///< "lvx 1.0", "lvx 1.1", "lvx2"
  std::optional<std::uint32_t> frame_duration_ms;  ///< none in LVX 1.0
  std::vector<LvxDeviceSummary> devices;        ///< in header order
  std::uint64_t frames = 0;
  std::uint64_t packages = 0;                   ///< of every device and kind
  std::uint64_t points = 0;                     ///< of every device
  std::optional<std::uint64_t> first_ns, last_ns;  ///< over every device's points
};

namespace detail {

inline constexpr std::uint32_t lvx_magic = 0xAC0EA767u;

/// The device type `value` in a file of `version`, or nullptr.
inline const LivoxDeviceType* find_lvx_device_type(LvxVersion version, std::uint8_t value) noexcept {
  return version == LvxVersion::v2 ? find_lvx2_device_type(value) : find_sdk1_device_type(value);
}

/// A package header, validated.
struct LvxPackage {
  std::uint64_t offset = 0;            ///< byte of its header
  std::uint64_t timestamp_offset = 0;  ///< byte of its timestamp field
  std::size_t device = 0;              ///< position in `LvxFile::devices()`
  const LivoxDataType* type = nullptr;
  std::uint64_t structs = 0;           ///< point structs (firings) in its body
  std::uint64_t timestamp_ns = 0;
};

/// The time [ns] of firing `firing` of `package`, or an InputError at its
/// timestamp when the sum overflows 64 bits.
inline std::uint64_t lvx_firing_time(const std::string& path, const LvxPackage& package, std::uint64_t firing,
                                     std::uint32_t interval_ns) {
  std::uint64_t offset = 0, t = 0;
  if (__builtin_mul_overflow(firing, std::uint64_t{interval_ns}, &offset) ||
      __builtin_add_overflow(package.timestamp_ns, offset, &t)) {
    throw InputError(path, where_byte(package.timestamp_offset),
                     "package timestamp " + std::to_string(package.timestamp_ns) + " ns + " + std::to_string(firing) +
                         " firings x " + std::to_string(interval_ns) + " ns overflows 64 bits");
  }
  return t;
}

/// The container of an LVX / LVX2 file: headers and device list at open, then
/// frames and packages in file order, each validated before it is used (frame
/// chain, package sizes against their frame, data types, devices,
/// timestamps: their type, UTC fields, and the last firing's time within 64
/// bits, whatever the device). Reads sequentially through one 64 KiB buffer; memory is
/// bounded by the device list (at most 255). Not thread-safe.
class LvxFile {
 public:
  /// Opens `path` and reads the headers; throws InputError.
  explicit LvxFile(const std::string& path) : src_(path) { read_headers(); }

  const std::string& path() const noexcept { return src_.path(); }
  LvxVersion version() const noexcept { return version_; }
  const char* encoding() const noexcept {
    return version_ == LvxVersion::v1_0 ? "lvx 1.0" : version_ == LvxVersion::v1_1 ? "lvx 1.1" : "lvx2";
  }
  std::optional<std::uint32_t> frame_duration_ms() const noexcept { return frame_duration_ms_; }
  const std::vector<LvxDevice>& devices() const noexcept { return devices_; }
  /// Frame headers read so far.
  std::uint64_t frames() const noexcept { return frames_; }
  /// The firing interval [ns] of device `k` (position in `devices()`); 0 for an unknown device type.
  std::uint32_t firing_interval_ns(std::size_t k) const noexcept { return intervals_ns_[k]; }

  /// Reads the next package header (skipping what is left of the previous
  /// package's body, and crossing frame headers); the source then stands at
  /// the package's body. False at the end of the file, which must come right
  /// after a frame. Throws InputError.
  bool next_package(LvxPackage& out) {
    if (src_.offset() < body_end_) skip_exact(body_end_ - src_.offset(), "package");
    while (!in_frame_ || src_.offset() == frame_end_) {
      if (!next_frame()) return false;
    }
    read_package_header(out);
    return true;
  }

  /// Reads the next `n` bytes of the current package's body into `dst`.
  void read_body(unsigned char* dst, std::size_t n) {
    if (src_.offset() + n > body_end_) {
      throw InputError(path(), where_byte(src_.offset()), "read past the end of a package body (a reader bug)");
    }
    read_exact(dst, n, "package");
  }

 private:
  // ------------------------------------------------------------- headers
  void read_headers() {
    unsigned char h[24];
    read_exact(h, sizeof h, "public header");
    static const char signature[16] = {'l', 'i', 'v', 'o', 'x', '_', 't', 'e', 'c', 'h', 0, 0, 0, 0, 0, 0};
    if (std::memcmp(h, signature, 16) != 0) {
      throw InputError(path(), "byte 0",
                       "not an LVX file: expected the signature \"livox_tech\" and 6 zero bytes, found " +
                           detail::quoted(std::string(reinterpret_cast<const char*>(h), 16)));
    }
    if (h[16] == 1 && h[17] <= 1) {
      version_ = h[17] == 0 ? LvxVersion::v1_0 : LvxVersion::v1_1;
    } else if (h[16] == 2 && h[17] == 0) {
      version_ = LvxVersion::v2;
    } else {
      throw InputError(path(), "byte 16",
                       "unsupported LVX version " + std::to_string(h[16]) + "." + std::to_string(h[17]) + "." +
                           std::to_string(h[18]) + "." + std::to_string(h[19]) +
                           ": expected 1.0, 1.1 (LVX) or 2.0 (LVX2)");
    }
    const auto magic = load_le<std::uint32_t>(h + 20);
    if (magic != lvx_magic) {
      throw InputError(path(), "byte 20", "wrong magic code " + hex32(magic) + ": expected 0xac0ea767");
    }

    std::uint64_t count_offset = 24;
    if (version_ != LvxVersion::v1_0) {
      unsigned char d[4];
      read_exact(d, 4, "private header");
      frame_duration_ms_ = load_le<std::uint32_t>(d);
      count_offset = 28;
    }
    unsigned char count = 0;
    read_exact(&count, 1, "private header");
    if (count == 0) {
      throw InputError(path(), where_byte(count_offset), "device count 0: expected at least one LiDAR");
    }
    const std::size_t record = version_ == LvxVersion::v1_0 ? 58 : version_ == LvxVersion::v1_1 ? 59 : 63;
    unsigned char r[63];
    for (std::size_t i = 0; i < count; ++i) {
      LvxDevice d;
      d.offset = src_.offset();
      read_exact(r, record, "device info");
      read_device(r, i, d);
      const LivoxDeviceType* type = find_lvx_device_type(version_, d.device_type);
      intervals_ns_.push_back(type ? type->firing_interval_ns : 0);
      devices_.push_back(std::move(d));
    }
  }

  void read_device(const unsigned char* r, std::size_t position, LvxDevice& d) {
    d.serial = c_string(r, 16);
    d.hub_serial = c_string(r + 16, 16);
    std::size_t p = 32;
    if (version_ == LvxVersion::v2) {
      d.lidar_id = load_le<std::uint32_t>(r + 32);
      d.index = static_cast<std::uint32_t>(position);
      d.device_type = r[37];  // r[36]: lidar_type, reserved
      d.extrinsic_enabled = r[38] != 0;
      p = 39;
    } else {
      d.index = r[32];
      d.device_type = r[33];
      p = 34;
      if (version_ == LvxVersion::v1_1) d.extrinsic_enabled = r[p++] != 0;
    }
    const LivoxDeviceType* type = find_lvx_device_type(version_, d.device_type);
    d.type_name = type ? type->name : "unknown";
    d.roll = load_le<float>(r + p);
    d.pitch = load_le<float>(r + p + 4);
    d.yaw = load_le<float>(r + p + 8);
    d.x = load_le<float>(r + p + 12);
    d.y = load_le<float>(r + p + 16);
    d.z = load_le<float>(r + p + 20);
    for (std::size_t k = 0; k < devices_.size(); ++k) {
      const LvxDevice& e = devices_[k];
      const bool same = version_ == LvxVersion::v2 ? e.lidar_id == d.lidar_id : e.index == d.index;
      if (same) {
        const std::string what = version_ == LvxVersion::v2 ? "LiDAR id " + std::to_string(*d.lidar_id)
                                                             : "device index " + std::to_string(d.index);
        throw InputError(path(), where_byte(d.offset + 32),
                         what + " appears twice in the header (devices " + std::to_string(k) + " and " +
                             std::to_string(position) + " from 0): expected each device once");
      }
    }
  }

  // -------------------------------------------------------------- frames
  bool next_frame() {
    const std::uint64_t at = src_.offset();
    const std::size_t size = version_ == LvxVersion::v1_0 ? 32 : 24;
    unsigned char h[32];
    const std::size_t got = src_.read(reinterpret_cast<char*>(h), size);
    if (got == 0) return false;  // the end of the file, right after a frame
    if (got < size) {
      throw InputError(path(), where_byte(at + got),
                       "truncated frame header: expected " + std::to_string(size) + " bytes from byte " +
                           std::to_string(at) + ", the file ends after " + std::to_string(got) +
                           (std::all_of(h, h + got, [](unsigned char c) { return c == 0; })
                                ? " (all zero: padding after the last frame?)"
                                : ""));
    }
    const auto current = load_le<std::uint64_t>(h);
    const auto next = load_le<std::uint64_t>(h + 8);
    if (current != at) {
      const bool zero = std::all_of(h, h + size, [](unsigned char c) { return c == 0; });
      throw InputError(path(), where_byte(at),
                       "frame header: current_offset is " + std::to_string(current) + ", expected " +
                           std::to_string(at) + " (the position of the frame)" +
                           (zero ? "; the header is all zero bytes: padding after the last frame?" : ""));
    }
    if (next < at + size) {
      throw InputError(path(), where_byte(at + 8),
                       "frame header: next_offset " + std::to_string(next) + " points back: expected at least " +
                           std::to_string(at + size) + " (the end of this frame header)");
    }
    if (src_.size() != std::numeric_limits<std::uint64_t>::max() && next > src_.size()) {
      throw InputError(path(), where_byte(at + 8),
                       "frame header: next_offset " + std::to_string(next) + " is beyond the end of the file (" +
                           std::to_string(src_.size()) + " bytes)");
    }
    if (version_ == LvxVersion::v1_0) {
      const auto packets = load_le<std::uint64_t>(h + 24);
      const std::uint64_t bytes = next - at - size;
      const std::uint64_t package = 19 + std::uint64_t{detail::lvx10_points.struct_bytes} * 100;
      if (packets > bytes / package || packets * package != bytes) {
        throw InputError(path(), where_byte(at + 24),
                         "frame header: packet_count " + std::to_string(packets) + " does not match the frame: " +
                             std::to_string(bytes) + " bytes of packages (next_offset - current_offset - 32) hold " +
                             (bytes % package == 0 ? std::to_string(bytes / package)
                                                   : "no whole number of") +
                             " packages of " + std::to_string(package) + " bytes");
      }
    }
    frame_end_ = next;
    in_frame_ = true;
    ++frames_;
    return true;
  }

  // ------------------------------------------------------------ packages
  void read_package_header(LvxPackage& out) {
    const std::uint64_t at = src_.offset();
    const std::size_t size = version_ == LvxVersion::v2 ? 27 : 19;
    const std::uint64_t left = frame_end_ - at;
    if (left < size) {
      throw InputError(path(), where_byte(at),
                       std::to_string(left) + " bytes left in the frame (it ends at byte " +
                           std::to_string(frame_end_) + ", its next_offset): too few for a package header of " +
                           std::to_string(size) + " bytes");
    }
    unsigned char h[27];
    read_exact(h, size, "package header");
    out.offset = at;
    std::uint64_t body = 0;
    std::string why;
    if (version_ == LvxVersion::v2) {
      const auto id = load_le<std::uint32_t>(h + 1);
      out.device = find_device(
          [&](const LvxDevice& d) { return d.lidar_id == id; }, at + 1, "LiDAR id " + std::to_string(id));
      out.type = find_lvx2_data_type(h[17]);
      if (!out.type) {
        throw InputError(path(), where_byte(at + 17),
                         "unknown data type " + std::to_string(h[17]) +
                             ": expected 1 (cartesian, int32 mm, 14 bytes per point) or 2 (cartesian, int16 cm, 8 "
                             "bytes per point)");
      }
      body = load_le<std::uint32_t>(h + 18);
      if (body % out.type->struct_bytes != 0) {
        throw InputError(path(), where_byte(at + 18),
                         "package length " + std::to_string(body) + " is not a whole number of points: data type " +
                             std::to_string(out.type->value) + " has " + std::to_string(out.type->struct_bytes) +
                             " bytes per point");
      }
      if (size + body > left) {
        throw InputError(path(), where_byte(at + 18),
                         "package length " + std::to_string(body) + " does not fit its frame: the package would end "
                         "at byte " + std::to_string(at + size + body) + ", the frame ends at byte " +
                             std::to_string(frame_end_) + " (its next_offset)");
      }
      out.structs = body / out.type->struct_bytes;
      out.timestamp_offset = at + 7;
      if (!decode_lvx2_timestamp(h[6], h + 7, out.timestamp_ns, why)) {
        throw InputError(path(), where_byte(at + 6), why);
      }
    } else {
      const unsigned char index = h[0];
      out.device = find_device([&](const LvxDevice& d) { return d.index == index; }, at,
                               "device index " + std::to_string(index));
      if (version_ == LvxVersion::v1_0) {
        if (h[10] != 0) {
          throw InputError(path(), where_byte(at + 10),
                           "data type " + std::to_string(h[10]) +
                               " in an LVX 1.0 package: expected 0 (LVX 1.0 packages hold 100 float points)");
        }
        out.type = &detail::lvx10_points;
      } else {
        out.type = find_sdk1_data_type(h[10]);
        if (!out.type) {
          throw InputError(path(), where_byte(at + 10),
                           "unknown data type " + std::to_string(h[10]) +
                               ": expected 0-8 (0 cartesian, 1 spherical, 2 extended cartesian, 3 extended "
                               "spherical, 4/5 dual, 6 IMU, 7/8 triple)");
        }
      }
      out.structs = out.type->structs_per_package;
      body = out.structs * out.type->struct_bytes;
      if (size + body > left) {
        throw InputError(path(), where_byte(at),
                         "package of data type " + std::to_string(out.type->value) + " (" + out.type->name + ", " +
                             std::to_string(out.structs) + " x " + std::to_string(out.type->struct_bytes) +
                             " bytes) needs " + std::to_string(size + body) + " bytes, its frame has " +
                             std::to_string(left) + " left (it ends at byte " + std::to_string(frame_end_) + ")");
      }
      out.timestamp_offset = at + 11;
      if (!decode_sdk1_timestamp(h[9], h + 11, out.timestamp_ns, why)) {
        throw InputError(path(), where_byte(at + 9), why);
      }
    }
    if (out.structs > 0 && out.type->returns > 0)  // the last firing's time fits 64 bits, so every one does
      lvx_firing_time(path(), out, out.structs - 1, intervals_ns_[out.device]);
    body_end_ = at + size + body;
  }

  template <class Match>
  std::size_t find_device(Match match, std::uint64_t where, const std::string& what) const {
    for (std::size_t k = 0; k < devices_.size(); ++k)
      if (match(devices_[k])) return k;
    std::string declared;
    for (std::size_t k = 0; k < devices_.size() && k < 16; ++k) {
      if (k) declared += ", ";
      declared += std::to_string(version_ == LvxVersion::v2 ? *devices_[k].lidar_id : devices_[k].index);
    }
    if (devices_.size() > 16) declared += ", ...";
    throw InputError(path(), where_byte(where),
                     "package of " + what + ", which the header does not declare (declared: " + declared + ")");
  }

  // ------------------------------------------------------------- helpers
  void read_exact(unsigned char* dst, std::size_t n, const char* what) {
    const std::uint64_t at = src_.offset();
    const std::size_t got = src_.read(reinterpret_cast<char*>(dst), n);
    if (got < n) {
      throw InputError(path(), where_byte(at + got),
                       std::string("truncated ") + what + ": expected " + std::to_string(n) + " bytes from byte " +
                           std::to_string(at) + ", the file ends after " + std::to_string(got));
    }
  }

  void skip_exact(std::uint64_t n, const char* what) {
    const std::uint64_t at = src_.offset();
    const std::uint64_t got = src_.skip(n);
    if (got < n) {
      throw InputError(path(), where_byte(at + got),
                       std::string("truncated ") + what + ": expected " + std::to_string(n) + " more bytes from byte " +
                           std::to_string(at) + ", the file ends after " + std::to_string(got));
    }
  }

  static std::string c_string(const unsigned char* p, std::size_t n) {
    const auto* c = reinterpret_cast<const char*>(p);
    return std::string(c, static_cast<std::size_t>(std::find(c, c + n, '\0') - c));
  }

  static std::string hex32(std::uint32_t v) {
    static const char* digits = "0123456789abcdef";
    std::string s = "0x";
    for (int shift = 28; shift >= 0; shift -= 4) s += digits[(v >> shift) & 15u];
    return s;
  }

  ByteSource src_;
  LvxVersion version_ = LvxVersion::v1_1;
  std::optional<std::uint32_t> frame_duration_ms_;
  std::vector<LvxDevice> devices_;
  std::vector<std::uint32_t> intervals_ns_;  // per device; 0 for an unknown type
  bool in_frame_ = false;
  std::uint64_t frame_end_ = 0;
  std::uint64_t body_end_ = 0;
  std::uint64_t frames_ = 0;
};

/// "index 0: serial 3GGDJ6K00100101, Avia; index 1: ..." (at most 16 devices).
inline std::string describe_lvx_devices(const std::vector<LvxDevice>& devices) {
  std::string s;
  for (std::size_t k = 0; k < devices.size() && k < 16; ++k) {
    const LvxDevice& d = devices[k];
    if (k) s += "; ";
    s += "index " + std::to_string(d.index) + ": serial " + detail::quoted(d.serial) + ", " + d.type_name;
    if (d.type_name == "unknown") s += " (type " + std::to_string(d.device_type) + ")";
    if (d.lidar_id) s += ", lidar id " + std::to_string(*d.lidar_id);
  }
  if (devices.size() > 16) s += "; ... (" + std::to_string(devices.size()) + " in all)";
  return s;
}

/// The device `topic` names: its serial number, or its index as a decimal
/// number; without a topic the only device. Throws InputError ("header")
/// naming the devices when there is no single answer.
inline std::size_t select_lvx_device(const std::vector<LvxDevice>& devices, const std::optional<std::string>& topic,
                                     const std::string& path) {
  if (!topic) {
    if (devices.size() == 1) return 0;
    throw InputError(path, "header",
                     std::to_string(devices.size()) +
                         " LiDARs in the file: choose one by serial number or index (--topic): " +
                         describe_lvx_devices(devices));
  }
  std::optional<std::uint64_t> number;
  std::uint64_t parsed = 0;
  if (topic->size() <= 10 && std::all_of(topic->begin(), topic->end(), [](char c) { return c >= '0' && c <= '9'; }) &&
      parse_uint64(*topic, parsed))
    number = parsed;
  std::vector<std::size_t> matches;
  for (std::size_t k = 0; k < devices.size(); ++k)
    if (devices[k].serial == *topic || (number && devices[k].index == *number)) matches.push_back(k);
  if (matches.size() == 1) return matches.front();
  throw InputError(path, "header",
                   std::string(matches.empty() ? "no LiDAR has" : "several LiDARs have") + " the serial number or index " +
                       detail::quoted(*topic) + ": the file holds " + describe_lvx_devices(devices));
}

}  // namespace detail

/// Reader of LVX 1.0 / 1.1 and LVX2 files (see the file comment). Records
/// come in file order, one per return of the chosen LiDAR; time in ns
/// (`ReadOptions::time_unit` and `point_rate` are ignored: the format fixes
/// the unit). Memory: one point struct and one file buffer (64 KiB), whatever
/// the file size.
///
///     io::ReadOptions options;
///     options.topic = "3GGDJ6K00100101";   // or "1" (index); needed with several LiDARs
///     io::LvxReader reader("scan.lvx", options);
///     std::vector<io::Record> chunk;
///     while (chunk.clear(), reader.read(chunk, 4096) > 0) ...
///
/// Thread safety: a reader is a single-threaded object.
class LvxReader final : public PointReader {
 public:
  /// Reads the headers and chooses the LiDAR (`ReadOptions::topic`: serial
  /// number or index; required with several). Throws InputError.
  LvxReader(const std::string& path, const ReadOptions& options) : PointReader(path), file_(path) {
    selected_ = detail::select_lvx_device(file_.devices(), options.topic, path_);
    const LvxDevice& d = file_.devices()[selected_];
    interval_ns_ = file_.firing_interval_ns(selected_);
    if (interval_ns_ == 0) {
      throw InputError(path_, detail::where_byte(d.offset + (file_.version() == LvxVersion::v2 ? 37 : 33)),
                       "unknown device type " + std::to_string(d.device_type) + " of LiDAR " +
                           detail::quoted(d.serial) + ": expected " +
                           (file_.version() == LvxVersion::v2 ? "9 (Mid-360) or 10 (HAP)"
                                                              : "0 (Hub), 1 (Mid-40), 2 (Tele-15), 3 (Horizon), 6 "
                                                                "(Mid-70) or 7 (Avia)") +
                           "; without it the time between its firings is not known");
    }
    info_.format = Format::lvx;
    info_.encoding = file_.encoding();
    info_.fields = {"x", "y", "z", "reflectivity", "tag", "time"};
    info_.has_time = true;
    info_.has_intensity = true;
    info_.time_field = "time";
    ReadOptions timed = options;
    timed.time_unit = TimeUnit::ns;
    setup_time(timed, TimeUnit::ns);
  }

  /// The LiDARs the header declares, and the one read.
  const std::vector<LvxDevice>& devices() const noexcept { return file_.devices(); }
  const LvxDevice& device() const noexcept { return file_.devices()[selected_]; }
  /// The chosen device's firing interval [ns] (livox_packet.hpp).
  std::uint32_t firing_interval_ns() const noexcept { return interval_ns_; }

  /// Appends up to `max_records` records; 0 at the end. O(records + bytes
  /// skipped). Throws InputError on malformed data, naming its byte.
  std::size_t read(std::vector<Record>& out, std::size_t max_records) override {
    std::size_t n = 0;
    while (n < max_records) {
      if (next_return_ < returns_) {
        const LivoxReturn& p = pending_[next_return_++];
        Record r;
        r.x = p.x;
        r.y = p.y;
        r.z = p.z;
        r.intensity = static_cast<float>(p.reflectivity);
        r.t = next_time_unsigned(pending_ns_);
        out.push_back(r);
        ++n;
        continue;
      }
      if (next_struct_ < package_.structs) {
        unsigned char s[64];
        file_.read_body(s, package_.type->struct_bytes);
        returns_ = decode_livox_struct(*package_.type, s, pending_);
        next_return_ = 0;
        pending_ns_ = detail::lvx_firing_time(path_, package_, next_struct_, interval_ns_);
        ++next_struct_;
        continue;
      }
      if (!next_point_package()) break;
    }
    return n;
  }

 private:
  /// Moves to the next package of the chosen device with points; false at the end.
  bool next_point_package() {
    while (!done_) {
      if (!file_.next_package(package_)) {
        done_ = true;
        break;
      }
      if (package_.device == selected_ && package_.type->returns > 0 && package_.structs > 0) {
        next_struct_ = 0;
        return true;
      }
    }
    package_ = detail::LvxPackage{};
    next_struct_ = 0;
    return false;
  }

  detail::LvxFile file_;
  std::size_t selected_ = 0;
  std::uint32_t interval_ns_ = 0;
  detail::LvxPackage package_;
  std::uint64_t next_struct_ = 0;
  LivoxReturn pending_[max_livox_returns];
  std::size_t returns_ = 0, next_return_ = 0;
  std::uint64_t pending_ns_ = 0;
  bool done_ = false;
};

/// Scans `path` once (the same validation as `LvxReader`, bodies skipped) and
/// returns its figures. O(file size) time, memory bounded by the device list;
/// thread-safe (each call has its own file). Throws InputError.
inline LvxSummary summarize_lvx(const std::string& path) {
  detail::LvxFile file(path);
  LvxSummary s;
  s.version = file.version();
  s.encoding = file.encoding();
  s.frame_duration_ms = file.frame_duration_ms();
  for (const LvxDevice& d : file.devices()) s.devices.push_back(LvxDeviceSummary{d, 0, 0, 0, {}, {}});
  detail::LvxPackage p;
  while (file.next_package(p)) {
    ++s.packages;
    LvxDeviceSummary& d = s.devices[p.device];
    if (p.type->returns == 0) {
      ++d.imu_packages;
      continue;
    }
    ++d.point_packages;
    if (p.structs == 0) continue;
    const std::uint64_t first = p.timestamp_ns;
    const std::uint64_t last = detail::lvx_firing_time(path, p, p.structs - 1, file.firing_interval_ns(p.device));
    const std::uint64_t points = p.structs * p.type->returns;
    d.points += points;
    s.points += points;
    d.first_ns = d.first_ns ? std::min(*d.first_ns, first) : first;
    d.last_ns = d.last_ns ? std::max(*d.last_ns, last) : last;
    s.first_ns = s.first_ns ? std::min(*s.first_ns, first) : first;
    s.last_ns = s.last_ns ? std::max(*s.last_ns, last) : last;
  }
  s.frames = file.frames();
  return s;
}

}  // namespace streamclust::io
