// SPDX-License-Identifier: MIT
#pragma once
// Type-level helpers over std::tuple lists of policies: the
// test kit's <streamclust/testing/type_product.hpp>, named in the tests' namespace.

#include <streamclust/testing/type_product.hpp>

namespace streamclust::test {

using ::streamclust::testing::tuple_concat;
using ::streamclust::testing::tuple_concat_t;
using ::streamclust::testing::tuple_product;
using ::streamclust::testing::tuple_product_t;
using ::streamclust::testing::tuple_pairwise;
using ::streamclust::testing::tuple_pairwise_t;
using ::streamclust::testing::apply_each;
using ::streamclust::testing::apply_each_t;
using ::streamclust::testing::tuple_filter;
using ::streamclust::testing::tuple_filter_t;
using ::streamclust::testing::tuple_stride;
using ::streamclust::testing::tuple_stride_t;
using ::streamclust::testing::tuple_contains;
using ::streamclust::testing::tuple_contains_v;
using ::streamclust::testing::type_tag;
using ::streamclust::testing::for_each_type;

}  // namespace streamclust::test
