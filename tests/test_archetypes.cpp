// SPDX-License-Identifier: MIT
// Archetypes: the smallest models of each concept, with nothing beyond the
// concept's valid expressions. Explicitly instantiating both clusterers with
// them proves the engines use nothing else; running them proves the models
// are enough to cluster.

#include <doctest/doctest.h>

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <cmath>
#include <vector>

namespace archetype {

using namespace streamclust;  // NOLINT: test-local brevity

struct Projection {
  struct Params {};
  explicit Projection(const Params&) {}
  Projected project(const Eigen::Vector3f& p) const {
    Projected r;
    r.range = p.norm();
    if (!std::isfinite(r.range)) r.reason = RejectReason::non_finite;
    if (r.range <= 0.0f) r.reason = RejectReason::too_close;
    r.u = 0.5f;
    r.v = 0.5f;
    return r;
  }
  bool wraps_horizontally() const { return false; }
  float fov_aspect() const { return 1.0f; }
  Projection(const Projection&) = default;
  Projection& operator=(const Projection&) = delete;
};

struct Index {
  struct Params {};
  explicit Index(const Params&) {}
  void reset(const GridShape& g) { cells.assign(g.cell_count(), {}); }
  void clear() {
    for (auto& c : cells) c.clear();
  }
  PointHandle insert(CellIndex c, PointHandle h) {
    cells[c].push_back(h);
    return kNoPoint;
  }
  void remove(CellIndex c, PointHandle h) {
    auto& v = cells[c];
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (v[i] == h) {
        v.erase(v.begin() + static_cast<std::ptrdiff_t>(i));
        return;
      }
    }
  }
  template <class F>
  void for_each(CellIndex c, F&& f) const {
    for (const PointHandle h : cells[c]) f(h);
  }
  std::size_t size() const {
    std::size_t n = 0;
    for (const auto& c : cells) n += c.size();
    return n;
  }
  std::vector<std::vector<PointHandle>> cells;
};

struct Linkage {
  struct Params {};
  explicit Linkage(const Params&) {}
  bool operator()(const Sample& a, const Sample& b) const { return (a.position - b.position).squaredNorm() < 1.0f; }
};

struct Window {
  struct Params {};
  explicit Window(const Params&) {}
  bool expired(double oldest, double newest, std::size_t) const { return newest - oldest > 1.0; }
  bool complete(double oldest, double newest, std::size_t) const { return newest - oldest >= 1.0; }
};

struct Resolution {
  struct Params {};
  explicit Resolution(const Params&) {}
  bool needs_calibration() const { return calibrate_pending; }
  GridSize grid() const { return GridSize{2, 2}; }
  GridSize calibrate(const std::vector<Projected>&, float) {
    calibrate_pending = false;
    return grid();
  }
  bool calibrate_pending = true;
};

struct Visitor {
  void cluster_created(ClusterId) {}
  void clusters_merged(ClusterId, ClusterId) {}
  void cluster_split(ClusterId, ClusterId) {}
  void cluster_evicted(ClusterId) {}
};

struct Config {
  using projection = Projection;
  using spatial_index = Index;
  using linkage = Linkage;
  using window = Window;
  using resolution = Resolution;
  using visitor = Visitor;
};

struct PointXYZT {
  float x, y, z;
  double t;
};

/// The archetype index plus the optional `prefetch` capability, counting
/// the hints it receives (the hint must not change what the index holds).
struct PrefetchingIndex : Index {
  using Index::Index;
  void prefetch(CellIndex) const { ++hints; }
  mutable std::size_t hints = 0;
};
struct PrefetchingConfig : Config {
  using spatial_index = PrefetchingIndex;
};

}  // namespace archetype

template class streamclust::StreamClusterer<archetype::Config>;
template class streamclust::BatchClusterer<archetype::Config>;
template class streamclust::StreamClusterer<archetype::PrefetchingConfig>;

// prefetch is optional: the archetype index has none, the engine still runs it.
static_assert(!streamclust::has_spatial_index_prefetch_v<archetype::Index>);
static_assert(streamclust::has_spatial_index_prefetch_v<archetype::PrefetchingIndex>);
static_assert(streamclust::is_spatial_index_policy_v<archetype::PrefetchingIndex>);

TEST_CASE("the engines run on archetype policies") {
  streamclust::StreamClusterer<archetype::Config> engine;
  CHECK(engine.calibrating());
  engine.insert(archetype::PointXYZT{5.0f, 0.0f, 0.0f, 0.0});
  engine.insert(archetype::PointXYZT{5.5f, 0.0f, 0.0f, 0.5});
  engine.insert(archetype::PointXYZT{9.0f, 0.0f, 0.0f, 1.0});  // completes the first window
  CHECK_FALSE(engine.calibrating());
  const auto& result = engine.retrieve();
  CHECK(result.points.size() == 3);
  CHECK(result.components.size() == 2);
  std::vector<archetype::PointXYZT> points = {{5.0f, 0.0f, 0.0f, 0.0}, {5.5f, 0.0f, 0.0f, 0.5}};
  streamclust::BatchClusterer<archetype::Config> batch;
  CHECK(batch.cluster(points).components == 1);
}

TEST_CASE("the engine uses an index's optional prefetch hint, with the same result") {
  streamclust::StreamClusterer<archetype::Config> plain;
  streamclust::StreamClusterer<archetype::PrefetchingConfig> hinted;
  const std::vector<archetype::PointXYZT> points = {
      {5.0f, 0.0f, 0.0f, 0.0}, {5.5f, 0.0f, 0.0f, 0.5}, {9.0f, 0.0f, 0.0f, 1.0}, {9.5f, 0.0f, 0.0f, 1.2}};
  for (const auto& p : points) {
    plain.insert(p);
    hinted.insert(p);
  }
  // four points were linked (the first window's three at the end of the
  // calibration, then the fourth): each searched its mask and hinted its cells
  CHECK(hinted.spatial_index().hints >= 4);
  const auto& a = plain.retrieve();
  const auto& b = hinted.retrieve();
  REQUIRE(a.points.size() == b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    CHECK(a.points[i].stream_index == b.points[i].stream_index);
    CHECK(a.points[i].label == b.points[i].label);
  }
}

#if defined(__cpp_concepts) && __cpp_concepts >= 201907L
// Under C++20 the same requirements are concepts usable in constraints.
namespace {
template <streamclust::LinkagePolicy L>
bool linked_with_itself(const L& l, const streamclust::Sample& s) {
  return l(s, s);
}
}  // namespace
static_assert(streamclust::ProjectionPolicy<archetype::Projection>);
static_assert(streamclust::SpatialIndexPolicy<archetype::Index>);
static_assert(streamclust::LinkagePolicy<archetype::Linkage>);
static_assert(streamclust::WindowPolicy<archetype::Window>);
static_assert(streamclust::ResolutionPolicy<archetype::Resolution>);
static_assert(streamclust::VisitorPolicy<archetype::Visitor>);
static_assert(!streamclust::LinkagePolicy<archetype::Window>);

TEST_CASE("C++20 concepts constrain templates") {
  const archetype::Linkage linkage{archetype::Linkage::Params{}};
  CHECK(linked_with_itself(linkage, streamclust::Sample{}));
}
#endif

// The C++17 traits say the same.
static_assert(streamclust::is_linkage_policy_v<archetype::Linkage>);
static_assert(!streamclust::is_linkage_policy_v<archetype::Window>);
static_assert(!streamclust::is_spatial_index_policy_v<archetype::Linkage>);
static_assert(streamclust::is_point_v<archetype::PointXYZT>);
static_assert(!streamclust::is_point_v<int>);
