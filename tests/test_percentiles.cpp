// SPDX-License-Identifier: MIT
// The project's one percentile definition (nearest rank) and its summary.

#include <doctest/doctest.h>

#include <streamclust/percentiles.hpp>

#include <vector>

TEST_CASE("nearest-rank percentiles: the smallest value with at least p % at or below it") {
  const std::vector<double> sorted{1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  CHECK(streamclust::percentile_sorted(sorted, 0.0) == 1.0);
  CHECK(streamclust::percentile_sorted(sorted, 10.0) == 1.0);
  CHECK(streamclust::percentile_sorted(sorted, 11.0) == 2.0);
  CHECK(streamclust::percentile_sorted(sorted, 50.0) == 5.0);
  CHECK(streamclust::percentile_sorted(sorted, 99.0) == 10.0);
  CHECK(streamclust::percentile_sorted(sorted, 100.0) == 10.0);
  CHECK(streamclust::percentile_sorted({}, 50.0) == 0.0);
  CHECK(streamclust::percentile({5, 1, 4, 2, 3}, 50.0) == 3.0);
  CHECK(streamclust::percentile({5, 1, 4, 2}, 50.0) == 2.0);  // no interpolation: a value of the sample
}

TEST_CASE("summarize: percentiles, maximum and mean of an unsorted sample") {
  std::vector<double> v;
  for (int i = 200; i >= 1; --i) v.push_back(i);
  const streamclust::LatencySummary s = streamclust::summarize(v);
  CHECK(s.count == 200);
  CHECK(s.p1 == 2.0);
  CHECK(s.q1 == 50.0);
  CHECK(s.median == 100.0);
  CHECK(s.q3 == 150.0);
  CHECK(s.p95 == 190.0);
  CHECK(s.p99 == 198.0);
  CHECK(s.p999 == 200.0);
  CHECK(s.max == 200.0);
  CHECK(s.mean == doctest::Approx(100.5));
  CHECK(streamclust::summarize({}).count == 0);
}
