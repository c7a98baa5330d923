// SPDX-License-Identifier: MIT
#pragma once
// The oracle of an engine with a ground or motion policy: the
// test kit's <streamclust/testing/oracle_input.hpp>, named in the tests' namespace.

#include <streamclust/testing/oracle_input.hpp>

namespace streamclust::test {

using ::streamclust::testing::compare_with_batch_on_input;

}  // namespace streamclust::test
