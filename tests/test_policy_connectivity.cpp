// SPDX-License-Identifier: MIT
// The connectivity slot: the concept, the default, and the union-find rebuild
// and spanning-forest strategies on hand-made streams (splits, stable ids,
// local clusters, expiring bridges, long chains, folds without retrieval) and
// against the paper's lazy BFS on a long synthetic stream.

#include <doctest/doctest.h>

#include <streamclust/concepts/connectivity.hpp>
#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/streamclust.hpp>

#include "support/last_labels.hpp"
#include "support/partition.hpp"
#include "support/points.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace sc = streamclust;

namespace {

template <class Connectivity>
struct ChainConfig {
  using projection = sc::SphericalProjection;
  using spatial_index = sc::BucketGrid;
  using linkage = sc::EuclideanLinkage;
  using window = sc::TimeWindow;
  using resolution = sc::FixedResolution;
  using connectivity = Connectivity;
};
struct NoSlotConfig {
  using projection = sc::SphericalProjection;
  using spatial_index = sc::BucketGrid;
  using linkage = sc::EuclideanLinkage;
  using window = sc::TimeWindow;
  using resolution = sc::FixedResolution;
};

struct MissingStrategy {  // no PointState, no stores_point_edges, no State
  struct Params {};
  explicit MissingStrategy(const Params&) {}
};
struct WrongStrategyType {  // stores_point_edges of the wrong type
  struct Params {};
  explicit WrongStrategyType(const Params&) {}
  struct PointState {};
  static constexpr int stores_point_edges = 1;
};

/// The connectivity policy of a configuration.
template <class Config>
using connectivity_of = typename sc::config_traits<Config>::connectivity;
template <class Config, class Policy>
constexpr bool uses = std::is_same_v<connectivity_of<Config>, Policy>;

template <class Config>
sc::ClustererParams<Config> chain_params(double window) {
  sc::ClustererParams<Config> p;
  p.resolution = {1, 1};  // one cell: the Euclidean linkage alone decides
  p.linkage.max_distance = 1.0f;
  p.window.duration = window;
  p.mask_size = 1;
  return p;
}

sc::Point at(float x, double t) { return sc::Point{x, 0.0f, 0.0f, 0.0f, t}; }

using streamclust::test::last_labels;

using Rebuild = ChainConfig<sc::UnionFindRebuildConnectivity>;
using Forest = ChainConfig<sc::SpanningForestConnectivity>;
using Lazy = ChainConfig<sc::LazyBfsConnectivity>;

using streamclust::test::at;

/// Sizes of the last retrieval's components, ascending.
template <class Engine>
std::vector<std::size_t> component_sizes(const Engine& e) {
  std::vector<std::size_t> out;
  for (const auto& c : e.last_result().components) out.push_back(c.size);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("connectivity concept: both policies model it, incomplete types do not, the default is the paper's") {
  CHECK(sc::is_connectivity_policy_v<sc::LazyBfsConnectivity>);
  CHECK(sc::is_connectivity_policy_v<sc::UnionFindRebuildConnectivity>);
  CHECK(sc::is_connectivity_policy_v<sc::SpanningForestConnectivity>);
  CHECK_FALSE(sc::is_connectivity_policy_v<MissingStrategy>);
  CHECK_FALSE(sc::is_connectivity_policy_v<WrongStrategyType>);
  CHECK_FALSE(sc::is_connectivity_policy_v<int>);
  CHECK(uses<NoSlotConfig, sc::LazyBfsConnectivity>);
  CHECK(uses<Rebuild, sc::UnionFindRebuildConnectivity>);
  CHECK(uses<Forest, sc::SpanningForestConnectivity>);
  CHECK(uses<sc::CArcConfig, sc::LazyBfsConnectivity>);
  CHECK(uses<sc::CArcFastConfig, sc::SpanningForestConnectivity>);
  CHECK(uses<sc::CArcCappedFastConfig, sc::SpanningForestConnectivity>);
  CHECK(uses<sc::CArcRebuildConfig, sc::UnionFindRebuildConnectivity>);
  CHECK_FALSE(sc::StreamClusterer<Forest>::stores_point_edges);
  CHECK(sc::StreamClusterer<Rebuild>::stores_point_edges);
  CHECK(sc::StreamClusterer<Lazy>::stores_point_edges);
}

TEST_CASE("spanning forest: min_fold_edges is validated") {
  using SF = sc::SpanningForestConnectivity;
  const auto make = [](std::uint32_t min_edges, std::uint32_t per_point) {
    return SF{SF::Params{min_edges, per_point}};
  };
  CHECK(SF{SF::Params{}}.fold_threshold(10) == 65536);
  CHECK(SF{SF::Params{}}.fold_threshold(100000) == 200000);
  CHECK(make(1, 1).fold_threshold(7) == 7);
  CHECK(make(SF::kMaxFoldEdges, 64).fold_threshold(1) == SF::kMaxFoldEdges);
  CHECK_THROWS_AS(make(0, 2), std::invalid_argument);
  CHECK_THROWS_AS(make(SF::kMaxFoldEdges + 1, 2), std::invalid_argument);
  CHECK_THROWS_AS(make(1, 0), std::invalid_argument);
  CHECK_THROWS_AS(make(1, 65), std::invalid_argument);
  auto params = chain_params<Forest>(1.0);
  params.connectivity.min_fold_edges = 0;
  CHECK_THROWS_WITH_AS(sc::StreamClusterer<Forest>{params}, doctest::Contains("min_fold_edges = 0"),
                       std::invalid_argument);
}

TEST_CASE_TEMPLATE("rebuild and forest: the middle of a chain leaving splits it; the larger part keeps the id", Config,
                   Rebuild, Forest) {
  sc::StreamClusterer<Config> engine(chain_params<Config>(1.0));
  engine.insert(at(5.0f, 0.0));  // middle of the chain, leaves first
  engine.insert(at(4.2f, 0.5));
  engine.insert(at(3.4f, 0.5));
  engine.insert(at(2.6f, 0.5));
  engine.insert(at(5.8f, 0.5));
  engine.insert(at(6.6f, 0.5));
  const auto& before = engine.retrieve();
  REQUIRE(before.components.size() == 1);
  const sc::ComponentId id = before.components[0].id;
  CHECK(engine.last_stats().points_validated == 6);

  engine.advance_to(1.01);
  const auto& after = engine.retrieve();
  REQUIRE(after.components.size() == 2);
  // Left part: 3 points (keeps the id), right part: 2 points (fresh id).
  for (const auto& c : after.components) {
    if (c.size == 3) CHECK(c.id == id);
    if (c.size == 2) CHECK(c.id > id);
  }
  CHECK(engine.last_stats().evicted == 1);
}

TEST_CASE_TEMPLATE("rebuild and forest: local clusters are the last retrieval's components, without bridges", Config,
                   Rebuild, Forest) {
  sc::StreamClusterer<Config> engine(chain_params<Config>(10.0));
  engine.insert(at(1.0f, 0.0));
  engine.insert(at(1.5f, 0.1));
  engine.insert(at(8.0f, 0.2));
  CHECK(engine.cluster_of(engine.handle_at(0)) == sc::kNoCluster);  // not labelled yet
  engine.retrieve();
  REQUIRE(engine.cluster_count() == 2);
  const sc::ClusterId a = engine.cluster_of(engine.handle_at(0));
  CHECK(engine.cluster_of(engine.handle_at(1)) == a);
  const sc::ClusterId b = engine.cluster_of(engine.handle_at(2));
  CHECK(a != b);
  CHECK(engine.cluster_size(a) == 2);
  CHECK(engine.cluster_size(b) == 1);
  CHECK(engine.bridges(a).empty());
  CHECK_FALSE(engine.cluster_pending(a));
  engine.insert(at(2.0f, 0.3));  // joins a, labelled at the next retrieval
  CHECK(engine.cluster_of(engine.handle_at(3)) == sc::kNoCluster);
  engine.retrieve();
  CHECK(engine.cluster_of(engine.handle_at(3)) == engine.cluster_of(engine.handle_at(0)));
  CHECK(engine.cluster_size(engine.cluster_of(engine.handle_at(0))) == 3);
}

TEST_CASE_TEMPLATE("rebuild and forest: ids persist, merge to the heavier side and are never reused", Config, Rebuild,
                   Forest) {
  sc::StreamClusterer<Config> engine(chain_params<Config>(100.0));
  engine.insert(at(10.0f, 0.0));
  engine.insert(at(10.5f, 0.1));
  engine.insert(at(10.9f, 0.2));
  engine.insert(at(13.0f, 0.3));
  engine.retrieve();
  const auto first = last_labels(engine);
  REQUIRE(first.size() == 4);
  const sc::ComponentId big = first[0];
  const sc::ComponentId small = first[3];
  CHECK(big != small);
  engine.insert(at(15.0f, 0.4));  // alone
  engine.retrieve();
  auto now = last_labels(engine);
  CHECK(now[0] == big);
  CHECK(now[3] == small);
  const sc::ComponentId fresh = now[4];
  CHECK(fresh != big);
  CHECK(fresh != small);
  engine.insert(at(11.8f, 0.5));  // 0.9 m from the big part's end: joins it
  engine.insert(at(12.5f, 0.6));  // 1.8 -> 2.5 and 2.5 -> 3.0: merges big and small
  engine.retrieve();
  now = last_labels(engine);
  CHECK(now[0] == big);  // the heavier id wins the merge
  CHECK(now[3] == big);
  CHECK(now[4] == fresh);
  std::set<sc::ComponentId> seen(now.begin(), now.end());
  CHECK(seen.count(small) == 0);  // the lighter id is retired, never handed out again
}

namespace {
template <class Connectivity>
struct FixedWith : sc::CArcFixedConfig {
  using connectivity = Connectivity;
};
}  // namespace

TEST_CASE_TEMPLATE("rebuild, forest and lazy BFS give the same partition, every retrieval, on a long stream", FastFixed,
                   FixedWith<sc::UnionFindRebuildConnectivity>, FixedWith<sc::SpanningForestConnectivity>) {
  using LazyPreset = sc::CArcFixedConfig;
  sc::ClustererParams<LazyPreset> lp;
  lp.resolution = {32, 256};
  lp.window.duration = 0.05;
  lp.linkage.theta_deg = 30.0f;
  sc::ClustererParams<FastFixed> fp;
  fp.resolution = lp.resolution;
  fp.window.duration = lp.window.duration;
  fp.linkage.theta_deg = lp.linkage.theta_deg;
  sc::StreamClusterer<LazyPreset> lazy(lp);
  sc::StreamClusterer<FastFixed> fast(fp);
  sc::SyntheticStream stream;
  int retrievals = 0;
  std::uint64_t split_work = 0;
  for (int i = 0; i < 60000; ++i) {
    const auto p = stream.next();
    lazy.insert(p);
    fast.insert(p);
    if (i % 2500 == 2499) {
      lazy.retrieve();
      fast.retrieve();
      ++retrievals;
      split_work += lazy.last_stats().clusters_split;
      INFO("retrieval " << retrievals);
      REQUIRE(sc::test::partition_mismatch(last_labels(lazy), last_labels(fast)) == "");
      CHECK(lazy.last_result().components.size() == fast.last_result().components.size());
    }
  }
  CHECK(retrievals == 24);
  CHECK(split_work > 0);  // the stream exercised splits, not just growth
}

// ------------------------------------------------ spanning forest edge cases

TEST_CASE_TEMPLATE("an old bridge expires while a younger path keeps the component connected", Config, Lazy, Rebuild,
                   Forest) {
  // a-b, a-c and b-c all link (0.90 m, 0.92 m, 0.92 m). The forest must keep
  // the younger edge b-c (it expires with b) over a second edge to a (which
  // expires with a): a forest of the two edges to a would fall apart when a
  // leaves.
  sc::StreamClusterer<Config> engine(chain_params<Config>(1.0));
  engine.insert(at(5.0f, 0.0f, 0.0));   // a
  engine.insert(at(5.9f, 0.0f, 0.5));   // b
  engine.insert(at(5.45f, 0.8f, 0.6));  // c
  engine.retrieve();
  REQUIRE(component_sizes(engine) == std::vector<std::size_t>{3});
  const sc::ComponentId id = engine.last_result().components[0].id;
  engine.advance_to(1.2);  // a leaves
  engine.retrieve();
  REQUIRE(component_sizes(engine) == std::vector<std::size_t>{2});
  CHECK(engine.last_result().components[0].id == id);
  engine.advance_to(1.55);  // b leaves: c alone, keeps the id (largest part)
  engine.retrieve();
  REQUIRE(component_sizes(engine) == std::vector<std::size_t>{1});
  CHECK(engine.last_result().components[0].id == id);
}

TEST_CASE_TEMPLATE("a ladder whose old rungs expire stays connected through its younger rungs", Config, Lazy, Rebuild,
                   Forest) {
  // Two rails 0.8 m apart (y = 0 and y = 0.8), points 0.9 m apart along x > 0,
  // inserted rail 0 first, then rail 1 from the other end: each rail is a
  // path, every rung (same x) links them. Old rungs leave with rail 0's
  // points; as long as one rung is live the ladder is one component.
  auto params = chain_params<Config>(1.0);
  sc::StreamClusterer<Config> engine(params);
  const int n = 12;
  double t = 0.0;
  for (int i = 0; i < n; ++i, t += 0.01) engine.insert(at(2.0f + 0.9f * static_cast<float>(i), 0.0f, t));
  for (int i = n - 1; i >= 0; --i, t += 0.01) engine.insert(at(2.0f + 0.9f * static_cast<float>(i), 0.8f, t));
  engine.retrieve();
  REQUIRE(component_sizes(engine) == std::vector<std::size_t>{2 * n});
  // Rail 0 leaves point by point (its point i at t = 0.01 i); the rung of
  // rail 0's newest live point always holds the ladder together.
  for (int gone = 1; gone < n; ++gone) {
    engine.advance_to(1.0 + 0.01 * gone - 0.005);
    engine.retrieve();
    INFO("rail-0 points evicted: " << gone);
    REQUIRE(engine.size() == static_cast<std::size_t>(2 * n - gone));
    CHECK(component_sizes(engine) == std::vector<std::size_t>{static_cast<std::size_t>(2 * n - gone)});
  }
}

TEST_CASE_TEMPLATE("a long chain evicted from its old end stays one component, with and without retrievals between",
                   Config, Lazy, Rebuild, Forest) {
  // A path (points 0.6 m apart, linkage 1.0 m: each links its predecessor
  // only) 2,000 points long through a window of 50 points.
  auto params = chain_params<Config>(0.495);
  if constexpr ((uses<Config, sc::SpanningForestConnectivity>)) params.connectivity = {1, 1};
  for (const int every : {1, 7, 1000000}) {
    sc::StreamClusterer<Config> engine(params);
    std::uint64_t folds = 0;
    for (int i = 0; i < 2000; ++i) {
      engine.insert(at(2.0f + 0.6f * static_cast<float>(i % 1000), 0.0f, 0.01 * i));  // restarts at x = 2 after 1,000
      if (i % every == every - 1 || i == 1999) {
        engine.retrieve();
        folds += engine.last_stats().forest_folds;
        INFO("every " << every << ", point " << i);
        const auto window = static_cast<std::size_t>(std::min(i + 1, 50));
        REQUIRE(engine.size() == window);
        if (i >= 1000 && i % 1000 < 49) {  // the restart cut the chain in two
          CHECK(component_sizes(engine).size() == 2);
        } else {
          CHECK(component_sizes(engine) == std::vector<std::size_t>{window});
        }
      }
    }
    if constexpr ((uses<Config, sc::SpanningForestConnectivity>)) {
      if (every == 1000000) CHECK(folds > 30);  // about one fold per 51 edges without labelling
    }
  }
}

TEST_CASE("spanning forest: folds without retrieval bound the new edges and keep labels identical to the rebuild's") {
  // Same stream, same retrievals: the partition is the same, and since both
  // use the same per-point vote rule, so are the stable ids, label for label.
  struct ForestFixed : sc::CArcFixedConfig {
    using connectivity = sc::SpanningForestConnectivity;
  };
  struct RebuildFixed : sc::CArcFixedConfig {
    using connectivity = sc::UnionFindRebuildConnectivity;
  };
  sc::ClustererParams<ForestFixed> fp;
  fp.resolution = {32, 256};
  fp.window.duration = 0.02;
  fp.linkage.theta_deg = 30.0f;
  fp.connectivity = {1, 1};  // fold whenever the new edges outnumber the window's points
  sc::ClustererParams<RebuildFixed> rp;
  rp.resolution = fp.resolution;
  rp.window.duration = fp.window.duration;
  rp.linkage.theta_deg = fp.linkage.theta_deg;
  sc::StreamClusterer<ForestFixed> forest(fp);
  sc::StreamClusterer<RebuildFixed> rebuild(rp);
  sc::SyntheticStream stream;
  std::uint64_t folds = 0;
  std::size_t components = 0;
  for (int i = 0; i < 40000; ++i) {
    const auto p = stream.next();
    forest.insert(p);
    rebuild.insert(p);
    if (i % 3001 == 3000) {
      forest.retrieve();
      rebuild.retrieve();
      folds += forest.last_stats().forest_folds;
      components += forest.last_result().components.size();
      INFO("point " << i);
      REQUIRE(last_labels(forest) == last_labels(rebuild));
      CHECK(forest.last_result().components.size() == rebuild.last_result().components.size());
    }
  }
  CHECK(folds > 13);  // more than one fold per retrieval
  CHECK(components > 13);  // not a single blob every time
}
