// SPDX-License-Identifier: MIT
// The test kit (<streamclust/testing/...>) catches what it promises to
// catch: planted mutations (an asymmetric linkage, a stateful linkage, an
// index that loses a handle, a connectivity that forgets an edge) each fail
// their law with a message that names the law and the evidence, and the
// exactness check reports the seed, the stream, the first mismatching
// retrieval and a shrunk stream. The stock ground and motion policies keep
// their laws (the other families' stock policies: tests/test_policy_*.cpp,
// the oracle: tests/test_oracle*.cpp, all through the same kit).

#include <doctest/doctest.h>

#include <streamclust/connectivity/union_find_rebuild.hpp>
#include <streamclust/ground/height_map_ground.hpp>
#include <streamclust/ground/no_ground.hpp>
#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/motion/no_motion.hpp>
#include <streamclust/motion/posed_motion.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/testing/connectivity_laws.hpp>
#include <streamclust/testing/doctest.hpp>
#include <streamclust/testing/exactness.hpp>
#include <streamclust/testing/ground_laws.hpp>
#include <streamclust/testing/index_laws.hpp>
#include <streamclust/testing/linkage_laws.hpp>
#include <streamclust/testing/motion_laws.hpp>
#include <streamclust/testing/type_product.hpp>

#include "support/contains.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

namespace sc = streamclust;
namespace kit = streamclust::testing;

namespace {

using streamclust::test::contains;

/// Mutation: the newer point gets the longer reach, |a - b| <= 0.6 m when a
/// is the newer, 0.3 m otherwise. Not symmetric.
struct AsymmetricLinkage {
  struct Params {};
  explicit AsymmetricLinkage(const Params&) {}
  bool operator()(const sc::Sample& a, const sc::Sample& b) const {
    const float reach = a.time >= b.time ? 0.6f : 0.3f;  // [m]
    return (a.position - b.position).squaredNorm() <= reach * reach;
  }
};

/// Mutation: a radius that adapts to the fraction of pairs linked so far,
/// 0.5 m x (1 + 0.2 x that fraction): each decision depends on the calls
/// before it. Symmetric for two calls in a row with little in between.
struct AdaptiveRadiusLinkage {
  struct Params {};
  explicit AdaptiveRadiusLinkage(const Params&) {}
  bool operator()(const sc::Sample& a, const sc::Sample& b) const {
    const double fraction = calls_ == 0 ? 0.0 : static_cast<double>(linked_) / static_cast<double>(calls_);
    const auto radius = static_cast<float>(0.5 * (1.0 + 0.2 * fraction));  // [m]
    const bool linked = (a.position - b.position).squaredNorm() <= radius * radius;
    ++calls_;
    linked_ += linked ? 1u : 0u;
    return linked;
  }
  mutable std::uint64_t calls_ = 0;
  mutable std::uint64_t linked_ = 0;
};

/// Mutation: a bucket grid that silently drops every 37th handle it is given.
struct LosingGrid : sc::BucketGrid {
  using sc::BucketGrid::BucketGrid;
  sc::PointHandle insert(sc::CellIndex cell, sc::PointHandle h) {
    if (++inserts_ % 37 == 0) return sc::kNoPoint;  // lost: neither stored nor reported displaced
    return sc::BucketGrid::insert(cell, h);
  }
  std::uint64_t inserts_ = 0;
};

/// Mutation: the union-find rebuild, forgetting the last neighbour of every
/// fifth point that links.
struct ForgetfulConnectivity : sc::UnionFindRebuildConnectivity {
  using Base = sc::UnionFindRebuildConnectivity;
  explicit ForgetfulConnectivity(const Params& p) : Base(p) {}
  template <class Ring>
  class State : public Base::State<Ring> {
   public:
    explicit State(const ForgetfulConnectivity& c) : Base::State<Ring>(c) {}
    template <class Ctx>
    void on_link(Ctx& ctx, sc::PointHandle h, const sc::PointHandle* nb, std::size_t count) {
      const bool forget = count > 0 && ++links_ % 5 == 0;
      Base::State<Ring>::on_link(ctx, h, nb, forget ? count - 1 : count);
    }

   private:
    std::uint64_t links_ = 0;
  };
};

struct AsymmetricConfig : sc::CArcFixedConfig {
  using linkage = AsymmetricLinkage;
};

struct GroundConfig : sc::CArcFastConfig {
  using ground = sc::HeightMapGround;
  using resolution = sc::FixedResolution;
  using linkage = sc::EuclideanLinkage;
};

}  // namespace

TEST_CASE("test kit: an asymmetric linkage fails the symmetry law, with the pair") {
  const kit::LawResult r = kit::check_linkage<AsymmetricLinkage>();
  CHECK_FALSE(r.passed);
  INFO(r.message);
  CHECK(contains(r.message, "linkage AsymmetricLinkage"));
  CHECK(contains(r.message, "not symmetric: link(a, b) = "));
  CHECK(contains(r.message, "a = {position ("));
}

TEST_CASE("test kit: the exactness check catches an asymmetric linkage, reports the seed and shrinks the stream") {
  sc::ClustererParams<AsymmetricConfig> params;
  params.resolution = {16, 64};
  params.window.duration = 0.05;  // [s]
  kit::ExactnessOptions options;
  options.seeds = 16;
  const kit::ExactnessReport r = kit::check_exactness<AsymmetricConfig>(params, options);
  CHECK_FALSE(r.passed);
  INFO(r.message);
  CHECK(contains(r.message, "exactness of AsymmetricConfig: seed "));
  CHECK(contains(r.message, " points, "));
  CHECK(contains(r.message, "retrieval "));
  CHECK(contains(r.message, "differs from the batch partition of its window"));
  CHECK(contains(r.message, "shrunk to "));
  // the shrunk stream is small enough to be listed point by point
  CHECK(contains(r.message, "points {x, y, z, intensity, t}:"));
}

TEST_CASE("test kit: a stateful linkage fails the statelessness law") {
  const kit::LawResult r = kit::check_linkage<AdaptiveRadiusLinkage>();
  CHECK_FALSE(r.passed);
  INFO(r.message);
  CHECK(contains(r.message, "not deterministic"));
  CHECK(contains(r.message, "stateless"));
}

TEST_CASE("test kit: an index that loses a handle fails the index laws, with the operation") {
  const kit::LawResult r = kit::check_index<LosingGrid>();
  CHECK_FALSE(r.passed);
  INFO(r.message);
  CHECK(contains(r.message, "index LosingGrid"));
  CHECK(contains(r.message, "after insert(cell "));
  CHECK((contains(r.message, "size() = ") || contains(r.message, "for_each lists")));
}

TEST_CASE("test kit: a connectivity that forgets an edge fails the exactness law") {
  kit::ConnectivityLawOptions<ForgetfulConnectivity> options;
  options.seeds = 24;
  const kit::LawResult r = kit::check_connectivity<ForgetfulConnectivity>(options);
  CHECK_FALSE(r.passed);
  INFO(r.message);
  CHECK(contains(r.message, "exactness of PolicyCombo<"));
  CHECK(contains(r.message, "ForgetfulConnectivity"));
  CHECK(contains(r.message, "differs from the batch partition of its window"));
}

TEST_CASE("test kit: the stock ground and motion policies keep their laws") {
  STREAMCLUST_CHECK_LAW(kit::check_ground<sc::NoGround>());
  sc::HeightMapGround::Params known_height;
  known_height.sensor_height = 1.0f;  // [m] the simulated sensor's
  known_height.lowest_ray_elevation_deg = -7.0f;
  kit::GroundLawOptions<sc::HeightMapGround> ground;
  ground.params = {sc::HeightMapGround::Params{}, known_height};
  STREAMCLUST_CHECK_LAW(kit::check_ground<sc::HeightMapGround>(ground));
  STREAMCLUST_CHECK_LAW(kit::check_motion<sc::NoMotion>());
  STREAMCLUST_CHECK_LAW(kit::check_motion<sc::PosedMotion>());
}

TEST_CASE("test kit: the exactness check of a configuration with ground removal on simulated Livox streams") {
  sc::ClustererParams<GroundConfig> params;
  params.resolution = {32, 128};
  params.window.duration = 0.05;  // [s]
  params.linkage.max_distance = 0.3f;  // [m]
  kit::ExactnessOptions options;
  options.seeds = 12;
  options.streams = kit::livox_stream_sources();
  const kit::ExactnessReport r = kit::check_exactness<GroundConfig>(params, options);
  STREAMCLUST_CHECK_LAW(r);
  CHECK(r.comparisons > 12);
}

namespace {
/// Lists of values as types: V<list, value>.
template <int L, int Value>
using V = std::integral_constant<int, L * 100 + Value>;
template <int L, int... Values>
using ValueList = std::tuple<V<L, Values>...>;

/// The combinations of a tuple of tuples of V<...> as rows of values.
template <class Combos>
std::vector<std::vector<int>> rows_of() {
  std::vector<std::vector<int>> rows;
  kit::for_each_type<Combos>([&rows](auto combo) {
    std::vector<int> row;
    kit::for_each_type<typename decltype(combo)::type>(
        [&row](auto value) { row.push_back(decltype(value)::type::value); });
    rows.push_back(row);
  });
  return rows;
}

/// The pairs (value of list a, value of list b), a < b, that no row holds.
std::size_t uncovered_pairs(const std::vector<std::vector<int>>& rows, const std::vector<int>& sizes) {
  std::size_t uncovered = 0;
  for (std::size_t a = 0; a < sizes.size(); ++a)
    for (std::size_t b = a + 1; b < sizes.size(); ++b)
      for (int i = 0; i < sizes[a]; ++i)
        for (int j = 0; j < sizes[b]; ++j) {
          bool held = false;
          for (const auto& row : rows)
            held = held || (row[a] == static_cast<int>(a) * 100 + i && row[b] == static_cast<int>(b) * 100 + j);
          if (!held) ++uncovered;
        }
  return uncovered;
}
}  // namespace

TEST_CASE("test kit: a pairwise cover holds every pair of two lists' values, in far fewer combinations") {
  // The oracle's list sizes: projections, indexes, linkages, windows, connectivities.
  using P = ValueList<0, 0, 1>;
  using I = ValueList<1, 0, 1, 2>;
  using L = ValueList<2, 0, 1, 2, 3, 4, 5>;
  using W = ValueList<3, 0, 1>;
  using C = ValueList<4, 0, 1, 2>;
  const auto cover = rows_of<kit::tuple_pairwise_t<P, I, L, W, C>>();
  const auto product = rows_of<kit::tuple_product_t<P, I, L, W, C>>();
  REQUIRE(product.size() == 216);
  CHECK(uncovered_pairs(cover, {2, 3, 6, 2, 3}) == 0);
  CHECK(cover.size() >= 18);  // linkages x connectivities alone need 18
  CHECK(cover.size() <= 21);
  // Distinct combinations of the product, in its order.
  std::size_t at = 0;
  for (const auto& row : cover) {
    while (at < product.size() && product[at] != row) ++at;
    CHECK(at < product.size());
    ++at;
  }
  // A cut cover misses pairs: the check above can fail.
  CHECK(uncovered_pairs(std::vector<std::vector<int>>(cover.begin(), cover.end() - 1), {2, 3, 6, 2, 3}) > 0);
  // Two lists: every pair is one combination, the cover is the product; one list: every value.
  CHECK(rows_of<kit::tuple_pairwise_t<I, L>>() == rows_of<kit::tuple_product_t<I, L>>());
  CHECK(rows_of<kit::tuple_pairwise_t<L>>().size() == 6);
  CHECK(std::tuple_size_v<kit::tuple_pairwise_t<L, std::tuple<>>> == 0);
}
