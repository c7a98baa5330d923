// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// HeightColumn: the heights of the window's points in one ground cell, as a
/// histogram that supports removal, with the lowest and highest supported
/// layers found in O(1) typical time.

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>

namespace streamclust {

/// A histogram of absolute height bins (bin b covers [b h, (b + 1) h) for the
/// owner's bin height h) over a span of kBins bins. The span is placed when
/// the first point arrives (kBins / 2 bins on each side of it) and follows
/// the points: it moves down for a lower point and up for a higher one, as
/// far as the points it holds allow. While the column's points span fewer
/// than kBins bins it is exact; beyond, points above the span count in its
/// top bin (and leave from there, so removal always finds the count an add
/// made), and the span only moves up again once they have left. Besides its
/// count, a bin sums its points' positions within it (in 1/kFractionUnits of
/// a bin, integers: removal is exact), so a layer's mean height is known to
/// far below a bin (`mean_bin`). 1,044 bytes. O(1) add and remove (O(kBins)
/// when the span moves), layer queries O(kBins / 64 + bins scanned). At
/// most 4 million points per bin. Thread safety: none.
class HeightColumn {
 public:
  static constexpr std::int32_t kBins = 128;
  /// Resolution of a point's position within its bin.
  static constexpr std::int32_t kFractionUnits = 1024;

  /// Counts a point in absolute bin `bin`, at `fraction` / kFractionUnits of
  /// the bin (in [0, kFractionUnits)).
  void add(std::int32_t bin, std::int32_t fraction) {
    if (points_ == 0) base_ = bin - kBins / 2;
    if (bin < base_) {
      // As far down as a margin, but not past what keeps the highest point in.
      const std::int32_t keeps_top = base_ + next_set_below(kBins) - (kBins - 1);
      move_base_to(std::min(bin, std::max(bin - kBins / 4, keeps_top)));
    } else if (bin - base_ >= kBins && above_ == 0) {
      // Up by the need plus a margin, but not past the lowest point.
      const std::int32_t need = bin - base_ - (kBins - 1);
      move_base_to(base_ + std::min(need + kBins / 4, next_set(0)));
    }
    const std::int32_t at = offset(bin);
    if (counts_[static_cast<std::size_t>(at)]++ == 0) set_bit(at);
    sums_[static_cast<std::size_t>(at)] += static_cast<std::uint32_t>(fraction);
    if (bin - base_ >= kBins) ++above_;
    ++points_;
  }

  /// Uncounts a point counted by `add(bin, fraction)` and not removed since.
  void remove(std::int32_t bin, std::int32_t fraction) {
    const std::int32_t at = offset(bin);
    if (--counts_[static_cast<std::size_t>(at)] == 0) clear_bit(at);
    sums_[static_cast<std::size_t>(at)] -= static_cast<std::uint32_t>(fraction);
    if (bin - base_ >= kBins) --above_;
    --points_;
  }

  /// Points counted in absolute bin `bin` (the top bin's include those
  /// above the span). O(1).
  std::uint32_t count(std::int32_t bin) const {
    if (bin < base_) return 0;
    return counts_[static_cast<std::size_t>(offset(bin))];
  }

  /// The bin of [first, last] holding the most points (the lowest of equals). O(last - first).
  std::int32_t densest(std::int32_t first, std::int32_t last) const {
    std::int32_t best = first;
    for (std::int32_t b = first + 1; b <= last; ++b) {
      if (count(b) > count(best)) best = b;
    }
    return best;
  }

  /// The mean position, in absolute bins (bin b spans [b, b + 1)), of the
  /// points in bins [first, last]; nullopt when they hold none. Points
  /// above the span count as in the top bin. O(last - first).
  std::optional<double> mean_bin(std::int32_t first, std::int32_t last) const {
    std::uint64_t n = 0;
    double sum = 0.0;
    for (std::int32_t b = std::max(first, base_); b <= last && b - base_ < kBins; ++b) {
      const std::uint32_t c = counts_[static_cast<std::size_t>(b - base_)];
      n += c;
      sum += static_cast<double>(c) * b + static_cast<double>(sums_[static_cast<std::size_t>(b - base_)]) / kFractionUnits;
    }
    if (n == 0) return std::nullopt;
    return sum / static_cast<double>(n);
  }

  std::uint32_t points() const { return points_; }

  /// The lowest absolute bin b holding, with b + 1, at least `support`
  /// points; nullopt when none does.
  std::optional<std::int32_t> lowest_supported(std::uint32_t support) const {
    for (std::int32_t at = next_set(0); at < kBins; at = next_set(at + 1)) {
      const std::uint32_t above = at + 1 < kBins ? counts_[static_cast<std::size_t>(at + 1)] : 0u;
      if (counts_[static_cast<std::size_t>(at)] + above >= support) return base_ + at;
    }
    return std::nullopt;
  }

  /// The highest absolute bin b holding, with b - 1, at least `support`
  /// points; nullopt when none does. The top bin also holds the points above
  /// the span.
  std::optional<std::int32_t> highest_supported(std::uint32_t support) const {
    for (std::int32_t at = previous_set(kBins - 1); at >= 0; at = previous_set(at - 1)) {
      const std::uint32_t below = at > 0 ? counts_[static_cast<std::size_t>(at - 1)] : 0u;
      if (counts_[static_cast<std::size_t>(at)] + below >= support) return base_ + at;
    }
    return std::nullopt;
  }

 private:
  std::int32_t offset(std::int32_t bin) const { return bin - base_ >= kBins ? kBins - 1 : bin - base_; }

  /// Moves the span to start at `new_base`: down (counts that fall off the
  /// top join the top bin) or up (never past the lowest count).
  void move_base_to(std::int32_t new_base) {
    const std::int32_t shift = base_ - new_base;  // > 0: down; < 0 (up) only with no point above the span
    const std::uint32_t top_in_span = counts_[kBins - 1] - above_;
    std::array<std::uint32_t, kBins> moved{};
    std::array<std::uint32_t, kBins> moved_sums{};
    for (std::int32_t at = 0; at < kBins; ++at) {
      const std::uint32_t n = counts_[static_cast<std::size_t>(at)];
      if (n == 0) continue;
      const std::int32_t to = at + shift < kBins ? at + shift : kBins - 1;
      moved[static_cast<std::size_t>(to)] += n;
      moved_sums[static_cast<std::size_t>(to)] += sums_[static_cast<std::size_t>(at)];
      if (at + shift >= kBins) above_ += at < kBins - 1 ? n : top_in_span;  // now above the span too
    }
    counts_ = moved;
    sums_ = moved_sums;
    occupied_ = {};
    for (std::int32_t at = 0; at < kBins; ++at) {
      if (counts_[static_cast<std::size_t>(at)] != 0) set_bit(at);
    }
    base_ = new_base;
  }

  void set_bit(std::int32_t at) { occupied_[static_cast<std::size_t>(at >> 6)] |= std::uint64_t{1} << (at & 63); }
  void clear_bit(std::int32_t at) { occupied_[static_cast<std::size_t>(at >> 6)] &= ~(std::uint64_t{1} << (at & 63)); }

  /// The first occupied offset >= at, or kBins.
  std::int32_t next_set(std::int32_t at) const {
    for (; at < kBins; at = (at | 63) + 1) {
      const std::uint64_t word = occupied_[static_cast<std::size_t>(at >> 6)] >> (at & 63);
      if (word != 0) return at + __builtin_ctzll(word);
    }
    return kBins;
  }
  /// The last occupied offset < at, or -1.
  std::int32_t next_set_below(std::int32_t at) const { return previous_set(at - 1); }
  /// The last occupied offset <= at, or -1.
  std::int32_t previous_set(std::int32_t at) const {
    for (; at >= 0; at = (at & ~63) - 1) {
      const int shift = 63 - (at & 63);
      const std::uint64_t word = occupied_[static_cast<std::size_t>(at >> 6)] << shift;
      if (word != 0) return at - __builtin_clzll(word);
    }
    return -1;
  }

  std::int32_t base_ = 0;
  std::uint32_t points_ = 0;
  std::uint32_t above_ = 0;  ///< points counted in the top bin that lie above the span
  std::array<std::uint64_t, kBins / 64> occupied_{};
  std::array<std::uint32_t, kBins> counts_{};
  std::array<std::uint32_t, kBins> sums_{};  ///< per bin: positions within it, in 1/kFractionUnits
};

}  // namespace streamclust
