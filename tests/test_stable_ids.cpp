// SPDX-License-Identifier: MIT
// Stable component ids under the rebuilding connectivity strategies, against
// an independent implementation of the documented rule: every point present
// at the previous retrieval votes for (its new component, its old id); an old
// id goes to the component with most of its votes (ties: the component whose
// oldest point is older), a component keeps the heaviest id it won (ties: the
// older id), the others get fresh ids, increasing in component order and
// larger than every id handed out before. Also: `components` sorted by id and
// consistent with the per-point labels.

#include <doctest/doctest.h>

#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/streamclust.hpp>

#include "support/fixed_configs.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

namespace sc = streamclust;

namespace {

using IdsByStreamIndex = std::unordered_map<std::uint64_t, sc::ComponentId>;  // stream index -> id

struct ExpectedIds {
  std::vector<sc::ComponentId> kept;  // per component in order of first point; kNoComponent = fresh
};

/// The rule, from the previous labels and the current result's grouping.
ExpectedIds expected_ids(const IdsByStreamIndex& previous, const sc::Clustering& now) {
  // Components in order of their oldest point (result points are oldest first).
  std::map<sc::ComponentId, std::size_t> order;
  std::vector<std::size_t> group_of(now.points.size());
  for (std::size_t i = 0; i < now.points.size(); ++i) {
    const auto it = order.emplace(now.points[i].label, order.size()).first;
    group_of[i] = it->second;
  }
  // Votes per old id: group -> weight.
  std::map<sc::ComponentId, std::map<std::size_t, std::uint64_t>> votes;
  for (std::size_t i = 0; i < now.points.size(); ++i) {
    const auto it = previous.find(now.points[i].stream_index);
    if (it != previous.end()) ++votes[it->second][group_of[i]];
  }
  ExpectedIds e;
  e.kept.assign(order.size(), sc::kNoComponent);
  std::vector<std::uint64_t> kept_weight(order.size(), 0);
  for (const auto& [old_id, by_group] : votes) {
    std::size_t winner = 0;
    std::uint64_t best = 0;
    for (const auto& [group, weight] : by_group) {  // ascending group: ties keep the first
      if (weight > best) {
        best = weight;
        winner = group;
      }
    }
    // ids are visited in increasing order: on a tie the older id stays.
    if (e.kept[winner] == sc::kNoComponent || best > kept_weight[winner]) {
      e.kept[winner] = old_id;
      kept_weight[winner] = best;
    }
  }
  return e;
}

template <class Config>
void check_rule_on_stream(std::uint32_t seed) {
  sc::ClustererParams<Config> params;
  params.resolution = {64, 512};
  params.window.duration = 0.04;
  params.linkage.theta_deg = 60.0f;
  sc::StreamClusterer<Config> engine(params);
  sc::SyntheticStream::Params stream_params;
  stream_params.point_rate = 60000.0;
  stream_params.seed = seed;
  sc::SyntheticStream stream(stream_params);
  IdsByStreamIndex previous;
  sc::ComponentId max_seen = 0;
  bool any_seen = false;
  int retrievals = 0, fresh_total = 0, kept_total = 0;
  for (int i = 0; i < 24000; ++i) {
    engine.insert(stream.next());
    if (i % 700 != 699) continue;
    const sc::Clustering& result = engine.retrieve();
    ++retrievals;
    // Sorted by id, sizes consistent with the labels.
    std::map<sc::ComponentId, std::uint32_t> counts;
    for (const auto& p : result.points) ++counts[p.label];
    REQUIRE(result.components.size() == counts.size());
    for (std::size_t k = 0; k < result.components.size(); ++k) {
      if (k > 0) REQUIRE(result.components[k - 1].id < result.components[k].id);
      REQUIRE(counts.count(result.components[k].id) == 1);
      REQUIRE(result.components[k].size == counts[result.components[k].id]);
    }
    // The id rule.
    const ExpectedIds e = expected_ids(previous, result);
    std::map<sc::ComponentId, std::size_t> order;
    for (const auto& p : result.points) order.emplace(p.label, order.size());
    std::vector<sc::ComponentId> actual(order.size());
    for (const auto& [id, group] : order) actual[group] = id;
    sc::ComponentId last_fresh = 0;
    bool any_fresh = false;
    for (std::size_t g = 0; g < actual.size(); ++g) {
      INFO("retrieval " << retrievals << ", component " << g << " of " << actual.size());
      if (e.kept[g] != sc::kNoComponent) {
        REQUIRE(actual[g] == e.kept[g]);
        ++kept_total;
      } else {
        REQUIRE((!any_seen || actual[g] > max_seen));
        REQUIRE((!any_fresh || actual[g] > last_fresh));
        last_fresh = actual[g];
        any_fresh = true;
        ++fresh_total;
      }
    }
    previous.clear();
    for (const auto& p : result.points) {
      previous[p.stream_index] = p.label;
      max_seen = any_seen ? std::max(max_seen, p.label) : p.label;
      any_seen = true;
    }
  }
  CHECK(retrievals > 30);
  CHECK(kept_total > 0);   // the stream exercises both branches
  CHECK(fresh_total > retrievals);
}

using streamclust::test::ForestConfig;
using streamclust::test::RebuildConfig;

struct CappedRebuildConfig : sc::CArcFixedConfig {
  using spatial_index = sc::CappedGrid;
  using connectivity = sc::UnionFindRebuildConnectivity;
};

}  // namespace

TEST_CASE_TEMPLATE("rebuilding strategies: stable ids follow the documented per-point vote rule", Config,
                   RebuildConfig, CappedRebuildConfig, ForestConfig) {
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    INFO("seed " << seed);
    check_rule_on_stream<Config>(seed);
  }
}
