// SPDX-License-Identifier: MIT
// The engine's exact-size point rings: a ring origin that advances by the
// capacity as evictions pass it, growth while the ring has wrapped, and a
// window whose size rises and falls across growths; checked against the
// batch oracle and against the ring's size bound.

#include <doctest/doctest.h>

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/streamclust.hpp>

#include "support/oracle.hpp"

#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

namespace sc = streamclust;

namespace {

struct ForestFixedConfig : sc::CArcFixedConfig {
  using connectivity = sc::SpanningForestConnectivity;
};
struct CappedForestFixedConfig : ForestFixedConfig {
  using spatial_index = sc::CappedGrid;
};
struct RebuildFixedConfig : sc::CArcFixedConfig {
  using connectivity = sc::UnionFindRebuildConnectivity;
};

/// One phase of the stream: `points` points, `rate` points per second.
struct Phase {
  std::size_t points;
  double rate;
};

}  // namespace

TEST_CASE_TEMPLATE("point rings: origin wraps and growth under a changing window agree with the batch oracle", Config,
                   sc::CArcFixedConfig, ForestFixedConfig, CappedForestFixedConfig, RebuildFixedConfig) {
  sc::ClustererParams<Config> params;
  params.resolution = {32, 256};
  params.window.duration = 0.01;  // 10 ms: 2,000 points at 200 kHz
  params.linkage.theta_deg = 30.0f;
  if constexpr (std::is_same_v<typename sc::config_traits<Config>::connectivity, sc::SpanningForestConnectivity>) {
    params.connectivity.min_fold_edges = 500;  // folds between retrievals too
  }
  sc::StreamClusterer<Config> engine(params);
  sc::BatchClusterer<Config> batch(params);
  sc::SyntheticStream stream;
  // Window of about 2,000 points (the ring grows past its first 1,024 slots
  // with nothing evicted), then 6,000 (it grows again after the origin has
  // advanced: live points straddle the ring's end), then 700 (it shrinks;
  // the origin passes the end many times), then 3,000.
  const Phase phases[] = {{30000, 200000.0}, {40000, 600000.0}, {30000, 70000.0}, {30000, 300000.0}};
  double t = 0.0;
  std::size_t inserted = 0;
  std::size_t peak = 0;
  int retrievals = 0;
  for (const Phase& phase : phases) {
    for (std::size_t i = 0; i < phase.points; ++i) {
      t += 1.0 / phase.rate;
      engine.insert(stream.next(), t);
      ++inserted;
      if (engine.size() > peak) peak = engine.size();
      if (inserted % 1733 == 0) {
        engine.retrieve();
        ++retrievals;
        const std::string mismatch = sc::test::compare_with_batch(engine, batch);
        INFO("after point " << inserted << ", window " << engine.size());
        REQUIRE(mismatch == "");
      }
    }
  }
  CHECK(retrievals > 60);
  CHECK(peak > 5000);
  CHECK(engine.size() < 4000);  // the window shrank after its peak
  // The ring: at most peak + peak / 8 slots (the growth rule), so below the
  // 8,192 slots of a power-of-two ring for a peak between 4,097 and 7,281.
  // Bytes per slot: an engine with one point holds the smallest ring, 1,024 slots.
  sc::StreamClusterer<Config> one(params);
  one.insert(stream.next(), t);
  const std::size_t first_ring = one.memory_usage().point_ring;
  REQUIRE(first_ring % 1024 == 0);
  const std::size_t slot_bytes = first_ring / 1024;
  const std::size_t slots = engine.memory_usage().point_ring / slot_bytes;
  INFO("peak window " << peak << ", ring slots " << slots);
  CHECK(slots >= peak);
  CHECK(slots <= peak + peak / 8);
  CHECK(slots < 8192);
}
