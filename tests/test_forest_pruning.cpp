// SPDX-License-Identifier: MIT
// The spanning forest's redundant-edge filter
// (SpanningForestConnectivity::Params::prune_witnesses): on a Livox-like
// stream it drops a large share of the new edges and changes nothing a user
// sees, retrieval for retrieval: same points, same labels, same stable ids,
// same summaries. (tests/test_oracle.cpp checks the partition against the
// batch clusterer with random witness counts on adversarial streams.)

#include <doctest/doctest.h>

#include <streamclust/sim/synthetic_stream.hpp>
#include <streamclust/streamclust.hpp>

#include "support/invalid_argument.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sc = streamclust;

namespace {

/// The fast preset with Euclidean linkage: no link_many, the pairwise path.
struct EuclideanFastConfig : sc::CArcFastConfig {
  using linkage = sc::EuclideanLinkage;
};

struct Run {
  std::vector<sc::Clustering> retrievals;
  std::uint64_t edges_found = 0;
  std::uint64_t edges_pruned = 0;
  std::uint64_t edges_folded = 0;
  std::uint64_t edges_accepted = 0;
  std::size_t edge_storage_bytes = 0;  // at the end
};

/// 0.6 s of the synthetic Mid-360-like stream, T_B = 0.2 s, a retrieval
/// every 50 ms (20 Hz).
template <class Config>
Run run(std::uint32_t witnesses) {
  sc::ClustererParams<Config> params;
  params.window.duration = 0.2;
  params.connectivity.prune_witnesses = witnesses;
  params.connectivity.min_fold_edges = 4096;  // the fold threshold then scales with the window
  sc::StreamClusterer<Config> engine(params);
  sc::SyntheticStream stream;
  Run out;
  double next_retrieval = 0.05;
  while (stream.time() < 0.6) {
    const sc::SyntheticPoint p = stream.next();
    engine.insert(sc::Point{p.x, p.y, p.z, p.intensity, p.t});
    if (p.t >= next_retrieval) {
      out.retrievals.push_back(engine.retrieve());
      const sc::RetrievalStats& stats = engine.last_stats();
      out.edges_found += stats.edges_found;
      out.edges_pruned += stats.edges_pruned;
      out.edges_folded += stats.edges_folded;
      out.edges_accepted += stats.edges_accepted;
      // The folds read only the kept new edges (the live ones), accept only
      // some of them, and leave a spanning forest: one edge fewer than
      // points per component.
      CHECK(stats.edges_folded <= stats.edges_found - stats.edges_pruned);
      CHECK(stats.edges_accepted <= stats.edges_folded);
      const sc::Clustering& c = out.retrievals.back();
      CHECK(stats.forest_edges == c.points.size() - c.components.size());
      next_retrieval += 0.05;
    }
  }
  out.edge_storage_bytes = engine.memory_usage().edge_storage;
  return out;
}

/// "" when both runs returned the same clusterings, else the first difference.
std::string compare(const Run& a, const Run& b) {
  if (a.retrievals.size() != b.retrievals.size()) return "retrieval counts differ";
  for (std::size_t r = 0; r < a.retrievals.size(); ++r) {
    const sc::Clustering& x = a.retrievals[r];
    const sc::Clustering& y = b.retrievals[r];
    const std::string at = "retrieval " + std::to_string(r) + ": ";
    if (x.points.size() != y.points.size()) return at + "window sizes differ";
    for (std::size_t i = 0; i < x.points.size(); ++i) {
      if (x.points[i].stream_index != y.points[i].stream_index || x.points[i].label != y.points[i].label)
        return at + "point " + std::to_string(i) + " differs";
    }
    if (x.components.size() != y.components.size()) return at + "component counts differ";
    for (std::size_t c = 0; c < x.components.size(); ++c) {
      const sc::ComponentSummary& u = x.components[c];
      const sc::ComponentSummary& v = y.components[c];
      if (u.id != v.id || u.size != v.size || u.centroid != v.centroid || u.min != v.min || u.max != v.max ||
          u.time_begin != v.time_begin || u.time_end != v.time_end)
        return at + "component " + std::to_string(c) + " differs";
    }
  }
  return "";
}

}  // namespace

TEST_CASE_TEMPLATE("spanning forest: dropping redundant edges changes no label, id or summary", Config,
                   sc::CArcFastConfig, sc::CArcCappedFastConfig, EuclideanFastConfig) {
  const Run all = run<Config>(0);
  const Run one = run<Config>(1);
  const Run three = run<Config>(3);
  REQUIRE(all.retrievals.size() >= 10);
  CHECK(all.retrievals.back().components.size() > 10);  // a scene with structure, not one blob
  CHECK(compare(all, one) == "");
  CHECK(compare(all, three) == "");
  // The same edges are found; none is dropped without witnesses, and a large
  // share is with them (a Livox rosette revisits each spot many times).
  CHECK(one.edges_found == all.edges_found);
  CHECK(three.edges_found == all.edges_found);
  CHECK(all.edges_pruned == 0);
  CHECK(one.edges_pruned * 5 > all.edges_found);  // > 20 %
  CHECK(three.edges_pruned > one.edges_pruned);
  CHECK(three.edge_storage_bytes < all.edge_storage_bytes);
  // Most new edges close a cycle and the folds reject them; the filter drops
  // edges before they reach a fold. (The forests may differ with it, the
  // components at every moment do not.)
  CHECK(all.edges_accepted > 0);
  CHECK(all.edges_accepted * 2 < all.edges_folded);
  CHECK(one.edges_folded < all.edges_folded);
  MESSAGE("new edges " << all.edges_found << ", dropped with 1 witness " << one.edges_pruned << ", with 3 "
                       << three.edges_pruned << "; folded " << all.edges_folded << ", accepted " << all.edges_accepted
                       << " (1 witness: " << one.edges_accepted << ", 3: " << three.edges_accepted
                       << "); edge storage " << all.edge_storage_bytes << " -> " << three.edge_storage_bytes << " bytes");
}

TEST_CASE("spanning forest: prune_witnesses is validated") {
  using SF = sc::SpanningForestConnectivity;
  SF::Params p;
  p.prune_witnesses = SF::kMaxPruneWitnesses;
  CHECK_NOTHROW(SF{p});
  p.prune_witnesses = 0;
  CHECK_NOTHROW(SF{p});
  p.prune_witnesses = SF::kMaxPruneWitnesses + 1;
  const std::string message = sc::test::invalid_argument_message([&] { SF{p}; });
  CHECK(message.find("prune_witnesses = 9") != std::string::npos);
  CHECK(message.find("[0, 8]") != std::string::npos);
}
