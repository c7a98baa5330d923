// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The reflectivity a simulated Livox reports for a return: the surface's
/// reflectance (materials.hpp), its incidence angle and range, and
/// measurement noise, on the Livox scale (0-150: diffuse reflectance 0-100 %
/// in the Lambertian model; 151-255: retroreflective targets).
///
/// Model (docs/simulation-scenes.md#intensity gives the reasons):
///
///     diffuse:  v = 150 rho cos(theta) exp(-range_decay R)       in [0, 150]
///     retro:    v = 151 + 104 g cos^2(theta) exp(-range_decay R) in [151, 255]
///     reported  = round(v + N(0, sigma)), clamped to the scale of v
///     sigma     = sqrt(noise_floor^2 + shot_noise^2 (v / 100) (R / 10 m)^2)
///
/// with rho the diffuse reflectance, g the retroreflective gain, theta the
/// angle between the ray and the surface normal and R the true range. The
/// sensor's calibration takes out the 1/R^2 of the received power, not the
/// cos(theta) of a Lambertian surface (it cannot know the angle); the
/// residual `range_decay` stands for what the calibration leaves (1/R^2 not
/// exactly compensated, atmospheric loss). Noise is photon (shot) noise,
/// whose variance in calibrated units grows with the value and with R^2,
/// plus a floor.
///
/// Thread safety: pure functions.

#include <streamclust/detail/parameter_check.hpp>

#include <algorithm>
#include <cmath>

namespace streamclust::sim {

/// Livox's reflectivity scale.
inline constexpr float kDiffuseFullScale = 150.0f;  ///< a 100 % Lambertian target at normal incidence
inline constexpr float kRetroFloor = 151.0f;        ///< the lowest retroreflective reading
inline constexpr float kReflectivityMax = 255.0f;

/// Parameters of the reported reflectivity (see the file comment).
struct IntensityModel {
  float range_decay = 0.005f;  ///< residual fall-off with range [1/m], >= 0: 18 % lower at 40 m
  float noise_floor = 1.0f;    ///< standard deviation at zero signal [units], >= 0
  float shot_noise = 2.0f;     ///< standard deviation of a reading of 100 at 10 m [units], >= 0

  /// Throws std::invalid_argument naming a negative or non-finite field.
  void validate() const {
    check(range_decay, "intensity.range_decay", "a finite value >= 0 [1/m]");
    check(noise_floor, "intensity.noise_floor", "a finite value >= 0 [units]");
    check(shot_noise, "intensity.shot_noise", "a finite value >= 0 [units]");
  }

 private:
  static void check(float v, const char* name, const char* allowed) {
    streamclust::detail::require_parameter(std::isfinite(v) && v >= 0.0f, "Simulator::Params", name, v, allowed);
  }
};

/// The noise-free reading: `reflectance` (rho, or g when `retroreflective`),
/// `cos_incidence` = |cos theta| (clamped into [0, 1]), `range` [m].
inline float expected_reflectivity(const IntensityModel& model, float reflectance, bool retroreflective,
                                   float cos_incidence, float range) {
  const float c = std::clamp(std::abs(cos_incidence), 0.0f, 1.0f);
  const float decay = std::exp(-model.range_decay * std::max(range, 0.0f));
  const float rho = std::max(reflectance, 0.0f);
  if (retroreflective) {
    return std::min(kReflectivityMax, kRetroFloor + (kReflectivityMax - kRetroFloor) * std::min(1.0f, rho) * c * c * decay);
  }
  return std::min(kDiffuseFullScale, kDiffuseFullScale * rho * c * decay);
}

/// The standard deviation of a reading of noise-free value `value` at `range` [m].
inline float reflectivity_sigma(const IntensityModel& model, float value, float range) {
  const float r = std::max(range, 0.0f) / 10.0f;
  return std::sqrt(model.noise_floor * model.noise_floor +
                   model.shot_noise * model.shot_noise * std::max(value, 0.0f) / 100.0f * r * r);
}

/// The reported reading: the expected value plus `standard_normal` sigmas,
/// rounded to a whole unit and clamped to its scale (0-150 diffuse,
/// 151-255 retroreflective).
inline float reported_reflectivity(const IntensityModel& model, float reflectance, bool retroreflective,
                                   float cos_incidence, float range, double standard_normal) {
  const float v = expected_reflectivity(model, reflectance, retroreflective, cos_incidence, range);
  const float noisy = std::round(v + reflectivity_sigma(model, v, range) * static_cast<float>(standard_normal));
  return retroreflective ? std::clamp(noisy, kRetroFloor, kReflectivityMax) : std::clamp(noisy, 0.0f, kDiffuseFullScale);
}

}  // namespace streamclust::sim
