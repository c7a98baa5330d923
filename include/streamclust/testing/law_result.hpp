// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// What every check of the test kit returns: whether the law held and, when
/// it did not, a message that names the policy, the law and the smallest
/// evidence found (the pair, the operation, the seed). Usable from any test
/// framework: `if (!r) fail(r.message)`; doctest: testing/doctest.hpp.

#include <streamclust/point_traits.hpp>
#include <streamclust/types.hpp>

#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

namespace streamclust::testing {

/// The outcome of one law (or of a family's laws, the first failure).
struct LawResult {
  bool passed = true;
  std::string message;  ///< on failure: what broke, with the evidence; on success: a summary (may be empty)

  explicit operator bool() const { return passed; }
};

inline LawResult law_passed(std::string summary = {}) { return LawResult{true, std::move(summary)}; }
inline LawResult law_failed(std::string message) { return LawResult{false, std::move(message)}; }

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
