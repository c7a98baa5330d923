// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The one rule that decides whether an offered point is clustered, shared
/// by the engine, the batch clusterer and the tools, so that the same point
/// is counted under the same reason everywhere.

#include <streamclust/types.hpp>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace streamclust {

/// Why a projected point is not accepted, in this order: a non-finite
/// coordinate or time (`non_finite`), then the projection's range and field
/// of view checks (`too_close`, `outside_fov`); `accepted` otherwise. The
/// time order is StreamTimeOrder's. O(1), pure.
inline RejectReason judge_point(const Projected& projected, double time) {
  if (projected.reason == RejectReason::non_finite || !std::isfinite(time)) return RejectReason::non_finite;
  return projected.reason;
}

/// The time order of a stream. A point earlier than the last point with a
/// valid time is rejected (`time_backwards`; equal times are fine). A point
/// more than `max_jump` seconds ahead of it, or beyond +-`max_abs_time`, is
/// rejected too (`time_jump`): one absurd timestamp costs that point, not
/// the rest of the stream, whose later points are judged against the last
/// valid time. A jump is taken as real (a pause in a recording) once
/// `jump_confirmations` consecutive jump points agree with each other (each
/// at most `max_jump` after the one before): that last one is accepted and
/// the stream goes on from it.
///
/// The order depends on times alone: a point rejected for its geometry
/// (range, field of view, pose) still moves it on. So a tool can judge
/// times before it offers points (to schedule its retrievals) with a copy
/// of the same order and reach the same decisions as the clusterer.
/// O(1) per point. Thread safety: none.
class StreamTimeOrder {
 public:
  struct Params {
    double max_jump = 60.0;                 ///< [s] > 0; infinity disables the jump check
    std::uint32_t jump_confirmations = 256;  ///< points that make a jump real (1.3 ms of a Livox stream)
    double max_abs_time = 9.0e9;            ///< [s] |t| beyond it is a jump whatever came before (year 2255 in Unix time)
  };

  StreamTimeOrder() = default;
  /// Throws std::invalid_argument for max_jump <= 0 or NaN, a zero
  /// jump_confirmations, or max_abs_time <= 0 or NaN.
  explicit StreamTimeOrder(const Params& params) : params_(params) {
    if (!(params_.max_jump > 0.0))
      throw std::invalid_argument("max_jump = " + std::to_string(params_.max_jump) + " s: expected > 0");
    if (params_.jump_confirmations == 0) throw std::invalid_argument("jump_confirmations: expected >= 1");
    if (!(params_.max_abs_time > 0.0))
      throw std::invalid_argument("max_abs_time = " + std::to_string(params_.max_abs_time) + " s: expected > 0");
  }

  const Params& params() const { return params_; }

  /// The time's verdict alone (`accepted`, `non_finite`, `time_backwards`,
  /// `time_jump`), recorded: a valid time moves the order on, a jump counts
  /// towards its confirmation.
  RejectReason admit_time(double time) {
    if (!std::isfinite(time)) return RejectReason::non_finite;
    if (!(std::fabs(time) <= params_.max_abs_time)) return RejectReason::time_jump;
    if (seen_valid_) {
      if (time < valid_) return RejectReason::time_backwards;
      if (time - valid_ > params_.max_jump && !confirms_jump(time)) return RejectReason::time_jump;
    }
    seen_valid_ = true;
    valid_ = time;
    jump_run_ = 0;
    return RejectReason::accepted;
  }

  /// The full reason for a point at `time` [s], its time recorded as
  /// admit_time records it: a non-finite coordinate or time first, then the
  /// projection's reason (judge_point), then the time order.
  RejectReason admit(const Projected& projected, double time) {
    const RejectReason order = admit_time(time);  // whatever the geometry
    const RejectReason point = judge_point(projected, time);
    const RejectReason verdict = point != RejectReason::accepted ? point : order;
    if (verdict == RejectReason::accepted) note_newest(time);
    return verdict;
  }

  /// A time `time` [s] may move the stream on (advance_to): finite and not
  /// before the last valid time. Jumps are allowed here: the caller says so.
  bool may_advance_to(double time) const { return std::isfinite(time) && !(seen_valid_ && time < valid_); }
  /// Moves the order to `time` (after may_advance_to).
  void advance(double time) {
    seen_valid_ = true;
    valid_ = time;
    jump_run_ = 0;
    note_newest(time);
  }

  /// True once a point was accepted or the stream advanced.
  bool seen() const { return seen_newest_; }
  /// The stream time of the newest accepted point or advance [s] (0 before any).
  double last() const { return newest_; }

 private:
  /// True when `time`, a jump ahead of the last valid time, is the
  /// jump_confirmations-th consecutive jump in agreement.
  bool confirms_jump(double time) {
    if (jump_run_ > 0 && time >= jump_last_ && time - jump_last_ <= params_.max_jump) {
      ++jump_run_;
    } else {
      jump_run_ = 1;
    }
    jump_last_ = time;
    return jump_run_ >= params_.jump_confirmations;
  }
  void note_newest(double time) {
    if (!seen_newest_ || time > newest_) newest_ = time;
    seen_newest_ = true;
  }

  Params params_{};
  bool seen_valid_ = false;
  double valid_ = 0.0;       ///< [s] the last valid time (point or advance)
  std::uint32_t jump_run_ = 0;
  double jump_last_ = 0.0;   ///< [s] the last jump of the current run
  bool seen_newest_ = false;
  double newest_ = 0.0;
};

}  // namespace streamclust
