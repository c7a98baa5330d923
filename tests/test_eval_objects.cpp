// SPDX-License-Identifier: MIT
// Unit tests of the object metrics for a pipeline that removes ground and
// ceiling (streamclust::eval::object_metrics and its parts): hand-made frames
// whose values are worked out in the comments (a split, an object glued to a
// wall or to the floor, ground taken for an object and the reverse, 79 / 80 /
// 81 % around the thresholds), degenerate frames, input errors, relabelling
// invariance, a brute-force oracle on seeded random frames, and averaging.

#include <doctest/doctest.h>

#include "support/approx.hpp"
#include "support/invalid_argument.hpp"

#include <streamclust/eval/metrics.hpp>
#include <streamclust/surface_class.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace ev = streamclust::eval;
using streamclust::SurfaceClass;

namespace {

using Labels = std::vector<std::int64_t>;
using streamclust::test::invalid_argument_message;
using streamclust::test::near;

constexpr SurfaceClass kObject = SurfaceClass::object;
constexpr SurfaceClass kGround = SurfaceClass::ground;
constexpr SurfaceClass kWall = SurfaceClass::wall;
constexpr SurfaceClass kCeiling = SurfaceClass::ceiling;
constexpr std::int64_t kG = ev::kClassedGround;    // -2
constexpr std::int64_t kC = ev::kClassedCeiling;  // -3
constexpr std::int64_t kW = ev::kClassedWall;     // -4
constexpr std::int64_t kU = ev::kUnlabelled;       // -1

/// One frame: per point its truth instance, truth class and prediction.
struct Frame {
  Labels instance;
  std::vector<SurfaceClass> cls;
  Labels predicted;

  /// `count` points of truth (instance, c) predicted `p`.
  Frame& add(std::int64_t inst, SurfaceClass c, std::int64_t p, std::size_t count) {
    instance.insert(instance.end(), count, inst);
    cls.insert(cls.end(), count, c);
    predicted.insert(predicted.end(), count, p);
    return *this;
  }
  ev::ObjectMetrics metrics(const ev::MetricOptions& options = {}) const {
    return ev::object_metrics(instance, cls, predicted, options);
  }
};

/// The outcome counts of a StrictObjectRates, for one-line comparisons.
struct Outcomes {
  std::size_t objects, correct, over, under, missed, both;
  bool operator==(const Outcomes& o) const {
    return objects == o.objects && correct == o.correct && over == o.over && under == o.under &&
           missed == o.missed && both == o.both;
  }
};
Outcomes outcomes(const ev::StrictObjectRates& r) {
  return {r.objects,         r.correct_objects, r.over_segmented_objects, r.under_segmented_objects,
          r.missed_objects,  r.over_and_under_objects};
}
doctest::String toString(const Outcomes& o) {
  const std::string s = "{objects " + std::to_string(o.objects) + ", correct " + std::to_string(o.correct) +
                        ", over " + std::to_string(o.over) + ", under " + std::to_string(o.under) + ", missed " +
                        std::to_string(o.missed) + ", both " + std::to_string(o.both) + "}";
  return doctest::String(s.c_str());
}

void check_scores(const ev::ClassScores& s, std::uint64_t tp, std::uint64_t fp, std::uint64_t fn, double precision,
                  double recall, double f1) {
  CHECK(s.true_positives == tp);
  CHECK(s.false_positives == fp);
  CHECK(s.false_negatives == fn);
  CHECK(s.precision == near(precision));
  CHECK(s.recall == near(recall));
  CHECK(s.f1 == near(f1));
}

// ------------------------------------------------------------ brute-force oracle

/// Strict outcomes straight from the definition, with nested maps and exact
/// integer fraction tests (n >= num/den * total  <=>  den n >= num total):
/// correct iff SOME cluster d holds >= a of g and >= b of d is g; over iff
/// no cluster holds >= a of g; under iff every cluster holding the most of g
/// has < b of its points from g; missed iff 2 * (points outside) > |g|.
Outcomes oracle_outcomes(const Frame& f, std::uint64_t a_num, std::uint64_t a_den, std::uint64_t b_num,
                         std::uint64_t b_den, std::size_t min_points) {
  std::map<std::int64_t, std::map<std::int64_t, std::uint64_t>> rows;  // g -> d -> n(g, d)
  std::map<std::int64_t, std::uint64_t> cluster_size;
  for (std::size_t i = 0; i < f.instance.size(); ++i) {
    if (f.instance[i] < 0) continue;
    const std::int64_t d = f.predicted[i] < 0 ? -1 : f.predicted[i];
    if (d >= 0) ++cluster_size[d];
    if (f.instance[i] > 0) ++rows[f.instance[i]][d];
  }
  Outcomes o{0, 0, 0, 0, 0, 0};
  for (const auto& [g, row] : rows) {
    std::uint64_t size = 0;
    for (const auto& kv : row) size += kv.second;
    if (size < std::max<std::size_t>(min_points, 1)) continue;
    ++o.objects;
    const auto outside = row.count(-1) ? row.at(-1) : 0;
    if (2 * outside > size) {
      ++o.missed;
      continue;
    }
    bool one_good = false, one_big = false;
    std::uint64_t most = 0;
    for (const auto& [d, n] : row) {
      if (d < 0) continue;
      most = std::max(most, n);
      one_big = one_big || a_den * n >= a_num * size;
      one_good = one_good || (a_den * n >= a_num * size && b_den * n >= b_num * cluster_size[d]);
    }
    bool all_impure = true;
    for (const auto& [d, n] : row) {
      if (d >= 0 && n == most && b_den * n >= b_num * cluster_size[d]) all_impure = false;
    }
    const bool over = !one_big, under = all_impure;
    o.over += over ? 1u : 0u;
    o.under += under ? 1u : 0u;
    o.both += (over && under) ? 1u : 0u;
    o.correct += one_good ? 1u : 0u;
    if (one_good != (!over && !under)) o.correct += 1000;  // the definitions disagree: fail loudly
  }
  return o;
}

/// Seeded random frame: objects 1..6 of random sizes, structure of every
/// class, ignored points; predictions follow the truth with random splits,
/// merges with structure and (but in every 4th frame) random losses,
/// misclassifications and noise clusters.
Frame random_frame(std::uint32_t seed) {
  std::mt19937 rng(seed);  // mt19937's output sequence is fixed by the standard
  Frame f;
  const std::size_t n = 150 + rng() % 250;
  for (std::size_t i = 0; i < n; ++i) {
    const auto r = rng();
    const std::int64_t inst = static_cast<std::int64_t>(r % 8) - 1;  // -1 .. 6
    SurfaceClass c = kObject;
    if (inst <= 0) c = static_cast<SurfaceClass>((r >> 3) % 4);  // stuff, ground, wall, ceiling
    std::int64_t p = 0;
    const auto roll = seed % 4 == 0 ? 19 : (r >> 6) % 20;  // every 4th frame without noise
    if (roll == 0) {
      p = kU;
    } else if (roll == 1) {
      p = kG;
    } else if (roll == 2) {
      p = kC;
    } else if (roll == 3) {
      p = static_cast<std::int64_t>((r >> 11) % 12);  // noise cluster
    } else if (inst > 0) {
      // Object 1 stays whole, the others split by a seed-dependent share.
      p = 100 + inst * 2 + (inst > 1 && ((r >> 16) % 8) < (seed % 5) ? 1 : 0);
    } else if (c == kGround) {
      p = ((r >> 16) % 6 == 0) ? 104 : kG;  // some ground glued to object 2
    } else if (c == kCeiling) {
      p = kC;
    } else {
      p = ((r >> 16) % 3 == 0) ? 106 : 50;  // some wall / stuff glued to object 3
    }
    f.add(inst, c, p, 1);
  }
  return f;
}

/// The frame with every predicted cluster id and every object instance id
/// mapped through a seeded bijection (negative values kept).
Frame relabelled(const Frame& f, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<std::int64_t> perm(400);
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  Frame out = f;
  for (auto& p : out.predicted) {
    if (p >= 0) p = 7 * perm[static_cast<std::size_t>(p)] + 3;
  }
  for (auto& g : out.instance) {
    if (g > 0) g = 1 + perm[static_cast<std::size_t>(g)];
  }
  return out;
}

}  // namespace

// ======================================================== degenerate frames

TEST_CASE("object_metrics: empty frame") {
  const auto m = Frame{}.metrics();
  CHECK(m.points == 0);
  CHECK(m.evaluated_points == 0);
  CHECK(m.object_points == 0);
  CHECK(outcomes(m.objects) == Outcomes{0, 0, 0, 0, 0, 0});
  CHECK(m.objects.correct == 0.0);  // no object: every rate 0
  CHECK(m.object_point_coverage == 1.0);
  check_scores(m.ground, 0, 0, 0, 1, 1, 1);
  check_scores(m.ceiling, 0, 0, 0, 1, 1, 1);
  CHECK(m.adjusted_rand_index == 1.0);
}

TEST_CASE("object_metrics: all ground, classed ground or taken for an object") {
  SUBCASE("classed ground") {
    const auto m = Frame{}.add(0, kGround, kG, 100).metrics();
    CHECK(m.points == 100);
    CHECK(m.evaluated_points == 100);
    CHECK(m.objects.objects == 0);
    check_scores(m.ground, 100, 0, 0, 1, 1, 1);
    check_scores(m.ceiling, 0, 0, 0, 1, 1, 1);
    CHECK(m.object_point_coverage == 1.0);
    CHECK(m.adjusted_rand_index == 1.0);
  }
  SUBCASE("one cluster: nothing classed ground, all of it missed") {
    const auto m = Frame{}.add(0, kGround, 4, 100).metrics();
    CHECK(m.objects.objects == 0);
    check_scores(m.ground, 0, 0, 100, 1, 0, 0);  // precision 1: nothing classed ground
  }
}

// ========================================================= hand-made frames

TEST_CASE("object_metrics: perfect prediction gives correct 1, coverage 1, F1 1, ARI 1") {
  Frame f;
  f.add(1, kObject, 10, 30).add(2, kObject, 11, 20).add(3, kObject, 12, 10);
  f.add(0, kGround, kG, 80).add(0, kCeiling, kC, 40).add(0, kWall, 50, 25).add(0, kWall, kU, 5);
  f.add(0, kObject, 51, 7);  // stuff (instance 0, class object) in a cluster of its own
  const auto m = f.metrics();
  CHECK(outcomes(m.objects) == Outcomes{3, 3, 0, 0, 0, 0});
  CHECK(m.objects.correct == 1.0);
  CHECK(m.object_points == 60);
  CHECK(m.object_point_coverage == 1.0);
  check_scores(m.ground, 80, 0, 0, 1, 1, 1);
  check_scores(m.ceiling, 40, 0, 0, 1, 1, 1);
  CHECK(m.adjusted_rand_index == 1.0);
}

TEST_CASE("object_metrics: one object split 50 / 50 is over-segmented, ARI 0") {
  const auto m = Frame{}.add(1, kObject, 3, 50).add(1, kObject, 4, 50).metrics();
  CHECK(outcomes(m.objects) == Outcomes{1, 0, 1, 0, 0, 0});
  CHECK(m.objects.over_segmented == 1.0);
  // n = 100, A = C(100,2) = 4950, B = 2 C(50,2) = 2450 = X, N = 4950: E = A B / N = 2450 = X -> 0
  CHECK(m.adjusted_rand_index == 0.0);
}

TEST_CASE("object_metrics: object glued to a wall: 80 % purity is correct, 79.4 % under-segmented") {
  // 100 object points + 25 wall points in cluster 7: 100 / 125 = 0.8 exactly -> correct
  const auto ok = Frame{}.add(1, kObject, 7, 100).add(0, kWall, 7, 25).add(0, kWall, kU, 10).metrics();
  CHECK(outcomes(ok.objects) == Outcomes{1, 1, 0, 0, 0, 0});
  // 26 wall points: 100 / 126 = 0.794 < 0.8 -> under-segmented, not over (it holds 100 % of the object)
  const auto glued = Frame{}.add(1, kObject, 7, 100).add(0, kWall, 7, 26).add(0, kWall, kU, 9).metrics();
  CHECK(outcomes(glued.objects) == Outcomes{1, 0, 0, 1, 0, 0});
  CHECK(glued.objects.under_segmented == 1.0);
  check_scores(glued.ground, 0, 0, 0, 1, 1, 1);  // walls are not ground
  CHECK(glued.adjusted_rand_index == 1.0);        // ARI sees object points only
}

TEST_CASE("object_metrics: object glued to the floor") {
  // 20 of 200 ground points in the object's cluster: purity 100 / 120 = 0.83 -> correct;
  // ground TP 180, FN 20: precision 1, recall 0.9, F1 = 360 / 380 = 18 / 19
  const auto ok = Frame{}.add(1, kObject, 7, 100).add(0, kGround, 7, 20).add(0, kGround, kG, 180).metrics();
  CHECK(outcomes(ok.objects) == Outcomes{1, 1, 0, 0, 0, 0});
  check_scores(ok.ground, 180, 0, 20, 1, 0.9, 18.0 / 19.0);
  // 30 ground points: 100 / 130 = 0.77 -> under-segmented; recall 0.85, F1 = 340 / 370
  const auto glued = Frame{}.add(1, kObject, 7, 100).add(0, kGround, 7, 30).add(0, kGround, kG, 170).metrics();
  CHECK(outcomes(glued.objects) == Outcomes{1, 0, 0, 1, 0, 0});
  check_scores(glued.ground, 170, 0, 30, 1, 0.85, 340.0 / 370.0);
}

TEST_CASE("object_metrics: ground taken for an object") {
  // Half of the ground clustered on its own (cluster 5), an object (cluster 6) untouched:
  // ground TP 50, FN 50: precision 1, recall 0.5, F1 = 100 / 150
  const auto m =
      Frame{}.add(0, kGround, 5, 50).add(0, kGround, kG, 50).add(1, kObject, 6, 20).metrics();
  CHECK(outcomes(m.objects) == Outcomes{1, 1, 0, 0, 0, 0});  // a ground-only cluster does not touch the object
  check_scores(m.ground, 50, 0, 50, 1, 0.5, 2.0 / 3.0);
  CHECK(m.object_point_coverage == 1.0);
  CHECK(m.adjusted_rand_index == 1.0);
}

TEST_CASE("object_metrics: object taken for ground") {
  SUBCASE("60 % classed ground: missed") {
    // object: 60 points -2, 40 in cluster 1; 100 ground points -2.
    // ground TP 100, FP 60: precision 100 / 160, recall 1, F1 = 200 / 260
    const auto m = Frame{}.add(1, kObject, kG, 60).add(1, kObject, 1, 40).add(0, kGround, kG, 100).metrics();
    CHECK(outcomes(m.objects) == Outcomes{1, 0, 0, 0, 1, 0});  // missed is exclusive
    CHECK(m.objects.missed == 1.0);
    CHECK(m.object_point_coverage == near(0.4));
    CHECK(m.object_points_classed_structure == 60);
    check_scores(m.ground, 100, 60, 0, 0.625, 1, 10.0 / 13.0);
  }
  SUBCASE("40 % classed ground: over-segmented (incomplete)") {
    const auto m = Frame{}.add(1, kObject, kG, 40).add(1, kObject, 1, 60).metrics();
    CHECK(outcomes(m.objects) == Outcomes{1, 0, 1, 0, 0, 0});
    CHECK(m.object_point_coverage == near(0.6));
    check_scores(m.ground, 0, 40, 0, 0, 1, 0);  // no ground in truth, 40 points classed ground
  }
}

TEST_CASE("object_metrics: ARI counts each point classed ground as a singleton") {
  // truth {1,1,1,1,2,2} vs {0,0,-2,-2,1,1}. Singletons: X = 1 + 1 = 2, A = 6 + 1 = 7,
  // B = 1 + 1 = 2, N = 15: ARI = (2 - 14/15) / (9/2 - 14/15) = (16/15) / (107/30) = 32/107.
  // (One "structure" label would give B = 3, X = 3: (3 - 1.4) / (5 - 1.4) = 4/9.)
  const auto m = Frame{}.add(1, kObject, 0, 2).add(1, kObject, kG, 2).add(2, kObject, 1, 2).metrics();
  CHECK(m.adjusted_rand_index == near(32.0 / 107.0));
  // A single object classed ground entirely: 4 singletons vs one instance -> ARI 0, not 1.
  const auto lost = Frame{}.add(1, kObject, kG, 4).metrics();
  CHECK(lost.adjusted_rand_index == 0.0);
}

TEST_CASE("object_metrics: two objects in one cluster are both under-segmented") {
  const auto m = Frame{}.add(1, kObject, 2, 50).add(2, kObject, 2, 50).metrics();
  CHECK(outcomes(m.objects) == Outcomes{2, 0, 0, 2, 0, 0});
  CHECK(m.objects.under_segmented == 1.0);
}

TEST_CASE("object_metrics: over and under at once, and how the rates add up") {
  // Object 1: 60 in cluster 8, 40 in cluster 9; object 2: 40 in cluster 8 (|8| = 100).
  // Object 1: 60 < 80 -> over; 60 / 100 < 0.8 -> under: both.
  // Object 2: all of it in cluster 8 (not over), 40 / 100 purity -> under.
  const auto m = Frame{}.add(1, kObject, 8, 60).add(1, kObject, 9, 40).add(2, kObject, 8, 40).metrics();
  CHECK(outcomes(m.objects) == Outcomes{2, 0, 1, 2, 0, 1});
  const auto& r = m.objects;
  CHECK(r.over_and_under == near(0.5));
  CHECK(r.correct + r.missed + r.over_segmented + r.under_segmented - r.over_and_under == near(1.0));
}

TEST_CASE("object_metrics: 79 % / 80 % / 81 % around the completeness threshold") {
  const auto at = [](std::size_t in_main, const ev::MetricOptions& options) {
    return Frame{}.add(1, kObject, 3, in_main).add(1, kObject, 4, 100 - in_main).metrics(options).objects;
  };
  const ev::MetricOptions defaults;
  CHECK(outcomes(at(81, defaults)) == Outcomes{1, 1, 0, 0, 0, 0});
  CHECK(outcomes(at(80, defaults)) == Outcomes{1, 1, 0, 0, 0, 0});  // exactly 80 %: correct
  CHECK(outcomes(at(79, defaults)) == Outcomes{1, 0, 1, 0, 0, 0});
  ev::MetricOptions stricter;
  stricter.strict_object_fraction = 0.85;
  CHECK(outcomes(at(81, stricter)) == Outcomes{1, 0, 1, 0, 0, 0});
  CHECK(outcomes(at(85, stricter)) == Outcomes{1, 1, 0, 0, 0, 0});
  // The remainder lost (unlabelled) instead of split counts the same way.
  const auto lost = Frame{}.add(1, kObject, 3, 79).add(1, kObject, kU, 21).metrics().objects;
  CHECK(outcomes(lost) == Outcomes{1, 0, 1, 0, 0, 0});
}

TEST_CASE("object_metrics: 79 % / 81 % around the purity threshold") {
  const auto with_wall = [](std::size_t wall, const ev::MetricOptions& options) {
    return Frame{}.add(1, kObject, 3, 100).add(0, kWall, 3, wall).metrics(options).objects;
  };
  const ev::MetricOptions defaults;
  CHECK(outcomes(with_wall(24, defaults)) == Outcomes{1, 1, 0, 0, 0, 0});  // 100 / 124 = 80.6 %
  CHECK(outcomes(with_wall(26, defaults)) == Outcomes{1, 0, 0, 1, 0, 0});  // 100 / 126 = 79.4 %
  ev::MetricOptions lenient;
  lenient.strict_purity_fraction = 0.75;
  CHECK(outcomes(with_wall(26, lenient)) == Outcomes{1, 1, 0, 0, 0, 0});
  CHECK(outcomes(with_wall(34, lenient)) == Outcomes{1, 0, 0, 1, 0, 0});  // 100 / 134 = 74.6 %
}

TEST_CASE("object_metrics: missed when strictly more than half is outside any cluster") {
  // Outside = unlabelled + classed ground + classed ceiling (+ other negative ids).
  const auto half = Frame{}
                        .add(1, kObject, kU, 20)
                        .add(1, kObject, kG, 20)
                        .add(1, kObject, kC, 10)
                        .add(1, kObject, 4, 50)
                        .metrics();
  CHECK(outcomes(half.objects) == Outcomes{1, 0, 1, 0, 0, 0});  // 50 outside: not missed, 50 % held -> over
  const auto more = Frame{}
                        .add(1, kObject, kU, 20)
                        .add(1, kObject, kG, 20)
                        .add(1, kObject, -7, 11)
                        .add(1, kObject, 4, 49)
                        .metrics();
  CHECK(outcomes(more.objects) == Outcomes{1, 0, 0, 0, 1, 0});
  CHECK(more.object_points_classed_structure == 20);  // -1 and -7 are unlabelled, not classed
  CHECK(more.object_point_coverage == near(0.8));
}

TEST_CASE("object_metrics: a tie for the largest piece is judged on the purer cluster, whatever the ids") {
  // Object 1: 5 points in a pure cluster, 5 in a cluster with 10 wall points. Over (5 < 8);
  // under only if the purer of the two tied clusters were impure: it is not.
  for (const auto& ids : {std::pair<std::int64_t, std::int64_t>{3, 8}, std::pair<std::int64_t, std::int64_t>{8, 3}}) {
    const std::int64_t pure = ids.first, mixed = ids.second;
    const auto m =
        Frame{}.add(1, kObject, pure, 5).add(1, kObject, mixed, 5).add(0, kWall, mixed, 10).metrics();
    CHECK(outcomes(m.objects) == Outcomes{1, 0, 1, 0, 0, 0});
  }
}

TEST_CASE("object_metrics: ignored points count nowhere") {
  Frame f;
  f.add(1, kObject, 7, 100).add(-1, kWall, 7, 50);  // would make the cluster 2/3 pure
  f.add(-1, kGround, kG, 30).add(-1, kCeiling, 9, 30).add(-4, kObject, kG, 5);
  const auto m = f.metrics();
  CHECK(m.points == 215);
  CHECK(m.evaluated_points == 100);
  CHECK(m.object_points == 100);
  CHECK(outcomes(m.objects) == Outcomes{1, 1, 0, 0, 0, 0});
  check_scores(m.ground, 0, 0, 0, 1, 1, 1);
  check_scores(m.ceiling, 0, 0, 0, 1, 1, 1);
  CHECK(m.object_point_coverage == 1.0);
}

TEST_CASE("object_metrics: ceiling and ground scores with confusions") {
  // Ceiling 40: 30 classed ceiling, 10 classed ground; ground 60 classed ground; wall 10 classed ceiling.
  // ground: TP 60, FP 10, FN 0 -> precision 6/7, recall 1, F1 120/130
  // ceiling: TP 30, FP 10, FN 10 -> 0.75, 0.75, 0.75
  Frame f;
  f.add(0, kCeiling, kC, 30).add(0, kCeiling, kG, 10).add(0, kGround, kG, 60).add(0, kWall, kC, 10);
  const auto m = f.metrics();
  check_scores(m.ground, 60, 10, 0, 6.0 / 7.0, 1, 12.0 / 13.0);
  check_scores(m.ceiling, 30, 10, 10, 0.75, 0.75, 0.75);
  // A frame with no ceiling where 5 points are classed ceiling: precision 0, recall 1, F1 0.
  const auto no_ceiling = Frame{}.add(0, kWall, kC, 5).add(0, kWall, 2, 5).metrics();
  check_scores(no_ceiling.ceiling, 0, 5, 0, 0, 1, 0);
}

TEST_CASE("object_metrics: walls in their own class: wall precision / recall, ground with walls apart") {
  // Wall 50: 30 classed wall, 10 classed ground, 10 in a cluster. Ground 60:
  // 50 classed ground, 5 classed wall, 5 unlabelled. Object 40: 36 in its
  // own cluster, 4 classed wall.
  // wall:   TP 30, FP 5 + 4, FN 10 + 10 -> precision 30/39, recall 0.6, F1 60/89
  // ground: TP 50, FP 10 (the wall called ground), FN 5 (the ground called wall) + 5 -> 5/6, 5/6, 5/6
  Frame f;
  f.add(0, kWall, kW, 30).add(0, kWall, kG, 10).add(0, kWall, 7, 10);
  f.add(0, kGround, kG, 50).add(0, kGround, kW, 5).add(0, kGround, kU, 5);
  f.add(1, kObject, 9, 36).add(1, kObject, kW, 4);
  const auto m = f.metrics();
  check_scores(m.wall, 30, 9, 20, 30.0 / 39.0, 0.6, 60.0 / 89.0);
  check_scores(m.ground, 50, 10, 10, 5.0 / 6.0, 5.0 / 6.0, 5.0 / 6.0);
  check_scores(m.ceiling, 0, 0, 0, 1, 1, 1);
  CHECK(m.object_points_classed_structure == 4);
  CHECK(m.object_point_coverage == near(0.9));
  CHECK(outcomes(m.objects) == Outcomes{1, 1, 0, 0, 0, 0});  // 36 of 40 in a pure cluster
  CHECK(ev::is_classed_structure(kW));
  CHECK_FALSE(ev::is_classed_structure(-5));
  CHECK_FALSE(ev::is_classed_structure(kU));

  // Averaged: per-frame means and pooled counts of the wall scores.
  ev::ObjectMetricsAverage average;
  average.add(m);
  average.add(Frame{}.add(0, kWall, kW, 10).add(0, kGround, kG, 10).metrics());  // a perfect frame
  check_scores(average.pooled_wall(), 40, 9, 20, 40.0 / 49.0, 40.0 / 60.0, 80.0 / 109.0);
  CHECK(average.mean().wall_f1 == near(0.5 * (60.0 / 89.0 + 1.0)));
  CHECK(average.mean().wall_precision == near(0.5 * (30.0 / 39.0 + 1.0)));
  CHECK(average.mean().wall_recall == near(0.5 * (0.6 + 1.0)));
}

TEST_CASE("RangeCoverage: object points kept per range band, pooled over frames") {
  using ev::RangeCoverage;
  CHECK(RangeCoverage::band_of(0.0) == 0);
  CHECK(RangeCoverage::band_of(9.999) == 0);
  CHECK(RangeCoverage::band_of(10.0) == 1);  // a band's lower edge belongs to it
  CHECK(RangeCoverage::band_of(29.99) == 1);
  CHECK(RangeCoverage::band_of(30.0) == 2);
  CHECK(RangeCoverage::band_of(400.0) == 2);
  RangeCoverage bands;
  for (std::size_t b = 0; b < RangeCoverage::kBands; ++b) CHECK(bands.coverage(b) == 1.0);  // nothing seen
  // Near: 4 object points, one classed ground. Middle: 2, one classed wall,
  // one unlabelled (still kept). Far: 2, one classed ceiling. Structure
  // and ignored points count nowhere.
  const Labels instance{1, 1, 1, 1, 2, 2, 3, 3, 0, 0, -1};
  const Labels predicted{5, 5, 5, kG, kW, kU, 8, kC, kG, 5, kG};
  const std::vector<float> range{2.0f, 3.0f, 9.0f, 1.0f, 12.0f, 29.0f, 31.0f, 35.0f, 15.0f, 40.0f, 50.0f};
  bands.add(instance, predicted, range);
  CHECK(bands.object_points(0) == 4);
  CHECK(bands.kept(0) == 3);
  CHECK(bands.coverage(0) == near(0.75));
  CHECK(bands.coverage(1) == near(0.5));
  CHECK(bands.coverage(2) == near(0.5));
  // A second frame, all kept: the counts pool.
  bands.add({4, 4}, {1, 1}, {45.0f, 50.0f});
  CHECK(bands.object_points(2) == 4);
  CHECK(bands.coverage(2) == near(0.75));
  CHECK(bands.coverage(0) == near(0.75));
  CHECK_THROWS_AS(bands.add({1}, {1, 2}, {1.0f, 2.0f}), std::invalid_argument);
  CHECK_THROWS_AS(bands.add({1, 2}, {1, 2}, {1.0f}), std::invalid_argument);
}

TEST_CASE("object_metrics: min_points leaves small objects unrated") {
  ev::MetricOptions options;
  options.min_points = 10;
  const auto m = Frame{}.add(1, kObject, 3, 9).add(2, kObject, 4, 5).add(2, kObject, 5, 5).metrics(options);
  // object 1 (9 points) is not rated; object 2 (10 points) is, and is split 50 / 50
  CHECK(outcomes(m.objects) == Outcomes{1, 0, 1, 0, 0, 0});
  CHECK(m.object_points == 19);  // the other metrics still see every object point
}

TEST_CASE("object_metrics: parts agree with the single-purpose functions") {
  const Frame f = random_frame(7);
  ev::MetricOptions options;
  options.ari_include_structure = true;  // object_metrics' ARI is on object points regardless
  const auto m = f.metrics(options);
  CHECK(outcomes(m.objects) == outcomes(ev::strict_object_rates(f.instance, f.predicted)));
  CHECK(m.adjusted_rand_index == ev::adjusted_rand_index(f.instance, f.predicted));
  const auto s = ev::surface_scores(f.instance, f.cls, f.predicted);
  CHECK(m.ground.f1 == s.ground.f1);
  CHECK(m.object_point_coverage == s.object_point_coverage);
}

// ============================================================== properties

TEST_CASE("object_metrics: brute-force oracle on seeded random frames") {
  struct Fractions {
    std::uint64_t a_num, a_den, b_num, b_den;
  };
  for (const Fractions fr : {Fractions{4, 5, 4, 5}, Fractions{3, 5, 9, 10}, Fractions{1, 1, 1, 1}}) {
    ev::MetricOptions options;
    options.strict_object_fraction = static_cast<double>(fr.a_num) / static_cast<double>(fr.a_den);
    options.strict_purity_fraction = static_cast<double>(fr.b_num) / static_cast<double>(fr.b_den);
    options.min_points = 3;
    Outcomes total{0, 0, 0, 0, 0, 0};
    for (std::uint32_t seed = 1; seed <= 30; ++seed) {
      const Frame f = random_frame(seed);
      const auto m = f.metrics(options);
      const Outcomes expected = oracle_outcomes(f, fr.a_num, fr.a_den, fr.b_num, fr.b_den, options.min_points);
      CAPTURE(seed);
      CHECK(outcomes(m.objects) == expected);
      total.correct += expected.correct;
      total.over += expected.over;
      total.under += expected.under;
      total.missed += expected.missed;
    }
    // The frames exercise every outcome (else the comparison proves little).
    CHECK(total.correct > 0);
    CHECK(total.over > 0);
    CHECK(total.under > 0);
  }
}

TEST_CASE("object_metrics: relabelling instances and clusters changes nothing") {
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    const Frame f = random_frame(seed);
    const Frame g = relabelled(f, seed * 31u);
    const auto a = f.metrics();
    const auto b = g.metrics();
    CAPTURE(seed);
    CHECK(outcomes(a.objects) == outcomes(b.objects));
    CHECK(a.adjusted_rand_index == b.adjusted_rand_index);
    CHECK(a.object_point_coverage == b.object_point_coverage);
    CHECK(a.ground.f1 == b.ground.f1);
    CHECK(a.ceiling.f1 == b.ceiling.f1);
  }
}

// ================================================================== errors

TEST_CASE("object_metrics: invalid inputs and options throw std::invalid_argument") {
  const Labels inst{1, 0}, pred{3, kG};
  const std::vector<SurfaceClass> cls{kObject, kGround};
  CHECK(invalid_argument_message([&] { ev::object_metrics(inst, {kObject}, pred); }).find("1 labels") !=
        std::string::npos);
  CHECK_THROWS_AS(ev::object_metrics(inst, cls, Labels{3}), std::invalid_argument);
  // An object instance must have the class object.
  const std::string m1 = invalid_argument_message([&] { ev::object_metrics(Labels{1, 5}, {kObject, kGround}, pred); });
  CHECK(m1.find("point 1") != std::string::npos);
  CHECK(m1.find("instance 5") != std::string::npos);
  CHECK(m1.find("ground") != std::string::npos);
  // Not an enumerator.
  const std::string m2 =
      invalid_argument_message([&] { ev::object_metrics(inst, {kObject, static_cast<SurfaceClass>(7)}, pred); });
  CHECK(m2.find("truth class 7") != std::string::npos);
  // Fractions must be in (0.5, 1].
  ev::MetricOptions half;
  half.strict_object_fraction = 0.5;
  const std::string m3 = invalid_argument_message([&] { ev::object_metrics(inst, cls, pred, half); });
  CHECK(m3.find("strict_object_fraction") != std::string::npos);
  CHECK(m3.find("(0.5, 1]") != std::string::npos);
  ev::MetricOptions nan;
  nan.strict_purity_fraction = std::numeric_limits<double>::quiet_NaN();
  CHECK(invalid_argument_message([&] { ev::strict_object_rates(inst, pred, nan); }).find("strict_purity_fraction") !=
        std::string::npos);
  ev::MetricOptions one;
  one.strict_object_fraction = 1.0;
  one.strict_purity_fraction = 1.0;
  CHECK_NOTHROW(ev::object_metrics(inst, cls, pred, one));
}

// =============================================================== averaging

TEST_CASE("ObjectMetricsAverage: per-frame means and pooled counts") {
  // A: one correct object; ground TP 10.   B: no object; 5 wall points classed ground (FP 5).
  // C: two objects, one correct, one missed (classed ground: FP 6); ground TP 4, FN 4.
  const auto a = Frame{}.add(1, kObject, 1, 10).add(0, kGround, kG, 10).metrics();
  const auto b = Frame{}.add(0, kWall, kG, 5).add(0, kWall, 2, 5).metrics();
  const auto c = Frame{}
                     .add(1, kObject, 1, 10)
                     .add(2, kObject, kG, 6)
                     .add(0, kGround, kG, 4)
                     .add(0, kGround, kU, 4)
                     .metrics();
  check_scores(b.ground, 0, 5, 0, 0, 1, 0);
  check_scores(c.ground, 4, 6, 4, 0.4, 0.5, 8.0 / 18.0);
  ev::ObjectMetricsAverage avg;
  CHECK(avg.mean().frames == 0);
  CHECK(avg.pooled_ground().f1 == 1.0);
  avg.add(a);
  avg.add(b);
  avg.add(c);
  const auto m = avg.mean();
  CHECK(m.frames == 3);
  CHECK(m.frames_with_objects == 2);
  CHECK(m.objects == near(1.0));              // (1 + 0 + 2) / 3
  CHECK(m.correct == near(0.75));             // (1 + 0.5) / 2: frame B has no rate
  CHECK(m.missed == near(0.25));
  CHECK(m.ground_f1 == near((1.0 + 0.0 + 8.0 / 18.0) / 3.0));
  CHECK(m.ground_precision == near((1.0 + 0.0 + 0.4) / 3.0));
  CHECK(m.object_point_coverage == near((1.0 + 1.0 + 10.0 / 16.0) / 3.0));
  CHECK(m.ari == near((1.0 + 1.0 + c.adjusted_rand_index) / 3.0));
  const auto objects = avg.pooled_objects();
  CHECK(outcomes(objects) == Outcomes{3, 2, 0, 0, 1, 0});
  CHECK(objects.correct == near(2.0 / 3.0));
  // pooled ground: TP 14, FP 11, FN 4 -> precision 14/25, recall 14/18, F1 28/43
  check_scores(avg.pooled_ground(), 14, 11, 4, 14.0 / 25.0, 14.0 / 18.0, 28.0 / 43.0);
  CHECK(avg.pooled_object_point_coverage() == near(20.0 / 26.0));
  check_scores(avg.pooled_ceiling(), 0, 0, 0, 1, 1, 1);
}
