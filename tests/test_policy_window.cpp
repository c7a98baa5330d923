// SPDX-License-Identifier: MIT
// Unit tests of the window policies: the contract of every window of the
// Windows list (support/policy_lists.hpp), then each window's eviction
// simulated as the engine does it.

#include <doctest/doctest.h>

#include <streamclust/testing/doctest.hpp>
#include <streamclust/testing/window_laws.hpp>

#include "support/invalid_argument.hpp"
#include "support/policy_hooks.hpp"
#include "support/policy_lists.hpp"

#include <streamclust/window/count_window.hpp>
#include <streamclust/window/time_window.hpp>

#include <cstddef>
#include <deque>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using streamclust::CountWindow;
using streamclust::TimeWindow;

namespace {

/// The engine's loop: before inserting a point at time t, evict the oldest
/// while expired(oldest, t, size including the new point); then insert.
template <class W>
void push(const W& window, std::deque<double>& times, double t) {
  while (!times.empty() && window.expired(times.front(), t, times.size() + 1)) times.pop_front();
  times.push_back(t);
}

using streamclust::test::invalid_argument_message;

}  // namespace

// The test kit's window laws (<streamclust/testing/window_laws.hpp>) at the
// defaults and 11 random parameter sets.
TEST_CASE_TEMPLATE_DEFINE("window contract: the test kit's window laws hold", W, window_contract_id) {
  streamclust::testing::WindowLawOptions<W> options;
  std::mt19937_64 rng(31);
  options.params.resize(12);
  for (std::size_t k = 1; k < options.params.size(); ++k)
    streamclust::test::RandomParams<W>::draw(options.params[k], rng);
  STREAMCLUST_CHECK_LAW(streamclust::testing::check_window<W>(options));
}

TEST_CASE_TEMPLATE_APPLY(window_contract_id, streamclust::test::Windows);

TEST_CASE("TimeWindow: keeps exactly the points within duration of the newest") {
  // times k / 64 s are exact in binary: the boundary (difference == duration) is tested exactly
  const TimeWindow window{{0.125}};
  std::deque<double> times;
  for (int k = 0; k < 40; ++k) {
    const double t = k / 64.0;
    push(window, times, t);
    const std::size_t expected = static_cast<std::size_t>(k < 8 ? k + 1 : 9);  // 0.125 s = 8 steps, inclusive
    REQUIRE(times.size() == expected);
    CHECK(times.front() == (k < 8 ? 0.0 : (k - 8) / 64.0));
    CHECK(window.complete(times.front(), t, times.size()) == (k >= 8));
  }
  CHECK(window.expired(0.0, 0.125, 1) == false);
  CHECK(window.expired(0.0, 0.125 + 1.0 / 1024, 1) == true);
  CHECK(window.complete(0.0, 0.125, 1));
  CHECK_FALSE(window.complete(0.0, 0.125 - 1.0 / 1024, 1 << 20));  // size is ignored
}

TEST_CASE("TimeWindow: irregular timestamps match a brute-force filter") {
  const TimeWindow window{{0.1}};
  std::mt19937 rng(5);
  std::exponential_distribution<double> gap(2000.0);  // ~2 kHz with bursts
  std::deque<double> times;
  std::vector<double> all;
  double t = 100.0;
  for (int i = 0; i < 5000; ++i) {
    t += (i % 50 == 0) ? 0.3 : gap(rng);  // occasional dropouts longer than the window
    push(window, times, t);
    all.push_back(t);
    std::deque<double> expected;
    for (const double s : all)
      if (!(t - s > 0.1)) expected.push_back(s);
    REQUIRE(times == expected);
    REQUIRE(times.back() == t);
  }
}

TEST_CASE("TimeWindow: zero duration keeps only the newest timestamp") {
  const TimeWindow window{{0.0}};
  std::deque<double> times;
  for (const double t : {1.0, 1.0, 1.0, 2.0, 2.0, 3.0}) push(window, times, t);
  CHECK(times == std::deque<double>{3.0});
  push(window, times, 3.0);
  CHECK(times == std::deque<double>{3.0, 3.0});
  CHECK(window.complete(3.0, 3.0, 1));
}

TEST_CASE("TimeWindow: invalid duration throws") {
  for (const double bad : {-0.1, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    const std::string m = invalid_argument_message([&] { TimeWindow{{bad}}; });
    CHECK(m.find("duration") != std::string::npos);
  }
  CHECK(TimeWindow{{}}.params().duration == 0.1);
}

TEST_CASE("CountWindow: keeps the last capacity points, oldest leaves first") {
  const CountWindow window{{5}};
  std::deque<double> times;
  for (int k = 0; k < 12; ++k) {
    push(window, times, 0.5 * k);  // times are ignored, only order matters
    REQUIRE(times.size() == static_cast<std::size_t>(k < 5 ? k + 1 : 5));
    CHECK(times.front() == 0.5 * (k < 5 ? 0 : k - 4));
    CHECK(times.back() == 0.5 * k);
    CHECK(window.complete(times.front(), times.back(), times.size()) == (k >= 4));
  }
  CHECK_FALSE(window.expired(0.0, 1e9, 5));
  CHECK(window.expired(0.0, 0.0, 6));
  const CountWindow one{{1}};
  std::deque<double> single;
  for (const double t : {1.0, 2.0, 3.0}) push(one, single, t);
  CHECK(single == std::deque<double>{3.0});
}

TEST_CASE("CountWindow: invalid capacity throws") {
  const std::string m = invalid_argument_message([] { CountWindow{{0}}; });
  CHECK(m.find("capacity") != std::string::npos);
  CHECK(CountWindow{{}}.params().capacity == 20000u);
}
