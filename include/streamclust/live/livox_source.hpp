// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The live source strings, `livox-sdk2://[HOST_IP][:PORT]` and
/// `livox-sdk1://[HOST_IP][:PORT]`, and the host ports they imply (as the
/// Livox SDKs number them). The command-line tool and the Python module
/// read sources with this one parser, so both accept and refuse the same.

#include <streamclust/io/input_stream.hpp>
#include <streamclust/live/udp_socket.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace streamclust::live {

enum class LivoxProtocol { sdk2, sdk1 };

/// A parsed source string.
struct LivoxSourceUrl {
  LivoxProtocol protocol = LivoxProtocol::sdk2;
  std::uint32_t host_address = 0;  ///< the host interface to bind (0: every interface)
  /// SDK2: the host's point port (IMU: port + 100, commands: port - 200);
  /// SDK1: the host's broadcast-listen port (commands: port + 500, data and
  /// IMU: port + 1000), as the Livox SDKs number them.
  std::uint16_t port = 0;
};

/// The default host ports: SDK2 points 56301, SDK1 broadcast listen 55000.
inline constexpr std::uint16_t kSdk2PointPort = 56301;
inline constexpr std::uint16_t kSdk1BroadcastPort = 55000;

/// Parses a source string; std::invalid_argument "SOURCE: ..." naming what
/// was expected and what is wrong. O(length).
inline LivoxSourceUrl parse_livox_source_url(const std::string& text) {
  const std::string expected = "expected livox-sdk2://[HOST_IP][:PORT] or livox-sdk1://[HOST_IP][:PORT], got '" +
                               text + "'";
  LivoxSourceUrl url;
  std::string rest;
  if (text.rfind("livox-sdk2://", 0) == 0) {
    url.protocol = LivoxProtocol::sdk2;
    url.port = kSdk2PointPort;
  } else if (text.rfind("livox-sdk1://", 0) == 0) {
    url.protocol = LivoxProtocol::sdk1;
    url.port = kSdk1BroadcastPort;
  } else {
    throw std::invalid_argument("SOURCE: " + expected);
  }
  rest = text.substr(13);
  if (!rest.empty() && rest.back() == '/') rest.pop_back();
  const auto colon = rest.find(':');
  const std::string host = rest.substr(0, colon);
  if (!host.empty()) {
    const auto a = parse_address(host);
    if (!a) throw std::invalid_argument("SOURCE: host '" + host + "' is not a dotted IPv4 address; " + expected);
    url.host_address = *a;
  }
  if (colon != std::string::npos) {
    const std::string port = rest.substr(colon + 1);
    std::int64_t p = 0;
    if (!io::detail::parse_int64(port, p) || p < 1 || p > 65535)
      throw std::invalid_argument("SOURCE: port '" + port + "' is not 1-65535; " + expected);
    url.port = static_cast<std::uint16_t>(p);
  }
  // The derived ports must fit: SDK2 commands at port - 200, IMU at + 100;
  // SDK1 commands at + 500, data at + 1000.
  const bool fits = url.protocol == LivoxProtocol::sdk2 ? url.port > 200 && url.port <= 65435 : url.port <= 64535;
  if (!fits) {
    throw std::invalid_argument("SOURCE: port " + std::to_string(url.port) + " leaves no room for the derived ports; " +
                                expected);
  }
  return url;
}

}  // namespace streamclust::live
