// SPDX-License-Identifier: MIT
#pragma once
// Comparing partitions up to renaming of labels, with a message: the
// test kit's <streamclust/testing/partition.hpp>, named in the tests' namespace.

#include <streamclust/testing/partition.hpp>

namespace streamclust::test {

using ::streamclust::testing::partition_mismatch;

}  // namespace streamclust::test
