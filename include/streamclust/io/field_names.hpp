// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Internals of the readers: the field names that play a role (position,
/// intensity, time, label), finding them, and rejecting a name given twice.

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace streamclust::io::detail {

/// Field names the readers recognise (case-insensitive), in order of preference.
inline constexpr const char* position_names[] = {"x", "y", "z"};
inline constexpr const char* intensity_names[] = {"intensity", "reflectivity", "reflectance"};
inline constexpr const char* time_names[] = {"t", "time", "timestamp", "offset_time"};
inline constexpr const char* label_names[] = {"label", "gt", "instance", "object"};

/// Index of the first name of `candidates` (in their order) among the
/// lower-cased `names`; nullopt when none is present. O(names x candidates).
template <std::size_t N>
std::optional<std::size_t> find_field(const std::vector<std::string>& lowered_names,
                                      const char* const (&candidates)[N]) {
  for (const char* c : candidates) {
    const auto it = std::find(lowered_names.begin(), lowered_names.end(), c);
    if (it != lowered_names.end()) return static_cast<std::size_t>(it - lowered_names.begin());
  }
  return std::nullopt;
}

/// True for a name that can play a role (any of the lists above; PLY's
/// `scalar_intensity` too). `lowered` is lower-case.
inline bool is_role_name(std::string_view lowered) {
  auto in = [&](const auto& names) {
    return std::any_of(std::begin(names), std::end(names), [&](const char* n) { return lowered == n; });
  };
  return in(position_names) || in(intensity_names) || in(time_names) || in(label_names) ||
         lowered == "scalar_intensity";
}

/// The first name of `lowered_names` that occurs again, as the indices of
/// its first and second occurrence; names `counts(name)` rejects are not
/// compared (empty names never). O(n^2) for n names (header fields: few).
template <class Counts>
std::optional<std::pair<std::size_t, std::size_t>> find_duplicate(const std::vector<std::string>& lowered_names,
                                                                  Counts counts) {
  for (std::size_t j = 1; j < lowered_names.size(); ++j) {
    if (lowered_names[j].empty() || !counts(lowered_names[j])) continue;
    for (std::size_t i = 0; i < j; ++i)
      if (lowered_names[i] == lowered_names[j]) return std::make_pair(i, j);
  }
  return std::nullopt;
}

}  // namespace streamclust::io::detail
