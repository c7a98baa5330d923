// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// PointRing: the window's points in insertion order, in parallel rings
/// with the same slots: what the linkage reads (Samples, or a compact
/// payload), a small record per point (stream index, grid cell and the
/// connectivity strategy's own per-point state).

#include <streamclust/concepts/linkage.hpp>
#include <streamclust/detail/hints.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace streamclust {

/// The record the ring keeps per point: 8 bytes plus the connectivity
/// strategy's `PointState` (concepts/connectivity.hpp).
template <class PointState>
struct PointRecord {
  std::uint32_t stream_index_low = 0;  ///< low 32 bits of the stream index (PointRing keeps the high ones)
  CellIndex cell = 0;                  ///< grid cell (set when the point is linked)
  PointState state{};                  ///< the strategy's bookkeeping
};

/// The window's points, oldest to newest, as handles [oldest(), next())
/// (32-bit sequence numbers that wrap; compare them modulo 2^32).
///
/// Three rings with the same slots: the records, the Samples (40 bytes; 24
/// when the linkage's payload carries the ray, `compact_samples`: position,
/// intensity and time only, the rest rebuilt from the payload) and, for a
/// linkage with a compact payload, the payloads (what the neighbour search
/// reads). Stream indexes keep their low 32 bits in the record and their
/// high words in a short list of epochs (1 entry unless the window straddles
/// a multiple of 2^32 offered points).
///
/// Growth: to the needed size + 1/8 (at least kMinCapacity slots), not to a
/// power of two, so a steady window of N points holds at most 1.125 N
/// slots; `reserve` sizes it up front. Never shrinks. The slot of a handle
/// needs no division (one conditional subtraction).
/// Thread safety: none (one engine, one thread).
template <class Linkage, class PointState>
class PointRing {
 public:
  using Record = PointRecord<PointState>;
  /// True when the linkage has a compact payload (concepts/linkage.hpp).
  static constexpr bool uses_payload = has_linkage_payload_v<Linkage>;
  /// The linkage's payload (`detail::NoPayload` without one).
  using payload_type = linkage_payload_t<Linkage>;
  /// True when the payload carries the ray: the sample ring then keeps 24 bytes.
  static constexpr bool compact_samples = has_linkage_ray_payload_v<Linkage>;
  /// What the sample ring keeps of a Sample under `compact_samples`. 24 bytes.
  struct SampleRest {
    Eigen::Vector3f position;  ///< sensor frame [m]
    float intensity;
    double time;  ///< [s]
  };
  static_assert(sizeof(SampleRest) == 24, "the compact sample is meant to stay 24 bytes");
  using StoredSample = std::conditional_t<compact_samples, SampleRest, Sample>;
  /// Smallest ring [slots].
  static constexpr std::size_t kMinCapacity = 1024;

  // ------------------------------------------------------------ the window
  /// Points in the window. O(1).
  std::size_t size() const { return static_cast<std::uint32_t>(next_ - oldest_); }
  PointHandle oldest() const { return oldest_; }
  /// The handle the next appended point gets.
  PointHandle next() const { return next_; }
  /// True when `h` is in the window.
  bool is_live(PointHandle h) const { return static_cast<PointHandle>(h - oldest_) < size(); }
  /// Ring slots [slots].
  std::uint32_t capacity() const { return capacity_; }

  /// Slot of a live handle (or of next()): h - origin, wrapped once
  /// (oldest - origin < capacity and the window holds at most capacity
  /// points, so h - origin < 2 x capacity). O(1), no division.
  static std::uint32_t slot(PointHandle h, PointHandle origin, std::uint32_t capacity) {
    const std::uint32_t d = static_cast<std::uint32_t>(h - origin);
    return d >= capacity ? d - capacity : d;
  }
  std::uint32_t slot(PointHandle h) const { return slot(h, origin_, capacity_); }
  /// The handle in slot 0 (for the hoisted slot computations of hot loops).
  PointHandle origin() const { return origin_; }

  Record& record(PointHandle h) { return records_[slot(h)]; }
  const Record& record(PointHandle h) const { return records_[slot(h)]; }
  const Eigen::Vector3f& position(PointHandle h) const { return samples_[slot(h)].position; }
  double time(PointHandle h) const { return samples_[slot(h)].time; }
  /// The rings by slot, for hot loops that hoist the slot computation
  /// (`slot(h, origin(), capacity())`).
  const StoredSample* samples() const { return samples_.data(); }
  Record* records() { return records_.data(); }
  const Record* records() const { return records_.data(); }
  const payload_type* payloads() const { return payloads_.data(); }
  const payload_type& payload(PointHandle h) const { return payloads_[slot(h)]; }

  /// The Sample of a live point, by value (40 bytes): with compact_samples
  /// rebuilt from the stored rest and the payload's ray, equal bit for bit to
  /// the Sample appended. O(1).
  Sample sample(PointHandle h) const {
    const std::uint32_t s = slot(h);
    if constexpr (compact_samples) {
      const StoredSample& stored = samples_[s];
      Sample out;
      out.position = stored.position;
      out.intensity = stored.intensity;
      out.time = stored.time;
      Linkage::restore_ray(payloads_[s], out);
      return out;
    } else {
      return samples_[s];
    }
  }

  /// Stream index of a live point. O(1) (O(epochs) when the window spans
  /// more than one 2^32 block of offered points).
  std::uint64_t stream_index(PointHandle h) const { return stream_index(h, slot(h)); }
  /// The same, for `h` in slot `at`.
  std::uint64_t stream_index(PointHandle h, std::uint32_t at) const {
    return (std::uint64_t{epoch_high(h)} << 32) | records_[at].stream_index_low;
  }
  /// Distinct high 32-bit words among the window's stream indexes (plus the
  /// last one seen when the window is empty). O(1).
  std::size_t stream_epochs() const { return epochs_.size(); }

  // --------------------------------------------------------------- changes
  /// Appends a point: its sample (and its payload, `linkage.make_payload(s)`)
  /// and a fresh record (cell 0, default PointState). Grows the rings when
  /// full. Returns its handle. Amortised O(1).
  STREAMCLUST_ALWAYS_INLINE PointHandle append(const Sample& s, std::uint64_t stream_index, const Linkage& linkage) {
    if (size() + 1 > capacity_) grow(std::max<std::size_t>(size() + 1 + (size() + 1) / 8, kMinCapacity));
    const PointHandle h = next_++;
    const std::uint32_t at = slot(h);
    if constexpr (compact_samples) {
      samples_[at] = SampleRest{s.position, s.intensity, s.time};
    } else {
      samples_[at] = s;
    }
    if constexpr (uses_payload) payloads_[at] = linkage.make_payload(s);
    Record& r = records_[at];
    r.stream_index_low = static_cast<std::uint32_t>(stream_index);
    r.cell = 0;
    r.state = PointState{};
    note_epoch(h, stream_index);
    return h;
  }

  /// Drops the oldest point (the window must not be empty). O(1).
  void pop_oldest() {
    ++oldest_;
    // The next epoch starts at the new oldest point: the first covers no
    // live point. Dropping it keeps every epoch but the first starting at a
    // live handle, which epoch_high compares modulo 2^32.
    if (epochs_.size() >= 2 && epochs_[1].first == oldest_) epochs_.erase(epochs_.begin());
    if (static_cast<std::uint32_t>(oldest_ - origin_) == capacity_) origin_ += capacity_;
  }

  /// Room for windows of up to `points` points. O(points) when it grows.
  void reserve(std::size_t points) {
    if (points > capacity_) grow(std::max<std::size_t>(points, kMinCapacity));
  }

  /// Heap bytes of the three rings (capacities). O(1).
  std::size_t heap_bytes() const {
    return records_.capacity() * sizeof(Record) + samples_.capacity() * sizeof(StoredSample) +
           payloads_.capacity() * sizeof(payload_type);
  }

 private:
  /// The high 32 bits of the stream indexes from handle `first` on.
  struct Epoch {
    PointHandle first;
    std::uint32_t high;
  };

  /// High word of live point `h`'s stream index: the newest epoch that starts
  /// at or before `h`. Every epoch but the first starts at a live handle, so
  /// the modular distances never alias.
  std::uint32_t epoch_high(PointHandle h) const {
    std::size_t i = epochs_.size() - 1;
    const auto back = static_cast<std::uint32_t>(next_ - h);  // handles appended since h, >= 1
    while (i > 0 && static_cast<std::uint32_t>(next_ - epochs_[i].first) < back) --i;
    return epochs_[i].high;
  }

  /// Records the epoch of just-appended `h` when its high word is new, and
  /// forgets the epochs no live point needs. Allocates only when the window
  /// spans a new maximum of epochs.
  void note_epoch(PointHandle h, std::uint64_t stream_index) {
    const auto high = static_cast<std::uint32_t>(stream_index >> 32);
    if (!epochs_.empty() && epochs_.back().high == high) return;
    epochs_.push_back(Epoch{h, high});
    const auto live = static_cast<std::uint32_t>(next_ - oldest_);
    while (epochs_.size() >= 2 && static_cast<std::uint32_t>(next_ - epochs_[1].first) >= live)
      epochs_.erase(epochs_.begin());
  }

  /// Reallocates the rings to `capacity` slots; the live points move to
  /// slots [0, size) and the origin to the oldest point. O(capacity).
  void grow(std::size_t capacity) {
    std::vector<Record> records(capacity);
    std::vector<StoredSample> samples(capacity);
    std::vector<payload_type> payloads(uses_payload ? capacity : 0);  // no ring without a payload
    std::uint32_t to = 0;
    for (PointHandle h = oldest_; h != next_; ++h, ++to) {
      const std::uint32_t from = slot(h);
      records[to] = records_[from];
      samples[to] = samples_[from];
      if constexpr (uses_payload) payloads[to] = payloads_[from];
    }
    records_.swap(records);
    samples_.swap(samples);
    payloads_.swap(payloads);
    capacity_ = static_cast<std::uint32_t>(capacity);
    origin_ = oldest_;
  }

  std::vector<Record> records_;
  std::vector<StoredSample> samples_;
  std::vector<payload_type> payloads_;  ///< empty without a payload linkage
  std::uint32_t capacity_ = 0;
  PointHandle origin_ = 0;  ///< the handle in slot 0: oldest_ - origin_ < capacity_ (mod 2^32)
  PointHandle oldest_ = 0;
  PointHandle next_ = 0;
  std::vector<Epoch> epochs_;  ///< never empty once a point was appended
};

}  // namespace streamclust
