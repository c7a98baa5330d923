// SPDX-License-Identifier: MIT
#pragma once
// Comparing partitions up to renaming of labels.

#include <cstddef>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace streamclust::test {

/// Empty when `a` and `b` describe the same partition (a bijection maps the
/// labels of one onto the other); otherwise a description of the first
/// mismatch. Both must have the same length.
template <class A, class B>
std::string partition_mismatch(const std::vector<A>& a, const std::vector<B>& b) {
  if (a.size() != b.size()) {
    std::ostringstream os;
    os << "sizes differ: " << a.size() << " vs " << b.size();
    return os.str();
  }
  std::map<A, B> forward;
  std::map<B, A> backward;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto f = forward.emplace(a[i], b[i]).first;
    const auto r = backward.emplace(b[i], a[i]).first;
    if (f->second != b[i] || r->second != a[i]) {
      std::ostringstream os;
      os << "point " << i << ": label " << a[i] << " vs " << b[i] << " (already paired with " << f->second << " / "
         << r->second << ")";
      return os.str();
    }
  }
  return {};
}

}  // namespace streamclust::test
