// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The disjoint-set forests of the project, one per use:
///  - UnionFind: union by size over any elements (the batch clusterer);
///  - OldestRootUnionFind: over window positions, the root of a set is its
///    oldest point (the union-find rebuild's edge pass);
///  - RankedUnionFind: over window positions, union by rank (the spanning
///    forest's Kruskal).
/// The two window forests turn their sets into dense component numbers in
/// order of each component's oldest point (`number_components`), after which
/// `component(i)` is the component of window position i.
/// Path halving everywhere. Not thread-safe.

#include <streamclust/detail/growth.hpp>

#include <cstddef>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace streamclust::detail {

/// Union by size with path halving. Near-constant amortised find and unite
/// (inverse Ackermann). Not thread-safe.
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

/// Over window positions 0..n-1 where every parent is older (smaller) than
/// its child: the root of a set is its oldest point. The caller unites by
/// hanging one root under another (`attach`), keeping that order; numbering
/// then needs no find. Not thread-safe.
class OldestRootUnionFind {
 public:
  /// `n` singletons; `room` as reserve_window. O(n).
  void reset(std::uint32_t n, std::size_t room) {
    reserve_window(parent_, n, room);
    parent_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) parent_[i] = i;
  }
  /// Root of `x`, halving the path. Amortised near O(1).
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  /// Hangs root `child` under root `parent` (parent < child). O(1).
  void attach(std::uint32_t child, std::uint32_t parent) { parent_[child] = parent; }
  /// Dense component numbers in order of each set's oldest point; returns
  /// their count. O(n), no find: in increasing order a non-root's parent
  /// already holds its component number.
  std::uint32_t number_components(std::uint32_t n) {
    std::uint32_t components = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t p = parent_[i];
      parent_[i] = p == i ? components++ : parent_[p];
    }
    return components;
  }
  /// Component of window position `i` after `number_components`.
  std::uint32_t component(std::uint32_t i) const { return parent_[i]; }
  const std::uint32_t* components() const { return parent_.data(); }
  std::size_t heap_bytes() const { return parent_.capacity() * sizeof(std::uint32_t); }

 private:
  std::vector<std::uint32_t> parent_;
};

/// Union by rank with path halving over window positions 0..n-1.
/// parent_[x] < kRoot: x's parent; >= kRoot: x is a root, the low bits its
/// rank (< 32). Needs fewer than 2^31 elements. Not thread-safe.
class RankedUnionFind {
 public:
  /// `n` singletons of rank 0; `room` as reserve_window. O(n).
  void reset(std::uint32_t n, std::size_t room) {
    reserve_window(parent_, n, room);
    parent_.assign(n, kRoot);
  }
  /// Root of `x`, halving the path. Amortised near O(1): by rank, trees are
  /// at most log2(n) deep.
  std::uint32_t find(std::uint32_t x) {
    for (;;) {
      const std::uint32_t p = parent_[x];
      if (p >= kRoot) return x;
      const std::uint32_t g = parent_[p];
      if (g >= kRoot) return p;
      parent_[x] = g;
      x = g;
    }
  }
  /// Unites the sets of `a` and `b` by rank. False when they were one set
  /// already. Amortised near O(1).
  bool unite(std::uint32_t a, std::uint32_t b) {
    std::uint32_t ra = find(a);
    std::uint32_t rb = find(b);
    if (ra == rb) return false;
    if (parent_[ra] < parent_[rb]) std::swap(ra, rb);  // ra: the higher rank
    if (parent_[ra] == parent_[rb]) ++parent_[ra];
    parent_[rb] = ra;
    return true;
  }
  /// Dense component numbers in order of each set's oldest point; returns
  /// their count. O(n): one pass of finds (short after Kruskal's halving)
  /// that points every position at its root, then one pass in order in
  /// which a root keeps the root flag until numbered and holds kNumbered +
  /// its number once numbered.
  std::uint32_t number_components(std::uint32_t n) {
    for (std::uint32_t i = 0; i < n; ++i) {
      if (parent_[i] < kRoot) parent_[i] = find(i);
    }
    std::uint32_t components = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t v = parent_[i];
      if (v >= kRoot) {  // a root: numbered already by an older member, or the set's oldest point
        parent_[i] = v >= kNumbered ? v - kNumbered : components++;
      } else if (v < i) {  // the root was older: it holds its number now
        parent_[i] = parent_[v];
      } else {  // the root is younger: number it at its oldest point, i
        std::uint32_t& root = parent_[v];
        if (root < kNumbered) root = kNumbered + components++;
        parent_[i] = root - kNumbered;
      }
    }
    return components;
  }
  /// Component of window position `i` after `number_components`.
  std::uint32_t component(std::uint32_t i) const { return parent_[i]; }
  const std::uint32_t* components() const { return parent_.data(); }
  std::size_t heap_bytes() const { return parent_.capacity() * sizeof(std::uint32_t); }

 private:
  static constexpr std::uint32_t kRoot = std::uint32_t{1} << 31;
  static constexpr std::uint32_t kMaxRank = 32;
  static constexpr std::uint32_t kNumbered = kRoot + kMaxRank;
  std::vector<std::uint32_t> parent_;
};

}  // namespace streamclust::detail
