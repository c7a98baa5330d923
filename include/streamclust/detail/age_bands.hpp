// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// AgeBands: the spanning forest's new edges, binned by their older endpoint
/// as they arrive, and handed back in Kruskal's order (increasing age) one
/// band at a time.

#include <streamclust/detail/hints.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust::detail {

/// An edge between two window points: `older` is its expiry (the edge dies
/// when that point leaves the window). 8 bytes; the default constructor
/// leaves it uninitialised on purpose (scratch buffers resized without a fill).
struct HandleEdge {
  PointHandle older;
  PointHandle newer;
  HandleEdge() noexcept {}  // NOLINT: uninitialised on purpose
  HandleEdge(PointHandle o, PointHandle n) noexcept : older(o), newer(n) {}
};

/// The edges inserted since the last fold of the spanning forest, binned at
/// insertion by the band of their older endpoint: band b holds the older
/// endpoints [base + b 2^kBandBits, base + (b + 1) 2^kBandBits), with `base`
/// the oldest window point at the last fold. A band is a list of chunks of
/// kChunkEdges edges in one pool. `next_band` then hands the bands back
/// newest first, each sorted by a counting sort on the low kBandBits bits
/// (its counters and the band fit in L1), without the expired edges: the
/// fold reads the new edges in Kruskal's order with no global sort and no
/// second buffer the size of the new edges (what a radix sort needs).
///
/// Memory: the pool (edges + less than one chunk per band used), grown by a
/// quarter when full and never shrunk, so a steady stream stops allocating
/// once the pool has held its largest period; plus one band's sorted copy.
/// Handles are modular: every older endpoint, and the `oldest` handed to
/// `next_band`, must lie less than 2^31 after `base` (the engine folds at
/// least every 2^30 points).
/// Thread safety: none (one engine, one thread).
class AgeBands {
 public:
  /// log2 of the older endpoints per band (kBandPoints).
  static constexpr unsigned kBandBits = 9;
  /// Older endpoints per band [points].
  static constexpr std::uint32_t kBandPoints = std::uint32_t{1} << kBandBits;
  /// Edges per chunk of a band's list (512 bytes).
  static constexpr std::uint32_t kChunkEdges = 64;

  /// Empties every band; older endpoints count from `base` on. O(bands used).
  void reset(PointHandle base) {
    std::fill(bands_.begin(), bands_.begin() + static_cast<std::ptrdiff_t>(bands_used_), Band{});
    bands_used_ = 0;
    chunks_used_ = 0;
    edges_ = 0;
    base_ = base;
    cursor_ = 0;
  }

  /// Appends the edges (older[k], newer) for k < count; no `older[k]` may
  /// precede `base`. O(count) amortised: allocates only when the bands
  /// outgrow the pool or the band table (a new maximum of edges, or of the
  /// handles spanned, per period).
  STREAMCLUST_ALWAYS_INLINE void append(const PointHandle* older, std::size_t count, PointHandle newer) {
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t b = static_cast<PointHandle>(older[k] - base_) >> kBandBits;
      if (b >= bands_used_) use_bands(b + 1);
      Band& band = bands_[b];
      if (band.count % kChunkEdges == 0) open_chunk(band);
      pool_[std::size_t{band.tail} * kChunkEdges + band.count % kChunkEdges] = HandleEdge{older[k], newer};
      ++band.count;
    }
    edges_ += count;
  }

  /// Sizes the band table for older endpoints spanning up to `handles`
  /// points from `base` (12 bytes per kBandPoints points), so that `append`
  /// does not grow it below that span. Never shrinks. O(bands).
  void reserve_span(std::size_t handles) {
    const std::size_t bands = handles / kBandPoints + 2;
    if (bands > bands_.size()) bands_.resize(bands);
  }

  /// Edges appended since the last reset, expired ones included.
  std::size_t size() const { return edges_; }
  bool empty() const { return edges_ == 0; }

  /// Starts handing the bands back, newest first (`next_band`). O(1).
  void rewind() { cursor_ = bands_used_; }

  /// Moves to the next band, newest first, that still holds a live edge;
  /// `band()` then holds its live edges (older endpoint in [oldest, oldest +
  /// window)) sorted by increasing age (decreasing older endpoint). False
  /// when no band is left: the older bands are entirely expired and are not
  /// read. O(band + 2^kBandBits); the sorted copy grows to the largest band.
  bool next_band(PointHandle oldest, std::uint32_t window) {
    while (cursor_ > 0) {
      const std::size_t b = --cursor_;
      const PointHandle band_first = base_ + static_cast<PointHandle>(b << kBandBits);
      // Every handle of the band precedes `oldest`: this band and the older ones expired.
      if (static_cast<PointHandle>(oldest - band_first) < (PointHandle{1} << 31) &&
          static_cast<PointHandle>(oldest - band_first) >= (PointHandle{1} << kBandBits)) {
        cursor_ = 0;
        return false;
      }
      const Band& band = bands_[b];
      if (band.count == 0) continue;
      sort_band(band, band_first, oldest, window);
      if (!sorted_.empty()) return true;
    }
    return false;
  }

  /// The band `next_band` moved to, sorted (valid until the next call).
  const std::vector<HandleEdge>& band() const { return sorted_; }

  /// Heap bytes held (capacities): pool, chunk links, band table, counters,
  /// sorted band. O(1).
  std::size_t heap_bytes() const {
    return pool_.capacity() * sizeof(HandleEdge) + chunk_next_.capacity() * sizeof(std::uint32_t) +
           bands_.capacity() * sizeof(Band) + counts_.capacity() * sizeof(std::uint32_t) +
           sorted_.capacity() * sizeof(HandleEdge);
  }

 private:
  struct Band {
    std::uint32_t head = 0;   ///< first chunk
    std::uint32_t tail = 0;   ///< last chunk (the one being filled)
    std::uint32_t count = 0;  ///< edges in the band
  };

  /// Bands [0, used) in use (the band table grows by a quarter). O(1) amortised.
  void use_bands(std::size_t used) {
    if (used > bands_.size()) bands_.resize(std::max(used, bands_.size() + bands_.size() / 4));
    bands_used_ = used;
  }

  /// Gives `band` a fresh chunk at its end (its first, or after a full one),
  /// from the pool, which grows by a quarter when it is full. The chunks are
  /// handed out in pool order, so the next one is prefetched for writing:
  /// the bands' tails are too many streams for the hardware prefetcher, and
  /// each chunk's first write would miss. O(1) amortised.
  void open_chunk(Band& band) {
    if (chunks_used_ == chunk_next_.size()) {
      const std::size_t chunks = chunk_next_.size() + chunk_next_.size() / 4 + 16;
      chunk_next_.resize(chunks);
      pool_.resize(chunks * kChunkEdges);
    }
    const std::uint32_t c = chunks_used_++;
    if (band.count == 0) {
      band.head = c;
    } else {
      chunk_next_[band.tail] = c;
    }
    band.tail = c;
    if (chunks_used_ < chunk_next_.size()) {
      const char* next = reinterpret_cast<const char*>(&pool_[std::size_t{chunks_used_} * kChunkEdges]);
      for (std::size_t line = 0; line < kChunkEdges * sizeof(HandleEdge); line += 64) prefetch_for_write(next + line);
    }
  }

  /// Counting sort of one band on its older endpoint's low bits, newest
  /// first, dropping the expired edges. O(band + 2^kBandBits).
  void sort_band(const Band& band, PointHandle band_first, PointHandle oldest, std::uint32_t window) {
    constexpr std::uint32_t kSlots = std::uint32_t{1} << kBandBits;
    counts_.assign(kSlots, 0u);  // allocates once
    std::uint32_t c = band.head;
    for (std::uint32_t left = band.count; left > 0; c = chunk_next_[c]) {
      const std::uint32_t in_chunk = std::min(left, kChunkEdges);
      const HandleEdge* e = &pool_[std::size_t{c} * kChunkEdges];
      for (std::uint32_t k = 0; k < in_chunk; ++k) {
        const bool live = static_cast<PointHandle>(e[k].older - oldest) < window;
        counts_[kSlots - 1 - static_cast<PointHandle>(e[k].older - band_first)] += live ? 1u : 0u;
      }
      left -= in_chunk;
    }
    std::uint32_t sum = 0;
    for (std::uint32_t s = 0; s < kSlots; ++s) {
      const std::uint32_t n = counts_[s];
      counts_[s] = sum;
      sum += n;
    }
    if (sorted_.capacity() < sum) sorted_.reserve(std::max<std::size_t>(sum, sorted_.capacity() + sorted_.capacity() / 4));
    sorted_.resize(sum);
    HandleEdge* const to = sorted_.data();
    c = band.head;
    for (std::uint32_t left = band.count; left > 0; c = chunk_next_[c]) {
      const std::uint32_t in_chunk = std::min(left, kChunkEdges);
      const HandleEdge* e = &pool_[std::size_t{c} * kChunkEdges];
      for (std::uint32_t k = 0; k < in_chunk; ++k) {
        if (static_cast<PointHandle>(e[k].older - oldest) < window) {
          to[counts_[kSlots - 1 - static_cast<PointHandle>(e[k].older - band_first)]++] = e[k];
        }
      }
      left -= in_chunk;
    }
  }

  std::vector<HandleEdge> pool_;          // chunks of kChunkEdges edges
  std::vector<std::uint32_t> chunk_next_;  // per chunk: the band's next chunk
  std::vector<Band> bands_;               // [0, bands_used_) in use
  std::vector<std::uint32_t> counts_;      // sort_band's counters, 2^kBandBits
  std::vector<HandleEdge> sorted_;         // the current band, sorted
  std::size_t bands_used_ = 0;
  std::uint32_t chunks_used_ = 0;
  std::size_t edges_ = 0;
  std::size_t cursor_ = 0;
  PointHandle base_ = 0;
};

}  // namespace streamclust::detail
