// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The laws the engine relies on for a projection (concepts/projection.hpp):
///   - fov_aspect() finite and > 0;
///   - NaN or inf in any coordinate is rejected `non_finite` (also where the
///     point would be too close); the origin is `too_close`;
///   - deterministic: the same point projects to the same bits;
///   - an accepted point has u, v in [0, 1] and its range |x| (relative
///     1e-5); a finite point is never rejected `non_finite`;
///   - the random points are accepted and (given parameter sets with a
///     narrower field of view) rejected at times.
/// Cost: O(parameter sets x points). Not thread-safe.

#include <streamclust/concepts/projection.hpp>
#include <streamclust/testing/law_result.hpp>
#include <streamclust/testing/type_name.hpp>

#include <cmath>
#include <cstddef>
#include <exception>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace streamclust::testing {

template <class P>
struct ProjectionLawOptions {
  std::vector<typename P::Params> params;  ///< parameter sets to test; empty: the defaults
  std::size_t points = 20000;              ///< random points per parameter set, in [-30, 30]^2 x [-6, 6] m
  bool expect_rejections = false;          ///< require that some random point is rejected
  std::uint64_t seed = 8;
};

/// Every law of a projection (see the file comment); the first failure.
template <class P>
LawResult check_projection(const ProjectionLawOptions<P>& options = {}) {
  static_assert(is_projection_policy_v<P>,
                "check_projection: P does not model the projection concept (concepts/projection.hpp)");
  const std::string name = "projection " + type_name<P>();
  const std::vector<typename P::Params> sets = internal::parameter_sets(options.params);
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<float> coord(-30.0f, 30.0f);
  std::size_t accepted = 0;
  std::size_t rejected = 0;
  const auto text = [](const Eigen::Vector3f& x) {
    std::ostringstream os;
    os.precision(9);
    os << "(" << x.x() << ", " << x.y() << ", " << x.z() << ")";
    return os.str();
  };
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const std::string context = name + ", parameter set " + std::to_string(k) + ": ";
    std::optional<P> holder;
    if (const std::string thrown = internal::construct_from(sets[k], holder); !thrown.empty())
      return law_failed(context + "the parameters do not construct: " + thrown);
    const P& proj = *holder;
    if (!std::isfinite(proj.fov_aspect()) || !(proj.fov_aspect() > 0.0f))
      return law_failed(context + "fov_aspect() = " + std::to_string(proj.fov_aspect()) + ", expected finite > 0");
    for (int c = 0; c < 3; ++c) {
      for (const float bad : {kNaN, kInf, -kInf}) {
        Eigen::Vector3f x(1.0f, 2.0f, 0.5f);
        x[c] = bad;
        for (int twice = 0; twice < 2; ++twice) {
          if (proj.project(x).reason != RejectReason::non_finite)
            return law_failed(context + "the non-finite point " + text(x) + " is not rejected non_finite");
          x = Eigen::Vector3f::Zero();
          x[c] = bad;
        }
      }
    }
    for (const Eigen::Vector3f& origin : {Eigen::Vector3f(0.0f, 0.0f, 0.0f), Eigen::Vector3f(-0.0f, 0.0f, -0.0f)}) {
      if (proj.project(origin).reason != RejectReason::too_close)
        return law_failed(context + "the origin " + text(origin) + " is not rejected too_close");
    }
    for (std::size_t i = 0; i < options.points; ++i) {
      const Eigen::Vector3f x(coord(rng), coord(rng), 0.2f * coord(rng));
      const Projected p = proj.project(x);
      const Projected again = proj.project(x);
      if (p.reason != again.reason || (p.accepted() && (!(p.u == again.u) || !(p.v == again.v))))
        return law_failed(context + "not deterministic: " + text(x) + " projects differently when asked again");
      if (!p.accepted()) {
        if (p.reason == RejectReason::non_finite)
          return law_failed(context + "the finite point " + text(x) + " is rejected non_finite");
        ++rejected;
        continue;
      }
      ++accepted;
      if (!(p.u >= 0.0f && p.u <= 1.0f && p.v >= 0.0f && p.v <= 1.0f)) {
        std::ostringstream os;
        os << context << text(x) << " projects to u = " << p.u << ", v = " << p.v << ", outside [0, 1]";
        return law_failed(os.str());
      }
      const float norm = x.norm();
      if (!(std::fabs(p.range - norm) <= 1e-5f * norm)) {
        std::ostringstream os;
        os.precision(9);
        os << context << text(x) << " has range " << p.range << ", expected |x| = " << norm;
        return law_failed(os.str());
      }
    }
  }
  if (accepted == 0) return law_failed(name + ": no random point was accepted");
  if (options.expect_rejections && rejected == 0)
    return law_failed(name + ": no random point was rejected, though the parameter sets narrow the field of view");
  return law_passed(name + ": " + std::to_string(accepted) + " points accepted, " + std::to_string(rejected) +
                    " rejected");
}

}  // namespace streamclust::testing
