// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// All policy concepts at once.

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/concepts/projection.hpp>
#include <streamclust/concepts/resolution.hpp>
#include <streamclust/concepts/spatial_index.hpp>
#include <streamclust/concepts/visitor.hpp>
#include <streamclust/concepts/window.hpp>
