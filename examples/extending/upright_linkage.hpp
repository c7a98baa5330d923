// SPDX-License-Identifier: MIT
#pragma once

// UprightLinkage: the objects preset's range-adaptive radius, stretched along z. People, poles,
// chairs and shelves are taller than wide; their returns break up vertically (occluded legs, a
// desk's shadow, scan lines apart at range) while their neighbours stand beside them. Links iff
//   dx^2 + dy^2 + (dz / stretch)^2 <= r^2,  r = max(min_distance, range_factor x nearer range)
// z up in the frame points are placed in (a mount's or poses' world); stretch 1: RangeAdaptiveLinkage.
// Symmetric bit for bit (a swap only flips the differences' signs), stateless, O(1). Thread-safe.

#include <streamclust/registry/descriptor.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace upright {

class UprightLinkage {
 public:
  struct Params {
    float min_distance = 0.4f;   ///< [m] radius near the sensor, finite, > 0 (the objects preset's)
    float range_factor = 0.03f;  ///< [m per m of range] growth of the radius, in [0, 1] (the objects preset's)
    float stretch = 2.0f;        ///< vertical reach / horizontal reach, in [1, 10]
  };

  explicit UprightLinkage(const Params& p) : params_(p), inverse_stretch_(1.0f / p.stretch) {
    require(p.min_distance > 0.0f && std::isfinite(p.min_distance), "min_distance", p.min_distance, "finite, > 0 m");
    require(p.range_factor >= 0.0f && p.range_factor <= 1.0f, "range_factor", p.range_factor, "[0, 1]");
    require(p.stretch >= 1.0f && p.stretch <= 10.0f, "stretch", p.stretch, "[1, 10]");
  }

  bool operator()(const streamclust::Sample& a, const streamclust::Sample& b) const {
    const float r = std::max(params_.min_distance, params_.range_factor * std::min(a.range, b.range));
    const Eigen::Vector3f d = a.position - b.position;
    const float dz = d.z() * inverse_stretch_;
    return d.x() * d.x() + d.y() * d.y() + dz * dz <= r * r;
  }

 private:
  static void require(bool valid, const char* name, float value, const char* allowed) {
    if (!valid)
      throw std::invalid_argument(std::string("UprightLinkage: ") + name + " = " + std::to_string(value) +
                                  " is invalid; allowed: " + allowed);
  }
  Params params_;
  float inverse_stretch_;
};

}  // namespace upright

// The linkage's name and options in the tool (streamclust_add_tool), its help and `evaluate --json`.
template <>
struct streamclust::registry::PolicyDescriptor<upright::UprightLinkage> {
  static constexpr Slot slot = Slot::linkage;
  static constexpr const char* name = "upright";
  static constexpr const char* summary = "range-adaptive radius, --stretch times longer along z (upright objects)";
  static std::vector<Option<upright::UprightLinkage::Params>> options() {
    using P = upright::UprightLinkage::Params;
    return {option("--min-distance", &P::min_distance, "M", ValueKind::positive, "radius near the sensor [m]",
                   "min_distance"),
            option("--range-factor", &P::range_factor, "F", ValueKind::number,
                   "growth of the radius per metre of range [m/m], in [0, 1]", "range_factor"),
            option("--stretch", &P::stretch, "S", ValueKind::positive, "vertical reach over horizontal, in [1, 10]",
                   "stretch")};
  }
};
