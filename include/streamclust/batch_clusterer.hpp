// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// BatchClusterer: clusters a set of points from scratch with the same
/// projection, index, mask and linkage as the continuous engine. It is the
/// oracle of the engine and, with an overwrite grid in range-image mode, the
/// classic frame-based baseline (Bogoslavskyi & Stachniss).

#include <streamclust/acceptance.hpp>
#include <streamclust/config.hpp>
#include <streamclust/detail/mask.hpp>
#include <streamclust/detail/union_find.hpp>
#include <streamclust/grid_choice.hpp>
#include <streamclust/point_traits.hpp>
#include <streamclust/types.hpp>

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

namespace streamclust {

/// How the batch clusterer uses its spatial index.
enum class BatchMode {
  /// Replay: points enter the index in input order and each links to the
  /// points the index holds when it arrives (query, then insert). A point
  /// displaced from a capped or overwrite grid keeps its links. This is
  /// exactly the engine's rule, so it is the oracle for every index.
  insertion_order,
  /// Range image: all points enter the index first; only the points the index
  /// still holds are linked to each other; displaced points stay unlabelled
  /// (-1). With OverwriteGrid this is the frame-based baseline.
  range_image,
};

/// Labels of one batch run.
struct BatchResult {
  /// Per input point: component number (0, 1, ... in order of first
  /// appearance) or -1 for a rejected or unlabelled point.
  std::vector<std::int64_t> labels;
  std::size_t components = 0;
  GridShape grid{};
  RejectionCounts rejections{};
};

/// Clusters whole point sets. O(n w^2 k) per run plus near-linear union-find.
/// With a motion policy, points are placed as the engine places them (give
/// the input points in the sensor frame, in time order). The ground policy
/// is not applied: the oracle of an engine with one clusters the engine's
/// object points (the engine's decisions, replayed).
/// Not thread-safe; one instance per thread.
///
/// \code
/// streamclust::BatchClusterer<streamclust::CArcConfig> batch(params);
/// batch.set_grid({64, 1024});                  // or let the resolution policy choose
/// const auto& result = batch.cluster(points);  // any range of points with point_traits
/// \endcode
template <class Config>
class BatchClusterer {
 public:
  using traits = config_traits<Config>;
  STREAMCLUST_CHECK_CONFIG(Config);
  using Params = ClustererParams<Config>;
  using motion_type = typename traits::motion;
  /// True when the linkage tests one payload against many (link_many):
  /// each point's candidates then go through one call, as in the engine.
  static constexpr bool tests_many = has_linkage_link_many_v<typename traits::linkage>;

  explicit BatchClusterer(const Params& params = Params{}, BatchMode mode = BatchMode::insertion_order)
      : params_(params),
        projection_(params.projection),
        linkage_(params.linkage),
        index_(params.spatial_index),
        half_(detail::checked_mask_half_width(params.mask_size)),
        mode_(mode) {
    typename traits::resolution resolution(params.resolution);
    if (!resolution.needs_calibration()) fixed_grid_ = resolution.grid();
  }

  /// Uses this grid for every run instead of the resolution policy's choice.
  void set_grid(GridSize size) { fixed_grid_ = size; }

  /// Clusters `points` (a range of any point type with point_traits) in their
  /// order. A calibrating resolution policy chooses the grid from these
  /// points unless `set_grid` was called. Returns a reference valid until the
  /// next run.
  template <class Range>
  const BatchResult& cluster(const Range& points) {
    samples_.clear();
    coords_.clear();
    result_ = BatchResult{};
    motion_type motion(params_.motion);  // a fresh cursor per run
    for (const auto& p : points) {
      const Eigen::Vector3f pos = position(p);
      const double time = stamp(p);
      Projected pr;
      PlacedPoint placed{pos, pos};
      if constexpr (motion_type::identity) {
        pr = projection_.project(pos);
      } else {
        // The engine's placement (StreamClusterer::prepare): world and ray.
        const RejectReason placement = std::isfinite(time) ? motion.place(pos, time, placed) : RejectReason::non_finite;
        if (placement == RejectReason::accepted) {
          pr = projection_.project(placed.ray);
        } else {
          pr.reason = placement;
        }
      }
      pr.reason = judge_point(pr, time);  // the engine's rule, without the time order (a batch is a window)
      ++result_.rejections[pr.reason];
      coords_.push_back(pr);
      if (!pr.accepted()) {
        samples_.push_back(Sample{});
      } else if constexpr (motion_type::identity) {
        samples_.push_back(make_sample(pos, pr.range, intensity(p), time));
      } else {
        samples_.push_back(make_sample(placed.world, placed.ray, pr.range, intensity(p), time));
      }
    }
    if (fixed_grid_) {
      result_.grid = grid_shape_for(*fixed_grid_, projection_);
    } else {
      accepted_.clear();
      for (const Projected& pr : coords_) {
        if (pr.accepted()) accepted_.push_back(pr);
      }
      typename traits::resolution resolution(params_.resolution);
      result_.grid = choose_grid(resolution, projection_, accepted_);
    }
    index_.reset(result_.grid);

    const std::size_t n = samples_.size();
    if constexpr (tests_many) {
      payloads_.clear();
      for (const Sample& smp : samples_) payloads_.push_back(linkage_.make_payload(smp));
    }
    cells_.assign(n, 0);
    sets_.reset(n);
    if (mode_ == BatchMode::insertion_order) {
      for (std::size_t i = 0; i < n; ++i) {
        if (!coords_[i].accepted()) continue;
        cells_[i] = result_.grid.cell_of(coords_[i].u, coords_[i].v);
        link_to_index(i);
        index_.insert(cells_[i], static_cast<PointHandle>(i));
      }
    } else {
      indexed_.assign(n, 0);
      for (std::size_t i = 0; i < n; ++i) {
        if (!coords_[i].accepted()) continue;
        cells_[i] = result_.grid.cell_of(coords_[i].u, coords_[i].v);
        indexed_[i] = 1;
        const PointHandle displaced = index_.insert(cells_[i], static_cast<PointHandle>(i));
        if (displaced != kNoPoint) indexed_[displaced] = 0;
      }
      for (std::size_t i = 0; i < n; ++i) {
        if (indexed_[i]) link_to_index(i);
      }
    }

    result_.labels.assign(n, -1);
    root_label_.assign(n, -1);
    for (std::size_t i = 0; i < n; ++i) {
      if (!coords_[i].accepted() || (mode_ == BatchMode::range_image && !indexed_[i])) continue;
      const std::uint32_t root = sets_.find(static_cast<std::uint32_t>(i));
      if (root_label_[root] < 0) root_label_[root] = static_cast<std::int64_t>(result_.components++);
      result_.labels[i] = root_label_[root];
    }
    return result_;
  }

  const BatchResult& last_result() const { return result_; }

 private:
  void link_to_index(std::size_t i) {
    if constexpr (tests_many) {
      // As the engine: every candidate in one call (the same decisions as
      // the pairwise operator, concepts/linkage.hpp), then the unions.
      candidates_.clear();
      detail::for_each_mask_cell(result_.grid, cells_[i], half_, [&](CellIndex c) {
        index_.for_each(c, [&](PointHandle h) {
          if (h != i) candidates_.push_back(h);
        });
      });
      linked_.resize(candidates_.size());
      linkage_.link_many(payloads_[i], payloads_.data(), candidates_.data(), candidates_.size(), linked_.data());
      for (std::size_t k = 0; k < candidates_.size(); ++k) {
        if (linked_[k]) sets_.unite(static_cast<std::uint32_t>(i), candidates_[k]);
      }
    } else {
      // The indexed point first (in insertion order the older one), where
      // the engine asks linkage(new, old): an asymmetric linkage, which has
      // no single-linkage partition, then shows as a mismatch of the oracle
      // (tests/test_testing_kit.cpp).
      const Sample& s = samples_[i];
      detail::for_each_mask_cell(result_.grid, cells_[i], half_, [&](CellIndex c) {
        index_.for_each(c, [&](PointHandle h) {
          if (h != i && linkage_(samples_[h], s)) sets_.unite(static_cast<std::uint32_t>(i), h);
        });
      });
    }
  }

  Params params_;
  typename traits::projection projection_;
  typename traits::linkage linkage_;
  typename traits::spatial_index index_;
  int half_;
  BatchMode mode_;
  std::optional<GridSize> fixed_grid_;
  std::vector<Sample> samples_;
  std::vector<linkage_payload_t<typename traits::linkage>> payloads_;  // with link_many: one per sample
  std::vector<PointHandle> candidates_;                                // with link_many: the mask's handles
  std::vector<std::uint8_t> linked_;                                   // with link_many: their decisions
  std::vector<Projected> coords_;
  std::vector<Projected> accepted_;
  std::vector<CellIndex> cells_;
  std::vector<char> indexed_;
  std::vector<std::int64_t> root_label_;
  detail::UnionFind sets_;
  BatchResult result_;
};

}  // namespace streamclust
