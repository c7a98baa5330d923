// SPDX-License-Identifier: MIT
// The single doctest main of the unit-test binary.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
