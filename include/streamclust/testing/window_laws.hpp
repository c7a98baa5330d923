// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The laws the engine relies on for a window (concepts/window.hpp), on the
/// engine's loop (before a point at time t enters, evict the oldest while
/// expired(oldest, t, size including the new point)) over irregular
/// timestamps with bursts of equal times:
///   - the newest point is never evicted, a point alone never expires;
///   - what stays is not expired;
///   - monotone: an older oldest point or a larger window expires too;
///   - a window that must evict has reached its extent (complete).
///   - the parameter sets construct, and the window bounds the stream.
/// Cost: O(parameter sets x steps). Not thread-safe.

#include <streamclust/concepts/window.hpp>
#include <streamclust/testing/law_result.hpp>
#include <streamclust/testing/type_name.hpp>

#include <cstddef>
#include <deque>
#include <exception>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace streamclust::testing {

template <class W>
struct WindowLawOptions {
  std::vector<typename W::Params> params;  ///< parameter sets to test; empty: the defaults
  std::size_t steps = 3000;                ///< points per parameter set
  double rate = 500.0;                     ///< mean points per second [Hz]
  std::uint64_t seed = 31;
};

/// Every law of a window (see the file comment); the first failure.
template <class W>
LawResult check_window(const WindowLawOptions<W>& options = {}) {
  static_assert(is_window_policy_v<W>, "check_window: W does not model the window concept (concepts/window.hpp)");
  const std::string name = "window " + type_name<W>();
  const std::vector<typename W::Params> sets = internal::parameter_sets(options.params);
  std::mt19937_64 rng(options.seed);
  std::exponential_distribution<double> gap(options.rate);  // [s]
  std::size_t evictions = 0;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    std::optional<W> holder;
    if (const std::string thrown = internal::construct_from(sets[k], holder); !thrown.empty())
      return law_failed(name + ", parameter set " + std::to_string(k) + ": the parameters do not construct: " + thrown);
    const W& window = *holder;
    std::deque<double> times;
    double t = 3.0;
    for (std::size_t step = 0; step < options.steps; ++step) {
      if (rng() % 4 != 0) t += gap(rng);
      while (!times.empty() && window.expired(times.front(), t, times.size() + 1)) {
        times.pop_front();
        ++evictions;
      }
      times.push_back(t);
      std::ostringstream at;
      at.precision(17);
      at << name << ", parameter set " << k << ", point " << step << " at t = " << t << " s, window of "
         << times.size() << " points from t = " << times.front() << " s: ";
      if (window.expired(t, t, 1)) return law_failed(at.str() + "a point alone expires");
      const double oldest = times.front();
      const std::size_t size = times.size();
      if (window.expired(oldest, t, size)) return law_failed(at.str() + "what the engine kept is expired");
      if (window.expired(oldest, t, size + 1) && !window.expired(oldest - 0.5, t, size + 1))
        return law_failed(at.str() + "not monotone: an older oldest point (0.5 s older) does not expire");
      if (window.expired(oldest - 0.5, t, size) && !window.expired(oldest - 0.5, t, size + 7))
        return law_failed(at.str() + "not monotone: a larger window (7 more points) does not expire");
      for (const std::size_t s : {size, size + 1, size + 100}) {
        for (const double o : {oldest, oldest - 0.01, oldest - 10.0}) {
          if (window.expired(o, t, s) && !window.complete(o, t, s)) {
            std::ostringstream os;
            os.precision(17);
            os << at.str() << "expired(" << o << ", " << t << ", " << s << ") but not complete: a window that "
               << "must evict has reached its extent";
            return law_failed(os.str());
          }
        }
      }
    }
  }
  if (evictions == 0) return law_failed(name + ": no point ever expired in " + std::to_string(options.steps) +
                                        " points per parameter set: the window does not bound the stream");
  return law_passed(name + ": " + std::to_string(sets.size()) + " parameter sets, " + std::to_string(evictions) +
                    " evictions");
}

}  // namespace streamclust::testing
