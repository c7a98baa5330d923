// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// SIGINT and SIGTERM as a stop request for the commands that run until
/// stopped (`live`, `ros2`, `replay`): while a StopSignals lives, either
/// signal sets `stop_requested()` instead of ending the process, and every
/// output is flushed and closed on the way out. The previous handlers come
/// back when it is destroyed. One at a time per process.

#include <atomic>
#include <csignal>

namespace streamclust::cli {

namespace detail {
inline std::atomic<bool> g_stop_requested{false};
extern "C" inline void request_stop(int) { g_stop_requested.store(true); }
}  // namespace detail

/// True once SIGINT or SIGTERM arrived while a StopSignals was installed.
inline bool stop_requested() { return detail::g_stop_requested.load(); }

class StopSignals {
 public:
  StopSignals() {
    detail::g_stop_requested.store(false);
    struct sigaction a {};
    a.sa_handler = detail::request_stop;
    sigemptyset(&a.sa_mask);
    ::sigaction(SIGINT, &a, &old_int_);
    ::sigaction(SIGTERM, &a, &old_term_);
  }
  ~StopSignals() {
    ::sigaction(SIGINT, &old_int_, nullptr);
    ::sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

}  // namespace streamclust::cli
