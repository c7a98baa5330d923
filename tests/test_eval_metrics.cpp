// SPDX-License-Identifier: MIT
// Unit tests of the clustering-quality metrics (streamclust::eval): every
// metric on hand-made partitions whose values are computed by hand in the
// comments, edge cases (IoU exactly 0.5, fractions exactly at the threshold,
// degenerate inputs), relabelling invariance, and brute-force oracles on
// seeded random partitions.

#include <doctest/doctest.h>

#include "support/approx.hpp"
#include "support/invalid_argument.hpp"

#include <streamclust/eval/metrics.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace ev = streamclust::eval;

namespace {

using Labels = std::vector<std::int64_t>;
using streamclust::test::invalid_argument_message;
using streamclust::test::near;

const double kLn2 = std::log(2.0);
const double kLn3 = std::log(3.0);

/// `count` copies of `label` appended to `v`.
void push(Labels& v, std::int64_t label, std::size_t count) { v.insert(v.end(), count, label); }

// ------------------------------------------------------------ brute-force oracles

/// ARI from the 2x2 pair-confusion counts, over all point pairs (independent
/// of the contingency formula): ARI = 2 (tp tn - fn fp) / ((tp + fn)(fn + tn) + (tp + fp)(fp + tn)).
double oracle_ari(const Labels& truth, const Labels& pred, bool include_structure) {
  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (truth[i] > 0 || (include_structure && truth[i] == 0)) used.push_back(i);
  }
  long double tp = 0, tn = 0, fp = 0, fn = 0;
  for (std::size_t a = 0; a < used.size(); ++a) {
    for (std::size_t b = a + 1; b < used.size(); ++b) {
      const auto i = used[a], j = used[b];
      const bool same_t = truth[i] == truth[j];
      const bool same_p = pred[i] >= 0 && pred[i] == pred[j];  // unlabelled: singletons
      if (same_t && same_p) tp += 1;
      else if (same_t) fn += 1;
      else if (same_p) fp += 1;
      else tn += 1;
    }
  }
  const long double den = (tp + fn) * (fn + tn) + (tp + fp) * (fp + tn);
  if (den == 0) return 1.0;
  return static_cast<double>(2 * (tp * tn - fn * fp) / den);
}

/// OSE / USE with nested maps.
ev::SegmentationEntropy oracle_entropy(const Labels& truth, const Labels& pred) {
  std::map<std::int64_t, std::map<std::int64_t, double>> by_gt, by_pred;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (truth[i] < 0) continue;
    const std::int64_t p = pred[i] < 0 ? -1 : pred[i];
    by_gt[truth[i]][p] += 1;
    by_pred[p][truth[i]] += 1;
  }
  ev::SegmentationEntropy e;
  for (const auto& [g, row] : by_gt) {
    if (g <= 0) continue;
    double size = 0;
    for (const auto& kv : row) size += kv.second;
    for (const auto& kv : row) e.over -= kv.second / size * std::log(kv.second / size);
    ++e.objects;
  }
  for (const auto& [d, col] : by_pred) {
    if (d < 0) continue;
    bool has_object = false;
    double size = 0;
    for (const auto& kv : col) {
      size += kv.second;
      has_object = has_object || kv.first > 0;
    }
    if (!has_object) continue;
    for (const auto& kv : col) e.under -= kv.second / size * std::log(kv.second / size);
    ++e.clusters;
  }
  return e;
}

/// Panoptic counts by explicit set intersection / union of every (g, d) pair.
ev::PanopticScores oracle_panoptic(const Labels& truth, const Labels& pred, std::size_t min_points) {
  std::set<std::int64_t> gts, preds;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (truth[i] > 0) gts.insert(truth[i]);
    if (truth[i] >= 0 && pred[i] >= 0) preds.insert(pred[i]);
  }
  ev::PanopticScores s;
  std::set<std::int64_t> gt_hit, pred_hit;
  double iou_sum = 0;
  for (const auto g : gts) {
    for (const auto d : preds) {
      double inter = 0, uni = 0;
      for (std::size_t i = 0; i < truth.size(); ++i) {
        if (truth[i] < 0) continue;
        const bool in_g = truth[i] == g, in_d = pred[i] == d;
        inter += (in_g && in_d) ? 1 : 0;
        uni += (in_g || in_d) ? 1 : 0;
      }
      if (inter / uni > 0.5) {
        ++s.true_positives;
        iou_sum += inter / uni;
        gt_hit.insert(g);
        pred_hit.insert(d);
      }
    }
  }
  for (const auto g : gts) {
    std::size_t size = 0;
    for (const auto t : truth) size += t == g ? 1u : 0u;
    if (!gt_hit.count(g) && size >= min_points) ++s.false_negatives;
  }
  for (const auto d : preds) {
    std::size_t size = 0, structure = 0;
    for (std::size_t i = 0; i < truth.size(); ++i) {
      if (truth[i] < 0 || pred[i] != d) continue;
      ++size;
      structure += truth[i] == 0 ? 1u : 0u;
    }
    if (!pred_hit.count(d) && size >= min_points && 2 * structure <= size) ++s.false_positives;
  }
  s.sq = s.true_positives ? iou_sum / static_cast<double>(s.true_positives) : 0.0;
  return s;
}

/// Seeded random scene: n points, truth in {-1, 0, 1..objects}, predictions
/// mostly following the truth with random splits, merges and losses.
void random_scene(std::uint32_t seed, std::size_t n, Labels& truth, Labels& pred) {
  std::mt19937 rng(seed);  // mt19937's output sequence is fixed by the standard
  truth.clear();
  pred.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const auto r = rng();
    const std::int64_t t = static_cast<std::int64_t>(r % 9) - 1;  // -1 .. 7
    std::int64_t p;
    switch ((r >> 8) % 6) {
      case 0: p = -1; break;                                          // lost
      case 1: p = static_cast<std::int64_t>((r >> 12) % 10); break;   // noise
      default: p = t < 0 ? 3 : t * 2 + static_cast<std::int64_t>((r >> 16) % 2);  // follow truth, split in two
    }
    truth.push_back(t);
    pred.push_back(p);
  }
}

}  // namespace

// ================================================================ contingency

TEST_CASE("ContingencyTable: ignored points dropped, unlabelled folded into -1, sorted layout") {
  // truth: 0 0 1 1 2 -1 -5 ; pred: -1 -7 7 7 7 3 -1
  const ev::ContingencyTable t{Labels{0, 0, 1, 1, 2, -1, -5}, Labels{-1, -7, 7, 7, 7, 3, -1}};
  CHECK(t.input_points() == 7);
  CHECK(t.evaluated_points() == 5);
  CHECK(t.ignored_points() == 2);
  CHECK(t.truth_labels() == Labels{0, 1, 2});
  CHECK(t.truth_sizes() == std::vector<std::uint64_t>{2, 2, 1});
  CHECK(t.predicted_labels() == Labels{-1, 7});  // 3 only labelled ignored points
  CHECK(t.predicted_sizes() == std::vector<std::uint64_t>{2, 3});
  REQUIRE(t.cells().size() == 3);
  CHECK(t.cells()[0].count == 2);  // (0, -1): both negative ids are one label
  CHECK(t.cells()[1].truth_index == 1);
  CHECK(t.cells()[1].predicted_index == 1);
  CHECK(t.row_begin(2) == 2);
  CHECK(t.row_end(2) == 3);
  CHECK(t.is_structure(0));
  CHECK(t.is_unlabelled(0));
  CHECK_FALSE(t.is_unlabelled(1));
}

// ======================================================================= ARI

TEST_CASE("ARI: classic contingency table computed by hand") {
  // truth {1,1,1,2,2,2} vs pred {0,0,1,1,2,2}: n_ij = [[2,1,0],[0,1,2]]
  // X = C(2,2)+C(2,2) = 2; A = 2 C(3,2) = 6; B = 3 C(2,2) = 3; N = C(6,2) = 15
  // E = 6*3/15 = 1.2; max = (6+3)/2 = 4.5; ARI = (2-1.2)/(4.5-1.2) = 0.8/3.3 = 8/33
  CHECK(ev::adjusted_rand_index(Labels{1, 1, 1, 2, 2, 2}, Labels{0, 0, 1, 1, 2, 2}) == near(8.0 / 33.0));
  // Negative: truth {1,1,2,2} vs pred {0,1,0,1}: X = 0, A = 2, B = 2, N = 6,
  // E = 4/6; max = 2; ARI = (0 - 2/3) / (2 - 2/3) = -1/2
  CHECK(ev::adjusted_rand_index(Labels{1, 1, 2, 2}, Labels{0, 1, 0, 1}) == near(-0.5));
  // A split into halves: truth {1,1,1,1} vs {5,5,6,6}: X = 2, A = 6, B = 2, N = 6: E = 2 = X -> exactly 0
  CHECK(ev::adjusted_rand_index(Labels{1, 1, 1, 1}, Labels{5, 5, 6, 6}) == 0.0);
}

TEST_CASE("ARI: unlabelled points are singletons, not one cluster") {
  // truth {1,1,2,2,2} vs pred {7,7,-1,-1,-1}; the three -1 are singletons:
  // X = C(2,2) = 1; A = 1 + 3 = 4; B = C(2,2) = 1; N = 10; E = 0.4; max = 2.5
  // ARI = 0.6 / 2.1 = 2/7.  (If -1 were one cluster the partitions would be identical: 1.)
  CHECK(ev::adjusted_rand_index(Labels{1, 1, 2, 2, 2}, Labels{7, 7, -1, -1, -1}) == near(2.0 / 7.0));
  // Any negative id is unlabelled.
  CHECK(ev::adjusted_rand_index(Labels{1, 1, 2, 2, 2}, Labels{7, 7, -1, -2, -3}) == near(2.0 / 7.0));
}

TEST_CASE("ARI: object points only by default, structure on request, ignored never") {
  const Labels truth{0, 0, 1, 1};
  const Labels pred{3, 3, 3, 3};
  // Objects only: two points of object 1, one cluster each side -> 1.
  CHECK(ev::adjusted_rand_index(truth, pred) == 1.0);
  // With structure: n_ij = [[2],[2]]: X = 2, A = 2, B = 6, N = 6: E = 2 = X -> 0.
  ev::MetricOptions with_structure;
  with_structure.ari_include_structure = true;
  CHECK(ev::adjusted_rand_index(truth, pred, with_structure) == 0.0);
  // Ignored points change nothing.
  CHECK(ev::adjusted_rand_index(Labels{1, 1, -1, 2, 2}, Labels{4, 4, 4, 5, 5}) == 1.0);
}

TEST_CASE("ARI: degenerate cases") {
  CHECK(ev::adjusted_rand_index(Labels{}, Labels{}) == 1.0);
  CHECK(ev::adjusted_rand_index(Labels{3}, Labels{-1}) == 1.0);            // one point
  CHECK(ev::adjusted_rand_index(Labels{0, 0, -1}, Labels{1, 2, 3}) == 1.0);  // no object point
  CHECK(ev::adjusted_rand_index(Labels{1, 2, 3}, Labels{-1, -1, -1}) == 1.0);  // all singletons both sides
  CHECK(ev::adjusted_rand_index(Labels{4, 4, 4}, Labels{9, 9, 9}) == 1.0);  // one cluster both sides
  // truth all singletons, prediction one cluster: X = 0, A = 0, B = 3, N = 3: E = 0, max = 1.5 -> 0
  CHECK(ev::adjusted_rand_index(Labels{1, 2, 3}, Labels{5, 5, 5}) == 0.0);
}

TEST_CASE("ARI: large inputs keep exact pair counts") {
  // 200000 points of one object split 150000 + 50000, against two objects
  // identical to the split except that 1 point moved: result close to 1, and
  // identical partitions give exactly 1 despite C(n,2) ~ 2e10 and products ~ 4e20.
  Labels truth, pred;
  push(truth, 1, 150000);
  push(truth, 2, 50000);
  pred = truth;
  CHECK(ev::adjusted_rand_index(truth, pred) == 1.0);
  pred[0] = 2;
  const double ari = ev::adjusted_rand_index(truth, pred);
  CHECK(ari < 1.0);
  CHECK(ari > 0.9999);
  // by hand: X = C(149999,2) + C(50000,2) + 0 (the moved point's cell is 1)
  // ... compared with the long-double oracle formula from pair counts:
  const long double n = 200000, a1 = 150000, a2 = 50000;
  const long double X = 149999.0L * 149998.0L / 2 + 50000.0L * 49999.0L / 2;
  const long double A = a1 * (a1 - 1) / 2 + a2 * (a2 - 1) / 2;
  const long double B = 149999.0L * 149998.0L / 2 + 50001.0L * 50000.0L / 2;
  const long double N = n * (n - 1) / 2;
  const long double E = A * B / N;
  CHECK(ari == near(static_cast<double>((X - E) / ((A + B) / 2 - E))));
}

// ============================================================ OSE / USE

TEST_CASE("entropy: perfect clustering is exactly 0") {
  const auto e = ev::segmentation_entropy(Labels{0, 0, 1, 1, 1, 2, 2}, Labels{-1, -1, 4, 4, 4, 9, 9});
  CHECK(e.over == 0.0);
  CHECK(e.under == 0.0);
  CHECK(e.objects == 2);
  CHECK(e.clusters == 2);
}

TEST_CASE("entropy: a split object adds ln 2 to OSE, the unlabelled points are ONE label") {
  // 4 points split 2+2: p = 1/2, 1/2 -> OSE = ln 2; both clusters pure -> USE = 0
  auto e = ev::segmentation_entropy(Labels{1, 1, 1, 1}, Labels{5, 5, 6, 6});
  CHECK(e.over == near(kLn2));
  CHECK(e.over_mean == near(kLn2));
  CHECK(e.under == 0.0);
  // 2 points unlabelled count like one cluster: OSE = ln 2
  e = ev::segmentation_entropy(Labels{1, 1, 1, 1}, Labels{5, 5, -1, -1});
  CHECK(e.over == near(kLn2));
  CHECK(e.clusters == 1);
  // {5, 6, -1, -1}: p = 1/4, 1/4, 1/2 -> OSE = 2 (1/4 ln 4) + 1/2 ln 2 = 1.5 ln 2
  // (unlabelled as singletons would give 4 (1/4 ln 4) = 2 ln 2)
  e = ev::segmentation_entropy(Labels{1, 1, 1, 1}, Labels{5, 6, -1, -1});
  CHECK(e.over == near(1.5 * kLn2));
  CHECK(e.under == 0.0);
  CHECK(e.clusters == 2);
}

TEST_CASE("entropy: a merge adds ln 2 to USE; structure is a GT label of USE") {
  auto e = ev::segmentation_entropy(Labels{1, 1, 2, 2}, Labels{3, 3, 3, 3});
  CHECK(e.under == near(kLn2));
  CHECK(e.over == 0.0);
  // object merged with ground: q = 1/2, 1/2
  e = ev::segmentation_entropy(Labels{0, 0, 1, 1}, Labels{3, 3, 3, 3});
  CHECK(e.under == near(kLn2));
  CHECK(e.clusters == 1);
  CHECK(e.objects == 1);
}

TEST_CASE("entropy: sums over clusters and their means") {
  // truth {1,1,1,1, 2,2, 0,0}, pred {5,5,6,6, 6,6, 6,6}
  // OSE: object 1 split 2+2 -> ln 2; object 2 whole -> 0.   OSE = ln 2, mean ln2 / 2
  // USE: cluster 5 pure -> 0; cluster 6 = {obj1: 2, obj2: 2, structure: 2} -> ln 3.  USE = ln 3, mean ln3 / 2
  const auto e = ev::segmentation_entropy(Labels{1, 1, 1, 1, 2, 2, 0, 0}, Labels{5, 5, 6, 6, 6, 6, 6, 6});
  CHECK(e.over == near(kLn2));
  CHECK(e.over_mean == near(kLn2 / 2));
  CHECK(e.under == near(kLn3));
  CHECK(e.under_mean == near(kLn3 / 2));
}

TEST_CASE("entropy: structure-only clusters excluded from USE, ignored points removed") {
  // truth {0,0,0,1,-1,-1}, pred {3,3,3,4,4,8}: cluster 3 holds only structure
  // (excluded); cluster 4 = {object 1} once its ignored point is removed (pure);
  // cluster 8 holds only an ignored point (absent).
  const auto e = ev::segmentation_entropy(Labels{0, 0, 0, 1, -1, -1}, Labels{3, 3, 3, 4, 4, 8});
  CHECK(e.under == 0.0);
  CHECK(e.clusters == 1);
  CHECK(e.over == 0.0);
  CHECK(e.objects == 1);
}

// =================================================================== panoptic

TEST_CASE("panoptic: perfect clustering") {
  // structure unlabelled or in its own cluster (100 is all structure: ignored, not FP)
  for (const auto& pred : {Labels{-1, -1, 4, 4, 4, 9, 9}, Labels{100, 100, 4, 4, 4, 9, 9}}) {
    const auto s = ev::panoptic_scores(Labels{0, 0, 1, 1, 1, 2, 2}, pred);
    CHECK(s.true_positives == 2);
    CHECK(s.false_positives == 0);
    CHECK(s.false_negatives == 0);
    CHECK(s.precision == 1.0);
    CHECK(s.recall == 1.0);
    CHECK(s.sq == 1.0);
    CHECK(s.rq == 1.0);
    CHECK(s.pq == 1.0);
  }
}

TEST_CASE("panoptic: IoU exactly 0.5 is not a match, just above is") {
  // object {a, b}, segment {a}: IoU = 1/2 -> no match; FP 1, FN 1
  auto s = ev::panoptic_scores(Labels{1, 1}, Labels{5, -1});
  CHECK(s.true_positives == 0);
  CHECK(s.false_positives == 1);
  CHECK(s.false_negatives == 1);
  CHECK(s.precision == 0.0);
  CHECK(s.recall == 0.0);
  CHECK(s.sq == 0.0);
  CHECK(s.pq == 0.0);
  // split 2+2: IoU 2/4 with both halves -> nothing matches; FP 2, FN 1; RQ = 0
  s = ev::panoptic_scores(Labels{1, 1, 1, 1}, Labels{5, 5, 6, 6});
  CHECK(s.true_positives == 0);
  CHECK(s.false_positives == 2);
  CHECK(s.false_negatives == 1);
  // object of 3, segment of 2 of them: IoU = 2/3 -> TP; SQ = 2/3, RQ = 1, PQ = 2/3
  s = ev::panoptic_scores(Labels{1, 1, 1}, Labels{5, 5, -1});
  CHECK(s.true_positives == 1);
  CHECK(s.false_negatives == 0);
  CHECK(s.sq == near(2.0 / 3.0));
  CHECK(s.rq == 1.0);
  CHECK(s.pq == near(2.0 / 3.0));
}

TEST_CASE("panoptic: structure points count in the segment area; mostly-structure segments are ignored") {
  // segment 5 = 2 object points + 1 structure point: IoU = 2 / (2 + 3 - 2) = 2/3 -> TP
  auto s = ev::panoptic_scores(Labels{1, 1, 0, 0}, Labels{5, 5, 5, -1});
  CHECK(s.true_positives == 1);
  CHECK(s.sq == near(2.0 / 3.0));
  // truth {0,0,0,1, 2,2}, pred {5,5,5,5, 6,6}: segment 5 is 3/4 structure -> ignored (not FP);
  // object 1: IoU with 5 = 1/4 -> FN; object 2 matched with IoU 1.
  // TP 1, FP 0, FN 1: P = 1, R = 1/2, SQ = 1, RQ = 1 / (1 + 0.5) = 2/3, PQ = 2/3
  s = ev::panoptic_scores(Labels{0, 0, 0, 1, 2, 2}, Labels{5, 5, 5, 5, 6, 6});
  CHECK(s.true_positives == 1);
  CHECK(s.false_positives == 0);
  CHECK(s.false_negatives == 1);
  CHECK(s.precision == 1.0);
  CHECK(s.recall == near(0.5));
  CHECK(s.rq == near(2.0 / 3.0));
  CHECK(s.pq == near(2.0 / 3.0));
  // exactly half structure still counts: truth {0,0,1,1,2}, pred {5,5,5,5,-1}:
  // IoU(1, 5) = 2/4 -> no match; FP 1 (segment 5), FN 2
  s = ev::panoptic_scores(Labels{0, 0, 1, 1, 2}, Labels{5, 5, 5, 5, -1});
  CHECK(s.true_positives == 0);
  CHECK(s.false_positives == 1);
  CHECK(s.false_negatives == 2);
  CHECK(s.rq == 0.0);
}

TEST_CASE("panoptic: two matches with partial IoU") {
  // truth {1,1,1,1, 2,2,2,2}, pred {5,5,5,6, 6,6,6,6}
  // IoU(1,5) = 3 / (4 + 3 - 3) = 0.75; IoU(2,6) = 4 / (4 + 5 - 4) = 0.8; IoU(1,6) = 1/8
  // TP 2, SQ = 0.775, RQ = 1, PQ = 0.775
  const auto s = ev::panoptic_scores(Labels{1, 1, 1, 1, 2, 2, 2, 2}, Labels{5, 5, 5, 6, 6, 6, 6, 6});
  CHECK(s.true_positives == 2);
  CHECK(s.false_positives == 0);
  CHECK(s.false_negatives == 0);
  CHECK(s.sq == near(0.775));
  CHECK(s.pq == near(0.775));
}

TEST_CASE("panoptic: min_points exempts small segments from FP / FN, not from TP") {
  // truth {1,1,1, 2, 3}, pred {5,5,5, -1, 8}: object 2 (1 point) lost,
  // object 3 (1 point) matched by segment 8 (IoU 1).
  const Labels truth{1, 1, 1, 2, 3};
  const Labels pred{5, 5, 5, -1, 8};
  ev::MetricOptions o;
  auto s = ev::panoptic_scores(truth, pred, o);  // min_points = 1: FN 1 -> RQ = 2 / (2 + 0.5) = 0.8
  CHECK(s.true_positives == 2);
  CHECK(s.false_negatives == 1);
  CHECK(s.rq == near(0.8));
  o.min_points = 2;  // object 2 too small to be a FN; the 1-point TP still counts
  s = ev::panoptic_scores(truth, pred, o);
  CHECK(s.true_positives == 2);
  CHECK(s.false_negatives == 0);
  CHECK(s.pq == 1.0);
  // a 1-point false segment: FP with min_points 1, not with 2
  s = ev::panoptic_scores(Labels{1, 1, 1, 0}, Labels{5, 5, 5, 7});  // segment 7 is all structure: ignored
  CHECK(s.false_positives == 0);
  s = ev::panoptic_scores(Labels{1, 1, 1, 1}, Labels{5, 5, 5, 7});  // IoU(1,5) = 3/4, segment 7 unmatched
  CHECK(s.false_positives == 1);
  s = ev::panoptic_scores(Labels{1, 1, 1, 1}, Labels{5, 5, 5, 7}, o);
  CHECK(s.false_positives == 0);
}

TEST_CASE("panoptic: 0/0 cases") {
  auto s = ev::panoptic_scores(Labels{}, Labels{});  // nothing at all: every score 1
  CHECK(s.precision == 1.0);
  CHECK(s.recall == 1.0);
  CHECK(s.sq == 1.0);
  CHECK(s.rq == 1.0);
  CHECK(s.pq == 1.0);
  s = ev::panoptic_scores(Labels{1, 1}, Labels{-1, -1});  // nothing predicted: precision 1, recall 0
  CHECK(s.precision == 1.0);
  CHECK(s.recall == 0.0);
  CHECK(s.pq == 0.0);
  s = ev::panoptic_scores(Labels{0, 0}, Labels{4, -1});  // no object, one structure segment: vacuous 1
  CHECK(s.false_positives == 0);
  CHECK(s.pq == 1.0);
}

// =================================================================== coverage

TEST_CASE("coverage: labelled fraction over all points, evaluated points, objects") {
  CHECK(ev::coverage(Labels{0, -1, 3, -1}) == 0.5);
  CHECK(ev::coverage(Labels{}) == 1.0);
  CHECK(ev::coverage(Labels{-1, -1}) == 0.0);
  // truth {-1,-1,1,0}, pred {-1,-1,2,-1}: all 1/4; evaluated 1/2; objects 1/1
  const Labels truth{-1, -1, 1, 0};
  const Labels pred{-1, -1, 2, -1};
  CHECK(ev::coverage(truth, pred, ev::CoverageScope::all_points) == 0.25);
  CHECK(ev::coverage(truth, pred) == 0.5);
  CHECK(ev::coverage(truth, pred, ev::CoverageScope::objects) == 1.0);
  const ev::ContingencyTable table{truth, pred};
  CHECK(ev::coverage(table) == 0.5);
  CHECK(ev::coverage(table, ev::CoverageScope::objects) == 1.0);
  CHECK_THROWS_AS(ev::coverage(table, ev::CoverageScope::all_points), std::invalid_argument);
  CHECK(ev::coverage(Labels{0, 0}, Labels{-1, -1}, ev::CoverageScope::objects) == 1.0);  // no object
}

// =============================================================== object rates

TEST_CASE("object rates: one correct, one over-, one under-segmented, one missed") {
  Labels truth, pred;
  push(truth, 1, 10), push(pred, 100, 10);                          // correct
  push(truth, 2, 6), push(pred, 200, 6);                            // over: 6 + 4
  push(truth, 2, 4), push(pred, 201, 4);
  push(truth, 3, 10), push(pred, 300, 10);                          // under: cluster 300 is
  push(truth, 0, 10), push(pred, 300, 10);                          //   half structure
  push(truth, 4, 8), push(pred, -1, 8);                             // missed: 8 of 10 lost
  push(truth, 4, 2), push(pred, 400, 2);
  push(truth, 0, 5), push(pred, -1, 5);                             // ground removed
  truth.insert(truth.end(), {-1, -1, -1}), pred.insert(pred.end(), {100, -1, 7});  // ignored
  const auto r = ev::object_rates(truth, pred);
  CHECK(r.objects == 4);
  CHECK(r.correct == 0.25);
  CHECK(r.over_segmented == 0.25);
  CHECK(r.under_segmented == 0.25);
  CHECK(r.missed == 0.25);
  CHECK(r.other == 0.0);

  // The full report on the same scene, by hand:
  const auto q = ev::evaluate(truth, pred);
  CHECK(q.points == 58);
  CHECK(q.evaluated_points == 55);
  CHECK(q.object_points == 40);
  // ARI on the 40 object points; the 8 lost points of object 4 are singletons.
  // X = C(10,2) + C(6,2) + C(4,2) + C(10,2) + C(2,2) = 45+15+6+45+1 = 112
  // A = 4 C(10,2) = 180; B (object points only) = 45+15+6+45+1 = 112; N = C(40,2) = 780
  // ARI = 2 (N X - A B) / (N A + N B - 2 A B) = 2*112*600 / (140400 + 87360 - 40320) = 134400/187440 = 560/781
  CHECK(q.adjusted_rand_index == near(560.0 / 781.0));
  // OSE = H(0.6, 0.4) + H(0.8, 0.2); USE = ln 2 (cluster 300) over 5 clusters
  const double h64 = -(0.6 * std::log(0.6) + 0.4 * std::log(0.4));
  const double h82 = -(0.8 * std::log(0.8) + 0.2 * std::log(0.2));
  CHECK(q.entropy.over == near(h64 + h82));
  CHECK(q.entropy.over_mean == near((h64 + h82) / 4));
  CHECK(q.entropy.under == near(kLn2));
  CHECK(q.entropy.clusters == 5);
  // Panoptic: TP (1,100) IoU 1 and (2,200) IoU 6/10; (3,300) IoU 10/20 = 0.5 no; (4,400) 2/10 no.
  // FP: 201, 300 (exactly half structure), 400 = 3; FN: objects 3, 4 = 2.
  // P = 2/5, R = 2/4, SQ = 0.8, RQ = 2 / (2 + 1.5 + 1) = 4/9, PQ = 3.2/9
  CHECK(q.panoptic.true_positives == 2);
  CHECK(q.panoptic.false_positives == 3);
  CHECK(q.panoptic.false_negatives == 2);
  CHECK(q.panoptic.precision == near(0.4));
  CHECK(q.panoptic.recall == near(0.5));
  CHECK(q.panoptic.sq == near(0.8));
  CHECK(q.panoptic.rq == near(4.0 / 9.0));
  CHECK(q.panoptic.pq == near(3.2 / 9.0));
  // coverage: labelled = 10+10+10+2 object + 10 structure + 2 ignored = 44 of 58;
  // evaluated 42 of 55; objects 32 of 40
  CHECK(q.coverage == near(44.0 / 58.0));
  CHECK(q.evaluated_coverage == near(42.0 / 55.0));
  CHECK(q.object_coverage == near(0.8));
  CHECK(q.objects.correct_objects == 1);
}

TEST_CASE("object rates: a merge of two objects flags both; small contamination does not") {
  // object 1 (10) + object 2 (2) in cluster 5: foreign shares 2/12 and 10/12, both >= 10 %
  auto r = ev::object_rates(Labels{1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 2}, Labels{5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5});
  CHECK(r.objects == 2);
  CHECK(r.under_segmented == 1.0);
  CHECK(r.correct == 0.0);
  // object 1: 19 points in cluster 5; object 2: 1 point in cluster 5, 9 in cluster 6.
  // object 1: foreign 1/20 = 5 % < 10 % -> correct.
  // object 2: pieces 9/10 and 1/10 (= 10 %, counts) -> over; cluster 6 pure -> not under.
  Labels truth, pred;
  push(truth, 1, 19), push(pred, 5, 19);
  push(truth, 2, 1), push(pred, 5, 1);
  push(truth, 2, 9), push(pred, 6, 9);
  r = ev::object_rates(truth, pred);
  CHECK(r.correct_objects == 1);
  CHECK(r.over_segmented_objects == 1);
  CHECK(r.under_segmented_objects == 0);
  // with a 20 % piece threshold the 1-point piece no longer counts
  ev::MetricOptions o;
  o.over_segmentation_fraction = 0.2;
  r = ev::object_rates(truth, pred, o);
  CHECK(r.correct_objects == 2);
  // with a 5 % contamination threshold object 1 (1/20 foreign) becomes under-segmented
  o.under_segmentation_fraction = 0.05;
  r = ev::object_rates(truth, pred, o);
  CHECK(r.under_segmented_objects == 1);
}

TEST_CASE("object rates: thresholds, ties, both flags, other, min_points") {
  // 7 % of 100 points is 7 points although 0.07 * 100 = 7.000000000000001 in double
  Labels truth, pred;
  push(truth, 1, 100), push(pred, 7, 93), push(pred, 8, 7);
  ev::MetricOptions seven;
  seven.over_segmentation_fraction = 0.07;
  CHECK(ev::object_rates(truth, pred, seven).over_segmented_objects == 1);
  truth.assign(100, 1), pred.assign(94, 7), push(pred, 8, 6);  // 6 % is no piece
  CHECK(ev::object_rates(truth, pred, seven).correct_objects == 1);
  // over AND under: object 1 = {7: 5, 8: 5} (tie -> smallest id 7), object 2 = {7: 5}
  // object 1: two 50 % pieces -> over; cluster 7 is half object 2 -> under. object 2: under.
  auto r = ev::object_rates(Labels{1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2},
                            Labels{7, 7, 7, 7, 7, 8, 8, 8, 8, 8, 7, 7, 7, 7, 7});
  CHECK(r.objects == 2);
  CHECK(r.over_segmented == 0.5);
  CHECK(r.under_segmented == 1.0);
  CHECK(r.correct == 0.0);
  // tie broken towards the smallest id: with the pure cluster holding id 6, object 1 is not under
  r = ev::object_rates(Labels{1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2},
                       Labels{7, 7, 7, 7, 7, 6, 6, 6, 6, 6, 7, 7, 7, 7, 7});
  CHECK(r.over_segmented_objects == 1);
  CHECK(r.under_segmented_objects == 1);
  // other: 20 points, 9 in cluster 3, 1 in cluster 4 (5 %: no piece), 10 unlabelled
  // (exactly half: not missed); majority 9 < 10 -> neither correct nor anything else
  truth.clear(), pred.clear();
  push(truth, 1, 20), push(pred, 3, 9), push(pred, 4, 1), push(pred, -1, 10);
  r = ev::object_rates(truth, pred);
  CHECK(r.other == 1.0);
  CHECK(r.missed == 0.0);
  // exactly half unlabelled, the other half in one cluster: correct
  r = ev::object_rates(Labels{1, 1, 1, 1}, Labels{-1, -1, 3, 3});
  CHECK(r.correct == 1.0);
  // one more lost point: missed
  r = ev::object_rates(Labels{1, 1, 1, 1}, Labels{-1, -1, -1, 3});
  CHECK(r.missed == 1.0);
  // min_points: the 2-point object 2 is not rated with min_points = 3
  ev::MetricOptions o;
  o.min_points = 3;
  r = ev::object_rates(Labels{1, 1, 1, 2, 2}, Labels{5, 5, 5, -1, -1}, o);
  CHECK(r.objects == 1);
  CHECK(r.correct == 1.0);
  // no object: zero rates
  r = ev::object_rates(Labels{0, 0}, Labels{1, 1});
  CHECK(r.objects == 0);
  CHECK(r.correct == 0.0);
}

// ================================================== report, invariance, errors

TEST_CASE("evaluate: perfect clustering") {
  const auto q = ev::evaluate(Labels{0, 0, 1, 1, 1, 2, 2}, Labels{-1, -1, 4, 4, 4, 9, 9});
  CHECK(q.adjusted_rand_index == 1.0);
  CHECK(q.entropy.over == 0.0);
  CHECK(q.entropy.under == 0.0);
  CHECK(q.panoptic.pq == 1.0);
  CHECK(q.objects.correct == 1.0);
  CHECK(q.coverage == near(5.0 / 7.0));
  CHECK(q.object_coverage == 1.0);
}

TEST_CASE("evaluate: empty input is defined") {
  const auto q = ev::evaluate(Labels{}, Labels{});
  CHECK(q.points == 0);
  CHECK(q.adjusted_rand_index == 1.0);
  CHECK(q.entropy.over == 0.0);
  CHECK(q.entropy.under == 0.0);
  CHECK(q.entropy.over_mean == 0.0);
  CHECK(q.panoptic.pq == 1.0);
  CHECK(q.coverage == 1.0);
  CHECK(q.objects.objects == 0);
}

TEST_CASE("relabelling invariance") {
  // GT ids g -> 13 g + 5 (objects only), predicted ids d -> 1000 - 7 d (labelled only):
  // every metric is unchanged. Random scenes (no object-rate ties checked here)...
  const auto relabel = [](const Labels& truth, const Labels& pred, Labels& t2, Labels& p2) {
    t2 = truth;
    p2 = pred;
    for (auto& t : t2) t = t > 0 ? 13 * t + 5 : t;
    for (auto& p : p2) p = p >= 0 ? 1000 - 7 * p : p;
  };
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    Labels truth, pred, t2, p2;
    random_scene(seed, 300, truth, pred);
    relabel(truth, pred, t2, p2);
    const auto a = ev::evaluate(truth, pred);
    const auto b = ev::evaluate(t2, p2);
    CHECK(a.adjusted_rand_index == b.adjusted_rand_index);  // exact integer pair counts
    CHECK(a.entropy.over == near(b.entropy.over));
    CHECK(a.entropy.under == near(b.entropy.under));
    CHECK(a.panoptic.true_positives == b.panoptic.true_positives);
    CHECK(a.panoptic.false_positives == b.panoptic.false_positives);
    CHECK(a.panoptic.false_negatives == b.panoptic.false_negatives);
    CHECK(a.panoptic.pq == near(b.panoptic.pq));
    CHECK(a.coverage == b.coverage);
  }
  // ...and a hand-made tie-free scene for the object rates (one of each outcome)
  Labels truth, pred, t2, p2;
  push(truth, 1, 10), push(pred, 0, 10);
  push(truth, 2, 6), push(pred, 1, 6), push(truth, 2, 4), push(pred, 2, 4);
  push(truth, 3, 10), push(pred, 3, 10), push(truth, 0, 10), push(pred, 3, 10);
  push(truth, 4, 8), push(pred, -1, 8), push(truth, 4, 2), push(pred, 4, 2);
  relabel(truth, pred, t2, p2);
  const auto a = ev::object_rates(truth, pred);
  const auto b = ev::object_rates(t2, p2);
  CHECK(a.correct_objects == 1);
  CHECK(b.correct_objects == 1);
  CHECK(a.over_segmented_objects == b.over_segmented_objects);
  CHECK(a.under_segmented_objects == b.under_segmented_objects);
  CHECK(a.missed_objects == b.missed_objects);
  CHECK(ev::adjusted_rand_index(truth, pred) == near(560.0 / 781.0));  // same scene as above
  CHECK(ev::adjusted_rand_index(t2, p2) == near(560.0 / 781.0));
}

TEST_CASE("brute-force oracles on random scenes") {
  for (std::uint32_t seed = 11; seed <= 30; ++seed) {
    Labels truth, pred;
    random_scene(seed, 150, truth, pred);
    CAPTURE(seed);
    CHECK(ev::adjusted_rand_index(truth, pred) == near(oracle_ari(truth, pred, false)));
    ev::MetricOptions o;
    o.ari_include_structure = true;
    CHECK(ev::adjusted_rand_index(truth, pred, o) == near(oracle_ari(truth, pred, true)));
    const auto e = ev::segmentation_entropy(truth, pred);
    const auto eo = oracle_entropy(truth, pred);
    CHECK(e.over == near(eo.over));
    CHECK(e.under == near(eo.under));
    CHECK(e.objects == eo.objects);
    CHECK(e.clusters == eo.clusters);
    for (const std::size_t min_points : {1u, 5u, 12u}) {
      o.min_points = min_points;
      const auto s = ev::panoptic_scores(truth, pred, o);
      const auto so = oracle_panoptic(truth, pred, min_points);
      CHECK(s.true_positives == so.true_positives);
      CHECK(s.false_positives == so.false_positives);
      CHECK(s.false_negatives == so.false_negatives);
      CHECK(s.sq == near(so.sq));
    }
  }
}

TEST_CASE("size mismatch and invalid options throw std::invalid_argument naming the values") {
  const Labels three{1, 1, 2};
  const Labels two{1, 1};
  const auto msg = invalid_argument_message([&] { ev::evaluate(three, two); });
  CHECK(msg.find("truth has 3") != std::string::npos);
  CHECK(msg.find("predicted has 2") != std::string::npos);
  CHECK_THROWS_AS(ev::adjusted_rand_index(three, two), std::invalid_argument);
  CHECK_THROWS_AS(ev::segmentation_entropy(three, two), std::invalid_argument);
  CHECK_THROWS_AS(ev::panoptic_scores(three, two), std::invalid_argument);
  CHECK_THROWS_AS(ev::object_rates(three, two), std::invalid_argument);
  CHECK_THROWS_AS(ev::coverage(three, two), std::invalid_argument);
  CHECK_THROWS_AS(ev::ContingencyTable(two, three), std::invalid_argument);

  ev::MetricOptions o;
  o.over_segmentation_fraction = 0.0;
  auto m = invalid_argument_message([&] { ev::object_rates(three, three, o); });
  CHECK(m.find("over_segmentation_fraction") != std::string::npos);
  CHECK(m.find("(0, 1]") != std::string::npos);
  o.over_segmentation_fraction = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(ev::evaluate(three, three, o), std::invalid_argument);
  o.over_segmentation_fraction = 0.1;
  o.under_segmentation_fraction = 1.5;
  m = invalid_argument_message([&] { ev::evaluate(three, three, o); });
  CHECK(m.find("under_segmentation_fraction = 1.5") != std::string::npos);
  o.under_segmentation_fraction = 1.0;  // upper bound allowed
  CHECK_NOTHROW(ev::evaluate(three, three, o));
}

TEST_CASE("evaluate_on_labelled scores both methods on the points the reference labelled") {
  // Two objects of 3 points. The baseline lost points 2 and 5 and got the
  // rest right; C-ARC kept every point but split point 2 off object 1.
  const Labels truth{1, 1, 1, 2, 2, 2};
  const Labels baseline{4, 4, -1, 6, 6, -1};
  const Labels carc{7, 7, 8, 9, 9, 9};

  // On all points: the baseline's unlabelled points count against it.
  const ev::QualityReport b_all = ev::evaluate(truth, baseline);
  CHECK(b_all.coverage == doctest::Approx(4.0 / 6.0));
  CHECK(b_all.adjusted_rand_index < 1.0);

  // On the baseline's labelled points {0, 1, 3, 4}: truth {1, 1, 2, 2},
  // baseline {4, 4, 6, 6}, C-ARC {7, 7, 9, 9}: both perfect there.
  const ev::LabelledSubset s = ev::restrict_to_labelled(truth, carc, baseline);
  CHECK(s.truth == Labels{1, 1, 2, 2});
  CHECK(s.predicted == Labels{7, 7, 9, 9});
  const ev::QualityReport b = ev::evaluate_on_labelled(truth, baseline, baseline);
  const ev::QualityReport c = ev::evaluate_on_labelled(truth, carc, baseline);
  CHECK(b.points == 4);
  CHECK(c.points == 4);
  CHECK(b.coverage == 1.0);
  CHECK(b.adjusted_rand_index == doctest::Approx(1.0));
  CHECK(c.adjusted_rand_index == doctest::Approx(1.0));
  CHECK(b.panoptic.pq == doctest::Approx(1.0));
  CHECK(c.panoptic.pq == doctest::Approx(1.0));

  // A C-ARC that merges both objects is not rescued by the restriction:
  // truth {1, 1, 2, 2} vs one cluster: pairs X = 2, A = 2, B = 6, E = A B / 6 = 2,
  // ARI = (2 - 2) / ((2 + 6) / 2 - 2) = 0; IoU of each object with the
  // merged cluster = 2 / 4 = 0.5, not > 0.5: no match, PQ = 0.
  const Labels merged{3, 3, 3, 3, 3, 3};
  const ev::QualityReport m = ev::evaluate_on_labelled(truth, merged, baseline);
  CHECK(m.points == 4);
  CHECK(m.adjusted_rand_index == doctest::Approx(0.0));
  CHECK(m.panoptic.pq == doctest::Approx(0.0));
  CHECK(m.panoptic.false_negatives == 2);

  // A reference that labelled nothing leaves an empty frame.
  const Labels none(6, -1);
  CHECK(ev::evaluate_on_labelled(truth, carc, none).points == 0);

  const Labels five{1, 1, 1, 2, 2};
  const auto msg = invalid_argument_message([&] { ev::restrict_to_labelled(truth, carc, five); });
  CHECK(msg.find("truth has 6") != std::string::npos);
  CHECK(msg.find("has 5") != std::string::npos);
}
