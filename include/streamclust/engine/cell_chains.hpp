// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// CellChains: where each grid cell's chain of successively linked points
/// starts, so that a crowded cell costs O(1) per point instead of O(k).

#include <streamclust/types.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {

/// Per grid cell, the start of its chain: the cell's points from `start` on,
/// in the order they entered the cell, each linked to the point that entered
/// just before it (the new point linked the cell's youngest point).
///
/// Why a chain makes its older points skippable: let q be a chain point and
/// y the cell's youngest. The edges (q, q'), (q', q''), ... up to y each
/// live until their older end leaves the window, never before q does, so q
/// and y stay joined through points no older than q for as long as q lives
/// (an edge the neighbour search dropped as redundant keeps that property:
/// its ends stay joined through points no older than it expires). A new
/// point h that links y therefore stays connected to every chain point for
/// that point's whole life: the edge (h, q) adds nothing to the window's
/// components and need not be tested or stored. Only the points older than
/// the chain start are tested one by one (NeighbourSearch).
///
/// Upkeep, at each insertion into a cell: a cell with fewer than
/// kCrowdedCell points restarts its chain at the new point; a crowded cell
/// keeps it when the new point links its youngest, else restarts it there.
/// A start older than the window's oldest point is moved up to it (all
/// points of the cell are then chain points), so a start is never more than
/// two windows old and handle differences cannot wrap.
///
/// A cell of identical or near-identical points (a no-return slot repeated
/// at one position, a wall at close range, duplicated packets) is one chain:
/// each new point tests O(kCrowdedCell) candidates there and stores O(1)
/// edges, where every pair would cost O(k) and O(k^2) in all.
///
/// Memory: 4 bytes per grid cell. Thread safety: none (one engine, one thread).
class CellChains {
 public:
  /// A cell holding at least this many points is crowded: its chain is read
  /// [points]. Below it every candidate is tested as before.
  static constexpr std::size_t kCrowdedCell = 16;

  /// One entry per cell of the new grid. O(cells).
  void reset(std::size_t cells) { starts_.assign(cells, PointHandle{0}); }

  /// The start of `cell`'s chain, moved up to `window_oldest` when older,
  /// judged from `newest` (the point being linked). O(1).
  PointHandle start(CellIndex cell, PointHandle window_oldest, PointHandle newest) {
    PointHandle& s = starts_[cell];
    if (static_cast<std::uint32_t>(newest - s) > static_cast<std::uint32_t>(newest - window_oldest)) s = window_oldest;
    return s;
  }

  /// Restarts `cell`'s chain at point `h`, which enters the cell next. O(1).
  void restart(CellIndex cell, PointHandle h) { starts_[cell] = h; }

  /// Heap bytes held [bytes].
  std::size_t heap_bytes() const { return starts_.capacity() * sizeof(PointHandle); }

 private:
  std::vector<PointHandle> starts_;
};

}  // namespace streamclust
