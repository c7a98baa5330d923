// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// CellTable: the columns of a horizontal grid that has no bounds (a sensor
/// that drives on), by cell coordinates, created on first use and released
/// when their last point leaves.

#include <streamclust/detail/growth.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {

/// A hash table from cell coordinates (ix, iy) to values of type `Column`
/// kept in a pool (indices stay valid until the column is released). Open
/// addressing with linear probing, deletion by backward shift (no
/// tombstones), at most half full. O(1) expected per operation; memory
/// O(live columns) after the peak (the pool and the table never shrink).
/// Thread safety: none.
template <class Column>
class CellTable {
 public:
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;

  /// The pool index of cell (ix, iy)'s column, or kNone. O(1) expected.
  std::uint32_t find(std::int32_t ix, std::int32_t iy) const { return find_packed(pack(ix, iy)); }
  /// As find(ix, iy), by any 64-bit key the caller packs its coordinates
  /// into (a voxel's three, say); one table takes one kind of key.
  std::uint32_t find_packed(std::uint64_t key) const {
    if (slots_.empty()) return kNone;
    for (std::size_t i = home(key);; i = (i + 1) & mask()) {
      const Slot& s = slots_[i];
      if (s.column == kNone) return kNone;
      if (s.key == key) return s.column;
    }
  }

  /// The pool index of cell (ix, iy)'s column, created (value-initialised)
  /// when absent. O(1) expected, amortised.
  std::uint32_t find_or_create(std::int32_t ix, std::int32_t iy) { return find_or_create_packed(pack(ix, iy)); }
  /// As find_or_create(ix, iy), by a packed key.
  std::uint32_t find_or_create_packed(std::uint64_t key) {
    if (2 * (live_ + 1) > slots_.size()) grow();
    std::size_t i = home(key);
    for (; slots_[i].column != kNone; i = (i + 1) & mask()) {
      if (slots_[i].key == key) return slots_[i].column;
    }
    std::uint32_t column;
    if (!free_.empty()) {
      column = free_.back();
      free_.pop_back();
      pool_[column] = Column{};
    } else {
      column = static_cast<std::uint32_t>(pool_.size());
      detail::reserve_geometric(pool_, pool_.size() + 1);
      // The free list never holds more than the pool: sized with it, so a
      // release never allocates.
      if (free_.capacity() < pool_.capacity()) free_.reserve(pool_.capacity());
      pool_.emplace_back();
    }
    slots_[i] = Slot{key, column};
    ++live_;
    return column;
  }

  /// Releases cell (ix, iy)'s column (it must exist). O(1) expected; never
  /// allocates.
  void release(std::int32_t ix, std::int32_t iy) { release_packed(pack(ix, iy)); }
  /// As release(ix, iy), by a packed key.
  void release_packed(std::uint64_t key) {
    std::size_t i = home(key);
    while (slots_[i].key != key || slots_[i].column == kNone) i = (i + 1) & mask();
    free_.push_back(slots_[i].column);
    --live_;
    // Backward shift: move later entries of the probe run into the hole
    // when their home does not lie cyclically in (hole, entry].
    std::size_t hole = i;
    for (std::size_t j = (i + 1) & mask(); slots_[j].column != kNone; j = (j + 1) & mask()) {
      const std::size_t h = home(slots_[j].key);
      const bool stays = hole <= j ? (hole < h && h <= j) : (hole < h || h <= j);
      if (stays) continue;
      slots_[hole] = slots_[j];
      hole = j;
    }
    slots_[hole] = Slot{};
  }

  Column& operator[](std::uint32_t column) { return pool_[column]; }
  const Column& operator[](std::uint32_t column) const { return pool_[column]; }
  /// Live columns.
  std::size_t size() const { return live_; }
  std::size_t heap_bytes() const {
    return slots_.capacity() * sizeof(Slot) + pool_.capacity() * sizeof(Column) +
           free_.capacity() * sizeof(std::uint32_t);
  }

 private:
  struct Slot {
    std::uint64_t key = 0;
    std::uint32_t column = kNone;
  };

  static std::uint64_t pack(std::int32_t ix, std::int32_t iy) {
    return (std::uint64_t{static_cast<std::uint32_t>(ix)} << 32) | static_cast<std::uint32_t>(iy);
  }
  std::size_t mask() const { return slots_.size() - 1; }
  std::size_t home(std::uint64_t key) const {
    key ^= key >> 29;
    key *= 0xBF58476D1CE4E5B9ull;
    key ^= key >> 32;
    return static_cast<std::size_t>(key) & mask();
  }

  void grow() {
    std::vector<Slot> old;
    old.swap(slots_);
    slots_.assign(old.empty() ? 64 : 2 * old.size(), Slot{});
    for (const Slot& s : old) {
      if (s.column == kNone) continue;
      std::size_t i = home(s.key);
      while (slots_[i].column != kNone) i = (i + 1) & mask();
      slots_[i] = s;
    }
  }

  std::vector<Slot> slots_;
  std::vector<Column> pool_;
  std::vector<std::uint32_t> free_;
  std::size_t live_ = 0;
};

}  // namespace streamclust
