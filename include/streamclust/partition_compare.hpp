// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Comparing two labelings of the same points as partitions, up to a
/// renaming of the labels: the check behind `streamclust cluster --verify`
/// and the oracle tests.

#include <algorithm>
#include <cstddef>
#include <map>
#include <optional>
#include <vector>

namespace streamclust {

/// Where two labelings stop describing the same partition.
struct PartitionMismatch {
  std::size_t position = 0;  ///< the first point at which no bijection of labels maps one onto the other
  bool sizes_differ = false;  ///< the labelings have different lengths (position = the shorter length)
};

/// The first point at which `a` and `b` stop being the same partition (no
/// bijection between their labels maps one onto the other), or nothing when
/// they agree. Any label value is a label, -1 included (the frame baseline's
/// "unlabelled" is then a set like any other). Labels need `operator<`.
/// O(n log k) for n points and k labels. Thread-safe (pure).
template <class A, class B>
std::optional<PartitionMismatch> first_partition_mismatch(const std::vector<A>& a, const std::vector<B>& b) {
  std::map<A, B> forward;
  std::map<B, A> backward;
  const std::size_t n = std::min(a.size(), b.size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto f = forward.emplace(a[i], b[i]).first;
    const auto r = backward.emplace(b[i], a[i]).first;
    if (f->second != b[i] || r->second != a[i]) return PartitionMismatch{i, false};
  }
  if (a.size() != b.size()) return PartitionMismatch{n, true};
  return std::nullopt;
}

}  // namespace streamclust
