// SPDX-License-Identifier: MIT
// Smallest use of an installed streamclust, one thing from each of its
// targets: the engine (streamclust::streamclust), a label codec
// (streamclust::io), the adjusted Rand index (streamclust::eval) and a
// simulated Mid-360 ray (streamclust::sim). Exits 0 when all agree with what
// they document. With CONSUMER_ENGINE_ONLY (built where no codec package is
// found) the engine alone.
#include <streamclust/streamclust.hpp>
#ifndef CONSUMER_ENGINE_ONLY
#include <streamclust/eval/rand_index.hpp>
#include <streamclust/io/writers.hpp>
#include <streamclust/live/livox_crc.hpp>
#include <streamclust/live/spsc_ring.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#endif

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

int main() {
  int failures = 0;
  const auto check = [&failures](bool ok, const char* what) {
    if (!ok) {
      std::fprintf(stderr, "consumer: %s failed\n", what);
      ++failures;
    }
  };

  auto c = streamclust::make_carc();
  streamclust::Point p{1.f, 2.f, 0.5f, 0.f, 0.0};
  c.insert(p);
  c.complete_calibration();  // one point never completes the adaptive grid's first window
  check(c.retrieve().points.size() == 1, "streamclust: one point in, one point out");

#ifndef CONSUMER_ENGINE_ONLY

  check(streamclust::io::semantickitti_decode(streamclust::io::semantickitti_encode(7)) == 7, "io: label round trip");

  const std::vector<std::int64_t> truth{1, 1, 2, 2};
  const std::vector<std::int64_t> relabelled{5, 5, 9, 9};
  check(streamclust::eval::adjusted_rand_index(truth, relabelled) == 1.0, "eval: ARI of a relabelling");

  streamclust::sim::Mid360Model mid360;
  const streamclust::sim::Ray r = mid360.next();
  check(std::fabs(r.direction.norm() - 1.0f) < 1e-4f && r.time == 0.0, "sim: a unit ray at t = 0");

  const std::uint8_t digits[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  check(streamclust::live::crc16_ccitt_false(digits, 9) == 0x29B1, "live: the SDK2 header CRC's check value");
  streamclust::live::SpscRing<int> ring(2);  // the receiver thread's hand-off (Threads linked)
  check(ring.try_push([](int& slot) { return slot = 3, true; }) && *ring.front() == 3, "live: a ring hands over");
#endif

  return failures == 0 ? 0 : 1;
}
