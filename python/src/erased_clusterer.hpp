// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// ErasedClusterer: one virtual interface over every compiled configuration
/// of the continuous engine (and of the frame clusterer of `--mode frame`),
/// so the module binds one class. A virtual call
/// per `insert` (a packet of points) or per retrieval, never per point: the
/// engine inside keeps its compiled fast paths. `make_erased_clusterer`
/// picks the configuration the CLI would run for the same options (its
/// instantiations are split over one translation unit per linkage, like
/// the CLI's).

#include "point_buffers.hpp"

#include "cli/options.hpp"

#include <streamclust/clustering.hpp>
#include <streamclust/tracking/object_boxes.hpp>
#include <streamclust/types.hpp>

#include <cstdint>
#include <memory>

namespace streamclust::python {

/// A StreamClusterer (or FrameClusterer) of some compiled configuration.
/// Not thread-safe (one caller at a time; the Python binding serialises
/// calls with a mutex).
class ErasedClusterer {
 public:
  virtual ~ErasedClusterer() = default;
  /// Offers `points` in order with `insert_batch`; writes one reason per
  /// point to `reasons` (room for points.size). Returns the points accepted.
  /// O(points) engine work.
  virtual std::size_t insert(const PointBuffers& points, RejectReason* reasons) = 0;
  /// StreamClusterer::advance_to (evicts up to stream time `time` [s]).
  virtual void advance_to(double time) = 0;
  virtual bool calibrating() const = 0;
  virtual void complete_calibration() = 0;
  /// StreamClusterer::retrieve; the reference stays valid until the next call.
  virtual const Clustering& retrieve() = 0;
  /// True for the continuous engine (stable component ids), false in frame mode.
  virtual bool continuous() const = 0;
  /// The observed objects of `result`, the last retrieve()'s
  /// (tracking::ObjectBoxes); nullptr in frame mode (no stable components).
  /// Valid until the next call.
  virtual const std::vector<tracking::ObjectObservation>* objects(const Clustering& result) = 0;
  /// Points offered so far (the next point's stream index).
  virtual std::uint64_t offered() const = 0;
  /// Points in the window.
  virtual std::size_t size() const = 0;
  virtual GridShape grid() const = 0;
};

/// The engine the CLI runs for `o`: continuous, or frame with `--mode
/// frame` (resolved: `o.setup` filled when motion or ground is asked for). Throws cli::UsageError for a value a
/// policy rejects.
std::unique_ptr<ErasedClusterer> make_erased_clusterer(const cli::ClusterOptions& o);

/// The same for one projection and linkage: defined in engine_clusterer.hpp,
/// explicitly instantiated in one translation unit per registered pair
/// (STREAMCLUST_INSTANTIATE_PYTHON_ENGINE).
template <class Projection, class Linkage>
std::unique_ptr<ErasedClusterer> make_for(const cli::ClusterOptions& o);

}  // namespace streamclust::python
