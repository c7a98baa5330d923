// SPDX-License-Identifier: MIT
// The live sources' transport: the receiver-to-engine ring, a real UDP socket
// on loopback, the device clock's epochs and the reorder window's counts.

#include <doctest/doctest.h>

#include <streamclust/live/device_clock.hpp>
#include <streamclust/live/packet_order.hpp>
#include <streamclust/live/spsc_ring.hpp>
#include <streamclust/live/udp_socket.hpp>

#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

namespace live = streamclust::live;

TEST_CASE("SpscRing: bounded, in order, lossless between two threads") {
  live::SpscRing<int> ring(3);
  CHECK(ring.capacity() == 4);
  for (int i = 0; i < 4; ++i) CHECK(ring.try_push([&](int& slot) { return slot = i, true; }));
  CHECK_FALSE(ring.try_push([](int&) { return true; }));  // full: the producer does not wait
  CHECK(ring.size() == 4);
  for (int i = 0; i < 4; ++i) {
    REQUIRE(ring.front() != nullptr);
    CHECK(*ring.front() == i);
    ring.pop();
  }
  CHECK(ring.front() == nullptr);
  CHECK_FALSE(ring.try_push([](int&) { return false; }));  // an abandoned fill publishes nothing
  CHECK(ring.front() == nullptr);
  CHECK_THROWS_AS(live::SpscRing<int>(1), std::invalid_argument);

  // One producer, one consumer: every pushed value arrives once, in order;
  // what the producer could not push is counted by it, not lost silently.
  live::SpscRing<std::uint64_t> shared(64);
  constexpr std::uint64_t kItems = 200000;
  std::uint64_t refused = 0;
  std::atomic<bool> done{false};
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < kItems; ++i) {
      if (!shared.try_push([&](std::uint64_t& s) { return s = i, true; })) ++refused;
    }
    done = true;
  });
  std::uint64_t received = 0, last = 0, out_of_order = 0;
  for (;;) {
    const bool finished = done.load();  // read before the ring: nothing is pushed after it
    if (const std::uint64_t* v = shared.front()) {
      if (received > 0 && *v <= last) ++out_of_order;
      last = *v;
      ++received;
      shared.pop();
    } else if (finished) {
      break;
    }
  }
  producer.join();
  CHECK(out_of_order == 0);
  CHECK(received + refused == kItems);
}

TEST_CASE("UdpSocket: datagrams on loopback keep their source; oversize and timeout are reported") {
  live::UdpSocket receiver(live::Endpoint{0x7F000001u, 0});
  const live::Endpoint to = receiver.local();
  CHECK(to.address == 0x7F000001u);
  CHECK(to.port != 0);
  CHECK(receiver.set_receive_buffer(1 << 20) >= (1u << 16));
  // A second loopback address as the sensor's (127.0.0.0/8 is all loopback).
  live::UdpSocket sender(live::Endpoint{0x7F000002u, 0});
  const std::vector<std::uint8_t> bytes{1, 2, 3, 4, 5};
  REQUIRE(sender.send_to(to, bytes.data(), bytes.size()));
  live::Datagram d;
  REQUIRE(receiver.receive(d, std::chrono::milliseconds(2000)) == live::ReceiveStatus::datagram);
  CHECK(d.size == 5);
  CHECK(d.bytes[4] == 5);
  CHECK(d.source == sender.local());
  CHECK(live::format_endpoint(d.source).rfind("127.0.0.2:", 0) == 0);
  CHECK(d.arrival_ns > 0);

  const std::vector<std::uint8_t> big(live::Datagram::kCapacity + 100, 7);
  REQUIRE(sender.send_to(to, big.data(), big.size()));
  CHECK(receiver.receive(d, std::chrono::milliseconds(2000)) == live::ReceiveStatus::oversize);
  CHECK(receiver.receive(d, std::chrono::milliseconds(20)) == live::ReceiveStatus::timeout);
  CHECK(receiver.kernel_drops().value_or(0) == 0);

  // A port another socket holds is refused (its datagrams are not split).
  CHECK_THROWS_WITH_AS(live::UdpSocket{to}, doctest::Contains("holds the port"), std::system_error);
  // An address this host does not have: the error names the endpoint.
  CHECK_THROWS_WITH_AS(live::UdpSocket(live::Endpoint{0x0A0B0C0Du, 9}), doctest::Contains("10.11.12.13:9"),
                       std::system_error);
}

TEST_CASE("endpoint text: dotted quads only") {
  CHECK(live::parse_address("192.168.1.50") == 0xC0A80132u);
  CHECK(live::format_address(0xC0A80132u) == "192.168.1.50");
  CHECK_FALSE(live::parse_address("192.168.1"));
  CHECK_FALSE(live::parse_address("192.168.1.256"));
  CHECK_FALSE(live::parse_address("192.168.1.5x"));
  CHECK_FALSE(live::parse_address(""));
}

TEST_CASE("DeviceClock: one offset per epoch; a reboot or a PTP step starts a new one, never backwards") {
  live::DeviceClock clock;  // 1 s threshold
  const std::int64_t host0 = 1'700'000'000'000'000'000;
  CHECK(clock.observe(5'000'000, host0, live::LivoxTimeSync::none));
  CHECK(clock.epochs() == 1);
  CHECK(clock.map(5'000'000) == host0);
  CHECK(clock.map(5'000'480) == host0 + 480);  // the device's spacing, exactly
  // 10 s later with 3 ms of extra network delay: same epoch.
  CHECK_FALSE(clock.observe(10'005'000'000, host0 + 10'003'000'000, live::LivoxTimeSync::none));
  const std::int64_t before = clock.map(10'005'000'000);
  CHECK(before == host0 + 10'000'000'000);
  // Reboot: the clock restarts near zero. New epoch, mapped after the last time.
  CHECK(clock.observe(1'000, host0 + 10'000'400'000, live::LivoxTimeSync::none));
  CHECK(clock.epochs() == 2);
  CHECK(clock.map(1'000) > before);
  CHECK(clock.map(1'000) == host0 + 10'000'400'000);
  // PTP acquired: the sync type changes, a new epoch even without a big jump.
  CHECK(clock.observe(2'000, host0 + 10'000'500'000, live::LivoxTimeSync::ptp));
  CHECK(clock.sync() == live::LivoxTimeSync::ptp);
  // A step to a time that maps before the last mapped time is held after it.
  const std::int64_t last = clock.map(2'000);
  CHECK(clock.observe(3'000, last - 5'000'000'000, live::LivoxTimeSync::ptp));
  CHECK(clock.map(3'000) == last + 1);
  // Garbage device times do not overflow (UBSan) and start an epoch.
  CHECK(clock.observe(~std::uint64_t{0}, host0, live::LivoxTimeSync::ptp));
}

TEST_CASE("DeviceClock: an epoch held after the last mapped time keeps its lead; only a further jump is another epoch") {
  live::DeviceClock clock;
  const std::int64_t host0 = 1'700'000'000'000'000'000;
  CHECK(clock.observe(0, host0, live::LivoxTimeSync::none));
  clock.map(10'000'000);
  // The host clock steps back 3 s: held after the last mapped time, 3 s ahead of the arrivals.
  CHECK(clock.observe(10'500'000, host0 - 3'000'000'000 + 10'500'000, live::LivoxTimeSync::none));
  CHECK(clock.map(10'500'000) == host0 + 10'000'001);
  // The packets after it keep that lead: no epoch each (they used to be one each).
  for (std::uint64_t k = 1; k <= 100; ++k) {
    const auto t = static_cast<std::int64_t>(10'500'000 + k * 500'000);
    CHECK_FALSE(clock.observe(static_cast<std::uint64_t>(t), host0 - 3'000'000'000 + t, live::LivoxTimeSync::none));
  }
  CHECK(clock.epochs() == 2);
  // A further jump beyond the threshold from that lead is an epoch again.
  CHECK(clock.observe(5'000'000'000'000, host0 - 3'000'000'000 + 70'000'000, live::LivoxTimeSync::none));
  CHECK(clock.epochs() == 3);
}

TEST_CASE("DeviceClock: a clock at another rate than the host's (a replay at 2x or 0.5x) stays one epoch; a step does not") {
  const std::int64_t host0 = 1'700'000'000'000'000'000;
  for (const double rate : {2.0, 0.5}) {
    CAPTURE(rate);
    live::DeviceClock clock;
    // A packet every 0.5 ms of device time for 10 s of host time: the drift grows to 10 s (2x) or -5 s (0.5x).
    std::uint64_t device = 1'000'000'000;
    for (std::int64_t host = 0; host <= 10'000'000'000; host += 500'000) {
      device = 1'000'000'000 + static_cast<std::uint64_t>(static_cast<double>(host) * rate);
      clock.observe(device, host0 + host, live::LivoxTimeSync::none);
    }
    CHECK(clock.epochs() == 1);
    CHECK(clock.map(device) - (host0 + 10'000'000'000) == static_cast<std::int64_t>((rate - 1.0) * 10'000'000'000));
    // A reboot is still a step of more than the threshold between two packets.
    CHECK(clock.observe(1'000, host0 + 10'000'500'000, live::LivoxTimeSync::none));
    CHECK(clock.epochs() == 2);
  }
}

TEST_CASE("DeviceClock: a packet of the previous epoch reordered after a jump is a straggler; a step back later is an epoch") {
  live::DeviceClock clock;
  const std::int64_t host0 = 1'700'000'000'000'000'000;
  constexpr std::uint64_t boot = 1'000'000'000, hour = 3'600'000'000'000;
  CHECK(clock.observe(boot, host0, live::LivoxTimeSync::none));
  CHECK(clock.observe(boot + hour + 1'000'000, host0 + 1'000'000, live::LivoxTimeSync::none));  // the jump
  CHECK(clock.epochs() == 2);
  // Sent 0.5 ms before the jump, arriving 0.5 ms after it: the previous epoch's.
  CHECK_FALSE(clock.observe(boot + 500'000, host0 + 1'500'000, live::LivoxTimeSync::none));
  CHECK(clock.straggler());
  CHECK(clock.epochs() == 2);
  CHECK_FALSE(clock.observe(boot + hour + 2'000'000, host0 + 2'000'000, live::LivoxTimeSync::none));
  CHECK_FALSE(clock.straggler());
  // Another sync type is never the previous epoch's.
  CHECK(clock.observe(boot + 600'000, host0 + 2'100'000, live::LivoxTimeSync::ptp));
  CHECK(clock.epochs() == 3);
  // Past the straggler window, the clock stepping back to the previous epoch's time is a new epoch.
  live::DeviceClock glitch;
  CHECK(glitch.observe(boot, host0, live::LivoxTimeSync::ptp));
  CHECK(glitch.observe(boot + hour + 1'000'000, host0 + 1'000'000, live::LivoxTimeSync::ptp));
  const std::int64_t later = 1'000'000 + live::DeviceClock::kStragglerWindowNs + 1'000'000;
  CHECK(glitch.observe(boot + static_cast<std::uint64_t>(later), host0 + later, live::LivoxTimeSync::ptp));
  CHECK_FALSE(glitch.straggler());
  CHECK(glitch.epochs() == 3);
}

namespace {

struct TestPacket {
  int id = 0;
};

// Feeds (time, counter) pairs with ids; returns the released ids in order.
std::vector<int> run_order(live::ReorderWindow<TestPacket>& w, const std::vector<live::PacketKey>& keys) {
  std::vector<int> out;
  int id = 0;
  for (const auto& k : keys) {
    w.next_slot().id = id++;
    w.commit(k, [&](const TestPacket& p) { out.push_back(p.id); });
  }
  w.flush([&](const TestPacket& p) { out.push_back(p.id); });
  return out;
}

live::PacketKey counted(std::int64_t t, std::uint16_t c) { return live::PacketKey{t, true, c, 0}; }

}  // namespace

TEST_CASE("ReorderWindow: reordering within the depth is undone; loss, duplicates and late packets are counted") {
  live::ReorderWindow<TestPacket> w(4);
  // 0 1 3 2 4 4(dup) 8 (5-7 lost)
  const auto ids = run_order(w, {counted(0, 10), counted(480, 11), counted(1440, 13), counted(960, 12),
                                 counted(1920, 14), counted(1920, 14), counted(3840, 18)});
  CHECK(ids == std::vector<int>{0, 1, 3, 2, 4, 6});
  CHECK(w.counters().released == 6);
  CHECK(w.counters().duplicates == 1);
  CHECK(w.counters().lost == 3);
  CHECK(w.counters().late == 0);

  // Beyond the depth a packet is late, dropped and counted.
  live::ReorderWindow<TestPacket> shallow(1);
  const auto ids2 = run_order(shallow, {counted(0, 0), counted(480, 1), counted(960, 2), counted(100, 5)});
  CHECK(ids2 == std::vector<int>{0, 1, 2});
  CHECK(shallow.counters().late == 1);
}

TEST_CASE("ReorderWindow: a flush between filling a slot and committing it keeps that slot's packet") {
  live::ReorderWindow<TestPacket> w(4);
  std::vector<int> out;
  auto keep = [&](const TestPacket& p) { out.push_back(p.id); };
  for (int i = 0; i < 3; ++i) {
    w.next_slot().id = i;
    w.commit(counted(480 * i, static_cast<std::uint16_t>(i)), keep);
  }
  w.next_slot().id = 100;  // read before the clock says: a new epoch
  w.flush(keep);
  w.restart();
  w.commit(counted(5, 0), keep);
  w.flush(keep);
  CHECK(out == std::vector<int>{0, 1, 2, 100});
}

TEST_CASE("ReorderWindow: the counter wraps at 65535; a large jump is a discontinuity, not loss") {
  live::ReorderWindow<TestPacket> w(2);
  run_order(w, {counted(0, 65534), counted(1, 65535), counted(2, 0), counted(3, 1)});
  CHECK(w.counters().lost == 0);
  CHECK(w.counters().released == 4);
  live::ReorderWindow<TestPacket> j(2);
  run_order(j, {counted(0, 100), counted(1, 9000), counted(2, 9001)});
  CHECK(j.counters().lost == 0);
  CHECK(j.counters().counter_jumps == 1);
}

TEST_CASE("ReorderWindow: without a counter, loss is the time gap over the packet period") {
  live::ReorderWindow<TestPacket> w(0);
  const std::int64_t period = 400'000;  // 96 points at 240 kHz
  run_order(w, {{0, false, 0, period}, {period, false, 0, period}, {4 * period + 3'000, false, 0, period},
                {5 * period - 2'000, false, 0, period}});
  CHECK(w.counters().lost == 2);
  CHECK(w.counters().released == 4);
  w.restart();  // a new epoch: the next packet has nothing to compare with
  run_order(w, {{1, false, 0, period}});
  CHECK(w.counters().lost == 2);
  CHECK(w.counters().late == 0);
}
