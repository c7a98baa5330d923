// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The objects engine of one linkage (cli/objects_engine.hpp): the
/// StreamClusterer of ObjectsEngineConfig<Linkage> with the preset's
/// parameters rebound (rebind_params), timed from outside, and the batch
/// clusterer that verifies it. Included only by the translation units that
/// instantiate it (STREAMCLUST_INSTANTIATE_OBJECTS_ENGINE).

#include "cli/objects_engine.hpp"

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/partition_compare.hpp>
#include <streamclust/rebind_params.hpp>
#include <streamclust/sensor_fit.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>

namespace streamclust::cli {
namespace detail {

/// ObjectsEngine over StreamClusterer<Config>: fed in stretches between
/// retrievals, the work between two take_cost() calls timed [ms]. A linkage
/// fitted to the sensor (sensor_fit.hpp) is fitted at the first feed, before
/// the engine is built, to the stream's first window T_B (sensor-frame
/// records) and the preset's mount and poses (untimed: the fit happens once,
/// before the stream); until then the engine counts as calibrating.
template <class Config>
class ObjectsEngineOf final : public ObjectsEngine {
  static_assert(std::is_same_v<typename Config::projection, SphericalProjection>,
                "STREAMCLUST_OBJECTS_PROJECTION: the objects engines are instantiated with the spherical projection's "
                "units; instantiate them with ObjectsConfig's projection");
  using Linkage = typename config_traits<Config>::linkage;

 public:
  using Clock = std::chrono::steady_clock;

  ObjectsEngineOf(const ClustererParams<Config>& params, bool verify) : params_(params), verify_(verify) {
    if constexpr (!has_sensor_fit_v<Linkage>) build(params_);
  }

  void feed(const std::vector<io::Record>& records, std::size_t first, std::size_t last) override {
    if (!engine_) build(fitted(records, first));
    const auto t0 = Clock::now();
    for (std::size_t i = first; i < last; ++i) engine_->insert(records[i], records[i].t);
    pending_ms_ += ms_since(t0);
  }
  const Clustering& retrieve(double time) override {
    if (!engine_) return empty_;
    const auto t0 = Clock::now();
    engine_->advance_to(time);
    const Clustering& result = engine_->retrieve();
    pending_ms_ += ms_since(t0);
    return result;
  }
  double take_cost() override {
    const double c = pending_ms_;
    pending_ms_ = 0.0;
    return c;
  }
  bool calibrating() const override { return !engine_ || engine_->calibrating(); }
  const std::vector<tracking::ObjectObservation>& boxes() override {
    if (!engine_) return no_boxes_;
    return boxes_.update(*engine_, engine_->last_result());
  }

  std::string verify(const std::vector<io::Record>& records, std::size_t outside) override {
    if (!verify_) throw std::logic_error("ObjectsEngine::verify: the engine was made without verify");
    if (!engine_) return "";
    const StreamClusterer<Config>& engine = *engine_;
    const Clustering& result = engine.last_result();
    if (outside != 0) return std::to_string(outside) + " labelled points outside the scored window";
    if (result.structure.size() != engine.structure_size()) return "the structure list and the structure ring differ";
    if (engine.calibrating()) return result.points.empty() ? "" : "labels while calibrating";
    if (result.points.size() != engine.size()) return "the result and the window differ in size";
    window_.clear();
    continuous_.clear();
    for (const PointLabel& p : result.points) {
      window_.push_back(records[static_cast<std::size_t>(p.stream_index)]);
      continuous_.push_back(p.label);
    }
    if (window_.empty()) return "";
    batch_->set_grid({engine.grid().rows, engine.grid().cols});
    const BatchResult& reference = batch_->cluster(window_);
    if (reference.rejections.rejected() != 0) return "the batch rejected a point the engine accepted";
    const auto m = first_partition_mismatch(continuous_, reference.labels);
    if (!m) return "";
    if (m->sizes_differ) return "the batch labelled a different number of points";
    return "window point " + std::to_string(m->position) + ": engine label " +
           std::to_string(continuous_[m->position]) + ", batch label " + std::to_string(reference.labels[m->position]);
  }

 private:
  static double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  }

  /// The engine (and, with verify, the batch clusterer) of `params`. Throws
  /// UsageError for parameters a policy rejects.
  void build(const ClustererParams<Config>& params) {
    try {
      engine_.emplace(params);
      if (verify_) batch_.emplace(params);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }

  /// The parameters with the linkage fitted to the records of the first
  /// window from `first` (sensor frame, T_B = the window's duration) and to
  /// the preset's mount and poses. O(window).
  ClustererParams<Config> fitted(const std::vector<io::Record>& records, std::size_t first) const {
    ClustererParams<Config> p = params_;
    if constexpr (has_sensor_fit_v<Linkage>) {
      SensorFit fit;
      fit.mount = p.motion.mount;
      fit.trajectory = p.motion.trajectory;
      const double t0 = first < records.size() ? records[first].t : 0.0;
      for (std::size_t i = first; i < records.size() && records[i].t - t0 < p.window.duration; ++i) {
        fit.first_window.emplace_back(records[i].x, records[i].y, records[i].z);
      }
      try {
        p.linkage = Linkage::fit_to_sensor(p.linkage, fit);
      } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("fitting the linkage to the first window: ") + e.what());
      }
    }
    return p;
  }

  ClustererParams<Config> params_;
  bool verify_;
  std::optional<StreamClusterer<Config>> engine_;
  std::optional<BatchClusterer<Config>> batch_;
  Clustering empty_;  ///< the result before the first feed
  tracking::ObjectBoxes boxes_;
  std::vector<tracking::ObjectObservation> no_boxes_;
  double pending_ms_ = 0.0;  ///< work since the last take_cost [ms]
  std::vector<io::Record> window_;       ///< verify's scratch: the window's records
  std::vector<ComponentId> continuous_;  ///< verify's scratch: the engine's labels
};

}  // namespace detail

template <class Linkage>
std::unique_ptr<ObjectsEngine> make_objects_engine_for(const ClustererParams<ObjectsConfig>& preset,
                                                       const typename Linkage::Params& linkage, bool verify) {
  using Config = ObjectsEngineConfig<Linkage>;
  return std::make_unique<detail::ObjectsEngineOf<Config>>(rebind_params<Config>(preset, linkage), verify);
}

}  // namespace streamclust::cli

/// The objects engine of `Linkage` (in the tool's generated translation unit
/// of the spherical projection and that linkage).
#define STREAMCLUST_INSTANTIATE_OBJECTS_ENGINE(Linkage)                                               \
  template std::unique_ptr<streamclust::cli::ObjectsEngine> streamclust::cli::make_objects_engine_for< \
      Linkage>(const streamclust::ClustererParams<streamclust::ObjectsConfig>&, const Linkage::Params&, bool)
