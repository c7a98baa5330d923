// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The laws the engine relies on for a resolution (concepts/resolution.hpp),
/// on an empty first window and uniform clouds of 1 to 20,000 points with
/// field-of-view aspects 0.5, 1 and 6:
///   - a grid it reports is never zero (rows, cols >= 1);
///   - calibrate returns a valid grid, ends the calibration (once), and
///     grid() reports it afterwards;
///   - deterministic: a second instance calibrates to the same grid.
/// Cost: the policy's calibration on 20,000 points, 12 times per parameter set.

#include <streamclust/concepts/resolution.hpp>
#include <streamclust/testing/law_result.hpp>
#include <streamclust/testing/type_name.hpp>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace streamclust::testing {

template <class R>
struct ResolutionLawOptions {
  std::vector<typename R::Params> params;  ///< parameter sets to test; empty: the defaults
  std::uint32_t seed = 3;
};

/// `n` accepted coordinates uniform in [0, 1)^2 (range 5 m).
inline std::vector<Projected> uniform_projected_cloud(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Projected> out;
  for (std::size_t i = 0; i < n; ++i) {
    Projected p;
    p.u = unit(rng);
    p.v = unit(rng);
    p.range = 5.0f;
    out.push_back(p);
  }
  return out;
}

/// Every law of a resolution (see the file comment); the first failure.
template <class R>
LawResult check_resolution(const ResolutionLawOptions<R>& options = {}) {
  static_assert(is_resolution_policy_v<R>,
                "check_resolution: R does not model the resolution concept (concepts/resolution.hpp)");
  const std::string name = "resolution " + type_name<R>();
  const std::vector<typename R::Params> sets = internal::parameter_sets(options.params);
  const auto valid = [](GridSize g) { return g.rows >= 1 && g.cols >= 1; };
  const auto text = [](GridSize g) { return std::to_string(g.rows) + "x" + std::to_string(g.cols); };
  for (std::size_t k = 0; k < sets.size(); ++k) {
    for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{500}, std::size_t{20000}}) {
      for (const float aspect : {0.5f, 1.0f, 6.0f}) {
        const std::string context = name + ", parameter set " + std::to_string(k) + ", " + std::to_string(n) +
                                    " points, aspect " + std::to_string(aspect) + ": ";
        const std::vector<Projected> cloud = uniform_projected_cloud(n, options.seed + static_cast<std::uint32_t>(n));
        std::optional<R> a, b;
        if (const std::string thrown = internal::construct_from(sets[k], a, b); !thrown.empty())
          return law_failed(context + "the parameters do not construct: " + thrown);
        if (!a->needs_calibration() && !valid(a->grid())) return law_failed(context + "grid() is " + text(a->grid()));
        const GridSize chosen = a->calibrate(cloud, aspect);
        if (!valid(chosen)) return law_failed(context + "calibrate chose " + text(chosen));
        if (a->needs_calibration()) return law_failed(context + "still needs calibration after calibrate");
        if (a->grid() != chosen)
          return law_failed(context + "grid() is " + text(a->grid()) + " after calibrate chose " + text(chosen));
        const GridSize again = b->calibrate(cloud, aspect);
        if (again != chosen)
          return law_failed(context + "not deterministic: a second instance chose " + text(again) + ", the first " +
                            text(chosen));
      }
    }
  }
  return law_passed(name + ": " + std::to_string(sets.size()) + " parameter sets");
}

}  // namespace streamclust::testing
