// SPDX-License-Identifier: MIT
// A fourth connectivity strategy written outside the library, in this one
// file, from the engine's parts: it stores the point edges (PointEdges) and
// recomputes the components by BFS at each retrieval. The engine takes it
// unchanged; the oracle holds, and its labels and ids equal the other
// rebuilding strategies' retrieval for retrieval (same votes, same numbering
// by oldest point).

#include <doctest/doctest.h>

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/engine/point_edges.hpp>
#include <streamclust/engine/rebuilt_components.hpp>
#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/streamclust.hpp>

#include "support/fixed_configs.hpp"
#include "support/oracle.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace sc = streamclust;

namespace {

/// Components by breadth-first search over the stored point edges.
struct BfsRebuildConnectivity {
  struct Params {};
  explicit BfsRebuildConnectivity(const Params&) {}
  static constexpr bool stores_point_edges = true;
  struct PointState {
    sc::ClusterId cluster = sc::kNoCluster;
    sc::EdgeLinks links;
  };

  template <class Ring>
  class State : public sc::ConnectivityStateDefaults, public sc::RebuiltComponents {
   public:
    explicit State(const BfsRebuildConnectivity&) {}

    template <class Ctx>
    void on_link(Ctx& ctx, sc::PointHandle h, const sc::PointHandle* nb, std::size_t count) {
      edges_.store(ctx.points, h, nb, count);
      mark_linked(ctx.points.record(h).state.cluster);
    }
    template <class Ctx>
    void on_evict(Ctx& ctx, sc::PointHandle h) {
      forget(ctx.points.record(h).state.cluster);
      edges_.release(ctx.points, h);
    }
    template <class Ctx>
    const sc::Clustering& retrieve(Ctx& ctx) {
      Search search{ctx.points, edges_, component_, queue_};
      return adopt_sets(ctx, search);
    }
    const sc::PointEdges& edges() const { return edges_; }
    void add_memory(sc::MemoryUsage& m) const { m.edge_storage += edges_.heap_bytes(); }

   private:
    /// The window union-find's interface (number_components, component) by BFS.
    struct Search {
      const Ring& ring;
      const sc::PointEdges& edges;
      std::vector<std::uint32_t>& numbers;
      std::vector<std::uint32_t>& queue;

      std::uint32_t number_components(std::uint32_t n) {
        constexpr std::uint32_t kUnseen = std::numeric_limits<std::uint32_t>::max();
        numbers.assign(n, kUnseen);
        std::uint32_t components = 0;
        const sc::PointHandle oldest = ring.oldest();
        for (std::uint32_t start = 0; start < n; ++start) {  // oldest first: numbered by oldest point
          if (numbers[start] != kUnseen) continue;
          numbers[start] = components;
          queue.assign(1, start);
          for (std::size_t q = 0; q < queue.size(); ++q) {
            edges.for_each_neighbor(ring, oldest + queue[q], [&](sc::PointHandle m) {
              const auto j = static_cast<std::uint32_t>(m - oldest);
              if (numbers[j] == kUnseen) {
                numbers[j] = components;
                queue.push_back(j);
              }
            });
          }
          ++components;
        }
        return components;
      }
      std::uint32_t component(std::uint32_t i) const { return numbers[i]; }
    };

    sc::PointEdges edges_;
    std::vector<std::uint32_t> component_;
    std::vector<std::uint32_t> queue_;
  };
};
static_assert(sc::is_connectivity_policy_v<BfsRebuildConnectivity>);

struct BfsConfig : sc::CArcFixedConfig {
  using connectivity = BfsRebuildConnectivity;
};
using streamclust::test::ForestConfig;

template <class Config>
sc::ClustererParams<Config> short_window() {
  sc::ClustererParams<Config> params;
  params.resolution = {32, 256};
  params.window.duration = 0.01;  // 2,000 points at 200 kHz
  params.linkage.theta_deg = 30.0f;
  return params;
}

}  // namespace

TEST_CASE("a strategy written in one file: the oracle holds and the labels equal the spanning forest's") {
  const auto params = short_window<BfsConfig>();
  sc::StreamClusterer<BfsConfig> engine(params);
  sc::BatchClusterer<BfsConfig> batch(params);
  sc::StreamClusterer<ForestConfig> forest(short_window<ForestConfig>());
  sc::SyntheticStream stream;
  int retrievals = 0;
  std::size_t components = 0;
  for (int i = 1; i <= 40000; ++i) {
    const auto p = stream.next();
    const double t = i / 200000.0;
    engine.insert(p, t);
    forest.insert(p, t);
    if (i % 1999 == 0) {
      const sc::Clustering& mine = engine.retrieve();
      const sc::Clustering& theirs = forest.retrieve();
      ++retrievals;
      INFO("after point " << i);
      REQUIRE(sc::test::compare_with_batch(engine, batch) == "");
      REQUIRE(mine.points.size() == theirs.points.size());
      for (std::size_t k = 0; k < mine.points.size(); ++k) {
        REQUIRE(mine.points[k].stream_index == theirs.points[k].stream_index);
        REQUIRE(mine.points[k].label == theirs.points[k].label);
      }
      components += mine.components.size();
    }
  }
  CHECK(retrievals == 20);
  CHECK(components > 20);  // more than one component per window: the test can tell partitions apart
}
