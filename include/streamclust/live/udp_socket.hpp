// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A UDP/IPv4 socket for the Livox protocols (POSIX; Linux reports kernel
/// drops): bind, a sized receive buffer, datagrams received with their
/// source, size and host arrival time, sends to any endpoint (broadcast
/// allowed). Errors throw std::system_error naming the endpoint and the OS
/// reason.
///
/// Thread safety: one thread receives; `send_to` may be called from another
/// thread at the same time (the kernel serialises datagrams).

#include <array>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

namespace streamclust::live {

/// An IPv4 address and UDP port, both in host byte order.
struct Endpoint {
  std::uint32_t address = 0;  ///< e.g. 0x7F000001 for 127.0.0.1; 0 = any
  std::uint16_t port = 0;

  friend bool operator==(Endpoint a, Endpoint b) noexcept { return a.address == b.address && a.port == b.port; }
  friend bool operator!=(Endpoint a, Endpoint b) noexcept { return !(a == b); }
};

/// "a.b.c.d" of an address in host byte order.
inline std::string format_address(std::uint32_t address) {
  return std::to_string(address >> 24) + "." + std::to_string((address >> 16) & 0xFFu) + "." +
         std::to_string((address >> 8) & 0xFFu) + "." + std::to_string(address & 0xFFu);
}

/// "a.b.c.d:port".
inline std::string format_endpoint(Endpoint e) { return format_address(e.address) + ":" + std::to_string(e.port); }

/// The dotted-quad address `text` ("192.168.1.50"), or nullopt when it is
/// not exactly four decimal octets.
inline std::optional<std::uint32_t> parse_address(std::string_view text) {
  std::uint32_t address = 0;
  std::size_t at = 0;
  for (int octet = 0; octet < 4; ++octet) {
    if (octet > 0) {
      if (at >= text.size() || text[at] != '.') return std::nullopt;
      ++at;
    }
    unsigned value = 0;
    std::size_t digits = 0;
    while (at < text.size() && text[at] >= '0' && text[at] <= '9' && digits < 3) {
      value = value * 10 + static_cast<unsigned>(text[at] - '0');
      ++at;
      ++digits;
    }
    if (digits == 0 || value > 255) return std::nullopt;
    address = (address << 8) | value;
  }
  if (at != text.size()) return std::nullopt;
  return address;
}

/// One received datagram: bytes, size, source and arrival time. Sized for
/// the largest Livox packet (SDK2 type 1: 1380 B; SDK1: 1362 B); a longer
/// datagram is reported `oversize` and its bytes are not kept.
struct Datagram {
  static constexpr std::size_t kCapacity = 1536;  ///< [B]
  std::array<std::uint8_t, kCapacity> bytes;
  std::uint16_t size = 0;                      ///< [B]
  Endpoint source;
  std::int64_t arrival_ns = 0;                 ///< host CLOCK_REALTIME at reception [ns since the Unix epoch]
  std::int64_t arrival_steady_ns = 0;          ///< host steady clock at reception [ns], for latencies
};

/// What `UdpSocket::receive` found.
enum class ReceiveStatus : std::uint8_t { datagram, timeout, oversize, interrupted };

class UdpSocket {
 public:
  /// A socket bound to `local` (address 0 = every interface, port 0 = any
  /// free port). No SO_REUSEADDR: a port another program (a Livox driver)
  /// holds is an error, not a silent split of its datagrams. Throws
  /// std::system_error.
  explicit UdpSocket(Endpoint local) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd_ < 0) fail("cannot create a UDP socket for " + format_endpoint(local));
#ifdef SO_RXQ_OVFL
    const int one = 1;
    // Linux: each datagram carries the socket's count of datagrams the
    // kernel dropped for want of buffer space (none while that count is 0).
    drops_reported_ = ::setsockopt(fd_, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one) == 0;
#endif
    sockaddr_in a = to_sockaddr(local);
    if (::bind(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
      const int e = errno;
      ::close(fd_);
      fd_ = -1;
      errno = e;
      fail("cannot bind UDP " + format_endpoint(local) +
           (e == EADDRINUSE ? " (another program, e.g. a Livox driver, holds the port)" : "") +
           (e == EADDRNOTAVAIL ? " (no interface of this host has that address)" : ""));
    }
  }
  ~UdpSocket() {
    if (fd_ >= 0) ::close(fd_);
  }
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;

  /// The bound address and port (the port the OS chose for port 0).
  Endpoint local() const {
    sockaddr_in a{};
    socklen_t n = sizeof a;
    if (::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &n) != 0) fail("getsockname");
    return from_sockaddr(a);
  }

  /// Asks for a receive buffer of `bytes`; returns what the kernel granted
  /// (Linux doubles the request for bookkeeping and caps it at
  /// net.core.rmem_max, unless the process may exceed that cap: root or
  /// CAP_NET_ADMIN, where SO_RCVBUFFORCE is tried first).
  std::size_t set_receive_buffer(std::size_t bytes) {
    const int want = bytes > 0x3FFFFFFFu ? 0x3FFFFFFF : static_cast<int>(bytes);
    if (::setsockopt(fd_, SOL_SOCKET, SO_RCVBUFFORCE, &want, sizeof want) != 0)
      ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &want, sizeof want);
    int got = 0;
    socklen_t n = sizeof got;
    ::getsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &got, &n);
    return static_cast<std::size_t>(got);
  }

  /// Allows sending to broadcast addresses (discovery).
  void enable_broadcast() {
    const int one = 1;
    if (::setsockopt(fd_, SOL_SOCKET, SO_BROADCAST, &one, sizeof one) != 0) fail("SO_BROADCAST");
  }

  /// Sends one datagram; returns false (and leaves errno) when the kernel
  /// refuses it (unreachable network, no buffer), never throws.
  bool send_to(Endpoint to, const std::uint8_t* data, std::size_t size) noexcept {
    sockaddr_in a = to_sockaddr(to);
    return ::sendto(fd_, data, size, MSG_NOSIGNAL, reinterpret_cast<const sockaddr*>(&a), sizeof a) ==
           static_cast<ssize_t>(size);
  }

  /// The file descriptor, for poll() over several sockets.
  int native_handle() const noexcept { return fd_; }

  /// Waits up to `timeout` for one datagram and receives it into `d`.
  ReceiveStatus receive(Datagram& d, std::chrono::milliseconds timeout) {
    pollfd p{fd_, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(timeout.count()));
    if (ready == 0) return ReceiveStatus::timeout;
    if (ready < 0) {
      if (errno == EINTR) return ReceiveStatus::interrupted;
      fail("poll");
    }
    return receive_ready(d);
  }

  /// Receives one datagram into `d` without waiting: `timeout` when none
  /// is queued.
  ReceiveStatus receive_ready(Datagram& d) {
    sockaddr_in from{};
    iovec iov{d.bytes.data(), d.bytes.size()};
    alignas(cmsghdr) std::array<unsigned char, 64> control{};
    msghdr m{};
    m.msg_name = &from;
    m.msg_namelen = sizeof from;
    m.msg_iov = &iov;
    m.msg_iovlen = 1;
    m.msg_control = control.data();
    m.msg_controllen = control.size();
    const ssize_t n = ::recvmsg(fd_, &m, MSG_DONTWAIT);
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK) return ReceiveStatus::timeout;
      if (errno == EINTR) return ReceiveStatus::interrupted;
      fail("recvmsg on UDP " + format_endpoint(local()));
    }
    d.arrival_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                       std::chrono::system_clock::now().time_since_epoch()).count();
    d.arrival_steady_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                              std::chrono::steady_clock::now().time_since_epoch()).count();
    d.source = from_sockaddr(from);
    read_drop_count(m);
    if ((m.msg_flags & MSG_TRUNC) != 0) {
      d.size = 0;
      return ReceiveStatus::oversize;
    }
    d.size = static_cast<std::uint16_t>(n);
    return ReceiveStatus::datagram;
  }

  /// Datagrams the kernel dropped on this socket for want of buffer space,
  /// as reported with the last datagram received after a drop (Linux
  /// SO_RXQ_OVFL); nullopt where the OS does not report drops.
  std::optional<std::uint64_t> kernel_drops() const noexcept {
    if (!drops_reported_) return std::nullopt;
    return kernel_drops_;
  }

 private:
  static sockaddr_in to_sockaddr(Endpoint e) noexcept {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(e.port);
    a.sin_addr.s_addr = htonl(e.address);
    return a;
  }
  static Endpoint from_sockaddr(const sockaddr_in& a) noexcept {
    return Endpoint{ntohl(a.sin_addr.s_addr), ntohs(a.sin_port)};
  }

  void read_drop_count(msghdr& m) noexcept {
#ifdef SO_RXQ_OVFL
    for (cmsghdr* c = CMSG_FIRSTHDR(&m); c != nullptr; c = CMSG_NXTHDR(&m, c)) {
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
        std::uint32_t count = 0;
        std::memcpy(&count, CMSG_DATA(c), sizeof count);
        kernel_drops_ = count;
      }
    }
#else
    (void)m;
#endif
  }

  [[noreturn]] static void fail(const std::string& what) {
    throw std::system_error(errno, std::generic_category(), what);
  }

  int fd_ = -1;
  std::uint64_t kernel_drops_ = 0;
  bool drops_reported_ = false;
};

}  // namespace streamclust::live
