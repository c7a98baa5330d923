// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// ComponentResult: writes a retrieval's Clustering from the component of
/// every window point and the ids each component keeps.

#include <streamclust/clustering.hpp>
#include <streamclust/detail/growth.hpp>
#include <streamclust/detail/hints.hpp>
#include <streamclust/engine/stable_ids.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace streamclust {

/// The one writer of the engine's result, whatever the connectivity
/// strategy. Given, per window position, a component number (dense, any
/// order) and, per component, the place in the previous result of the id it
/// keeps (StableIdVotes::resolve), it orders the components by id without a
/// comparison sort (the kept ids in their previous order, then fresh ids in
/// component order, which exceed every id handed out before), then labels
/// every point and builds the summaries in one pass in window order.
///
/// A component's summary is opened by its first point (its place carries an
/// "unopened" flag until then): the first point writes it whole, so there is
/// no zeroing pass and no read of a stale summary. Sums for the centroids
/// are kept only for components of two or more points (a single point is
/// its own centroid), numbered as the pass opens them: few on a fragmented
/// window. O(N + components + previous components); allocates only when a
/// size exceeds its previous peak (per-point vectors: to the room given).
/// Thread safety: none.
class ComponentResult {
 public:
  /// No place (StableIdVotes' mark of a component without a kept id).
  static constexpr std::uint32_t kNone = StableIdVotes::kNone;

  const Clustering& result() const { return result_; }
  /// The structure points of the result, written by the engine after the
  /// strategy wrote the rest.
  std::vector<StructurePoint>& structure() { return result_.structure; }
  /// Place in the last result of component `k` of the last write.
  std::uint32_t place_of(std::uint32_t k) const { return place_of_[k]; }
  /// Id at place `r` of the last result.
  ComponentId id_at(std::uint32_t r) const { return ids_[r]; }
  /// Components of the last result.
  std::uint32_t components() const { return static_cast<std::uint32_t>(ids_.size()); }

  /// A retrieval with nothing to label yet (the first window is still
  /// buffered): no labels, no components. O(1).
  const Clustering& write_empty(double time) {
    result_.time = time;
    ++result_.cycle;
    result_.points.clear();
    result_.components.clear();
    ids_.clear();
    return result_;
  }

  /// Writes the result of `n` window points of `ring`, oldest first.
  /// `component_at(i)` is the component of window position i (< components);
  /// `component_size(k)` its points; `multiple` the components of two or
  /// more points; `kept_place[k]` the previous place of the id component k
  /// keeps, or kNone. Fresh ids come from `next_id`. `room` is the capacity
  /// to give per-point vectors when they grow (the point rings').
  /// O(n + components + previous).
  template <class Ring, class ComponentAt, class ComponentSize>
  const Clustering& write(const Ring& ring, std::uint32_t n, std::uint32_t components, std::uint32_t multiple,
                          const std::vector<std::uint32_t>& kept_place, ComponentAt&& component_at,
                          ComponentSize&& component_size, double time, ComponentId& next_id, std::size_t room) {
    order_ids(components, kept_place, next_id);
    result_.time = time;
    ++result_.cycle;
    detail::reserve_window(result_.points, n, room);
    result_.points.resize(n);
    detail::reserve_geometric(result_.components, components);
    result_.components.resize(components);
    detail::reserve_geometric(sums_, multiple);
    sums_.resize(multiple);
    detail::reserve_geometric(sum_place_, multiple);
    sum_place_.resize(multiple);
    detail::reserve_geometric(sum_of_, components);
    sum_of_.resize(components);  // written when a component of 2+ points opens
    std::uint32_t summed = 0;
    ComponentSummary* const summaries = result_.components.data();
    PointLabel* const labels = result_.points.data();
    const ComponentId* const ids = ids_.data();
    std::uint32_t* const place_of = place_of_.data();
    const bool scattered = components >= kPrefetchMinComponents;
    const PointHandle oldest = ring.oldest();
    const PointHandle origin = ring.origin();  // hoisted: the stores below could alias the ring's members
    const std::uint32_t capacity = ring.capacity();
    const auto* const samples = ring.samples();
    for (std::uint32_t i = 0; i < n; ++i) {
      if (scattered && i + kPrefetchDistance < n) {
        // The summary's lines (72 bytes may straddle two): scattered over the
        // components, likely misses.
        const std::uint32_t ahead = place_of[component_at(i + kPrefetchDistance)] & ~kUnopened;
        detail::prefetch(&summaries[ahead]);
        detail::prefetch(&summaries[ahead].time_end);
      }
      const PointHandle h = oldest + i;
      const std::uint32_t k = component_at(i);
      std::uint32_t at = place_of[k];
      const std::uint32_t slot = Ring::slot(h, origin, capacity);
      const auto& stored = samples[slot];  // position and time only
      const Eigen::Vector3f& p = stored.position;
      ComponentSummary& sm = summaries[at & ~kUnopened];
      if (at & kUnopened) {
        at &= ~kUnopened;
        place_of[k] = at;
        sm.id = ids[at];
        sm.size = 1;
        sm.min = p;
        sm.max = p;
        sm.centroid = p;  // (double(p) / 1) as float is p: final for a single point
        sm.time_begin = stored.time;
        sm.time_end = stored.time;
        if (component_size(k) > 1) {
          sum_of_[k] = summed;
          sum_place_[summed] = at;
          sums_[summed++] = p.template cast<double>();
        }
      } else {
        sm.min = sm.min.cwiseMin(p);
        sm.max = sm.max.cwiseMax(p);
        sm.time_end = stored.time;
        sums_[sum_of_[k]] += p.template cast<double>();
        ++sm.size;
      }
      labels[i] = PointLabel{ring.stream_index(h, slot), ids[at]};
    }
    // The centroids of the components of two or more points.
    for (std::uint32_t s = 0; s < summed; ++s) {
      ComponentSummary& sm = summaries[sum_place_[s]];
      sm.centroid = (sums_[s] / static_cast<double>(sm.size)).template cast<float>();
    }
    return result_;
  }

  std::size_t heap_bytes() const {
    return result_.points.capacity() * sizeof(PointLabel) +
           result_.components.capacity() * sizeof(ComponentSummary) +
           result_.structure.capacity() * sizeof(StructurePoint);
  }
  std::size_t scratch_bytes() const {
    return ids_.capacity() * sizeof(ComponentId) +
           (place_of_.capacity() + by_place_.capacity() + sum_of_.capacity() + sum_place_.capacity()) * sizeof(std::uint32_t) +
           sums_.capacity() * sizeof(Eigen::Vector3d);
  }

 private:
  /// Place flag of a component whose summary no point opened yet.
  static constexpr std::uint32_t kUnopened = std::uint32_t{1} << 31;
  /// Points ahead whose summaries the pass prefetches [points].
  static constexpr std::uint32_t kPrefetchDistance = 16;
  /// Components from which it prefetches: 4096 summaries are 288 KB.
  static constexpr std::uint32_t kPrefetchMinComponents = 4096;


  /// The ids by place: kept ids in their previous order, then fresh ones in
  /// component order; leaves place_of_[k] = component k's place with the
  /// unopened flag. In place: the previous ids are read before overwritten.
  /// O(components + previous).
  void order_ids(std::uint32_t components, const std::vector<std::uint32_t>& kept_place, ComponentId& next_id) {
    const auto previous = static_cast<std::uint32_t>(ids_.size());
    detail::reserve_geometric(by_place_, previous);
    by_place_.assign(previous, kNone);
    for (std::uint32_t k = 0; k < components; ++k) {
      if (kept_place[k] != kNone) by_place_[kept_place[k]] = k;
    }
    detail::reserve_geometric(place_of_, components);
    place_of_.resize(components);
    detail::reserve_geometric(ids_, std::max(components, previous));
    ids_.resize(std::max(components, previous));
    ComponentId* const ids = ids_.data();
    std::uint32_t placed = 0;
    for (std::uint32_t s = 0; s < previous; ++s) {  // placed <= s: id s was read already
      const std::uint32_t k = by_place_[s];
      if (k == kNone) continue;
      place_of_[k] = placed | kUnopened;
      ids[placed++] = ids[s];
    }
    for (std::uint32_t k = 0; k < components; ++k) {
      if (kept_place[k] != kNone) continue;
      place_of_[k] = placed | kUnopened;
      ids[placed++] = next_id++;
    }
    ids_.resize(components);
  }

  Clustering result_;
  std::vector<ComponentId> ids_;          ///< id per place of the last result
  std::vector<std::uint32_t> place_of_;   ///< component -> place (flagged until opened)
  std::vector<std::uint32_t> by_place_;   ///< previous place -> component that kept its id
  std::vector<std::uint32_t> sum_of_;     ///< component of 2+ points -> its sum
  std::vector<std::uint32_t> sum_place_;  ///< sum -> its component's place
  std::vector<Eigen::Vector3d> sums_;     ///< position sums, for the centroids
};

}  // namespace streamclust
