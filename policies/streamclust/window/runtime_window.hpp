// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// RuntimeWindow: a time or count window chosen at run time.

#include <streamclust/concepts/window.hpp>
#include <streamclust/window/count_window.hpp>
#include <streamclust/window/time_window.hpp>

#include <cstddef>

namespace streamclust {

/// Forwards to TimeWindow or CountWindow. Thread safety: const. O(1).
class RuntimeWindow {
 public:
  enum class Kind { time, count };
  struct Params {
    Kind kind = Kind::time;
    TimeWindow::Params time{};
    CountWindow::Params count{};
  };

  explicit RuntimeWindow(const Params& params) : kind_(params.kind), time_(params.time), count_(params.count) {}

  bool expired(double oldest, double newest, std::size_t size) const {
    return kind_ == Kind::time ? time_.expired(oldest, newest, size) : count_.expired(oldest, newest, size);
  }
  bool complete(double oldest, double newest, std::size_t size) const {
    return kind_ == Kind::time ? time_.complete(oldest, newest, size) : count_.complete(oldest, newest, size);
  }
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
  TimeWindow time_;
  CountWindow count_;
};

static_assert(is_window_policy_v<RuntimeWindow>);

}  // namespace streamclust
