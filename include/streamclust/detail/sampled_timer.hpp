// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// SampledTimer: the total time of a call made once per point, estimated
/// from one call in kEvery.

#include <chrono>
#include <cstdint>
#include <type_traits>

namespace streamclust::detail {

/// Times one call in kEvery and counts it kEvery times: an estimate of the
/// calls' total time at a sixteenth of the clock reads (two reads of about
/// 20 ns each per timed call, against calls of 20-100 ns). Unbiased over
/// many calls when their cost does not follow the sampling period. Thread
/// safety: none.
class SampledTimer {
 public:
  static constexpr std::uint32_t kEvery = 16;

  /// Runs `call` and returns what it returns; times it when its turn comes.
  template <class Call>
  decltype(auto) run(Call&& call) {
    if (++calls_ % kEvery != 0) return call();
    const auto t0 = std::chrono::steady_clock::now();
    if constexpr (std::is_void_v<decltype(call())>) {
      call();
      add_since(t0);
    } else {
      decltype(auto) result = call();
      add_since(t0);
      return result;
    }
  }

  /// Estimated time in the calls since construction [us].
  double elapsed_us() const { return elapsed_us_; }

 private:
  void add_since(std::chrono::steady_clock::time_point t0) {
    elapsed_us_ += kEvery * std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  }

  std::uint32_t calls_ = 0;
  double elapsed_us_ = 0.0;
};

}  // namespace streamclust::detail
