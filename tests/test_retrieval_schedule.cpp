// SPDX-License-Identifier: MIT
// RetrievalSchedule: retrievals at t0 + k / rate, before the first record at
// or after each, a pause skipped, never the same time twice.

#include <doctest/doctest.h>

#include <streamclust/retrieval_schedule.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

using streamclust::RetrievalSchedule;

namespace {

std::vector<double> due_times(RetrievalSchedule& s, const std::vector<double>& times) {
  std::vector<double> out;
  for (const double t : times) {
    if (const auto due = s.on_record(t)) out.push_back(*due);
  }
  return out;
}

}  // namespace

TEST_CASE("RetrievalSchedule: one retrieval per period, a pause skips the empty ones") {
  RetrievalSchedule s(10.0);
  CHECK_FALSE(s.started());
  CHECK_FALSE(s.on_record(std::numeric_limits<double>::quiet_NaN()).has_value());  // does not start it
  CHECK_FALSE(s.started());
  // t0 = 1.0: retrievals due at 1.1 (before 1.12), 1.2 (before 1.25), then
  // the pause to 1.62 gives one at 1.3 and the next is 1.7 (before 1.71).
  const auto due = due_times(s, {1.0, 1.05, 1.12, 1.15, 1.25, 1.62, 1.65, 1.71});
  CHECK(s.started());
  CHECK(s.first_time() == 1.0);
  REQUIRE(due.size() == 4);
  CHECK(due[0] == doctest::Approx(1.1));
  CHECK(due[1] == doctest::Approx(1.2));
  CHECK(due[2] == doctest::Approx(1.3));
  CHECK(due[3] == doctest::Approx(1.7));
  CHECK(s.next_time() == doctest::Approx(1.8));
  CHECK(s.period() == doctest::Approx(0.1));
}

TEST_CASE("RetrievalSchedule never schedules the same time twice when floor() rounds down") {
  // From t0 = 0.3 at 10 Hz, (0.7 - 0.3) / 0.1 is 3.9999999999999996 in double.
  RetrievalSchedule s(10.0);
  const auto due = due_times(s, {0.3, 0.45, 0.65, 0.7, 0.72, 0.75});
  REQUIRE(due.size() == 3);
  CHECK(due[0] == doctest::Approx(0.4));
  CHECK(due[1] == doctest::Approx(0.5));
  CHECK(due[2] == doctest::Approx(0.7));
  for (std::size_t i = 1; i < due.size(); ++i) CHECK(due[i] > due[i - 1]);
}

TEST_CASE("RetrievalSchedule rejects a rate that is not finite and positive") {
  CHECK_THROWS_AS(RetrievalSchedule{0.0}, std::invalid_argument);
  CHECK_THROWS_AS(RetrievalSchedule{-5.0}, std::invalid_argument);
  CHECK_THROWS_AS(RetrievalSchedule{std::numeric_limits<double>::infinity()}, std::invalid_argument);
}
