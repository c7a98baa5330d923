// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The implementations of ErasedClusterer: EngineClusterer<Config>, a
/// StreamClusterer of the compiled configuration `Config` (continuous mode),
/// and FrameEngineClusterer<Config>, a FrameClusterer (frame mode: the
/// `baseline` preset), and `make_for<Projection, Linkage>`, which picks
/// Config from the options with the CLI's `with_engine_config`. Included
/// only by the translation units that instantiate them
/// (erased_clusterer_*.cpp).

#include "erased_clusterer.hpp"

#include "cli/engine_config.hpp"

#include <streamclust/frame_clusterer.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <algorithm>
#include <memory>
#include <stdexcept>

namespace streamclust::python {

template <class Config>
class EngineClusterer;
template <class Config>
class FrameEngineClusterer;

/// The implementation of a mode, as a type for generic lambdas.
struct StreamEngineTag {
  template <class Config>
  using engine = EngineClusterer<Config>;
};
struct FrameEngineTag {
  template <class Config>
  using engine = FrameEngineClusterer<Config>;
};

/// What both modes forward to their engine alike.
template <class Engine>
class ForwardingClusterer : public ErasedClusterer {
 public:
  template <class Params>
  explicit ForwardingClusterer(const Params& params) : engine_(params) {}

  std::size_t insert(const PointBuffers& points, RejectReason* reasons) override {
    const ArrayPointIterator first(&points, 0), last(&points, points.size);
    RejectReason* const end = engine_.insert_batch(first, last, reasons);
    return static_cast<std::size_t>(std::count(reasons, end, RejectReason::accepted));
  }
  void advance_to(double time) override { engine_.advance_to(time); }
  bool calibrating() const override { return engine_.calibrating(); }
  void complete_calibration() override { engine_.complete_calibration(); }
  std::uint64_t offered() const override { return engine_.offered(); }
  std::size_t size() const override { return engine_.size(); }
  GridShape grid() const override { return engine_.grid(); }

 protected:
  Engine engine_;
};

template <class Config>
class EngineClusterer final : public ForwardingClusterer<StreamClusterer<Config>> {
 public:
  using ForwardingClusterer<StreamClusterer<Config>>::ForwardingClusterer;
  const Clustering& retrieve() override { return this->engine_.retrieve(); }
};

/// A FrameClusterer (each retrieval re-clusters the window from scratch,
/// the paper's baseline) seen as the continuous engine: its labels become
/// a Clustering, with a summary per component computed here. Component ids
/// are the frame's numbering (0, 1, ... by first appearance): not stable
/// across retrievals, as in the CLI's frame mode.
template <class Config>
class FrameEngineClusterer final : public ForwardingClusterer<FrameClusterer<Config>> {
 public:
  using ForwardingClusterer<FrameClusterer<Config>>::ForwardingClusterer;

  /// The frame's labels in window order (as the CLI's frame mode writes
  /// them) and the components' summaries. O(window) beyond the batch run.
  const Clustering& retrieve() override {
    const BatchResult& frame = this->engine_.retrieve();
    result_.points.clear();
    result_.components.assign(frame.components, ComponentSummary{});
    result_.structure.clear();
    std::size_t i = 0;
    this->engine_.for_each_point([&](const Sample& s, std::uint64_t stream_index) {
      const std::int64_t label = i < frame.labels.size() ? frame.labels[i] : -1;
      ++i;
      result_.points.push_back(PointLabel{stream_index, label < 0 ? kNoComponent : static_cast<ComponentId>(label)});
      result_.time = s.time;
      if (label < 0 || static_cast<std::size_t>(label) >= result_.components.size()) return;
      ComponentSummary& c = result_.components[static_cast<std::size_t>(label)];
      if (c.size == 0) {
        c.id = static_cast<ComponentId>(label);
        c.min = c.max = s.position;
        c.time_begin = s.time;
      }
      ++c.size;
      c.centroid += s.position;  // the sum until the division below
      c.min = c.min.cwiseMin(s.position);
      c.max = c.max.cwiseMax(s.position);
      c.time_end = s.time;
    });
    for (ComponentSummary& c : result_.components) {
      if (c.size > 0) c.centroid /= static_cast<float>(c.size);
    }
    ++result_.cycle;
    return result_;
  }

 private:
  Clustering result_;
};

/// The engine of `o` for one projection and linkage (mode, index, window
/// and connectivity from `o`, as the CLI picks them). Policy parameter
/// errors become cli::UsageError.
template <class Projection, class Linkage>
std::unique_ptr<ErasedClusterer> make_for(const cli::ClusterOptions& o) {
  const auto make = [&](auto engine_tag, auto config) -> std::unique_ptr<ErasedClusterer> {
    using Config = typename decltype(config)::type;
    using Engine = typename decltype(engine_tag)::template engine<Config>;
    try {
      return std::make_unique<Engine>(cli::make_params<Config>(o));
    } catch (const std::invalid_argument& e) {
      throw cli::UsageError(e.what());
    }
  };
  if (o.mode == cli::Mode::frame) {
    return cli::with_engine_config<true, Projection, Linkage>(
        o, [&](auto config) { return make(FrameEngineTag{}, config); });
  }
  return cli::with_engine_config<false, Projection, Linkage>(
      o, [&](auto config) { return make(StreamEngineTag{}, config); });
}

}  // namespace streamclust::python

/// The translation unit of the module's engines for one projection and
/// linkage (every index, window, mode and connectivity of the registry).
#define STREAMCLUST_INSTANTIATE_PYTHON_ENGINE(Projection, Linkage) \
  template std::unique_ptr<streamclust::python::ErasedClusterer>   \
  streamclust::python::make_for<Projection, Linkage>(const streamclust::cli::ClusterOptions&)
