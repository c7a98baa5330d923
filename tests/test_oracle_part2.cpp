// SPDX-License-Identifier: MIT
// The oracle, slice 2 of 3 of the generated product of the policy lists
// (support/oracle_product.hpp; slice 1 is in test_oracle.cpp).

#include <doctest/doctest.h>

#include "support/oracle_product.hpp"

TEST_CASE_TEMPLATE_APPLY(oracle_id, streamclust::test::OracleSlice<1>);
