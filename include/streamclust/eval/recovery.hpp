// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Recovery: how long a per-retrieval error metric (e.g. the
/// under-segmentation entropy) stays raised after a disturbance (e.g. a burst
/// of fast ego-motion) has ended.

#include <cmath>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust {
namespace eval {

/// The disturbance of an error metric (higher = worse) and its recovery.
struct Recovery {
  double before = 0.0;     ///< mean over [begin of the series, event_start)
  double peak = 0.0;       ///< maximum over [event_start, settle_from)
  double settled = 0.0;    ///< mean over [settle_from, end of the series]
  double threshold = 0.0;  ///< settled + fraction x (peak - settled)
  /// Time from event_end [s] to the first sample at or after event_end from
  /// which the metric stays <= threshold until settle_from; 0 when the peak
  /// does not exceed the settled level; empty when it never gets there.
  std::optional<double> time;
};

/// Measures the recovery of `values` (sampled at ascending `times` [s]) after
/// an event over [event_start, event_end): the settled level is the mean over
/// the samples at t >= settle_from (a time long enough after the event for
/// the disturbance to be gone, e.g. event_end + 3 windows), and the metric
/// counts as recovered once it stays within `fraction` of the way from the
/// settled level to the peak. The level after the event, not before it, is the
/// reference because ego-motion changes the view (the scene is seen from
/// elsewhere afterwards).
///
/// Throws std::invalid_argument when the sizes differ, the times are not
/// ascending, event_start > event_end > settle_from is violated, fraction is
/// outside (0, 1), or no sample lies in [settle_from, end]. O(n); pure.
inline Recovery recovery_after(const std::vector<double>& times, const std::vector<double>& values, double event_start,
                               double event_end, double settle_from, double fraction = 0.2) {
  if (times.size() != values.size()) throw std::invalid_argument("recovery_after: times and values differ in length");
  for (std::size_t i = 1; i < times.size(); ++i) {
    if (!(times[i] > times[i - 1])) throw std::invalid_argument("recovery_after: times must be strictly ascending");
  }
  if (!(event_start <= event_end && event_end <= settle_from)) {
    throw std::invalid_argument("recovery_after: expected event_start <= event_end <= settle_from");
  }
  if (!(fraction > 0.0 && fraction < 1.0)) {
    std::string msg("recovery_after: fraction = ");
    msg.append(std::to_string(fraction)).append(" is invalid: expected a value in (0, 1)");
    throw std::invalid_argument(msg);
  }
  Recovery r;
  double before_sum = 0.0, settled_sum = 0.0;
  std::size_t before_n = 0, settled_n = 0;
  bool has_peak = false;
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (times[i] < event_start) {
      before_sum += values[i];
      ++before_n;
    } else if (times[i] < settle_from) {
      if (!has_peak || values[i] > r.peak) r.peak = values[i];
      has_peak = true;
    } else {
      settled_sum += values[i];
      ++settled_n;
    }
  }
  if (settled_n == 0) throw std::invalid_argument("recovery_after: no sample at or after settle_from");
  r.before = before_n ? before_sum / static_cast<double>(before_n) : 0.0;
  r.settled = settled_sum / static_cast<double>(settled_n);
  if (!has_peak) r.peak = r.settled;
  r.threshold = r.settled + fraction * (r.peak - r.settled);
  if (!(r.peak > r.settled)) {
    r.time = 0.0;
    return r;
  }
  // Scan backwards from settle_from: the earliest sample at or after
  // event_end from which every later sample before settle_from is <= threshold.
  std::optional<double> since;
  for (std::size_t k = times.size(); k-- > 0;) {
    if (times[k] >= settle_from) continue;
    if (times[k] < event_end || values[k] > r.threshold) break;
    since = times[k];
  }
  if (since) r.time = *since - event_end;
  return r;
}

}  // namespace eval
}  // namespace streamclust
