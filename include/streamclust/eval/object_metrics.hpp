// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// ObjectMetrics and object_metrics(): are the clusters objects, once a
/// structure stage has taken ground, wall and ceiling points out of
/// clustering? Strict object rates, object-point coverage, ground, wall and
/// ceiling precision / recall / F1, and the adjusted Rand index on object
/// points, from one call.

#include <streamclust/eval/contingency.hpp>
#include <streamclust/eval/options.hpp>
#include <streamclust/eval/rand_index.hpp>
#include <streamclust/eval/strict_object_rates.hpp>
#include <streamclust/eval/surface_scores.hpp>
#include <streamclust/surface_class.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {
namespace eval {

/// The object metrics of one frame (object_metrics()).
struct ObjectMetrics {
  std::size_t points = 0;                           ///< input length
  std::size_t evaluated_points = 0;                 ///< points with truth instance >= 0
  std::size_t object_points = 0;                    ///< points with truth instance > 0
  StrictObjectRates objects;                        ///< strict_object_rates()
  double object_point_coverage = 1.0;               ///< object points not classed ground / ceiling / wall (fraction)
  std::size_t object_points_classed_structure = 0;  ///< object points predicted -2, -3 or -4
  ClassScores ground;                               ///< predicted -2 against the class ground
  ClassScores ceiling;                              ///< predicted -3 against the class ceiling
  ClassScores wall;                                 ///< predicted -4 against the class wall
  double adjusted_rand_index = 1.0;                 ///< on object points; every negative prediction a singleton
};

/// Every object metric of one frame.
///
/// Inputs, one entry per point (same length, else std::invalid_argument):
/// - `truth_instance`: 0 = structure / stuff, > 0 = object instance, < 0 =
///   ignored (removed before every metric, from cluster sizes too).
/// - `truth_class`: the point's SurfaceClass; an object instance (> 0) must
///   have the class object (else std::invalid_argument).
/// - `predicted`: a cluster id >= 0, kUnlabelled (-1, or any negative other
///   than -2, -3 and -4), kClassedGround (-2), kClassedCeiling (-3) or
///   kClassedWall (-4).
///
/// Fields:
/// - objects: strict_object_rates() (a point predicted -1 ... -4 is in no
///   cluster; structure in a cluster is foreign to every object).
/// - object_point_coverage, ground, ceiling, wall: surface_scores().
/// - adjusted_rand_index: adjusted_rand_index() between truth instance and
///   prediction on the object points only (truth_instance > 0, whatever
///   options.ari_include_structure says), each point predicted -1 ... -4
///   a singleton cluster: an object the removal stage swallowed is lost, not
///   one well-grouped cluster.
///
/// \code
///   using streamclust::SurfaceClass;
///   std::vector<std::int64_t> instance{0, 0, 0, 1, 1, 1};
///   std::vector<SurfaceClass> cls{SurfaceClass::ground, SurfaceClass::ground, SurfaceClass::wall,
///                                 SurfaceClass::object, SurfaceClass::object, SurfaceClass::object};
///   std::vector<std::int64_t> predicted{-2, -2, 4, 7, 7, 7};
///   auto m = streamclust::eval::object_metrics(instance, cls, predicted);
///   // m.objects.correct == 1, m.object_point_coverage == 1, m.ground.f1 == 1, m.adjusted_rand_index == 1
/// \endcode
///
/// Complexity O(n log n) (one contingency table, 16 bytes per point
/// transiently) + O(n) (one pass for the surface scores); thread safety: pure
/// function. Throws std::invalid_argument on differing sizes, an invalid
/// class or invalid options.
inline ObjectMetrics object_metrics(const std::vector<std::int64_t>& truth_instance,
                                    const std::vector<SurfaceClass>& truth_class,
                                    const std::vector<std::int64_t>& predicted, const MetricOptions& options = {}) {
  options.validate();
  const SurfaceScores surfaces = surface_scores(truth_instance, truth_class, predicted);  // checks the inputs
  const ContingencyTable table{truth_instance, predicted};
  ObjectMetrics m;
  m.points = table.input_points();
  m.evaluated_points = table.evaluated_points();
  m.object_points = surfaces.object_points;
  m.objects = strict_object_rates(table, options);
  m.object_point_coverage = surfaces.object_point_coverage;
  m.object_points_classed_structure = surfaces.object_points_classed_structure;
  m.ground = surfaces.ground;
  m.ceiling = surfaces.ceiling;
  m.wall = surfaces.wall;
  MetricOptions objects_only = options;
  objects_only.ari_include_structure = false;
  m.adjusted_rand_index = adjusted_rand_index(table, objects_only);
  return m;
}

}  // namespace eval
}  // namespace streamclust
