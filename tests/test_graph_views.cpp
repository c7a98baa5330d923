// SPDX-License-Identifier: MIT
// The point graph and the component graph are Boost.Graph models: BGL's own
// connected_components on them must reproduce retrieve().

#include <doctest/doctest.h>

#include <streamclust/graph/component_graph.hpp>
#include <streamclust/graph/point_graph.hpp>
#include <streamclust/streamclust.hpp>

#include <boost/graph/connected_components.hpp>

#include "support/partition.hpp"
#include "support/streams.hpp"

#include <vector>

namespace sc = streamclust;

namespace {
struct ViewConfig {
  using projection = sc::SphericalProjection;
  using spatial_index = sc::BucketGrid;
  using linkage = sc::EuclideanLinkage;
  using window = sc::TimeWindow;
  using resolution = sc::FixedResolution;
};
}  // namespace

TEST_CASE("boost::connected_components on the point graph and the component graph matches retrieve()") {
  for (std::uint64_t seed = 0; seed < 30; ++seed) {
    sc::ClustererParams<ViewConfig> params;
    params.resolution = {16, 64};
    params.linkage.max_distance = 0.6f;
    params.window.duration = 0.05;
    params.mask_size = 3;
    sc::StreamClusterer<ViewConfig> engine(params);
    const auto stream = sc::test::make_stream(sc::test::StreamKind::blobs, 400, seed, 2000.0);
    for (std::size_t i = 0; i < stream.size(); ++i) {
      engine.insert(stream[i]);
      if (i % 50 != 49) continue;
      const auto& result = engine.retrieve();
      std::vector<sc::ComponentId> labels;
      for (const auto& p : result.points) labels.push_back(p.label);

      const auto points = sc::point_graph(engine);
      REQUIRE(num_vertices(points) == engine.size());
      std::vector<int> point_component(num_vertices(points));
      const int n = boost::connected_components(points, point_component.data());
      INFO("seed " << seed << " point " << i);
      CHECK(static_cast<std::size_t>(n) == result.components.size());
      CHECK(sc::test::partition_mismatch(labels, point_component) == "");

      const auto clusters = sc::component_graph(engine);
      std::vector<int> cluster_component(num_vertices(clusters));
      boost::connected_components(clusters, cluster_component.data());
      std::vector<int> via_clusters;
      for (std::size_t v = 0; v < engine.size(); ++v) {
        via_clusters.push_back(cluster_component[engine.cluster_of(engine.handle_at(v))]);
      }
      CHECK(sc::test::partition_mismatch(labels, via_clusters) == "");
    }
  }
}

TEST_CASE("point graph out-edges are the live links, symmetric") {
  sc::ClustererParams<ViewConfig> params;
  params.resolution = {1, 1};
  params.linkage.max_distance = 1.0f;
  params.window.duration = 1.0;
  params.mask_size = 1;
  sc::StreamClusterer<ViewConfig> engine(params);
  engine.insert(sc::Point{5.0f, 0.0f, 0.0f, 0.0f, 0.0});
  engine.insert(sc::Point{5.5f, 0.0f, 0.0f, 0.0f, 0.5});
  engine.insert(sc::Point{6.0f, 0.0f, 0.0f, 0.0f, 0.6});
  const auto g = sc::point_graph(engine);
  CHECK(out_degree(0, g) == 2);
  CHECK(out_degree(1, g) == 2);
  engine.advance_to(1.2);  // the first point leaves
  const auto h = sc::point_graph(engine);
  REQUIRE(num_vertices(h) == 2);
  std::vector<std::size_t> targets;
  for (auto [it, end] = out_edges(0, h); it != end; ++it) targets.push_back(target(*it, h));
  CHECK(targets == std::vector<std::size_t>{1});
  targets.clear();
  for (auto [it, end] = out_edges(1, h); it != end; ++it) targets.push_back(target(*it, h));
  CHECK(targets == std::vector<std::size_t>{0});
}
