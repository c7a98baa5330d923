// SPDX-License-Identifier: MIT
#pragma once
// Readable names of types: the
// test kit's <streamclust/testing/type_name.hpp>, named in the tests' namespace.

#include <streamclust/testing/type_name.hpp>

namespace streamclust::test {

using ::streamclust::testing::type_name;

}  // namespace streamclust::test
