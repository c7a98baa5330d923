// SPDX-License-Identifier: MIT
#pragma once
// Random and adversarial point streams for the property tests: the
// test kit's <streamclust/testing/streams.hpp>, named in the tests' namespace.

#include <streamclust/testing/streams.hpp>

namespace streamclust::test {

using ::streamclust::testing::StreamKind;
using ::streamclust::testing::offer;
using ::streamclust::testing::to_string;
using ::streamclust::testing::point_at;
using ::streamclust::testing::make_stream;

}  // namespace streamclust::test
