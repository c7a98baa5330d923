// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// What the SDK2 and SDK1 connections share: the error type of a failed
/// connection, the LiDAR a discovery found, the choice of LiDAR by serial
/// number or address, and the host address that reaches a LiDAR.
/// Facts and sources: docs/live.md.

#include <streamclust/live/udp_socket.hpp>

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

namespace streamclust::live {

/// A network failure of a LiDAR connection (a port that cannot be bound, a
/// LiDAR that does not answer or refuses a command); the message names the
/// endpoint and the reason. The command-line tool exits 6 on it.
class ConnectionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One LiDAR found by discovery (SDK2) or by its broadcast (SDK1).
struct FoundLidar {
  std::uint32_t address = 0;
  std::string serial;
  std::string model;
  std::uint16_t command_port = 0;  ///< where its commands go (SDK2: from the ACK; SDK1: the broadcast's source port)
};

/// The address of this host's interface that reaches `remote` (the source
/// address the kernel would choose); 0 when there is no route.
inline std::uint32_t local_address_towards(std::uint32_t remote) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return 0;
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(9);
  a.sin_addr.s_addr = htonl(remote);
  std::uint32_t local = 0;
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0) {
    sockaddr_in l{};
    socklen_t n = sizeof l;
    if (::getsockname(fd, reinterpret_cast<sockaddr*>(&l), &n) == 0) local = ntohl(l.sin_addr.s_addr);
  }
  ::close(fd);
  return local;
}

/// A UdpSocket bound to `at`, or a ConnectionError "`what`: OS reason".
inline std::unique_ptr<UdpSocket> bind_or_fail(Endpoint at, const std::string& what) {
  try {
    return std::make_unique<UdpSocket>(at);
  } catch (const std::system_error& e) {
    throw ConnectionError(what + ": " + e.what());
  }
}

/// Does one of `lidars` (serial numbers or dotted addresses) name a device
/// with serial `serial` at `address`? Empty: any device.
inline bool lidar_matches(const std::vector<std::string>& lidars, const std::string& serial, std::uint32_t address) {
  if (lidars.empty()) return true;
  for (const std::string& l : lidars) {
    if (l == serial) return true;
    if (const auto a = parse_address(l); a && *a == address) return true;
  }
  return false;
}

/// "a, b, c" of `names`.
inline std::string comma_list(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& s : names) list += (list.empty() ? "" : ", ") + s;
  return list;
}

}  // namespace streamclust::live
