// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// SplitMix64: a small deterministic generator, the same on every platform.

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace streamclust::detail {

/// SplitMix64 with its own distributions, so that the simulator's streams
/// are bit-identical across standard libraries (std::*_distribution are
/// implementation-defined). Not thread-safe; cheap to copy.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed = 1) : state_(seed) {}

  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  float uniform(float lo, float hi) { return lo + static_cast<float>(uniform()) * (hi - lo); }
  /// Uniform integer in [lo, hi] (hi >= lo; the tiny modulo bias is irrelevant here).
  int uniform_int(int lo, int hi) {
    const auto span = static_cast<std::uint64_t>(static_cast<std::int64_t>(hi) - lo + 1);
    return lo + static_cast<int>(next() % span);
  }
  /// Uniform integer in [0, n) (n > 0; the modulo bias is below 2^-40 for n < 2^24).
  std::size_t below(std::size_t n) { return static_cast<std::size_t>((next() >> 11) % n); }
  /// Standard normal (Box-Muller, one value per call).
  double normal() {
    constexpr double kTwoPi = 6.283185307179586476925;
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
  }

 private:
  std::uint64_t state_;
};

}  // namespace streamclust::detail
