// SPDX-License-Identifier: MIT
// The result of a retrieval, for every connectivity strategy, on fragmented
// windows (many small components, so each retrieval keeps many ids and hands
// out many fresh ones): `components` strictly sorted by id, one summary per
// label, every summary equal to the one recomputed from the window (size,
// box, time span, centroid from a double sum in window order), and ids never
// reused: an id absent from the previous result exceeds every id seen before.

#include <doctest/doctest.h>

#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/streamclust.hpp>

#include "support/fixed_configs.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <set>
#include <vector>

namespace sc = streamclust;

namespace {

struct ExpectedSummary {
  std::size_t size = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Vector3f min, max;
  double time_begin = 0.0, time_end = 0.0;
};

struct Tally {
  int retrievals = 0;
  std::size_t kept = 0;       // ids also in the previous result
  std::size_t fresh = 0;      // ids new in this result
  int mixed = 0;              // retrievals with at least 10 kept and 10 fresh ids
  std::size_t max_components = 0;
};

template <class Engine>
void check_result(const Engine& engine, const sc::Clustering& result, std::set<sc::ComponentId>& previous,
                  sc::ComponentId& max_seen, bool& any_seen, Tally& tally) {
  // Sorted strictly by id.
  for (std::size_t k = 1; k < result.components.size(); ++k) {
    REQUIRE(result.components[k - 1].id < result.components[k].id);
  }
  // The summaries, recomputed from the window in window order.
  REQUIRE(result.points.size() == engine.size());
  std::map<sc::ComponentId, ExpectedSummary> expected;
  std::size_t i = 0;
  engine.for_each_point([&](const sc::Sample& s, std::uint64_t stream_index) {
    REQUIRE(i < result.points.size());
    REQUIRE(result.points[i].stream_index == stream_index);
    ExpectedSummary& e = expected[result.points[i].label];
    if (e.size == 0) {
      e.min = e.max = s.position;
      e.time_begin = s.time;
    } else {
      e.min = e.min.cwiseMin(s.position);
      e.max = e.max.cwiseMax(s.position);
    }
    e.time_end = s.time;
    e.sum += s.position.cast<double>();
    ++e.size;
    ++i;
  });
  REQUIRE(result.components.size() == expected.size());
  std::size_t kept = 0;
  std::size_t fresh = 0;
  for (const sc::ComponentSummary& c : result.components) {
    const auto it = expected.find(c.id);
    REQUIRE(it != expected.end());
    const ExpectedSummary& e = it->second;
    CHECK(c.size == e.size);
    CHECK(c.min == e.min);
    CHECK(c.max == e.max);
    CHECK(c.time_begin == e.time_begin);
    CHECK(c.time_end == e.time_end);
    const Eigen::Vector3f centroid = (e.sum / static_cast<double>(e.size)).cast<float>();
    CHECK(c.centroid == centroid);
    // Never reused: a new id exceeds every id handed out before.
    if (previous.count(c.id) != 0) {
      ++kept;
    } else {
      REQUIRE((!any_seen || c.id > max_seen));
      ++fresh;
    }
  }
  previous.clear();
  for (const sc::ComponentSummary& c : result.components) {
    previous.insert(c.id);
    max_seen = any_seen ? std::max(max_seen, c.id) : c.id;
    any_seen = true;
  }
  ++tally.retrievals;
  tally.kept += kept;
  tally.fresh += fresh;
  if (kept >= 10 && fresh >= 10) ++tally.mixed;
  tally.max_components = std::max(tally.max_components, result.components.size());
}

template <class Config>
Tally run_fragmented(std::uint32_t seed) {
  sc::ClustererParams<Config> params;
  params.resolution = {64, 512};
  params.window.duration = 0.03;
  params.linkage.theta_deg = 80.0f;  // fragments the scene: many small components
  sc::StreamClusterer<Config> engine(params);
  sc::SyntheticStream::Params stream_params;
  stream_params.point_rate = 80000.0;
  stream_params.seed = seed;
  sc::SyntheticStream stream(stream_params);
  std::set<sc::ComponentId> previous;
  sc::ComponentId max_seen = 0;
  bool any_seen = false;
  Tally tally;
  for (int i = 0; i < 20000; ++i) {
    engine.insert(stream.next());
    if (i % 450 != 449) continue;
    check_result(engine, engine.retrieve(), previous, max_seen, any_seen, tally);
  }
  return tally;
}

/// CArcFixedConfig with another connectivity strategy and spatial index.
template <class Connectivity, class Index = sc::config_traits<sc::CArcFixedConfig>::spatial_index>
struct CArcFixedWith : sc::CArcFixedConfig {
  using connectivity = Connectivity;
  using spatial_index = Index;
};
using LazyConfig = CArcFixedWith<sc::LazyBfsConnectivity>;
using streamclust::test::RebuildConfig;
using streamclust::test::ForestConfig;
using CappedForestConfig = CArcFixedWith<sc::SpanningForestConnectivity, sc::CappedGrid>;

}  // namespace

TEST_CASE_TEMPLATE("result order and summaries on fragmented windows: sorted ids, exact summaries, no id reuse", Config,
                   LazyConfig, RebuildConfig, ForestConfig, CappedForestConfig) {
  for (std::uint32_t seed : {4u, 5u}) {
    INFO("seed " << seed);
    const Tally t = run_fragmented<Config>(seed);
    CHECK(t.retrievals > 40);
    // The stream exercises what the ordering merges: many kept and many
    // fresh ids in one retrieval.
    CHECK(t.max_components >= 100);
    CHECK(t.mixed > t.retrievals / 2);
    CHECK(t.kept > 0);
    CHECK(t.fresh > 0);
  }
}

TEST_CASE_TEMPLATE("rebuilding strategies: local clusters are the last retrieval's components", Config, RebuildConfig,
                   ForestConfig, CappedForestConfig) {
  sc::ClustererParams<Config> params;
  params.resolution = {64, 512};
  params.window.duration = 0.03;
  params.linkage.theta_deg = 80.0f;
  sc::StreamClusterer<Config> engine(params);
  sc::SyntheticStream stream;
  for (int i = 0; i < 6000; ++i) engine.insert(stream.next());
  const sc::Clustering& r = engine.retrieve();
  // Per cluster: its points in the window, counted through cluster_of.
  std::map<sc::ClusterId, std::size_t> members;
  std::map<sc::ClusterId, std::set<sc::ComponentId>> labels;
  for (std::size_t i = 0; i < engine.size(); ++i) {
    const sc::ClusterId c = engine.cluster_of(engine.handle_at(i));
    REQUIRE(c != sc::kNoCluster);
    ++members[c];
    labels[c].insert(r.points[i].label);
  }
  CHECK(engine.cluster_slots() == r.components.size());
  CHECK(engine.cluster_count() == r.components.size());
  for (const auto& m : members) {
    const sc::ClusterId c = m.first;
    CHECK(engine.cluster_alive(c));
    CHECK(engine.cluster_size(c) == m.second);
    CHECK_FALSE(engine.cluster_pending(c));
    CHECK(engine.bridges(c).empty());
    CHECK(labels[c].size() == 1);  // a cluster is one component
  }
  // Evictions lower the sizes; a cluster whose points all left is dead.
  const std::size_t before = engine.size();
  const sc::ClusterId oldest = engine.cluster_of(engine.handle_at(0));
  const std::size_t oldest_size = engine.cluster_size(oldest);
  engine.advance_to(r.time + params.window.duration + 1.0);  // everything expires
  REQUIRE(engine.size() == 0);
  CHECK(before > 0);
  CHECK(oldest_size > 0);
  CHECK(engine.cluster_size(oldest) == 0);
  CHECK_FALSE(engine.cluster_alive(oldest));
  CHECK(engine.cluster_count() == 0);
}
