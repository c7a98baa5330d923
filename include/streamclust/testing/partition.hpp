// SPDX-License-Identifier: MIT
#pragma once
// Comparing partitions up to renaming of labels, with a message for the
// tests (the comparison itself is the library's, streamclust/partition_compare.hpp).

#include <streamclust/partition_compare.hpp>

#include <sstream>
#include <string>
#include <vector>

namespace streamclust::testing {

/// Empty when `a` and `b` describe the same partition (a bijection maps the
/// labels of one onto the other); otherwise a description of the first
/// mismatch.
template <class A, class B>
std::string partition_mismatch(const std::vector<A>& a, const std::vector<B>& b) {
  const auto m = first_partition_mismatch(a, b);
  if (!m) return {};
  std::ostringstream os;
  if (m->sizes_differ) {
    os << "sizes differ: " << a.size() << " vs " << b.size();
  } else {
    os << "point " << m->position << ": label " << a[m->position] << " vs " << b[m->position]
       << " (no bijection of the labels before it extends to this pair)";
  }
  return os.str();
}

}  // namespace streamclust::testing
