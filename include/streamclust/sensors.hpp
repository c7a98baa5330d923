// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The facts of the Livox sensors streamclust knows, in one table: field of
/// view, point rate, lasers. The presets, the scan simulator's sensor models,
/// the command-line tool, the examples, the tests and the benchmarks read
/// them from here.

namespace streamclust {

/// Degrees by which a projection's bounds exceed a sensor's field of view
/// (SensorFacts::projection_*): every ray of the real firing tables and of the
/// simulator's models falls inside (the Mid-360's official table reaches
/// -7.2 .. 52.2 deg of elevation against the spec sheet's -7 .. 52; the Avia
/// model reaches 35.23 deg of azimuth against 35.2).
inline constexpr double kFieldOfViewMarginDeg = 0.5;

/// What a sensor's spec sheet says, as far as streamclust uses it. Angles in
/// degrees in the sensor frame (x forward, y left, z up; azimuth about +z from
/// +x, elevation from the x-y plane). A plain constexpr aggregate: no
/// allocation, thread-safe.
struct SensorFacts {
  const char* name;             ///< product name, e.g. "Livox Mid-360"
  double horizontal_fov_deg;    ///< azimuth extent [deg], centred on +x; 360 = all around
  double vertical_fov_min_deg;  ///< lowest elevation [deg]
  double vertical_fov_max_deg;  ///< highest elevation [deg]
  bool circular_fov;            ///< the FOV is a disc about +x of diameter horizontal_fov_deg (Mid-40, Mid-70)
  double point_rate_hz;         ///< points per second, first return [Hz]
  int lasers;                   ///< lasers (beams) fired in turn, slot i is laser i mod lasers; 0 = not stated

  /// Vertical extent [deg].
  constexpr double vertical_fov_deg() const { return vertical_fov_max_deg - vertical_fov_min_deg; }

  /// True when the azimuth covers the full circle.
  constexpr bool all_around() const { return horizontal_fov_deg >= 360.0; }

  /// Bounds of a spherical projection holding every ray of the sensor: the
  /// FOV widened by `margin_deg` on each side, within [-180, 180] x [-90, 90].
  /// Float, as SphericalProjection::Params holds them.
  constexpr float projection_azimuth_min_deg(double margin_deg = kFieldOfViewMarginDeg) const {
    return all_around() ? -180.0f : static_cast<float>(clamp(-horizontal_fov_deg / 2.0 - margin_deg, 180.0));
  }
  constexpr float projection_azimuth_max_deg(double margin_deg = kFieldOfViewMarginDeg) const {
    return all_around() ? 180.0f : static_cast<float>(clamp(horizontal_fov_deg / 2.0 + margin_deg, 180.0));
  }
  constexpr float projection_elevation_min_deg(double margin_deg = kFieldOfViewMarginDeg) const {
    return static_cast<float>(clamp(vertical_fov_min_deg - margin_deg, 90.0));
  }
  constexpr float projection_elevation_max_deg(double margin_deg = kFieldOfViewMarginDeg) const {
    return static_cast<float>(clamp(vertical_fov_max_deg + margin_deg, 90.0));
  }

 private:
  static constexpr double clamp(double v, double limit) { return v < -limit ? -limit : (v > limit ? limit : v); }
};

/// Livox Mid-360: 360 x 59 deg (-7 .. 52 deg elevation), 200 kHz, 4 lasers.
/// Its official firing table (replayed by sim::TableReplay) spans -7.2 .. 52.2 deg.
inline constexpr SensorFacts livox_mid360{"Livox Mid-360", 360.0, -7.0, 52.0, false, 200000.0, 4};

/// Livox Avia: 70.4 x 77.2 deg (non-repetitive, circular-ish rosette), 240 kHz
/// first return, 6 beams of 40 kHz.
inline constexpr SensorFacts livox_avia{"Livox Avia", 70.4, -38.6, 38.6, false, 240000.0, 6};

/// Livox Mid-40: 38.4 deg circular FOV, 100 kHz, 1 laser.
inline constexpr SensorFacts livox_mid40{"Livox Mid-40", 38.4, -19.2, 19.2, true, 100000.0, 1};

/// Livox Mid-70: 70.4 deg circular FOV (rosette, dense centre), 100 kHz, 1 laser.
inline constexpr SensorFacts livox_mid70{"Livox Mid-70", 70.4, -35.2, 35.2, true, 100000.0, 1};

/// Livox Mid-100: three Mid-40 units side by side, 98.4 x 38.4 deg, 300 kHz
/// (100 kHz per unit, one laser each).
inline constexpr SensorFacts livox_mid100{"Livox Mid-100", 98.4, -19.2, 19.2, false, 300000.0, 3};

/// Livox Horizon: 81.7 x 25.1 deg, 240 kHz, 6 lasers.
inline constexpr SensorFacts livox_horizon{"Livox Horizon", 81.7, -12.55, 12.55, false, 240000.0, 6};

/// Livox Tele-15: 14.5 x 16.2 deg, 240 kHz.
inline constexpr SensorFacts livox_tele15{"Livox Tele-15", 14.5, -8.1, 8.1, false, 240000.0, 0};

/// Livox HAP (TX): 120 x 25 deg, 452 kHz.
inline constexpr SensorFacts livox_hap{"Livox HAP", 120.0, -12.5, 12.5, false, 452000.0, 0};

}  // namespace streamclust
