// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The test kit: the laws the engine relies on for each policy family, and
/// the exactness check of a configuration, as plain functions that return a
/// LawResult (passed + a readable message); testing/doctest.hpp reports them
/// in doctest. Header-only; CMake target `streamclust::testing`
/// (streamclust + sim). docs/testing.md shows how to test a policy of your own.

#include <streamclust/testing/candidate_pairs.hpp>
#include <streamclust/testing/connectivity_laws.hpp>
#include <streamclust/testing/exactness.hpp>
#include <streamclust/testing/exactness_run.hpp>
#include <streamclust/testing/ground_laws.hpp>
#include <streamclust/testing/index_laws.hpp>
#include <streamclust/testing/law_result.hpp>
#include <streamclust/testing/linkage_laws.hpp>
#include <streamclust/testing/livox_streams.hpp>
#include <streamclust/testing/motion_laws.hpp>
#include <streamclust/testing/projection_laws.hpp>
#include <streamclust/testing/random_params.hpp>
#include <streamclust/testing/resolution_laws.hpp>
#include <streamclust/testing/window_laws.hpp>
