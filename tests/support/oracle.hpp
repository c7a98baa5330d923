// SPDX-License-Identifier: MIT
#pragma once
// The oracle comparison of the engine's last retrieval with a batch run: the
// test kit's <streamclust/testing/oracle.hpp>, named in the tests' namespace.

#include <streamclust/testing/oracle.hpp>

namespace streamclust::test {

using ::streamclust::testing::compare_window_with_batch;
using ::streamclust::testing::compare_with_batch;

}  // namespace streamclust::test
