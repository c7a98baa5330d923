// SPDX-License-Identifier: MIT
// Stream indexes: the engine's point records keep the low 32 bits and a
// short list of epochs the high ones (StreamClusterer::StreamEpoch). These
// cases start the numbering near 2^32 and 2^64 (Params::first_stream_index)
// so that a window spans an epoch change, with rejected points on both
// sides, and check every way the index leaves the engine.

#include <doctest/doctest.h>

#include <streamclust/streamclust.hpp>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace sc = streamclust;

namespace {

template <class Connectivity>
struct IndexConfig {
  using projection = sc::SphericalProjection;
  using spatial_index = sc::CappedGrid;
  using linkage = sc::AngularLinkage;
  using window = sc::CountWindow;
  using resolution = sc::FixedResolution;
  using connectivity = Connectivity;
};

template <class Config>
sc::ClustererParams<Config> index_params(std::uint64_t first, std::size_t capacity) {
  sc::ClustererParams<Config> p;
  p.resolution = {1, 1};
  p.window.capacity = capacity;
  p.mask_size = 1;
  p.first_stream_index = first;
  return p;
}

/// Offers `pattern` (true = a valid point, false = a NaN record) and returns
/// the stream indexes of the accepted points, in order.
template <class Engine>
std::vector<std::uint64_t> offer(Engine& engine, const std::vector<bool>& pattern, double& t) {
  std::vector<std::uint64_t> accepted;
  const std::uint64_t first = engine.params().first_stream_index;
  for (const bool valid : pattern) {
    const std::uint64_t index = first + engine.offered();
    const float x = valid ? 5.0f + 0.001f * static_cast<float>(t) : std::numeric_limits<float>::quiet_NaN();
    if (engine.insert(sc::Point{x, 0.0f, 0.0f, 0.0f, t}) == sc::RejectReason::accepted) accepted.push_back(index);
    t += 0.001;
  }
  return accepted;
}

/// The window's stream indexes, read in the three ways the engine offers.
template <class Engine>
void require_window_indexes(Engine& engine, const std::vector<std::uint64_t>& expected) {
  REQUIRE(engine.size() == expected.size());
  std::vector<std::uint64_t> visited;
  engine.for_each_point([&](const sc::Sample&, std::uint64_t i) { visited.push_back(i); });
  CHECK(visited == expected);
  for (std::size_t pos = 0; pos < expected.size(); ++pos)
    CHECK(engine.stream_index(engine.handle_at(pos)) == expected[pos]);
  const auto& result = engine.retrieve();
  REQUIRE(result.points.size() == expected.size());
  for (std::size_t pos = 0; pos < expected.size(); ++pos) CHECK(result.points[pos].stream_index == expected[pos]);
}

}  // namespace

TEST_CASE_TEMPLATE("stream indexes stay exact across the 2^32 and 2^64 boundaries", Conn, sc::LazyBfsConnectivity,
                   sc::UnionFindRebuildConnectivity, sc::SpanningForestConnectivity) {
  using Config = IndexConfig<Conn>;
  constexpr std::uint64_t two32 = std::uint64_t{1} << 32;
  for (const std::uint64_t first : {std::uint64_t{0}, std::uint64_t{1000}, two32 - 5, 3 * two32 - 2,
                                    ~std::uint64_t{0} - 3}) {
    INFO("first stream index " << first);
    sc::StreamClusterer<Config> engine(index_params<Config>(first, 6));
    double t = 0.0;
    std::vector<std::uint64_t> accepted;
    // rejections before, across and after the boundary; the count window
    // (6 points) spans it for a while, then leaves it behind
    for (const auto& pattern : {std::vector<bool>{true, false, true, false},
                                std::vector<bool>{false, true, true, false, false, true},
                                std::vector<bool>{true, true, true, true, false, true, true},
                                std::vector<bool>{true, true, true, true, true, true}}) {
      for (const std::uint64_t i : offer(engine, pattern, t)) accepted.push_back(i);
      const std::size_t kept = accepted.size() < 6 ? accepted.size() : 6;
      require_window_indexes(engine, std::vector<std::uint64_t>(accepted.end() - static_cast<std::ptrdiff_t>(kept),
                                                                accepted.end()));
    }
    CHECK(accepted.front() == first);
    CHECK(accepted.size() == 17);
  }
}

TEST_CASE("a resumed stream numbers from first_stream_index; the count of offered points does not") {
  using Config = IndexConfig<sc::SpanningForestConnectivity>;
  sc::StreamClusterer<Config> engine(index_params<Config>(std::uint64_t{7} << 40, 4));
  double t = 0.0;
  const auto accepted = offer(engine, {false, true, true}, t);
  CHECK(engine.offered() == 3);
  CHECK(accepted == std::vector<std::uint64_t>{(std::uint64_t{7} << 40) + 1, (std::uint64_t{7} << 40) + 2});
  require_window_indexes(engine, accepted);
}

TEST_CASE("the epochs of the window follow it: one again as soon as the old epoch's last point leaves") {
  using Config = IndexConfig<sc::SpanningForestConnectivity>;
  constexpr std::uint64_t two32 = std::uint64_t{1} << 32;
  sc::StreamClusterer<Config> engine(index_params<Config>(two32 - 3, 4));
  double t = 0.0;
  offer(engine, {true, true, true}, t);  // 2^32 - 3 .. 2^32 - 1
  CHECK(engine.stream_epochs() == 1);
  offer(engine, {true}, t);  // 2^32: the window straddles the boundary
  CHECK(engine.stream_epochs() == 2);
  offer(engine, {true, true}, t);  // evicts 2^32 - 3 and 2^32 - 2
  CHECK(engine.stream_epochs() == 2);
  offer(engine, {true}, t);  // evicts 2^32 - 1, the old epoch's last point
  CHECK(engine.stream_epochs() == 1);
  require_window_indexes(engine, {two32, two32 + 1, two32 + 2, two32 + 3});
  engine.advance_to(t + 100.0);  // a count window ignores time: nothing leaves
  CHECK(engine.stream_epochs() == 1);
}

