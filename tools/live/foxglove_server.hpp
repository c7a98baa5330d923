// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A Foxglove WebSocket server (protocol v1, live/foxglove_protocol.hpp) for a
/// live view: the application advertises channels and publishes messages;
/// Foxglove (or any client of the protocol) subscribes and receives them.
/// Built on websocketpp with standalone asio, which stay inside the .cpp: this
/// header names no type of theirs.
///
/// Usage:
/// \code
///   live::FoxgloveServer server({"127.0.0.1", 8765, "streamclust"});
///   const auto points = server.advertise({0, "/streamclust/points", "cdr", "foxglove_msgs/msg/PointCloud",
///                                         io::foxglove::ros2_definition("foxglove_msgs/PointCloud"), "ros2msg"});
///   for (;;) server.publish(points, log_time_ns, cdr.data(), cdr.size());  // never waits for clients
/// \endcode
///
/// Drop policy: each client has a send buffer of at most
/// `Options::send_buffer_limit` bytes. A message that would take a client past
/// it is not sent to that client (whole messages only), counted, and the client
/// gets a warning `status` at most once a second. So a slow or stalled client
/// loses messages, the others do not, and the publisher never waits.
///
/// Threads: the server runs one network thread of its own. `advertise`,
/// `publish` and `stats` are thread-safe and return without waiting for the
/// network; every socket operation happens on the network thread.
/// Memory: at most `send_buffer_limit` bytes queued per client plus at most
/// `send_buffer_limit` bytes of published messages not yet handed to the
/// clients (beyond that, `publish` drops the message and counts it).

#include "live/foxglove_protocol.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace streamclust::live {

/// The live view's WebSocket server (see the file comment).
class FoxgloveServer {
 public:
  struct Options {
    std::string address = "127.0.0.1";  ///< IPv4 or IPv6 address to listen on; "0.0.0.0" for every interface
    std::uint16_t port = 8765;          ///< TCP port; 0 picks a free one (see port())
    std::string name = "streamclust";   ///< the server name clients show
    std::size_t send_buffer_limit = 10'000'000;  ///< [bytes] queued per client before its messages are dropped
  };

  /// Counters since the start. `messages_sent` and `messages_dropped` count
  /// one per subscribed client and message.
  struct Stats {
    std::size_t clients = 0;               ///< connected now
    std::uint64_t messages_published = 0;  ///< publish() calls accepted
    std::uint64_t messages_sent = 0;       ///< queued to a subscribed client
    std::uint64_t messages_dropped = 0;    ///< not sent to a subscribed client: its send buffer was full
    std::uint64_t publishes_dropped = 0;   ///< publish() calls dropped before the network thread took them
    std::uint64_t bytes_sent = 0;          ///< [bytes] of Message Data frames queued to clients
    std::string network_error;             ///< why the network thread stopped early; empty while it runs
  };

  /// Listens on `options.address`:`options.port` and starts the network
  /// thread. Throws std::invalid_argument for an address that does not parse or
  /// a zero send buffer limit, std::runtime_error naming address:port and the
  /// OS reason when it cannot listen there.
  explicit FoxgloveServer(Options options);
  /// Closes every connection and joins the network thread; a client that does
  /// not answer the close is cut after at most a second.
  ~FoxgloveServer();
  FoxgloveServer(const FoxgloveServer&) = delete;
  FoxgloveServer& operator=(const FoxgloveServer&) = delete;

  /// The port it listens on (the one chosen when Options::port was 0).
  std::uint16_t port() const;

  /// Advertises a channel to every client, now and on connection; its
  /// `id` is ignored and the assigned one returned. O(channel size).
  std::uint32_t advertise(foxglove::Channel channel);
  /// Withdraws a channel; its subscriptions end.
  void unadvertise(std::uint32_t channel_id);

  /// Sends `size` bytes at `data` (one message) with log time `log_time_ns`
  /// to every client subscribed to channel `channel_id`. Copies the bytes once
  /// and hands them to the network thread: O(size), never waits for a client.
  /// Throws std::invalid_argument for a channel id advertise() never returned;
  /// a withdrawn channel's messages reach no one.
  void publish(std::uint32_t channel_id, std::uint64_t log_time_ns, const std::uint8_t* data, std::size_t size);

  /// The counters now. O(1); thread-safe.
  Stats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace streamclust::live
