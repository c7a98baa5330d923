// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// One command-line option of a policy: a member of its `Params`, with the
/// option's name, its value's placeholder, help text, kind of number and
/// allowed range. A policy's descriptor (registry/descriptor.hpp) lists its
/// options; the registry parses them, prints them in the help, reports them
/// in JSON and offers them as Python keywords. Parsing is not on the hot
/// path: an option is read once per run.
///
///     registry::option("--theta", &AngularLinkage::Params::theta_deg, "DEG", registry::ValueKind::positive,
///                      "link when the angle between the rays exceeds it")

#include <streamclust/registry/values.hpp>

#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

namespace streamclust::registry {

/// How an option's text becomes a number (registry/values.hpp).
enum class ValueKind {
  number,    ///< any number (parse_number); the policy's constructor checks the range
  positive,  ///< > 0 (parse_positive, or parse_positive_float for a float member)
  count,     ///< a whole number >= 1 (parse_count)
};

/// One option of a policy whose parameters are `Params`. Copyable; the
/// functions hold a member pointer only.
template <class Params>
struct Option {
  std::string name;     ///< on the command line, with its dashes: "--theta"
  std::string metavar;  ///< the value's placeholder in the help: "DEG"
  std::string key;      ///< the parameter's name in JSON reports: "theta_deg"
  std::string help;     ///< one line, units in brackets
  ValueKind kind = ValueKind::number;
  bool integral = false;  ///< the member is a whole number (reports print it without a fraction)
  /// Parses `value` (the text after the option) into `params`; throws
  /// UsageError naming the option. read() adds the at_most check.
  std::function<void(Params& params, const std::string& value)> parse;
  /// The parameter's value in `params`, as a double (reports, help defaults).
  std::function<double(const Params& params)> value;

  /// The Python keyword: the name without its dashes, '-' as '_' ("min_ray_angle").
  std::string keyword() const {
    std::string k = name.substr(name.find_first_not_of('-'));
    for (char& c : k) c = c == '-' ? '_' : c;
    return k;
  }

  /// The default (the value in a default-constructed Params) as the help prints it.
  std::string default_text() const { return format_number(value(Params{})); }

  /// Refuses values above `max` with "NAME: `message`" (after the kind's own check).
  Option at_most(double max, std::string message) && {
    max_value = max;
    max_message = name + ": " + std::move(message);
    return std::move(*this);
  }

  /// Reads `text` into `params` (unchanged on error); throws UsageError.
  void read(Params& params, const std::string& text) const {
    Params tried = params;
    parse(tried, text);
    if (value(tried) > max_value) throw UsageError(max_message);
    params = tried;
  }

  /// %g of `v`, as the help and reports print numbers.
  static std::string format_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
  }

  double max_value = std::numeric_limits<double>::infinity();  ///< see at_most
  std::string max_message;
};

/// The option `name` for `member` of `Params`: parsed as `kind`, converted to
/// the member's type. O(1).
template <class Params, class T>
Option<Params> option(std::string name, T Params::*member, std::string metavar, ValueKind kind, std::string help,
                      std::string key) {
  static_assert(std::is_arithmetic_v<T>, "STREAMCLUST_REGISTRY_OPTION: an option's member must be a number");
  Option<Params> o;
  o.name = std::move(name);
  o.metavar = std::move(metavar);
  o.key = std::move(key);
  o.help = std::move(help);
  o.kind = kind;
  o.integral = std::is_integral_v<T>;
  o.parse = [member, kind, option = o.name](Params& p, const std::string& text) {
    double v = 0.0;
    switch (kind) {
      case ValueKind::positive:
        v = std::is_same_v<T, float> ? static_cast<double>(parse_positive_float(option, text))
                                     : parse_positive(option, text);
        break;
      case ValueKind::count: v = static_cast<double>(parse_count(option, text)); break;
      case ValueKind::number: v = parse_number(option, text); break;
    }
    p.*member = static_cast<T>(v);
  };
  o.value = [member](const Params& p) { return static_cast<double>(p.*member); };
  return o;
}

}  // namespace streamclust::registry
