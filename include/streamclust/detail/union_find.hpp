// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Disjoint sets with union by size and path halving, for the batch
/// clusterer (which never needs to split a set).

#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace streamclust::detail {

/// Near-constant amortised find and unite (inverse Ackermann). Not thread-safe.
class UnionFind {
 public:
  void reset(std::size_t n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), std::uint32_t{0});
    size_.assign(n, 1);
  }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }

 private:
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint32_t> size_;
};

}  // namespace streamclust::detail
