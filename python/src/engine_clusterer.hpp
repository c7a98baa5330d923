// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// EngineClusterer<Config>: the one implementation of ErasedClusterer, a
/// StreamClusterer of the compiled configuration `Config`, and
/// `make_for<Projection, Linkage>`, which picks Config from the options with
/// the CLI's `with_engine_config`. Included only by the translation units
/// that instantiate it (erased_clusterer_*.cpp).

#include "erased_clusterer.hpp"

#include "cli/engine_config.hpp"

#include <streamclust/stream_clusterer.hpp>

#include <memory>
#include <stdexcept>

namespace streamclust::python {

template <class Config>
class EngineClusterer final : public ErasedClusterer {
 public:
  explicit EngineClusterer(const ClustererParams<Config>& params) : engine_(params) {}

  std::size_t insert(const PointBuffers& points, RejectReason* reasons) override {
    const ArrayPointIterator first(&points, 0), last(&points, points.size);
    RejectReason* const end = engine_.insert_batch(first, last, reasons);
    std::size_t accepted = 0;
    for (const RejectReason* r = reasons; r != end; ++r) accepted += *r == RejectReason::accepted;
    return accepted;
  }
  void advance_to(double time) override { engine_.advance_to(time); }
  bool calibrating() const override { return engine_.calibrating(); }
  void complete_calibration() override { engine_.complete_calibration(); }
  const Clustering& retrieve() override { return engine_.retrieve(); }
  std::uint64_t offered() const override { return engine_.offered(); }
  std::size_t size() const override { return engine_.size(); }
  GridShape grid() const override { return engine_.grid(); }

 private:
  StreamClusterer<Config> engine_;
};

/// The engine of `o` for one projection and linkage (index, window and
/// connectivity from `o`, as the CLI picks them). Policy parameter errors
/// become cli::UsageError.
template <class Projection, class Linkage>
std::unique_ptr<ErasedClusterer> make_for(const cli::ClusterOptions& o) {
  return cli::with_engine_config<false, Projection, Linkage>(o, [&](auto config) -> std::unique_ptr<ErasedClusterer> {
    using Config = typename decltype(config)::type;
    try {
      return std::make_unique<EngineClusterer<Config>>(cli::make_params<Config>(o));
    } catch (const std::invalid_argument& e) {
      throw cli::UsageError(e.what());
    }
  });
}

}  // namespace streamclust::python
