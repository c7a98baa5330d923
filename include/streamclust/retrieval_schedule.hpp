// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// RetrievalSchedule: when a driver retrieves clusters from a recorded
/// stream, at a fixed rate of stream time.

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace streamclust {

/// Retrievals at t0 + k / rate (k = 1, 2, ...) of stream time, t0 the first
/// finite record time. A retrieval at time T is due before the first record
/// with t >= T; a pause in the stream skips the scheduled times it spans
/// (one retrieval, not a burst of empty ones), and the schedule always moves
/// strictly forward, even when rounding puts (t - t0) * rate a hair below a
/// whole number.
///
/// \code
/// streamclust::RetrievalSchedule schedule(20.0);  // 20 Hz
/// for (const auto& record : records) {
///   if (const auto due = schedule.on_record(record.t)) {
///     engine.advance_to(*due);
///     use(engine.retrieve());
///   }
///   engine.insert(record);
/// }
/// \endcode
///
/// O(1) per record. Not thread-safe; one instance per stream.
class RetrievalSchedule {
 public:
  /// `rate_hz`: retrievals per second of stream time [Hz], finite and > 0;
  /// else std::invalid_argument.
  explicit RetrievalSchedule(double rate_hz) : period_(1.0 / rate_hz) {
    if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
      throw std::invalid_argument("RetrievalSchedule: rate_hz = " + std::to_string(rate_hz) +
                                  " is invalid: expected a finite rate > 0 Hz");
    }
  }

  /// Takes the time [s] of the next record in stream order. Returns the
  /// scheduled time of the retrieval due before that record, if one is. A
  /// non-finite time never triggers one (nor starts the schedule).
  std::optional<double> on_record(double t) {
    if (!std::isfinite(t)) return std::nullopt;
    if (!started_) {
      started_ = true;
      first_ = t;
      return std::nullopt;
    }
    const double due = next_time();
    if (!(t >= due)) return std::nullopt;
    // Skip the empty retrievals of a pause, but always move on: floor() may
    // round (t - t0) / period a hair below k although t >= t0 + k period,
    // which would schedule this retrieval again.
    k_ = std::max(k_ + 1.0, std::floor((t - first_) / period_) + 1.0);
    return due;
  }

  /// True once a finite record time was seen.
  bool started() const { return started_; }
  /// The first finite record time t0 [s] (0 before `started()`).
  double first_time() const { return first_; }
  /// The time of the next scheduled retrieval [s] (meaningful once started).
  double next_time() const { return first_ + k_ * period_; }
  /// 1 / rate [s].
  double period() const { return period_; }

 private:
  double period_;
  double first_ = 0.0;
  double k_ = 1.0;  // the next retrieval is the k-th
  bool started_ = false;
};

}  // namespace streamclust
