// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The stream time of a reader's raw time values: the field's unit applied
/// and the stream's whole-second origin (stream_time.hpp) taken off.

#include <streamclust/io/record.hpp>
#include <streamclust/io/stream_time.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

namespace streamclust::io {

/// Turns raw time values, in file order, into seconds since the stream's
/// origin: the origin given, or else the whole seconds of the first finite
/// value (until then, and for a stream of small times, zero). Decimal text
/// and integers are shifted exactly (a stream and its copy shifted by whole
/// seconds decode to the same doubles); binary floats keep what they hold. O(1) per value (O(text) for text); not thread-safe.
class TimeDecoder {
 public:
  explicit TimeDecoder(TimeUnit unit = TimeUnit::s, std::optional<TimeOrigin> origin = std::nullopt)
      : seconds_per_unit_(seconds_per(unit)),
        units_per_second_(units_per_second(unit)),
        origin_(origin.value_or(TimeOrigin{})),
        found_(origin.has_value()) {}

  /// The origin in effect: given, found, or zero while none is found.
  TimeOrigin origin() const noexcept { return origin_; }
  /// True once the origin is given or found.
  bool origin_found() const noexcept { return found_; }

  /// A value written as decimal text whose correctly rounded value is `parsed`.
  double from_text(std::string_view text, double parsed) {
    find(parsed);
    return relative_seconds_of_text(text, parsed, seconds_per_unit_, units_per_second_, origin_);
  }

  /// A value stored as a signed integer.
  double from_integer(std::int64_t raw) noexcept {
    find(static_cast<double>(raw));
    // Divided, not multiplied by 1e-9: the quotient is correctly rounded, the
    // same double as the decimal text of the value (150000000 ns -> 0.15).
    std::int64_t shift = 0, relative = 0;
    if (origin_.seconds == 0) return static_cast<double>(raw) / static_cast<double>(units_per_second_);
    if (!__builtin_mul_overflow(origin_.seconds, units_per_second_, &shift) &&
        !__builtin_sub_overflow(raw, shift, &relative))
      return static_cast<double>(relative) / static_cast<double>(units_per_second_);
    return from_real(static_cast<double>(raw));
  }

  /// A value stored as an unsigned integer.
  double from_unsigned(std::uint64_t raw) noexcept {
    if (raw <= static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
      return from_integer(static_cast<std::int64_t>(raw));
    return from_real(static_cast<double>(raw));
  }

  /// A value stored as a binary float: in seconds the difference is exact
  /// (a double at epoch scale has no bits below what the result can hold).
  double from_real(double raw) noexcept {
    find(raw);
    return raw / static_cast<double>(units_per_second_) - static_cast<double>(origin_.seconds);
  }

 private:
  static std::int64_t units_per_second(TimeUnit u) noexcept {
    switch (u) {
      case TimeUnit::s: return 1;
      case TimeUnit::ms: return 1000;
      case TimeUnit::us: return 1000000;
      case TimeUnit::ns: return 1000000000;
    }
    return 1;
  }

  void find(double raw) noexcept {
    if (found_) return;
    if (const auto o = origin_of(raw * seconds_per_unit_)) {
      origin_ = *o;
      found_ = true;
    }
  }

  double seconds_per_unit_;
  std::int64_t units_per_second_;
  TimeOrigin origin_;
  bool found_;
};

}  // namespace streamclust::io
