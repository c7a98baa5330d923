// SPDX-License-Identifier: MIT
// The connectivity slot: the concept, the default, and the union-find rebuild
// strategy on hand-made streams (splits, stable ids, local clusters) and
// against the paper's lazy BFS on a long synthetic stream.

#include <doctest/doctest.h>

#include <streamclust/concepts/connectivity.hpp>
#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/streamclust.hpp>

#include "support/partition.hpp"

#include <set>
#include <string>
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

struct MissingStrategy {
  struct Params {};
  explicit MissingStrategy(const Params&) {}
};
struct WrongStrategyType {
  struct Params {};
  explicit WrongStrategyType(const Params&) {}
  static constexpr int strategy = 1;
};

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

template <class Engine>
std::vector<sc::ComponentId> labels(const Engine& e) {
  std::vector<sc::ComponentId> out;
  for (const auto& p : e.last_result().points) out.push_back(p.label);
  return out;
}

using Rebuild = ChainConfig<sc::UnionFindRebuildConnectivity>;
using Lazy = ChainConfig<sc::LazyBfsConnectivity>;

}  // namespace

TEST_CASE("connectivity concept: both policies model it, incomplete types do not, the default is the paper's") {
  CHECK(sc::is_connectivity_policy_v<sc::LazyBfsConnectivity>);
  CHECK(sc::is_connectivity_policy_v<sc::UnionFindRebuildConnectivity>);
  CHECK_FALSE(sc::is_connectivity_policy_v<MissingStrategy>);
  CHECK_FALSE(sc::is_connectivity_policy_v<WrongStrategyType>);
  CHECK_FALSE(sc::is_connectivity_policy_v<int>);
  CHECK(sc::config_traits<NoSlotConfig>::connectivity::strategy == sc::ConnectivityStrategy::lazy_bfs);
  CHECK(sc::config_traits<Rebuild>::connectivity::strategy == sc::ConnectivityStrategy::union_find_rebuild);
  CHECK_FALSE(sc::StreamClusterer<NoSlotConfig>::rebuilds_components);
  CHECK(sc::StreamClusterer<Rebuild>::rebuilds_components);
  CHECK(sc::StreamClusterer<sc::CArcFastConfig>::rebuilds_components);
  CHECK_FALSE(sc::StreamClusterer<sc::CArcConfig>::rebuilds_components);
}

TEST_CASE("union-find rebuild: the middle of a chain leaving splits it; the larger part keeps the id") {
  sc::StreamClusterer<Rebuild> engine(chain_params<Rebuild>(1.0));
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

TEST_CASE("union-find rebuild: local clusters are the last retrieval's components, without bridges") {
  sc::StreamClusterer<Rebuild> engine(chain_params<Rebuild>(10.0));
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

TEST_CASE("union-find rebuild: ids persist, merge to the heavier side and are never reused") {
  sc::StreamClusterer<Rebuild> engine(chain_params<Rebuild>(100.0));
  engine.insert(at(10.0f, 0.0));
  engine.insert(at(10.5f, 0.1));
  engine.insert(at(10.9f, 0.2));
  engine.insert(at(13.0f, 0.3));
  engine.retrieve();
  const auto first = labels(engine);
  REQUIRE(first.size() == 4);
  const sc::ComponentId big = first[0];
  const sc::ComponentId small = first[3];
  CHECK(big != small);
  engine.insert(at(15.0f, 0.4));  // alone
  engine.retrieve();
  auto now = labels(engine);
  CHECK(now[0] == big);
  CHECK(now[3] == small);
  const sc::ComponentId fresh = now[4];
  CHECK(fresh != big);
  CHECK(fresh != small);
  engine.insert(at(11.8f, 0.5));  // 0.9 m from the big part's end: joins it
  engine.insert(at(12.5f, 0.6));  // 1.8 -> 2.5 and 2.5 -> 3.0: merges big and small
  engine.retrieve();
  now = labels(engine);
  CHECK(now[0] == big);  // the heavier id wins the merge
  CHECK(now[3] == big);
  CHECK(now[4] == fresh);
  std::set<sc::ComponentId> seen(now.begin(), now.end());
  CHECK(seen.count(small) == 0);  // the lighter id is retired, never handed out again
}

TEST_CASE("union-find rebuild and lazy BFS give the same partition, every retrieval, on a long stream") {
  using LazyPreset = sc::CArcFixedConfig;
  struct FastFixed : sc::CArcFixedConfig {
    using connectivity = sc::UnionFindRebuildConnectivity;
  };
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
      REQUIRE(sc::test::partition_mismatch(labels(lazy), labels(fast)) == "");
      CHECK(lazy.last_result().components.size() == fast.last_result().components.size());
    }
  }
  CHECK(retrievals == 24);
  CHECK(split_work > 0);  // the stream exercised splits, not just growth
}
