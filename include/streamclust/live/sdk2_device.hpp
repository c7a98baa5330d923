// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The constants of a Livox SDK2 device (Mid-360, Mid-360S, HAP): its
/// default UDP ports, on the LiDAR and on the host, and the device types its
/// discovery answer names.
///
/// Sources: `Livox-SDK/Livox-SDK2:sdk_core/comm/define.h` (ports, `kHAP*Port`);
/// the Mid-360 wiki page "Livox Ethernet protocol", "Port Description" (host
/// ports are configurable, 5630x by default); `Livox-SDK/Livox-SDK2:include/livox_lidar_def.h`
/// (`LivoxLidarDeviceType`).
///
/// Plain constants and one lookup; thread-safe.

#include <cstdint>

namespace streamclust::live {

/// The UDP ports of one device family: where the LiDAR sends from and
/// listens, and where the host listens by default.
struct Sdk2Ports {
  std::uint16_t discovery;         ///< discovery broadcasts (cmd 0x0000), both sides
  std::uint16_t lidar_command;     ///< the LiDAR's control port (requests go here)
  std::uint16_t host_command;      ///< the host's control port (ACKs come here)
  std::uint16_t lidar_push;        ///< the LiDAR's status-push source (cmd 0x0102)
  std::uint16_t host_push;         ///< the host's status-push port
  std::uint16_t lidar_points;      ///< the LiDAR's point-packet source
  std::uint16_t host_points;       ///< the host's point-packet port
  std::uint16_t lidar_imu;         ///< the LiDAR's IMU-packet source
  std::uint16_t host_imu;          ///< the host's IMU-packet port
};

/// Mid-360 (and Mid-360S): the numbers of the port table.
inline constexpr Sdk2Ports sdk2_mid360_ports{56000, 56100, 56101, 56200, 56201, 56300, 56301, 56400, 56401};

/// HAP: commands and pushes share 56000; points from 57000, IMU from 58000
/// (`kHAP*Port`). The sources define only the LiDAR's side; the host ports
/// here repeat its numbers (a host may listen on any port it configures).
inline constexpr Sdk2Ports sdk2_hap_ports{56000, 56000, 56000, 56000, 56000, 57000, 57000, 58000, 58000};

/// The largest control frame, header included [bytes] (`kMaxCommandBufferSize`).
inline constexpr std::uint16_t sdk2_max_control_bytes = 1400;

/// Device types of the discovery ACK's dev_type byte (`LivoxLidarDeviceType`).
inline constexpr std::uint8_t sdk2_device_mid360 = 9;
inline constexpr std::uint8_t sdk2_device_industrial_hap = 10;
inline constexpr std::uint8_t sdk2_device_hap = 15;

/// The product name of a dev_type byte ("Mid-360", "HAP (industrial)", "HAP"),
/// or nullptr for a value the sources do not name. O(1).
inline const char* sdk2_device_name(std::uint8_t dev_type) noexcept {
  switch (dev_type) {
    case sdk2_device_mid360: return "Mid-360";
    case sdk2_device_industrial_hap: return "HAP (industrial)";
    case sdk2_device_hap: return "HAP";
    default: return nullptr;
  }
}

}  // namespace streamclust::live
