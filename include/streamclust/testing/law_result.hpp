// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// What every check of the test kit returns: whether the law held and, when
/// it did not, a message that names the policy, the law and the smallest
/// evidence found (the pair, the operation, the seed). Usable from any test
/// framework: `if (!r) fail(r.message)`; doctest: testing/doctest.hpp.

#include <streamclust/point_traits.hpp>
#include <streamclust/types.hpp>

#include <exception>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::testing {

/// The outcome of one law (or of a family's laws, the first failure).
struct LawResult {
  bool passed = true;
  std::string message;  ///< on failure: what broke, with the evidence; on success: a summary (may be empty)

  explicit operator bool() const { return passed; }
};

inline LawResult law_passed(std::string summary = {}) { return LawResult{true, std::move(summary)}; }
inline LawResult law_failed(std::string message) { return LawResult{false, std::move(message)}; }

namespace internal {

/// The parameter sets a check runs: `given`, or the defaults alone.
template <class Params>
std::vector<Params> parameter_sets(const std::vector<Params>& given) {
  return given.empty() ? std::vector<Params>(1) : given;
}

/// Constructs every `out` from `params`: "" or what a constructor threw.
template <class Params, class... Policies>
std::string construct_from(const Params& params, std::optional<Policies>&... out) {
  try {
    (out.emplace(params), ...);
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

/// The law "the default Params construct": "" or the failure, for `name`.
template <class Policy>
std::string default_params_failure(const std::string& name) {
  std::optional<Policy> p;
  const std::string thrown = construct_from(typename Policy::Params{}, p);
  return thrown.empty() ? thrown : name + ": the default Params do not construct: " + thrown;
}

}  // namespace internal

/// A Sample as text, every float with enough digits to rebuild it bit for
/// bit (max_digits10): paste it into a regression test.
inline std::string describe(const Sample& s) {
  std::ostringstream os;
  os << std::setprecision(std::numeric_limits<float>::max_digits10) << "{position (" << s.position.x() << ", "
     << s.position.y() << ", " << s.position.z() << ") m, direction (" << s.direction.x() << ", " << s.direction.y()
     << ", " << s.direction.z() << "), range " << s.range << " m, intensity " << s.intensity << ", time "
     << std::setprecision(std::numeric_limits<double>::max_digits10) << s.time << " s}";
  return os.str();
}

/// A Point as text (x y z intensity t), exact as describe(Sample).
inline std::string describe(const Point& p) {
  std::ostringstream os;
  os << std::setprecision(std::numeric_limits<float>::max_digits10) << "{" << p.x << ", " << p.y << ", " << p.z
     << ", " << p.intensity << ", " << std::setprecision(std::numeric_limits<double>::max_digits10) << p.t << "}";
  return os.str();
}

}  // namespace streamclust::testing
