// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// merge_forest: one Kruskal pass over a maximum spanning forest and the new
/// edges of its age bands, written in place.

#include <streamclust/detail/age_bands.hpp>
#include <streamclust/detail/ring_queue.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust::detail {

/// What one merge_forest pass did [edges].
struct MergeCounts {
  std::size_t displaced = 0;     ///< kept edges that went through the queue
  std::size_t new_read = 0;      ///< live new edges read from the bands
  std::size_t new_accepted = 0;  ///< of those, accepted into the forest
};

/// Kruskal over `forest` (the kept edges, live and in increasing age) and
/// the live new edges of `bands` (older endpoint in [oldest, oldest +
/// window)), taking the edges by increasing age, a kept edge before a new
/// one of the same age: every edge that `unite(e)` accepts (true: it joined
/// two sets) is kept, in that order, and `forest` ends up holding exactly
/// those. `age(e)` must be below `window` for a live edge.
///
/// In place: the kept edges first move to the end of `forest`'s capacity,
/// which must exceed any forest the pass can write (the caller reserves at
/// least `window` edges); the accepted edges are written from the front.
/// When a write would land on a kept edge not read yet (the accepted new
/// edges outnumbered the rejected kept ones by the whole gap), that edge
/// moves to `displaced` first, and kept edges are read from the queue before
/// the array. Returns what the pass counted (MergeCounts).
/// O(kept + new edges + bands x 2^AgeBands::kBandBits) plus the unions;
/// allocates only when `displaced` or a sorted band outgrows its capacity.
template <class Age, class Unite>
MergeCounts merge_forest(std::vector<HandleEdge>& forest, AgeBands& bands, RingQueue<HandleEdge>& displaced,
                         PointHandle oldest, std::uint32_t window, const Age& age, Unite&& unite) {
  const std::size_t kept_count = forest.size();
  const std::size_t total = forest.capacity();
  forest.resize(total);  // HandleEdge leaves the tail uninitialised: no fill
  HandleEdge* const f = forest.data();
  std::copy_backward(f, f + kept_count, f + total);
  displaced.clear();
  bands.rewind();
  std::size_t read = total - kept_count;  // the next kept edge in f, neither read nor displaced
  std::size_t written = 0;                // accepted edges, at the front of f
  MergeCounts counts;
  const HandleEdge* added = nullptr;
  std::size_t added_count = 0;
  std::size_t j = 0;
  bool bands_left = true;
  for (;;) {
    if (j == added_count && bands_left) {
      bands_left = bands.next_band(oldest, window);
      added = bands_left ? bands.band().data() : nullptr;
      added_count = bands_left ? bands.band().size() : 0;
      counts.new_read += added_count;  // a band is read to its end before the pass stops
      j = 0;
    }
    // Age `window`: that list is exhausted.
    const bool from_queue = !displaced.empty();
    const std::uint32_t kept_age = from_queue ? age(displaced.front()) : read < total ? age(f[read]) : window;
    const std::uint32_t added_age = j < added_count ? age(added[j]) : window;
    HandleEdge e;
    const bool is_new = kept_age > added_age;
    if (!is_new) {
      if (kept_age >= window) break;
      if (from_queue) {
        e = displaced.front();
        displaced.pop();
      } else {
        e = f[read++];
      }
    } else {
      e = added[j++];
    }
    if (unite(e)) {
      if (written == read && read < total) {
        displaced.push(f[read++]);
        ++counts.displaced;
      }
      f[written++] = e;
      counts.new_accepted += is_new ? 1u : 0u;
    }
  }
  forest.resize(written);
  return counts;
}

}  // namespace streamclust::detail
