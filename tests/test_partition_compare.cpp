// SPDX-License-Identifier: MIT
// first_partition_mismatch: labelings compared as partitions, up to renaming.

#include <doctest/doctest.h>

#include <streamclust/partition_compare.hpp>

#include <cstdint>
#include <vector>

using streamclust::first_partition_mismatch;

TEST_CASE("first_partition_mismatch finds the first point where two partitions differ") {
  using V = std::vector<std::int64_t>;
  CHECK_FALSE(first_partition_mismatch(V{0, 0, 1, 2}, V{7, 7, 3, 9}).has_value());
  CHECK_FALSE(first_partition_mismatch(V{}, V{}).has_value());
  const auto split = first_partition_mismatch(V{0, 0, 1}, V{7, 8, 3});
  REQUIRE(split.has_value());
  CHECK(split->position == 1);
  CHECK_FALSE(split->sizes_differ);
  const auto merge = first_partition_mismatch(V{0, 1, 1}, V{4, 4, 4});
  REQUIRE(merge.has_value());
  CHECK(merge->position == 1);
  const auto late = first_partition_mismatch(V{0, 1, 0, 1}, V{5, 6, 5, 5});
  REQUIRE(late.has_value());
  CHECK(late->position == 3);
  const auto lengths = first_partition_mismatch(V{0, 1}, V{0, 1, 2});
  REQUIRE(lengths.has_value());
  CHECK(lengths->position == 2);
  CHECK(lengths->sizes_differ);
}

TEST_CASE("first_partition_mismatch compares labels of different types; -1 is a label like any other") {
  const std::vector<std::uint64_t> engine{3, 3, 9};
  const std::vector<std::int64_t> batch{0, 0, -1};
  CHECK_FALSE(first_partition_mismatch(engine, batch).has_value());
  CHECK(first_partition_mismatch(std::vector<std::int64_t>{-1, 0}, std::vector<std::int64_t>{-1, -1}).has_value());
}
