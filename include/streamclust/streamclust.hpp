// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Everything a typical user needs: the engine, the batch clusterer, the
/// standard policies and the presets. Boost.Graph adaptors are separate
/// (<streamclust/graph/point_graph.hpp>, <streamclust/graph/component_graph.hpp>)
/// to keep this header light.

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/clustering.hpp>
#include <streamclust/connectivity/lazy_bfs.hpp>
#include <streamclust/connectivity/union_find_rebuild.hpp>
#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/index/overwrite_grid.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/combinators.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/linkage/scan_adaptive.hpp>
#include <streamclust/objects_presets.hpp>
#include <streamclust/point_traits.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/projection/cylindrical.hpp>
#include <streamclust/rebind_params.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/resolution/adaptive.hpp>
#include <streamclust/resolution/fixed.hpp>
#include <streamclust/stream_clusterer.hpp>
#include <streamclust/window/count_window.hpp>
#include <streamclust/window/time_window.hpp>
