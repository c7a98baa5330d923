// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Command-line values: the number parsers every registered option uses,
/// and the error they throw. A bad value is a UsageError whose message names
/// the option, what it expected and what it got ("--theta: expected a
/// positive number, got 'x'"); the `streamclust` tool maps it to exit code 2.
/// Pure functions, thread-safe.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace streamclust::registry {

/// A usage error: bad option, value or combination.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Any finite or infinite number std::stod reads, the whole text.
inline double parse_number(std::string_view option, const std::string& value) {
  try {
    std::size_t used = 0;
    const double v = std::stod(value, &used);
    if (used != value.size()) throw std::invalid_argument("trailing characters");
    return v;
  } catch (const std::exception&) {
    throw UsageError(std::string(option) + ": expected a number, got '" + value + "'");
  }
}

/// A number in (0, 1e12].
inline double parse_positive(std::string_view option, const std::string& value) {
  const double v = parse_number(option, value);
  if (!(v > 0.0) || v > 1e12) throw UsageError(std::string(option) + ": expected a positive number, got '" + value + "'");
  return v;
}

/// parse_positive for a float option: a value that rounds to 0 as a float
/// (below 1e-45) is refused too.
inline float parse_positive_float(std::string_view option, const std::string& value) {
  const auto v = static_cast<float>(parse_positive(option, value));
  if (!(v > 0.0f)) throw UsageError(std::string(option) + ": expected a positive number, got '" + value + "'");
  return v;
}

/// A whole number in [1, 4e9].
inline std::uint64_t parse_count(std::string_view option, const std::string& value) {
  const double v = parse_number(option, value);
  if (!(v >= 1.0) || v > 4e9 || v != static_cast<double>(static_cast<std::uint64_t>(v))) {
    throw UsageError(std::string(option) + ": expected a whole number >= 1, got '" + value + "'");
  }
  return static_cast<std::uint64_t>(v);
}

}  // namespace streamclust::registry
