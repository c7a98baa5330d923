// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Command-line options of bench_soak. A bad option is a SoakUsageError
/// (exit code 2).

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::bench {

struct SoakUsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct SoakOptions {
  double seconds = 600.0;            ///< stream time per preset [s]
  double warmup = 10.0;              ///< stream time before the steady state [s]
  std::vector<std::string> presets;  ///< CLI preset names, run in this order
  std::string out_dir = ".";         ///< soak_<preset>.csv and soak_<preset>_cycles.csv go here
  std::string livox_data;            ///< folder with patterns/mid360_u16le.bin; empty: the default
  bool estimate_setup = false;       ///< objects preset: the tool's first-window mount and height, not the simulator's
  bool trace_allocs = false;         ///< print the stack of every steady-state engine allocation
  bool smoke = false;                ///< a short run whose verdicts do not set the exit code
};

inline constexpr const char* kSoakUsage =
    "usage: bench_soak [--seconds S] [--preset carc|objects-mid360|both] [--out-dir DIR]\n"
    "                  [--warmup S] [--livox-data DIR] [--estimate-setup] [--trace-allocs] [--smoke]\n"
    "  --seconds S       stream time per preset (default 600)\n"
    "  --preset P        the CLI preset to soak (default both: carc, then objects-mid360)\n"
    "  --out-dir DIR     where the CSV files go (default .)\n"
    "  --warmup S        stream time before the steady state (default 10)\n"
    "  --livox-data DIR  folder with patterns/mid360_u16le.bin (default $STREAMCLUST_LIVOX_DATA,\n"
    "                    else ../shared/data/livox next to the sources; the analytic model without it)\n"
    "  --estimate-setup  objects-mid360: estimate mount and sensor height from the first window as the\n"
    "                    tool does without --mount/--sensor-height (default: the simulated level 1 m)\n"
    "  --trace-allocs    print the call stack of every engine allocation after the warm-up\n"
    "  --smoke           3 s, warm-up 1 s, both presets; verdicts printed, exit 0 unless an error\n"
    "exit: 0 every target met, 1 a target missed, 2 usage error, 3 error\n";

/// Parses argv (without the program name). Throws SoakUsageError.
inline SoakOptions parse_soak_options(const std::vector<std::string>& args) {
  SoakOptions o;
  bool seconds_given = false, warmup_given = false;
  std::string preset = "both";
  const auto number = [](const std::string& option, const std::string& value, double lo, double hi) {
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !(v >= lo && v <= hi)) {
      throw SoakUsageError(option + ": expected a number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                           "], got '" + value + "'");
    }
    return v;
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw SoakUsageError(a + ": missing value");
      return args[++i];
    };
    if (a == "--seconds") {
      o.seconds = number(a, value(), 2.0, 86400.0);
      seconds_given = true;
    } else if (a == "--warmup") {
      o.warmup = number(a, value(), 0.0, 86400.0);
      warmup_given = true;
    } else if (a == "--preset") {
      preset = value();
    } else if (a == "--out-dir") {
      o.out_dir = value();
    } else if (a == "--livox-data") {
      o.livox_data = value();
    } else if (a == "--estimate-setup") {
      o.estimate_setup = true;
    } else if (a == "--trace-allocs") {
      o.trace_allocs = true;
    } else if (a == "--smoke") {
      o.smoke = true;
    } else {
      throw SoakUsageError("unknown option '" + a + "'");
    }
  }
  if (o.smoke) {
    if (!seconds_given) o.seconds = 3.0;
    if (!warmup_given) o.warmup = 1.0;
  }
  if (preset == "both") {
    o.presets = {"carc", "objects-mid360"};
  } else if (preset == "carc" || preset == "objects-mid360") {
    o.presets = {preset};
  } else {
    throw SoakUsageError("--preset: expected carc, objects-mid360 or both, got '" + preset + "'");
  }
  if (!(o.warmup < o.seconds)) throw SoakUsageError("--warmup must be shorter than --seconds");
  return o;
}

}  // namespace streamclust::bench
