// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The UDP ports and the connection timing of the Livox SDK1 protocol (Avia,
/// Mid-40/100, Mid-70, Horizon, Tele-15). Sources:
/// `Livox-SDK/Livox-SDK:sdk_core/src/device_discovery.h` (`kListenPort`,
/// `kCmdPortOffset`, `kDataPortOffset`, `kSensorPortOffset`),
/// `sdk_core/src/command_handler/command_channel.cpp` (the LiDAR's command
/// port 65000, the heartbeat sent 800 ms after the last one, a device given
/// up after 3 s without a heartbeat ACK), `command_impl.h` (heartbeats "at
/// least every second", the 500 ms command timeout).
///
/// Constants only.

#include <chrono>
#include <cstdint>

namespace streamclust::live {

/// The host listens here for the LiDARs' broadcast messages.
inline constexpr std::uint16_t sdk1_broadcast_listen_port = 55000;

/// The LiDAR's command port: the host sends its commands there.
inline constexpr std::uint16_t sdk1_lidar_command_port = 65000;

/// The host's command port for its `n`-th LiDAR (n from 0): 55500 + n.
constexpr std::uint16_t sdk1_host_command_port(std::uint16_t n) noexcept {
  return static_cast<std::uint16_t>(sdk1_broadcast_listen_port + 500 + n);
}

/// The host's data port for its `n`-th LiDAR: 56000 + n. The SDK gives the
/// IMU (sensor) stream the same port; the data type tells the packets apart.
constexpr std::uint16_t sdk1_host_data_port(std::uint16_t n) noexcept {
  return static_cast<std::uint16_t>(sdk1_broadcast_listen_port + 1000 + n);
}

/// The host's IMU (sensor) port for its `n`-th LiDAR: the data port.
constexpr std::uint16_t sdk1_host_sensor_port(std::uint16_t n) noexcept { return sdk1_host_data_port(n); }

/// The longest a host may wait between two heartbeats.
inline constexpr std::chrono::milliseconds sdk1_heartbeat_max_period{1000};

/// When the SDK sends the next heartbeat: 800 ms after the last one, a
/// margin below the maximum.
inline constexpr std::chrono::milliseconds sdk1_heartbeat_period{800};

/// A LiDAR that has not answered a heartbeat for this long is disconnected.
inline constexpr std::chrono::milliseconds sdk1_disconnect_timeout{3000};

/// How long the SDK waits for the ACK of a command.
inline constexpr std::chrono::milliseconds sdk1_command_timeout{500};

}  // namespace streamclust::live
