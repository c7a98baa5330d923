// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The receiver thread of the live sources: it reads the LiDARs' datagrams
/// from one or more UDP sockets (points, IMU), routes each by its source
/// address to that LiDAR's queue, and never waits for the engine: a full
/// queue drops the whole datagram and counts it. Datagrams from addresses
/// that are none of the chosen LiDARs are counted as foreign and dropped,
/// so two devices streaming to one port are never mixed.
///
/// Memory: each LiDAR's queue is allocated once (`queue_packets` slots of
/// 1.5 kB); the sockets' kernel buffers are asked for `socket_buffer_bytes`.
///
/// Thread safety: construct, `start`, `stop` and destroy from one thread;
/// `queue(i)` is consumed by exactly one engine thread per LiDAR; `stats`
/// and `device_address` may be read from any thread.

#include <streamclust/live/spsc_ring.hpp>
#include <streamclust/live/udp_socket.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <poll.h>

namespace streamclust::live {

struct ReceiverOptions {
  std::vector<Endpoint> ports;              ///< host sockets to bind (points, IMU; one is enough when shared)
  /// The LiDARs' source addresses, one queue each. Empty: the first address
  /// a datagram comes from becomes the only LiDAR.
  std::vector<std::uint32_t> devices;
  std::size_t queue_packets = 4096;         ///< per LiDAR: about 2 s of a Mid-360's 2,083 packets/s
  std::size_t socket_buffer_bytes = 8u << 20;
  /// Called on the receiver thread about every `tick_period` (control work
  /// such as SDK1 heartbeats); must not block.
  std::function<void(std::chrono::steady_clock::time_point)> on_tick;
  std::chrono::milliseconds tick_period{50};
};

/// Counters of the receiver (snapshots; each is monotonic).
struct ReceiverStats {
  std::uint64_t datagrams = 0;      ///< received from the chosen LiDARs
  std::uint64_t bytes = 0;          ///< their payload bytes
  std::uint64_t foreign = 0;        ///< from other addresses: dropped
  std::uint64_t oversize = 0;       ///< longer than any Livox packet: dropped
  std::uint64_t queue_drops = 0;    ///< the engine fell behind: whole datagrams dropped
  std::uint64_t kernel_drops = 0;   ///< dropped by the OS for want of socket buffer (Linux)
  bool kernel_drops_known = false;  ///< the OS reports kernel drops
  std::size_t socket_buffer_bytes = 0;  ///< what the OS granted (smallest socket)
};

class LivoxReceiver {
 public:
  /// Binds every port (throws std::system_error naming the endpoint) and
  /// allocates the queues; call `start` to receive.
  explicit LivoxReceiver(ReceiverOptions options) : options_(std::move(options)) {
    if (options_.ports.empty()) throw std::invalid_argument("LivoxReceiver: no port to listen on");
    const std::size_t n = options_.devices.empty() ? 1 : options_.devices.size();
    for (std::size_t i = 0; i < n; ++i) {
      auto d = std::make_unique<Device>(options_.queue_packets);
      if (!options_.devices.empty()) d->address.store(options_.devices[i]);
      devices_.push_back(std::move(d));
    }
    granted_buffer_ = static_cast<std::size_t>(-1);
    for (const Endpoint& e : options_.ports) {
      sockets_.push_back(std::make_unique<UdpSocket>(e));
      const std::size_t got = sockets_.back()->set_receive_buffer(options_.socket_buffer_bytes);
      if (got < granted_buffer_) granted_buffer_ = got;
    }
  }
  ~LivoxReceiver() { stop(); }
  LivoxReceiver(const LivoxReceiver&) = delete;
  LivoxReceiver& operator=(const LivoxReceiver&) = delete;

  void start() {
    if (thread_.joinable()) return;
    running_ = true;
    thread_ = std::thread([this] { run(); });
  }
  /// Stops receiving and joins the thread (within one poll period, 20 ms).
  void stop() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
  }

  std::size_t devices() const noexcept { return devices_.size(); }
  /// LiDAR `i`'s queue (its one consumer is that LiDAR's engine thread).
  SpscRing<Datagram>& queue(std::size_t i) { return devices_.at(i)->queue; }
  /// LiDAR `i`'s address, 0 until a first datagram claims it (automatic choice).
  std::uint32_t device_address(std::size_t i) const { return devices_.at(i)->address.load(); }
  /// The bound endpoint of socket `i` (in `ReceiverOptions::ports` order).
  Endpoint local(std::size_t i) const { return sockets_.at(i)->local(); }

  ReceiverStats stats() const {
    ReceiverStats s;
    s.datagrams = datagrams_.load(std::memory_order_relaxed);
    s.bytes = bytes_.load(std::memory_order_relaxed);
    s.foreign = foreign_.load(std::memory_order_relaxed);
    s.oversize = oversize_.load(std::memory_order_relaxed);
    for (const auto& d : devices_) s.queue_drops += d->drops.load(std::memory_order_relaxed);
    s.kernel_drops = kernel_drops_.load(std::memory_order_relaxed);
    s.kernel_drops_known = kernel_drops_known_.load(std::memory_order_relaxed);
    s.socket_buffer_bytes = granted_buffer_;
    return s;
  }
  /// Why the receiver thread stopped on its own (a socket error), or empty
  /// while it runs.
  std::string error() const { return failed_.load(std::memory_order_acquire) ? error_ : std::string(); }

  /// Datagrams dropped because LiDAR `i`'s queue was full.
  std::uint64_t queue_drops(std::size_t i) const { return devices_.at(i)->drops.load(std::memory_order_relaxed); }
  /// Datagrams (and their bytes) from LiDAR `i` handed to its queue.
  std::uint64_t datagrams(std::size_t i) const { return devices_.at(i)->datagrams.load(std::memory_order_relaxed); }
  std::uint64_t bytes(std::size_t i) const { return devices_.at(i)->bytes.load(std::memory_order_relaxed); }

 private:
  struct Device {
    explicit Device(std::size_t slots) : queue(slots) {}
    SpscRing<Datagram> queue;
    std::atomic<std::uint32_t> address{0};
    std::atomic<std::uint64_t> drops{0};
    std::atomic<std::uint64_t> datagrams{0}, bytes{0};
  };

  void run() {
    try {
      receive_loop();
    } catch (const std::exception& e) {
      error_ = e.what();
      failed_.store(true, std::memory_order_release);
    }
  }

  void receive_loop() {
    std::vector<pollfd> fds;
    for (const auto& s : sockets_) fds.push_back(pollfd{s->native_handle(), POLLIN, 0});
    Datagram scratch;  // received here, then copied into its LiDAR's queue
    auto next_tick = std::chrono::steady_clock::now();
    while (running_.load(std::memory_order_relaxed)) {
      if (options_.on_tick) {
        const auto now = std::chrono::steady_clock::now();
        if (now >= next_tick) {
          options_.on_tick(now);
          next_tick = now + options_.tick_period;
        }
      }
      for (pollfd& p : fds) p.revents = 0;
      const int ready = ::poll(fds.data(), fds.size(), 20);
      if (ready <= 0) continue;  // timeout or EINTR: check `running_` and the tick
      for (std::size_t k = 0; k < fds.size(); ++k) {
        if ((fds[k].revents & POLLIN) == 0) continue;
        drain(*sockets_[k], scratch);
      }
    }
  }

  // Receives what the socket holds now (at most 64 datagrams per call, so
  // one busy socket does not starve the others or the tick). One copy per
  // datagram into its queue slot (1.4 kB: negligible at 2,000 packets/s).
  void drain(UdpSocket& socket, Datagram& d) {
    for (int burst = 0; burst < 64; ++burst) {
      const ReceiveStatus status = socket.receive_ready(d);
      if (status == ReceiveStatus::timeout || status == ReceiveStatus::interrupted) return;
      update_kernel_drops(socket);
      if (status == ReceiveStatus::oversize) {
        oversize_.fetch_add(1, std::memory_order_relaxed);
        continue;
      }
      Device* target = route(d.source);
      if (target == nullptr) {
        foreign_.fetch_add(1, std::memory_order_relaxed);
        continue;
      }
      if (!target->queue.try_push([&](Datagram& slot) { return copy(d, slot); })) {
        target->drops.fetch_add(1, std::memory_order_relaxed);
        continue;
      }
      datagrams_.fetch_add(1, std::memory_order_relaxed);
      bytes_.fetch_add(d.size, std::memory_order_relaxed);
      target->datagrams.fetch_add(1, std::memory_order_relaxed);
      target->bytes.fetch_add(d.size, std::memory_order_relaxed);
    }
  }

  static bool copy(const Datagram& from, Datagram& to) noexcept {
    to.size = from.size;
    to.source = from.source;
    to.arrival_ns = from.arrival_ns;
    to.arrival_steady_ns = from.arrival_steady_ns;
    std::copy(from.bytes.begin(), from.bytes.begin() + from.size, to.bytes.begin());
    return true;
  }

  // The LiDAR a source address belongs to; the first address claims an
  // automatic LiDAR. Null: foreign.
  Device* route(Endpoint source) noexcept {
    for (const auto& d : devices_) {
      std::uint32_t a = d->address.load(std::memory_order_relaxed);
      if (a == 0 && options_.devices.empty()) {
        d->address.store(source.address);
        a = source.address;
      }
      if (a == source.address) return d.get();
    }
    return nullptr;
  }

  void update_kernel_drops(const UdpSocket& socket) noexcept {
    if (const auto k = socket.kernel_drops()) {
      kernel_drops_known_.store(true, std::memory_order_relaxed);
      if (*k > kernel_drops_.load(std::memory_order_relaxed)) kernel_drops_.store(*k, std::memory_order_relaxed);
    }
  }

  ReceiverOptions options_;
  std::vector<std::unique_ptr<Device>> devices_;
  std::vector<std::unique_ptr<UdpSocket>> sockets_;
  std::size_t granted_buffer_ = 0;
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::atomic<std::uint64_t> datagrams_{0}, bytes_{0}, foreign_{0}, oversize_{0}, kernel_drops_{0};
  std::atomic<bool> kernel_drops_known_{false};
  std::atomic<bool> failed_{false};
  std::string error_;  // written before failed_ is set
};

}  // namespace streamclust::live
