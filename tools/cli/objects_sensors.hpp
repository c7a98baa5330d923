// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The sensors `streamclust evaluate --objects` simulates, read by its
/// option parser (the names) and by the evaluation (the facts and the
/// paper's theta of each). Constant data, thread-safe.

#include "cli/options.hpp"

#include <streamclust/sensors.hpp>

#include <string>

namespace streamclust::cli {

/// The sensors this evaluation knows: their facts (FOV) and the paper's theta.
struct ObjectsSensor {
  const char* name;
  const SensorFacts* facts;
  float carc_theta_deg;  ///< the paper's per-sensor theta; 10 (Bogoslavskyi's) where the paper gives none
};

inline constexpr ObjectsSensor kObjectsSensors[] = {{"mid360", &livox_mid360, 30.0f},
                                                    {"avia", &livox_avia, 80.0f},
                                                    {"mid40", &livox_mid40, 10.0f},
                                                    {"mid70", &livox_mid70, 10.0f}};

/// The sensor named `name`; UsageError naming the known ones otherwise. O(1).
inline const ObjectsSensor& objects_sensor(const std::string& name) {
  for (const ObjectsSensor& s : kObjectsSensors) {
    if (name == s.name) return s;
  }
  throw UsageError("--sensor: evaluate --objects needs a Livox model: mid360|avia|mid40|mid70, got '" + name + "'");
}

}  // namespace streamclust::cli
