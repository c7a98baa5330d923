// SPDX-License-Identifier: MIT
#pragma once

// A linkage the library does not ship, registered for a tool built by
// streamclust_add_tool (tests/CMakeLists.txt: the add_tool test): Euclidean
// within --distance and intensities at most --intensity-gap apart.

#include <streamclust/registry/descriptor.hpp>
#include <streamclust/types.hpp>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace gated {

class IntensityGatedLinkage {
 public:
  struct Params {
    float max_distance = 0.5f;   ///< [m], > 0
    float intensity_gap = 20.0f;  ///< [intensity units], > 0
  };
  explicit IntensityGatedLinkage(const Params& p) : params_(p) {
    if (!(p.max_distance > 0.0f) || !(p.intensity_gap > 0.0f) || !std::isfinite(p.intensity_gap))
      throw std::invalid_argument("IntensityGatedLinkage: max_distance and intensity_gap must be finite and > 0");
  }
  /// Symmetric: both tests are.
  bool operator()(const streamclust::Sample& a, const streamclust::Sample& b) const {
    return (a.position - b.position).squaredNorm() <= params_.max_distance * params_.max_distance &&
           std::abs(a.intensity - b.intensity) <= params_.intensity_gap;
  }

 private:
  Params params_;
};

}  // namespace gated

template <>
struct streamclust::registry::PolicyDescriptor<gated::IntensityGatedLinkage> {
  static constexpr Slot slot = Slot::linkage;
  static constexpr const char* name = "intensity-gated";
  static constexpr const char* summary = "Euclidean within --distance, intensities within --intensity-gap";
  static std::vector<Option<gated::IntensityGatedLinkage::Params>> options() {
    using P = gated::IntensityGatedLinkage::Params;
    return {option("--distance", &P::max_distance, "M", ValueKind::positive, "threshold [m]", "distance"),
            option("--intensity-gap", &P::intensity_gap, "I", ValueKind::positive,
                   "largest intensity difference of a link", "intensity_gap")};
  }
};
