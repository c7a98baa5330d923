// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The test kit in doctest: a law that fails is a doctest failure that
/// prints the law's message (the policy, the law, the evidence).
///
/// \code
/// #include <streamclust/testing/doctest.hpp>
/// #include <streamclust/testing/testing.hpp>
/// TEST_CASE("my linkage keeps the linkage laws") {
///   STREAMCLUST_CHECK_LAW(streamclust::testing::check_linkage<MyLinkage>());
/// }
/// \endcode
/// Needs doctest's include directory (doctest/doctest.h); any other
/// framework uses the LawResult directly: `passed` and `message`.

#include <doctest/doctest.h>

#include <streamclust/testing/law_result.hpp>

/// A doctest CHECK of a LawResult (or an ExactnessReport): on failure the
/// law's message is the check's message. Evaluates the expression once.
#define STREAMCLUST_CHECK_LAW(...)                                                     \
  do {                                                                                 \
    const ::streamclust::testing::LawResult& streamclust_law_result_ = (__VA_ARGS__);  \
    CHECK_MESSAGE(streamclust_law_result_.passed, streamclust_law_result_.message);    \
  } while (false)

/// As STREAMCLUST_CHECK_LAW, a REQUIRE: the test case stops on failure.
#define STREAMCLUST_REQUIRE_LAW(...)                                                   \
  do {                                                                                 \
    const ::streamclust::testing::LawResult& streamclust_law_result_ = (__VA_ARGS__);  \
    REQUIRE_MESSAGE(streamclust_law_result_.passed, streamclust_law_result_.message);  \
  } while (false)
