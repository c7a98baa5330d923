// SPDX-License-Identifier: MIT
// The stream's time order: points going back in time and absurd jumps ahead
// cost those points only; a pause confirmed by the points after it is taken;
// the engine and the batch clusterer still agree on every window.

#include <doctest/doctest.h>

#include <streamclust/acceptance.hpp>
#include <streamclust/batch_clusterer.hpp>
#include <streamclust/frame_clusterer.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/stream_clusterer.hpp>

#include "support/oracle.hpp"
#include "support/streams.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace sc = streamclust;
using sc::RejectReason;

namespace {

sc::Projected valid_projection() {
  sc::Projected p;
  p.reason = RejectReason::accepted;
  return p;
}

sc::StreamTimeOrder::Params small_confirmation(std::uint32_t n) {
  sc::StreamTimeOrder::Params p;
  p.max_jump = 1.0;
  p.jump_confirmations = n;
  return p;
}

/// A blob stream at `rate` points per second with `spikes` (index -> time).
std::vector<sc::Point> stream_with(std::size_t n, double rate, const std::vector<std::pair<std::size_t, double>>& spikes) {
  std::vector<sc::Point> s = sc::test::make_stream(sc::test::StreamKind::blobs, n, 11, rate);
  for (const auto& spike : spikes) s[spike.first].t = spike.second;
  return s;
}

}  // namespace

TEST_CASE("StreamTimeOrder: backwards and absurd times are rejected; later points are judged against the last valid time") {
  sc::StreamTimeOrder order(small_confirmation(4));
  const sc::Projected ok = valid_projection();
  CHECK(order.admit(ok, 1e300) == RejectReason::time_jump);  // absurd as the first time too
  CHECK_FALSE(order.seen());
  CHECK(order.admit(ok, 10.0) == RejectReason::accepted);
  CHECK(order.admit(ok, 9.5) == RejectReason::time_backwards);
  CHECK(order.admit(ok, 10.0) == RejectReason::accepted);  // equal times are fine
  CHECK(order.admit(ok, 1e300) == RejectReason::time_jump);
  CHECK(order.admit(ok, 10.5) == RejectReason::accepted);  // judged against 10.0, not 1e300
  CHECK(order.admit(ok, 12.0) == RejectReason::time_jump);  // 1.5 s ahead, max_jump 1 s
  CHECK(order.admit(ok, 10.6) == RejectReason::accepted);
  CHECK(order.admit(ok, std::numeric_limits<double>::quiet_NaN()) == RejectReason::non_finite);
  CHECK(order.admit(ok, -std::numeric_limits<double>::infinity()) == RejectReason::non_finite);
  CHECK(order.admit(ok, 10.7) == RejectReason::accepted);
  CHECK(order.last() == 10.7);
}

TEST_CASE("StreamTimeOrder: a jump that enough points agree on is a pause, and the stream goes on from it") {
  sc::StreamTimeOrder order(small_confirmation(4));
  const sc::Projected ok = valid_projection();
  REQUIRE(order.admit(ok, 1.0) == RejectReason::accepted);
  CHECK(order.admit(ok, 50.0) == RejectReason::time_jump);
  CHECK(order.admit(ok, 50.1) == RejectReason::time_jump);
  CHECK(order.admit(ok, 50.2) == RejectReason::time_jump);
  CHECK(order.admit(ok, 50.3) == RejectReason::accepted);  // the 4th in agreement
  CHECK(order.admit(ok, 1.1) == RejectReason::time_backwards);
  CHECK(order.admit(ok, 50.4) == RejectReason::accepted);

  // Spikes that do not agree with each other never confirm.
  sc::StreamTimeOrder spikes(small_confirmation(3));
  REQUIRE(spikes.admit(ok, 1.0) == RejectReason::accepted);
  for (int i = 0; i < 100; ++i) {
    REQUIRE(spikes.admit(ok, i % 2 == 0 ? 1000.0 + i * 10.0 : 1.0 + i * 1e-3) ==
            (i % 2 == 0 ? RejectReason::time_jump : RejectReason::accepted));
  }
  // A valid point between jumps restarts the count; so does a jump that goes back.
  sc::StreamTimeOrder restart(small_confirmation(3));
  REQUIRE(restart.admit(ok, 1.0) == RejectReason::accepted);
  CHECK(restart.admit(ok, 100.0) == RejectReason::time_jump);
  CHECK(restart.admit(ok, 99.0) == RejectReason::time_jump);  // behind the run: a new run
  CHECK(restart.admit(ok, 99.5) == RejectReason::time_jump);
  CHECK(restart.admit(ok, 99.6) == RejectReason::accepted);
}

TEST_CASE("StreamTimeOrder: geometry does not change the order; advance may jump; parameters are checked") {
  sc::StreamTimeOrder order(small_confirmation(4));
  sc::Projected far = valid_projection();
  far.reason = RejectReason::outside_fov;
  REQUIRE(order.admit(valid_projection(), 1.0) == RejectReason::accepted);
  CHECK(order.admit(far, 1.5) == RejectReason::outside_fov);
  CHECK(order.admit(valid_projection(), 1.2) == RejectReason::time_backwards);  // the order moved to 1.5
  CHECK(order.last() == 1.0);  // the newest accepted point's time
  sc::StreamTimeOrder copy(small_confirmation(4));
  CHECK(copy.admit_time(1.0) == RejectReason::accepted);
  CHECK(copy.admit_time(1.5) == RejectReason::accepted);
  CHECK(copy.admit_time(1.2) == RejectReason::time_backwards);  // the same decisions from times alone
  REQUIRE(order.may_advance_to(100.0));
  order.advance(100.0);
  CHECK(order.admit(valid_projection(), 100.5) == RejectReason::accepted);
  CHECK_FALSE(order.may_advance_to(99.0));

  sc::StreamTimeOrder::Params bad;
  bad.max_jump = 0.0;
  CHECK_THROWS_AS(sc::StreamTimeOrder{bad}, std::invalid_argument);
  bad = {};
  bad.jump_confirmations = 0;
  CHECK_THROWS_AS(sc::StreamTimeOrder{bad}, std::invalid_argument);
  bad = {};
  bad.max_abs_time = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(sc::StreamTimeOrder{bad}, std::invalid_argument);
}

TEST_CASE("engine: one absurd timestamp costs one point; the oracle holds before and after it") {
  using Config = sc::CArcConfig;
  sc::ClustererParams<Config> params;
  params.window.duration = 0.05;
  const std::size_t n = 6000;
  const std::vector<sc::Point> clean = stream_with(n, 20000.0, {});
  const std::vector<sc::Point> spiked = stream_with(n, 20000.0, {{2000, 1e300}, {3000, 5000.0}, {4000, -1e12}});
  for (const bool continuous : {true, false}) {
    INFO((continuous ? "StreamClusterer" : "FrameClusterer"));
    std::vector<RejectReason> reasons;
    std::size_t cycles = 0;
    if (continuous) {
      sc::StreamClusterer<Config> engine(params);
      sc::BatchClusterer<Config> batch(params, sc::BatchMode::insertion_order);
      for (std::size_t i = 0; i < n; ++i) {
        reasons.push_back(engine.insert(spiked[i]));
        if (i % 500 == 499) {
          engine.retrieve();
          if (engine.calibrating()) continue;
          ++cycles;
          REQUIRE(sc::test::compare_with_batch(engine, batch) == "");
        }
      }
    } else {
      sc::FrameClusterer<Config> frame(params);
      for (std::size_t i = 0; i < n; ++i) reasons.push_back(frame.insert(spiked[i]));
      cycles = 1;
    }
    CHECK(cycles > 0);
    std::size_t jumps = 0, other = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (reasons[i] == RejectReason::time_jump) {
        ++jumps;
      } else if (reasons[i] != RejectReason::accepted) {
        ++other;
      }
    }
    // 1e300 and -1e12 are absurd; 5000 s is a jump of hours that no later point agrees with.
    CHECK(jumps == 3);
    CHECK(reasons[2000] == RejectReason::time_jump);
    CHECK(reasons[3000] == RejectReason::time_jump);
    CHECK(reasons[4000] == RejectReason::time_jump);
    // The clean stream's rejections, no more (blobs: none).
    std::size_t clean_rejected = 0;
    sc::StreamClusterer<Config> reference(params);
    for (const sc::Point& p : clean) clean_rejected += reference.insert(p) != RejectReason::accepted;
    CHECK(other == clean_rejected);
  }
}

TEST_CASE("engine: a pause longer than max_jump is taken after jump_confirmations points, oracle-exact") {
  using Config = sc::CArcConfig;
  sc::ClustererParams<Config> params;
  params.window.duration = 0.05;
  params.time_order.max_jump = 2.0;
  params.time_order.jump_confirmations = 16;
  std::vector<sc::Point> s = stream_with(4000, 20000.0, {});
  for (std::size_t i = 2000; i < s.size(); ++i) s[i].t += 30.0;  // a 30 s pause
  sc::StreamClusterer<Config> engine(params);
  sc::BatchClusterer<Config> batch(params, sc::BatchMode::insertion_order);
  std::vector<RejectReason> reasons;
  for (std::size_t i = 0; i < s.size(); ++i) {
    reasons.push_back(engine.insert(s[i]));
    if (i % 400 == 399) {
      engine.retrieve();
      if (!engine.calibrating()) REQUIRE(sc::test::compare_with_batch(engine, batch) == "");
    }
  }
  for (std::size_t i = 2000; i < 2015; ++i) CHECK(reasons[i] == RejectReason::time_jump);
  CHECK(reasons[2015] == RejectReason::accepted);
  std::size_t accepted_after = 0;
  for (std::size_t i = 2015; i < s.size(); ++i) accepted_after += reasons[i] == RejectReason::accepted;
  CHECK(accepted_after == s.size() - 2015);
  CHECK(engine.last_result().time == doctest::Approx(s.back().t));
}
