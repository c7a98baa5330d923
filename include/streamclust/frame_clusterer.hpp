// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// FrameClusterer: the frame-based way of clustering a stream, the
/// counterpart of StreamClusterer. It keeps the sliding window of accepted
/// points and, at each retrieval, clusters the whole window from scratch
/// with a BatchClusterer; with an OverwriteGrid in BatchMode::range_image
/// (the default mode) this is the classic range-image baseline (Bogoslavskyi
/// & Stachniss) on the same windows as the continuous engine.

#include <streamclust/acceptance.hpp>
#include <streamclust/batch_clusterer.hpp>
#include <streamclust/config.hpp>
#include <streamclust/grid_choice.hpp>
#include <streamclust/point_traits.hpp>
#include <streamclust/types.hpp>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

namespace streamclust {

/// Clusters the sliding window from scratch at every retrieval.
///
/// Input follows StreamClusterer: the same acceptance rules in the same
/// order (non-finite time, projection: range and field of view, time order),
/// the same window policy, the same stream indices (every offered point
/// counts), and the same calibration: a calibrating resolution policy
/// chooses the grid from the first complete window (nothing is retrieved
/// before, see `calibrating()`), a fixed one or `set_grid` gives it at once.
/// A retrieval labels every window point, oldest first: the component
/// number (0, 1, ... in order of first appearance) or -1 for a point the
/// index displaced (range_image mode).
///
/// \code
/// using Frame = streamclust::FrameBaselineConfig;  // overwrite grid
/// streamclust::FrameClusterer<Frame> frame(params);
/// for (const auto& p : packet) frame.insert(p);
/// frame.advance_to(now);
/// if (!frame.calibrating()) {
///   const streamclust::BatchResult& r = frame.retrieve();  // r.labels[i]: the i-th window point
/// }
/// \endcode
///
/// Costs: insert O(1) amortised (projection and eviction); retrieve O(N w^2 k)
/// plus near-linear union-find for N window points. Not thread-safe; one
/// instance per thread.
template <class Config>
class FrameClusterer {
 public:
  using traits = config_traits<Config>;
  STREAMCLUST_CHECK_CONFIG(Config);
  using Params = ClustererParams<Config>;
  using projection_type = typename traits::projection;
  using window_type = typename traits::window;
  using resolution_type = typename traits::resolution;

  /// Throws std::invalid_argument when a parameter is out of range.
  explicit FrameClusterer(const Params& params = Params{}, BatchMode mode = BatchMode::range_image)
      : projection_(params.projection),
        window_(params.window),
        resolution_(params.resolution),
        batch_(params, mode),
        first_stream_index_(params.first_stream_index),
        time_order_(params.time_order) {
    if (!resolution_.needs_calibration()) set_grid(resolution_.grid());
  }

  /// Uses `size` from now on and ends a pending calibration (the resolution
  /// policy is then not asked).
  void set_grid(GridSize size) {
    grid_ = size;
    calibrating_ = false;
    batch_.set_grid(size);
  }

  /// Offers one point, its time read with `stamp(p)`; returns why it was not
  /// taken, or `accepted`. O(1) amortised.
  template <class P>
  RejectReason insert(const P& p) {
    return insert(p, stamp(p));
  }

  /// Offers one point with an explicit stream time [s].
  template <class P>
  RejectReason insert(const P& p, double time) {
    static_assert(is_point_v<P>, "STREAMCLUST_POINT_TYPE_INVALID: specialise streamclust::point_traits for this type");
    const std::uint64_t stream_index = first_stream_index_ + offered_++;
    const Eigen::Vector3f pos = position(p);
    const Projected pr = projection_.project(pos);
    const RejectReason verdict = time_order_.admit(pr, time);  // the engine's rule (acceptance.hpp)
    ++rejections_[verdict];
    if (verdict != RejectReason::accepted) return verdict;
    if (calibrating_) {
      // As the engine: the point that completes the first window is not part
      // of the calibration; nothing expires before it.
      if (!points_.empty() && window_.complete(points_.front().sample.time, time, points_.size() + 1)) {
        finish_calibration();
      } else {
        points_.push_back({make_sample(pos, pr.range, intensity(p), time), stream_index});
        return RejectReason::accepted;
      }
    }
    evict_expired(time, points_.size() + 1);
    points_.push_back({make_sample(pos, pr.range, intensity(p), time), stream_index});
    return RejectReason::accepted;
  }

  /// Offers [first, last) in order, writing each point's RejectReason to
  /// `reasons` (an output iterator); returns `reasons` past the last one.
  template <class It, class ReasonOut>
  ReasonOut insert_batch(It first, It last, ReasonOut reasons) {
    for (; first != last; ++first) *reasons++ = insert(*first);
    return reasons;
  }

  /// Offers [first, last) in order; returns the points accepted.
  template <class It>
  std::size_t insert_batch(It first, It last) {
    std::size_t accepted = 0;
    for (; first != last; ++first) accepted += insert(*first) == RejectReason::accepted;
    return accepted;
  }

  /// Evicts the points that have left the window at stream time `time` [s];
  /// a time that completes the first window ends the calibration. An
  /// earlier time than the newest point's is ignored (as the engine).
  void advance_to(double time) {
    if (!time_order_.may_advance_to(time)) return;
    time_order_.advance(time);
    if (calibrating_) {
      if (!points_.empty() && window_.complete(points_.front().sample.time, time, points_.size())) {
        finish_calibration();
      }
      if (calibrating_) return;
    }
    evict_expired(time, points_.size());
  }

  /// Ends the calibration now on the buffered points (e.g. a stream shorter
  /// than one window). No-op when not calibrating or nothing is buffered.
  void complete_calibration() {
    if (calibrating_ && !points_.empty()) finish_calibration();
  }

  /// Clusters the window from scratch. While calibrating the result is empty.
  /// The reference stays valid until the next call.
  const BatchResult& retrieve() {
    if (calibrating_) {
      last_is_batch_ = false;
      return empty_;
    }
    samples_.clear();
    for (const Entry& e : points_) samples_.push_back(e.sample);
    last_is_batch_ = true;
    return batch_.cluster(samples_);
  }

  /// Clusters a given window from scratch (a range of points with
  /// point_traits, e.g. another clusterer's window, oldest first) on this
  /// clusterer's grid, ignoring its own window: a frame peer for a window
  /// that is already at hand. Before the grid is known (calibrating) the
  /// resolution policy chooses one from `window`. Costs as `retrieve()`.
  template <class Range>
  const BatchResult& cluster(const Range& window) {
    last_is_batch_ = true;
    return batch_.cluster(window);
  }

  /// The last retrieval's result (empty before the first).
  const BatchResult& last_result() const { return last_is_batch_ ? batch_.last_result() : empty_; }

  /// Calls `f(const Sample&, std::uint64_t stream_index)` for each window
  /// point, oldest first (the order of `retrieve()`'s labels).
  template <class F>
  void for_each_point(F&& f) const {
    for (const Entry& e : points_) f(e.sample, e.stream_index);
  }

  /// Points in the window (buffered ones while calibrating).
  std::size_t size() const { return points_.size(); }
  bool empty() const { return points_.empty(); }
  /// True while the first window is buffered to choose the grid.
  bool calibrating() const { return calibrating_; }
  /// The grid in use (rows x cols; zero while calibrating), wrapped like the projection.
  GridShape grid() const { return GridShape{grid_.rows, grid_.cols, projection_.wraps_horizontally()}; }
  const resolution_type& resolution() const { return resolution_; }
  const projection_type& projection() const { return projection_; }
  /// Points offered so far (accepted or not).
  std::uint64_t offered() const { return offered_; }
  const RejectionCounts& rejections() const { return rejections_; }

 private:
  struct Entry {
    Sample sample;
    std::uint64_t stream_index;
  };

  void evict_expired(double newest_time, std::size_t count) {
    while (!points_.empty() && window_.expired(points_.front().sample.time, newest_time, count)) {
      points_.pop_front();
      --count;
    }
  }

  void finish_calibration() {
    std::vector<Projected> coords;
    coords.reserve(points_.size());
    for (const Entry& e : points_) coords.push_back(projection_.project(e.sample.position));
    const GridShape chosen = choose_grid(resolution_, projection_, coords);  // the engine's choice (grid_choice.hpp)
    set_grid(GridSize{chosen.rows, chosen.cols});
  }

  projection_type projection_;
  window_type window_;
  resolution_type resolution_;
  BatchClusterer<Config> batch_;
  std::uint64_t first_stream_index_ = 0;
  std::deque<Entry> points_;
  std::vector<Sample> samples_;
  BatchResult empty_;           // the result while calibrating
  bool last_is_batch_ = false;  // the last retrieval ran the batch clusterer
  GridSize grid_{};
  bool calibrating_ = true;
  StreamTimeOrder time_order_;
  std::uint64_t offered_ = 0;
  RejectionCounts rejections_{};
};

}  // namespace streamclust
