// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The result of one retrieval: a label per point in the window and a summary
/// per connected component, with range-v3 views instead of copies.

#include <streamclust/surface_class.hpp>
#include <streamclust/types.hpp>

#include <range/v3/view/filter.hpp>
#include <range/v3/view/transform.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {

/// One point of the window and the component it belongs to.
struct PointLabel {
  std::uint64_t stream_index = 0;  ///< position of the point in the input stream (0-based, rejected points counted)
  ComponentId label = kNoComponent;  ///< stable id of the point's component
};

/// A window point the ground policy classed as structure (ground, wall or
/// ceiling).
struct StructurePoint {
  std::uint64_t stream_index = 0;              ///< position of the point in the input stream
  SurfaceClass surface = SurfaceClass::ground;  ///< ground, wall or ceiling
};

/// Summary of one connected component.
struct ComponentSummary {
  ComponentId id = kNoComponent;  ///< stable id (see StreamClusterer for the merge/split rule)
  std::size_t size = 0;           ///< points in the window
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  ///< mean position [m]
  Eigen::Vector3f min = Eigen::Vector3f::Zero();       ///< axis-aligned box, lower corner [m]
  Eigen::Vector3f max = Eigen::Vector3f::Zero();       ///< axis-aligned box, upper corner [m]
  double time_begin = 0.0;  ///< oldest point [s]
  double time_end = 0.0;    ///< newest point [s]
};

/// A labelled window. Every window point is in exactly one of `points` (an
/// object point, labelled with its component) and `structure` (classed
/// ground, wall or ceiling by the engine's ground policy; empty without one);
/// rejected points are in neither (the engine's RejectionCounts). Both are
/// in window order (oldest first); `components` is sorted by id. Filled by
/// `StreamClusterer::retrieve()`; the engine reuses the storage on the next
/// retrieval.
struct Clustering {
  std::vector<PointLabel> points;
  std::vector<ComponentSummary> components;
  std::vector<StructurePoint> structure;
  double time = 0.0;        ///< stream time of the newest point [s]
  std::uint64_t cycle = 0;  ///< retrievals so far, this one included

  /// View of the components with at least `min_points` points (no copy).
  auto components_with_at_least(std::size_t min_points) const {
    return components | ranges::views::filter([min_points](const ComponentSummary& c) { return c.size >= min_points; });
  }
  /// View of the labels in window order.
  auto labels() const {
    return points | ranges::views::transform([](const PointLabel& p) { return p.label; });
  }
};

}  // namespace streamclust
