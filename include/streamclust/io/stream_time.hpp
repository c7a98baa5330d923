// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Stream times at any scale. Recordings carry absolute times (Unix epoch,
/// about 1.7e9 s) at which a double resolves only 0.24 us, and two copies of
/// a stream that differ by a shift would round differently. So the readers
/// count a stream's times from a whole-second origin (`TimeOrigin`, the
/// whole seconds of its first time): a record's `t` is the seconds since it,
/// computed from the file's text or integer exactly as the same value would
/// be read without the origin. The writers add the origin back: as text,
/// exactly; as a double where a format stores one.
///
/// All functions are pure and thread-safe.

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

namespace streamclust::io {

/// The whole seconds a stream's times are counted from: absolute time =
/// seconds + t. Zero for a stream whose times start below 1 s.
struct TimeOrigin {
  std::int64_t seconds = 0;  ///< [s]

  friend bool operator==(TimeOrigin a, TimeOrigin b) noexcept { return a.seconds == b.seconds; }
  friend bool operator!=(TimeOrigin a, TimeOrigin b) noexcept { return a.seconds != b.seconds; }
};

/// Largest |origin| [s] (year 2255): the origin in nanoseconds fits int64.
inline constexpr double max_time_origin_seconds = 9.0e9;

/// The origin of a stream whose first time is `seconds`: its whole seconds
/// (floor); nullopt when it is not finite or beyond max_time_origin_seconds.
inline std::optional<TimeOrigin> origin_of(double seconds) noexcept {
  if (!(std::fabs(seconds) <= max_time_origin_seconds)) return std::nullopt;
  return TimeOrigin{static_cast<std::int64_t>(std::floor(seconds))};
}

namespace detail {

/// Room for a shifted decimal: 20 integer digits, a sign, a point and the
/// fraction; longer fractions (exponents below -400) are not shifted.
inline constexpr std::size_t shifted_decimal_capacity = 448;

/// Writes the decimal text `s` (optional sign, digits with an optional
/// point, optional exponent; no "nan"/"inf") minus the integer `shift` into
/// `out` as plain decimal text, exactly: ("1700000003.25", 1700000000) ->
/// "3.25", ("1.7000000005e9", 1700000000) -> "0.5". Returns the length, or
/// 0 when `s` is not such a number, its integer part exceeds int64, or the
/// result would change sign (a value below the shift; callers fall back to
/// floating point there). O(|s|).
inline std::size_t shift_decimal(std::string_view s, std::int64_t shift, char (&out)[shifted_decimal_capacity]) {
  std::size_t i = 0;
  bool negative = false;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) negative = s[i++] == '-';
  const std::size_t int_begin = i;
  while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
  const std::size_t int_end = i;
  std::size_t frac_begin = i, frac_end = i;
  if (i < s.size() && s[i] == '.') {
    frac_begin = ++i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
    frac_end = i;
  }
  if (int_end == int_begin && frac_end == frac_begin) return 0;  // no digit
  long exponent = 0;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    bool exp_negative = false;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) exp_negative = s[i++] == '-';
    const std::size_t exp_begin = i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') {
      if (exponent > 100000) return 0;
      exponent = exponent * 10 + (s[i++] - '0');
    }
    if (i == exp_begin) return 0;
    if (exp_negative) exponent = -exponent;
  }
  if (i != s.size()) return 0;
  // The digits d[0..n) with the decimal point after `point` of them.
  const long n_int = static_cast<long>(int_end - int_begin);
  const long n = n_int + static_cast<long>(frac_end - frac_begin);
  const long point = n_int + exponent;
  auto digit = [&](long k) -> int {  // 0 outside the written digits
    if (k < 0 || k >= n) return 0;
    const std::size_t at = k < n_int ? int_begin + static_cast<std::size_t>(k)
                                     : frac_begin + static_cast<std::size_t>(k - n_int);
    return s[at] - '0';
  };
  std::uint64_t integer = 0;
  for (long k = 0; k < point; ++k) {
    const int d = digit(k);
    if (integer > (std::numeric_limits<std::uint64_t>::max() - static_cast<std::uint64_t>(d)) / 10) return 0;
    integer = integer * 10 + static_cast<std::uint64_t>(d);
  }
  if (integer > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) return 0;
  // value = sign * (integer + fraction); value - shift keeps the sign of value
  // when (integer - shift) >= 0 for a positive value, (integer + shift) >= 0
  // for a negative one.
  std::int64_t whole = 0;
  const auto signed_integer = static_cast<std::int64_t>(integer);
  if (negative ? __builtin_add_overflow(signed_integer, shift, &whole)
               : __builtin_sub_overflow(signed_integer, shift, &whole))
    return 0;
  if (whole < 0) return 0;
  const long frac_from = point > 0 ? point : 0;
  const long frac_digits = n - frac_from + (point < 0 ? -point : 0);
  if (frac_digits > static_cast<long>(shifted_decimal_capacity) - 24) return 0;
  std::size_t len = 0;
  if (negative) out[len++] = '-';
  const auto r = std::to_chars(out + len, out + shifted_decimal_capacity, whole);
  len = static_cast<std::size_t>(r.ptr - out);
  if (frac_digits > 0) {
    out[len++] = '.';
    for (long k = point < 0 ? point : frac_from; k < n; ++k) out[len++] = static_cast<char>('0' + digit(k));
  }
  return len;
}

}  // namespace detail

/// The seconds since `origin` of the decimal text `s` of a time in units of
/// `seconds_per_unit` (1, 1e-3, 1e-6, 1e-9) with `units_per_second`
/// (1, 1e3, 1e6, 1e9), where `parsed` is the text's correctly rounded value.
/// With origin zero this is parsed * seconds_per_unit; otherwise the text is
/// shifted by the origin before it is parsed, so the result equals what the
/// text of the shifted value gives (the same stream starting at zero reads
/// the same doubles). Values below the origin fall back to floating point
/// (`parsed` minus the origin).
inline double relative_seconds_of_text(std::string_view s, double parsed, double seconds_per_unit,
                                       std::int64_t units_per_second, TimeOrigin origin) {
  // Divided by the units per second, not multiplied by seconds per unit: the
  // quotient is correctly rounded, so "150000000" ns reads as "0.15" s does.
  (void)seconds_per_unit;
  const auto per_second = static_cast<double>(units_per_second);
  if (origin.seconds == 0) return parsed / per_second;
  char shifted[detail::shifted_decimal_capacity];
  std::int64_t shift = 0;
  if (!__builtin_mul_overflow(origin.seconds, units_per_second, &shift)) {
    if (const std::size_t len = detail::shift_decimal(s, shift, shifted)) {
      double v = 0.0;
      const auto r = std::from_chars(shifted, shifted + len, v);
      if (r.ec == std::errc() && r.ptr == shifted + len) return v / per_second;
    }
  }
  return parsed / per_second - static_cast<double>(origin.seconds);
}

/// The absolute time of stream time `t` as a double [s], correctly rounded
/// (the origin is exact as a double): resolves 0.24 us at epoch scale (for
/// binary formats that store a double).
inline double absolute_seconds(TimeOrigin origin, double t) noexcept { return static_cast<double>(origin.seconds) + t; }

/// The absolute time of stream time `t` as decimal text with nanoseconds
/// ("%.9f" of origin + t, composed in integers so it is exact at any
/// origin): (1700000000, 0.15) -> "1700000000.150000000". Non-finite t is
/// written "nan", "inf", "-inf"; |t| beyond 1e9 s as "%.17g".
inline std::string format_time(TimeOrigin origin, double t) {
  char buf[64];
  if (!std::isfinite(t)) return std::isnan(t) ? "nan" : (t > 0 ? "inf" : "-inf");
  const double ns = std::round(t * 1e9);
  std::int64_t origin_ns = 0, total = 0;
  if (std::fabs(ns) < 1e18 && !__builtin_mul_overflow(origin.seconds, std::int64_t{1000000000}, &origin_ns) &&
      !__builtin_add_overflow(origin_ns, static_cast<std::int64_t>(ns), &total)) {
    const bool negative = total < 0;
    const std::uint64_t magnitude =
        negative ? static_cast<std::uint64_t>(-(total + 1)) + 1 : static_cast<std::uint64_t>(total);
    std::snprintf(buf, sizeof buf, "%s%llu.%09llu", negative ? "-" : "",
                  static_cast<unsigned long long>(magnitude / 1000000000),
                  static_cast<unsigned long long>(magnitude % 1000000000));
    return buf;
  }
  // Beyond 1e9 s (31 years) of stream time: an absurd value, written to read back.
  std::snprintf(buf, sizeof buf, "%.17g", static_cast<double>(origin.seconds) + t);
  return buf;
}

/// Appends the absolute time of stream time `t` as the shortest text that
/// reads back (with this origin) to the same t: "1700000000" followed by the
/// fraction of t's own shortest fixed text. For text point formats.
inline void append_time(std::string& s, TimeOrigin origin, double t) {
  char buf[400];
  if (!std::isfinite(t)) {
    s += std::isnan(t) ? "nan" : (t > 0 ? "inf" : "-inf");
    return;
  }
  if (origin.seconds == 0 || t < 0.0 || t >= 1e15) {
    if (origin.seconds == 0) {
      const auto r = std::to_chars(buf, buf + sizeof buf, t);
      s.append(buf, r.ptr);
    } else {
      s += format_time(origin, t);
    }
    return;
  }
  // t >= 0: its fixed text is "W.F" with W < 1e15; write (origin + W).F.
  const auto r = std::to_chars(buf, buf + sizeof buf, t, std::chars_format::fixed);
  const std::string_view text(buf, static_cast<std::size_t>(r.ptr - buf));
  const std::size_t dot = text.find('.');
  std::int64_t whole = 0;
  std::from_chars(text.data(), text.data() + (dot == std::string_view::npos ? text.size() : dot), whole);
  s += std::to_string(origin.seconds + whole);
  if (dot != std::string_view::npos) s.append(text.substr(dot));
}

}  // namespace streamclust::io
