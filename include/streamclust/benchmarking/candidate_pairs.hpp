// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The point pairs a linkage is asked about, as the engine asks: each point
/// of a simulated Livox stream (the query, in firing order) against the
/// earlier points it is offered (its candidates), stored as one slot list
/// per query into the stream's samples, the way the engine hands
/// `link_many` its candidates.
///
/// ```cpp
/// namespace bk = streamclust::benchmarking;
/// // what a 5 x 5 mask offers in 0.1 s of a Mid-360 in the office
/// const bk::CandidatePairs& pairs = bk::mask_candidates({bk::Sensor::mid360, "office"});
/// for (std::size_t i = 0; i < pairs.samples.size(); ++i)
///   for (std::uint32_t k = pairs.first[i]; k < pairs.first[i + 1]; ++k)
///     linkage(pairs.samples[i], pairs.samples[pairs.slots[k]]);
/// ```
/// Thread-safety: the builders cache their result (function-local statics
/// guarded by a mutex); a CandidatePairs is immutable once built.

#include <streamclust/benchmarking/simulated_streams.hpp>
#include <streamclust/detail/mask.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/resolution/adaptive.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace streamclust::benchmarking {

/// Queries and their candidates (see the file comment). Query i's
/// candidates are `samples[slots[k]]` for k in [first[i], first[i + 1]),
/// all earlier in the stream than i.
struct CandidatePairs {
  std::string name;                  ///< e.g. "mid360_office_mask5"
  std::vector<Sample> samples;       ///< the stream's points, firing order
  std::vector<std::uint32_t> first;  ///< samples.size() + 1 offsets into slots
  std::vector<std::uint32_t> slots;  ///< candidate indices into samples
  std::size_t max_candidates = 0;    ///< the most candidates of one query

  std::size_t pair_count() const { return slots.size(); }
};

/// The first `seconds` of scenario `s` as Samples (sensor frame: position,
/// range, intensity, time).
inline std::vector<Sample> simulated_samples(const Scenario& s, double seconds) {
  std::vector<Sample> samples;
  const auto& points = simulated_points(s, seconds);
  samples.reserve(points.size());
  for (const sim::SimPoint& p : points) {
    const Eigen::Vector3f pos(p.x, p.y, p.z);
    samples.push_back(make_sample(pos, pos.norm(), p.intensity, p.t));
  }
  return samples;
}

namespace detail {

/// Fills `first` from per-query candidate counts already appended to slots.
inline void close_query(CandidatePairs& pairs) {
  const auto end = static_cast<std::uint32_t>(pairs.slots.size());
  pairs.max_candidates = std::max<std::size_t>(pairs.max_candidates, end - pairs.first.back());
  pairs.first.push_back(end);
}

}  // namespace detail

/// What a w x w mask offers: the first `seconds` of scenario `s` projected
/// by the sensor's field of view onto the grid the adaptive resolution
/// calibrates on those points (T_M = 2, its defaults), each point against
/// every earlier point in the `mask_size` x `mask_size` cells around its own
/// (the window holds the whole stream). Cached per (scenario, seconds,
/// mask_size). O(points x mask_size^2 + pairs) the first time.
inline const CandidatePairs& mask_candidates(const Scenario& s, double seconds = 0.1, int mask_size = 5) {
  const Scenario key{s.sensor, s.scene + "/mask" + std::to_string(mask_size)};
  return detail::cached<CandidatePairs>(key, seconds, [&] {
    CandidatePairs pairs;
    pairs.name = s.name() + "_mask" + std::to_string(mask_size);
    pairs.samples = simulated_samples(s, seconds);
    const SphericalProjection projection(field_of_view(s.sensor));
    std::vector<Projected> projected;
    std::vector<std::uint32_t> accepted;  // indices of the points the projection keeps
    for (std::uint32_t i = 0; i < pairs.samples.size(); ++i) {
      const Projected q = projection.project(pairs.samples[i].position);
      if (!q.accepted()) continue;
      projected.push_back(q);
      accepted.push_back(i);
    }
    AdaptiveResolution resolution{AdaptiveResolution::Params{}};
    const GridSize size = resolution.calibrate(projected, projection.fov_aspect());
    const GridShape grid{size.rows, size.cols, s.sensor == Sensor::mid360};
    std::vector<std::vector<std::uint32_t>> cells(grid.cell_count());
    // Keep only the accepted points: slots index the kept samples.
    std::vector<Sample> kept;
    kept.reserve(accepted.size());
    pairs.first.push_back(0);
    for (std::size_t n = 0; n < accepted.size(); ++n) {
      const CellIndex c = grid.cell_of(projected[n].u, projected[n].v);
      streamclust::detail::for_each_mask_cell(grid, c, mask_size / 2, [&](CellIndex m) {
        pairs.slots.insert(pairs.slots.end(), cells[m].begin(), cells[m].end());
      });
      detail::close_query(pairs);
      cells[c].push_back(static_cast<std::uint32_t>(n));
      kept.push_back(pairs.samples[accepted[n]]);
    }
    pairs.samples = std::move(kept);
    return pairs;
  });
}

/// Each point of the first `seconds` of scenario `s` against the `back`
/// points fired just before it (neighbours on the same laser's recent sweep
/// and the adjacent lasers; the first `back` points are no queries). Cheaper
/// to build than mask_candidates, with a fixed count per query. Cached.
inline const CandidatePairs& firing_order_candidates(const Scenario& s, double seconds = 0.1, std::uint32_t back = 16) {
  const Scenario key{s.sensor, s.scene + "/back" + std::to_string(back)};
  return detail::cached<CandidatePairs>(key, seconds, [&] {
    CandidatePairs pairs;
    pairs.name = s.name() + "_back" + std::to_string(back);
    pairs.samples = simulated_samples(s, seconds);
    pairs.first.push_back(0);
    const auto n = static_cast<std::uint32_t>(pairs.samples.size());
    for (std::uint32_t i = 0; i < n; ++i) {
      if (i >= back) {
        for (std::uint32_t j = i - back; j < i; ++j) pairs.slots.push_back(j);
      }
      detail::close_query(pairs);
    }
    return pairs;
  });
}

}  // namespace streamclust::benchmarking
