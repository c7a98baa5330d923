// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The laws the engine relies on for a motion policy (concepts/motion.hpp):
/// the engine places every offered point, the batch clusterer (the oracle)
/// only the window's object points with a fresh instance, so a placement
/// must not depend on which points were placed before:
///   - the default Params construct;
///   - `identity`: the world and the ray are the point, always accepted;
///   - history-free: one instance placing every point in time order, one
///     placing every other point and a fresh instance per point agree bit
///     for bit (reason, world, ray);
///   - a placement is `accepted` (world and ray finite) or `no_pose`;
///   - something is accepted.
/// Cost: O(points) placements, three times per parameter set. Not thread-safe.

#include <streamclust/concepts/motion.hpp>
#include <streamclust/testing/law_result.hpp>
#include <streamclust/testing/type_name.hpp>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace streamclust::testing {

template <class M>
struct MotionLawOptions {
  std::vector<typename M::Params> params;  ///< parameter sets to test; empty: the defaults
  /// The points (sensor frame, time in s, non-decreasing); empty: 5,000
  /// random points within 30 m over the first 2 s.
  std::vector<Point> points;
  std::uint64_t seed = 17;
};

/// Every law of a motion policy (see the file comment); the first failure.
template <class M>
LawResult check_motion(const MotionLawOptions<M>& options = {}) {
  static_assert(is_motion_policy_v<M>, "check_motion: M does not model the motion concept (concepts/motion.hpp)");
  const std::string name = "motion " + type_name<M>();
  if (const std::string failure = internal::default_params_failure<M>(name); !failure.empty())
    return law_failed(failure);
  std::vector<Point> points = options.points;
  if (points.empty()) {
    std::mt19937_64 rng(options.seed);
    std::uniform_real_distribution<float> coord(-30.0f, 30.0f);
    for (int i = 0; i < 5000; ++i) {
      const float x = coord(rng), y = coord(rng), z = 0.2f * coord(rng);
      points.push_back(Point{x, y, z, 0.0f, 2.0 * i / 5000.0});
    }
  }
  const std::vector<typename M::Params> sets = internal::parameter_sets(options.params);
  std::size_t accepted = 0;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const std::string context = name + ", parameter set " + std::to_string(k) + ": ";
    std::optional<M> all, every_other;
    if (const std::string thrown = internal::construct_from(sets[k], all, every_other); !thrown.empty())
      return law_failed(context + "the parameters do not construct: " + thrown);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3f p(points[i].x, points[i].y, points[i].z);
      const double t = points[i].t;
      PlacedPoint a, b, c;
      const RejectReason ra = all->place(p, t, a);
      RejectReason rb = ra;
      if (i % 2 == 0) {
        rb = every_other->place(p, t, b);
      } else {
        b = a;
      }
      M fresh{sets[k]};
      const RejectReason rc = fresh.place(p, t, c);
      const auto same = [&](const PlacedPoint& x, const PlacedPoint& y) {
        return (x.world.array() == y.world.array()).all() && (x.ray.array() == y.ray.array()).all();
      };
      std::ostringstream at;
      at.precision(17);
      at << context << "point " << i << " " << describe(points[i]) << ": ";
      if (ra != rb || ra != rc || (ra == RejectReason::accepted && (!same(a, b) || !same(a, c))))
        return law_failed(at.str() + "placed differently by an instance that placed every point before it, one that "
                          "placed every other point and a fresh one: a placement must not depend on the points "
                          "placed before");
      if (ra != RejectReason::accepted && ra != RejectReason::no_pose)
        return law_failed(at.str() + "rejected with a reason other than no_pose");
      if (ra != RejectReason::accepted) continue;
      ++accepted;
      if (!a.world.allFinite() || !a.ray.allFinite())
        return law_failed(at.str() + "accepted with a non-finite world point or ray");
      if constexpr (M::identity) {
        if (!(a.world.array() == p.array()).all() || !(a.ray.array() == p.array()).all())
          return law_failed(at.str() + "an identity motion must place the point at itself (world = ray = point)");
      }
    }
  }
  if (accepted == 0) return law_failed(name + ": no point was accepted");
  return law_passed(name + ": " + std::to_string(accepted) + " placements accepted");
}

}  // namespace streamclust::testing
