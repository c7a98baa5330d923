// SPDX-License-Identifier: MIT
// The spanning forest's fold without a sort buffer: the new edges binned by
// age band (detail::AgeBands), the FIFO ring (detail::RingQueue) and the
// in-place Kruskal merge (detail::merge_forest), each against a plain
// reference: std::stable_sort and a textbook Kruskal over a fresh vector.
// (The engine-level oracle, tests/test_oracle.cpp, checks whole partitions,
// but its windows are too small to span several bands or to reach the
// merge's displacement queue; these cases do both on purpose.)

#include <doctest/doctest.h>

#include <streamclust/detail/age_bands.hpp>
#include <streamclust/detail/forest_merge.hpp>
#include <streamclust/detail/ring_queue.hpp>
#include <streamclust/detail/union_find.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace sc = streamclust;
namespace scd = streamclust::detail;

namespace {

struct Edge {
  sc::PointHandle older;
  sc::PointHandle newer;
  bool operator==(const Edge& o) const { return older == o.older && newer == o.newer; }
};

/// Every band `bands` hands back, concatenated.
std::vector<Edge> drain(scd::AgeBands& bands, sc::PointHandle oldest, std::uint32_t window) {
  std::vector<Edge> out;
  bands.rewind();
  while (bands.next_band(oldest, window)) {
    CHECK_FALSE(bands.band().empty());
    for (const scd::HandleEdge& e : bands.band()) out.push_back(Edge{e.older, e.newer});
  }
  return out;
}

/// The reference: the live edges (older in [oldest, oldest + window)) by
/// increasing age, ties in append order.
std::vector<Edge> reference_order(std::vector<Edge> appended, sc::PointHandle oldest, std::uint32_t window,
                                  sc::PointHandle newest) {
  appended.erase(std::remove_if(appended.begin(), appended.end(),
                                [&](const Edge& e) { return static_cast<sc::PointHandle>(e.older - oldest) >= window; }),
                 appended.end());
  std::stable_sort(appended.begin(), appended.end(), [&](const Edge& a, const Edge& b) {
    return static_cast<sc::PointHandle>(newest - a.older) < static_cast<sc::PointHandle>(newest - b.older);
  });
  return appended;
}

/// True when `a` and `b` were in different sets, which are then one
/// (the batch clusterer's union-find as the reference Kruskal's).
bool joined(scd::UnionFind& sets, std::uint32_t a, std::uint32_t b) {
  if (sets.find(a) == sets.find(b)) return false;
  sets.unite(a, b);
  return true;
}

}  // namespace

TEST_CASE("age bands hand back the live new edges by increasing age, band by band") {
  std::mt19937_64 rng(7);
  // Bases near the 32-bit wrap of the handles included.
  for (const sc::PointHandle base : {sc::PointHandle{0}, sc::PointHandle{1000}, sc::PointHandle{0xFFFFF000u}}) {
    for (int round = 0; round < 20; ++round) {
      scd::AgeBands bands;
      const std::uint32_t span = 1 + static_cast<std::uint32_t>(rng() % 5000);  // up to ~10 bands
      const std::size_t edges = rng() % 3000;
      bands.reset(base);
      std::vector<Edge> appended;
      for (std::size_t k = 0; k < edges; ++k) {
        const auto older = static_cast<sc::PointHandle>(base + rng() % span);
        const auto newer = static_cast<sc::PointHandle>(older + 1 + rng() % 50);
        const sc::PointHandle one[1] = {older};
        bands.append(one, 1, newer);
        appended.push_back(Edge{older, newer});
      }
      CHECK(bands.size() == edges);
      const sc::PointHandle newest = base + span + 60;
      // The window has moved on: a random prefix of the handles expired.
      const auto expired = static_cast<std::uint32_t>(rng() % (span + 1));
      const sc::PointHandle oldest = base + expired;
      const std::uint32_t window = span + 61 - expired;
      INFO("base " << base << ", span " << span << ", edges " << edges << ", expired " << expired);
      CHECK(drain(bands, oldest, window) == reference_order(appended, oldest, window, newest));
    }
  }
}

TEST_CASE("a band's edges of one older endpoint keep their append order, and an emptied window hands back nothing") {
  scd::AgeBands bands;
  bands.reset(100);
  const sc::PointHandle olders[4] = {700, 100, 700, 611};
  bands.append(olders, 4, 900);
  const sc::PointHandle more[2] = {700, 100};
  bands.append(more, 2, 901);
  const std::vector<Edge> expected = {{700, 900}, {700, 900}, {700, 901}, {611, 900}, {100, 900}, {100, 901}};
  CHECK(drain(bands, 100, 802) == expected);
  // Everything below 650 expired: band 0 (100..611) is partly, then wholly, gone.
  const std::vector<Edge> after = {{700, 900}, {700, 900}, {700, 901}};
  CHECK(drain(bands, 650, 252) == after);
  CHECK(drain(bands, 701, 201).empty());
  bands.reset(701);
  CHECK(bands.empty());
  CHECK(drain(bands, 701, 201).empty());
}

TEST_CASE("age bands reuse their pool: a period no larger than an earlier one allocates nothing") {
  scd::AgeBands bands;
  std::mt19937_64 rng(11);
  sc::PointHandle base = 0;
  std::size_t bytes_after_first = 0;
  for (int period = 0; period < 30; ++period) {
    bands.reset(base);
    const std::size_t edges = period == 0 ? 20000 : 10000 + rng() % 10000;
    for (std::size_t k = 0; k < edges; ++k) {
      const sc::PointHandle one[1] = {static_cast<sc::PointHandle>(base + rng() % 40000)};
      bands.append(one, 1, one[0] + 1);
    }
    drain(bands, base, 40001);
    if (period == 0) bytes_after_first = bands.heap_bytes();
    CHECK(bands.heap_bytes() == bytes_after_first);
    base += 5000;
  }
}

TEST_CASE("the ring queue is first in, first out through its growth and wrap-around") {
  scd::RingQueue<int> q;
  int pushed = 0;
  int popped = 0;
  std::mt19937_64 rng(3);
  for (int step = 0; step < 20000; ++step) {
    if (q.empty() || rng() % 3 != 0) {
      q.push(pushed++);
    } else {
      REQUIRE(q.front() == popped);
      q.pop();
      ++popped;
    }
    if (step == 10000) {  // drain half-way, then refill: the head wraps
      while (!q.empty()) {
        REQUIRE(q.front() == popped++);
        q.pop();
      }
    }
  }
  CHECK(q.size() == static_cast<std::size_t>(pushed - popped));
  const std::size_t bytes = q.heap_bytes();
  q.clear();
  CHECK(q.empty());
  for (int k = 0; k < 64; ++k) q.push(k);
  CHECK(q.heap_bytes() == bytes);  // never shrinks, no growth below the old occupancy
}

namespace {

/// One fold, in place (detail::merge_forest) and by the reference (a new
/// vector, std::stable_sort of kept + new edges, kept first on equal ages):
/// the same forest, edge for edge. `kept` must be a forest in increasing
/// age. Also checks the merge's counts of new edges read and accepted.
/// Returns the merge's displaced count.
std::size_t check_fold(const std::vector<Edge>& kept, const std::vector<Edge>& added, sc::PointHandle oldest,
                       std::uint32_t window, std::size_t capacity) {
  const sc::PointHandle newest = oldest + window - 1;
  const auto age = [newest](const auto& e) { return static_cast<std::uint32_t>(newest - e.older); };
  struct Tagged {
    Edge edge;
    bool is_new;
  };
  std::vector<Tagged> all;
  for (const Edge& e : kept) all.push_back(Tagged{e, false});
  const std::vector<Edge> sorted_added = reference_order(added, oldest, window, newest);
  for (const Edge& e : sorted_added) all.push_back(Tagged{e, true});
  std::stable_sort(all.begin(), all.end(), [&](const Tagged& a, const Tagged& b) { return age(a.edge) < age(b.edge); });
  scd::UnionFind reference_sets;
  reference_sets.reset(window);
  std::vector<Edge> expected;
  std::size_t expected_new_accepted = 0;
  for (const Tagged& t : all) {
    if (joined(reference_sets, t.edge.older - oldest, t.edge.newer - oldest)) {
      expected.push_back(t.edge);
      expected_new_accepted += t.is_new ? 1u : 0u;
    }
  }

  std::vector<scd::HandleEdge> forest;
  forest.reserve(capacity);
  for (const Edge& e : kept) forest.emplace_back(e.older, e.newer);
  scd::AgeBands bands;
  bands.reset(oldest);
  for (const Edge& e : added) {
    const sc::PointHandle one[1] = {e.older};
    bands.append(one, 1, e.newer);
  }
  scd::RingQueue<scd::HandleEdge> displaced;
  scd::UnionFind sets;
  sets.reset(window);
  const scd::MergeCounts counts = scd::merge_forest(forest, bands, displaced, oldest, window, age,
                                                    [&](const scd::HandleEdge& e) {
                                                      return joined(sets, e.older - oldest, e.newer - oldest);
                                                    });
  std::vector<Edge> got;
  for (const scd::HandleEdge& e : forest) got.push_back(Edge{e.older, e.newer});
  CHECK(got == expected);
  CHECK(counts.new_read == sorted_added.size());
  CHECK(counts.new_accepted == expected_new_accepted);
  return counts.displaced;
}

/// Kruskal's forest (increasing age) of random edges among `n` points from `oldest`.
std::vector<Edge> random_forest(std::mt19937_64& rng, sc::PointHandle oldest, std::uint32_t n, std::size_t edges) {
  std::vector<Edge> candidates;
  for (std::size_t k = 0; k < edges; ++k) {
    const auto a = static_cast<std::uint32_t>(rng() % n);
    const auto b = static_cast<std::uint32_t>(rng() % n);
    if (a == b) continue;
    candidates.push_back(Edge{oldest + std::min(a, b), oldest + std::max(a, b)});
  }
  // Kruskal's order: the youngest older endpoint first (offsets: the handles may wrap).
  std::stable_sort(candidates.begin(), candidates.end(), [&](const Edge& x, const Edge& y) {
    return static_cast<sc::PointHandle>(x.older - oldest) > static_cast<sc::PointHandle>(y.older - oldest);
  });
  scd::UnionFind sets;
  sets.reset(n);
  std::vector<Edge> forest;
  for (const Edge& e : candidates) {
    if (joined(sets, e.older - oldest, e.newer - oldest)) forest.push_back(e);
  }
  return forest;
}

}  // namespace

TEST_CASE("the in-place merge builds Kruskal's forest of the kept and the new edges") {
  std::mt19937_64 rng(5);
  for (int round = 0; round < 60; ++round) {
    const sc::PointHandle oldest = round % 3 == 0 ? 0xFFFFFF00u : static_cast<sc::PointHandle>(rng() % 100000);
    const auto n = static_cast<std::uint32_t>(2 + rng() % 4000);
    const std::vector<Edge> kept = random_forest(rng, oldest, n, rng() % (2 * n));
    std::vector<Edge> added;
    const std::size_t new_edges = rng() % (3 * n);
    for (std::size_t k = 0; k < new_edges; ++k) {
      const auto a = static_cast<std::uint32_t>(rng() % n);
      const auto b = static_cast<std::uint32_t>(rng() % n);
      if (a != b) added.push_back(Edge{oldest + std::min(a, b), oldest + std::max(a, b)});
    }
    INFO("round " << round << ", n " << n << ", kept " << kept.size() << ", new " << added.size());
    // Capacity: exactly the window (the tightest the engine allows), or more.
    check_fold(kept, added, oldest, n, round % 2 == 0 ? n : n + n / 8);
  }
}

TEST_CASE("the in-place merge moves kept edges aside when the new forest outgrows the gap") {
  // Stars: k leaves, each linked to its old centre only (the kept forest:
  // k edges of the centre's age). New points chain the leaves with younger
  // edges, which Kruskal accepts first (2k - 1 per star), before it
  // rejects k - 1 kept edges of each star. With the capacity at the window,
  // the writes reach the kept edges not read yet: the queue must take them.
  const std::uint32_t stars = 40;
  const std::uint32_t k = 5;
  // Handles: centres first, then the leaves, then the new points.
  const std::uint32_t n = stars * (1 + 2 * k);
  const sc::PointHandle oldest = 0xFFFFFFF0u;  // across the wrap, too
  const auto centre = [&](std::uint32_t s) { return oldest + s; };
  const auto leaf = [&](std::uint32_t s, std::uint32_t i) { return oldest + stars + s * k + i; };
  const auto fresh = [&](std::uint32_t s, std::uint32_t i) { return oldest + stars + stars * k + s * k + i; };
  std::vector<Edge> kept;  // increasing age: the younger centres first
  for (std::uint32_t s = stars; s-- > 0;) {
    for (std::uint32_t i = 0; i < k; ++i) kept.push_back(Edge{centre(s), leaf(s, i)});
  }
  std::vector<Edge> added;
  for (std::uint32_t s = 0; s < stars; ++s) {
    for (std::uint32_t i = 0; i < k; ++i) {
      added.push_back(Edge{leaf(s, i), fresh(s, i)});
      if (i + 1 < k) added.push_back(Edge{fresh(s, i), fresh(s, i + 1)});
    }
  }
  const std::size_t moved = check_fold(kept, added, oldest, n, n);
  CHECK(moved > 0);
  // With room for both, nothing moves.
  CHECK(check_fold(kept, added, oldest, n, n + kept.size() + added.size()) == 0);
}
