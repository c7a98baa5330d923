// SPDX-License-Identifier: MIT
// The tracking metrics: the optimal assignment against brute force,
// footprint IoU against known areas, CLEAR MOT / IDF1 on hand-made
// sequences with known counts, and the centroid peer tracker.

#include <doctest/doctest.h>

#include <streamclust/eval/assignment.hpp>
#include <streamclust/eval/footprint.hpp>
#include <streamclust/eval/track_metrics.hpp>
#include <streamclust/tracking/centroid_tracker.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

namespace {

namespace ev = streamclust::eval;
namespace tk = streamclust::tracking;

/// The best (most pairs, then least cost) over every assignment, by brute force.
std::pair<std::size_t, double> brute_force(const std::vector<double>& cost, std::size_t rows, std::size_t cols,
                                           double forbidden) {
  std::vector<std::size_t> perm(std::max(rows, cols));
  std::iota(perm.begin(), perm.end(), 0);
  std::pair<std::size_t, double> best{0, 0.0};
  do {
    std::size_t pairs = 0;
    double total = 0.0;
    for (std::size_t r = 0; r < rows; ++r) {
      if (perm[r] >= cols) continue;
      const double c = cost[r * cols + perm[r]];
      if (c >= forbidden) continue;
      ++pairs;
      total += c;
    }
    if (pairs > best.first || (pairs == best.first && total < best.second - 1e-12)) best = {pairs, total};
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

ev::TruthObjectState truth(std::int64_t id, float x, float y, std::size_t points = 100, float vx = 0.0f) {
  ev::TruthObjectState t;
  t.id = id;
  t.box = ev::Footprint{{x, y}, 0.0f, 1.0f, 1.0f};
  t.points = points;
  t.velocity = {vx, 0.0f};
  t.moving = vx != 0.0f;
  return t;
}

ev::TrackReport report(std::uint64_t id, float x, float y, float vx = 0.0f) {
  return ev::TrackReport{id, ev::Footprint{{x, y}, 0.0f, 1.0f, 1.0f}, {vx, 0.0f}};
}

tk::ObjectObservation observe(float x, float y, std::size_t points = 40) {
  tk::ObjectObservation o;
  o.box.center = Eigen::Vector3f(x, y, 0.8f);
  o.box.length = o.box.width = 0.6f;
  o.box.height = 1.7f;
  o.box.points = points;
  return o;
}

}  // namespace

TEST_CASE("eval assignment: the most pairs at the least cost, as brute force finds") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(0.0, 10.0);
  std::bernoulli_distribution forbid(0.3);
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t rows = 1 + rng() % 5, cols = 1 + rng() % 5;
    std::vector<double> cost(rows * cols);
    for (double& c : cost) c = forbid(rng) ? 1e9 : std::round(value(rng));
    const std::vector<long> a = ev::min_cost_assignment(cost, rows, cols, 1e9);
    std::size_t pairs = 0;
    double total = 0.0;
    std::vector<int> used(cols, 0);
    for (std::size_t r = 0; r < rows; ++r) {
      if (a[r] < 0) continue;
      const auto c = static_cast<std::size_t>(a[r]);
      REQUIRE(c < cols);
      CHECK(++used[c] == 1);
      CHECK(cost[r * cols + c] < 1e9);
      ++pairs;
      total += cost[r * cols + c];
    }
    const auto best = brute_force(cost, rows, cols, 1e9);
    CHECK(pairs == best.first);
    CHECK(total == doctest::Approx(best.second));
  }
  CHECK(ev::min_cost_assignment({}, 0, 3, 1.0).empty());
  CHECK_THROWS_AS(ev::min_cost_assignment({-1.0}, 1, 1, 5.0), std::invalid_argument);
  CHECK_THROWS_AS(ev::min_cost_assignment({1.0, 2.0}, 1, 1, 5.0), std::invalid_argument);
}

TEST_CASE("eval footprint: IoU of known overlaps, distance to a rectangle") {
  const ev::Footprint a{{0, 0}, 0.0f, 2.0f, 2.0f};
  CHECK(ev::footprint_iou(a, a) == doctest::Approx(1.0f));
  CHECK(ev::footprint_iou(a, ev::Footprint{{1, 0}, 0.0f, 2.0f, 2.0f}) == doctest::Approx(1.0f / 3.0f));
  CHECK(ev::footprint_iou(a, ev::Footprint{{5, 0}, 0.0f, 2.0f, 2.0f}) == 0.0f);
  // The square turned by 45 degrees: the overlap is a regular octagon, 8 (sqrt 2 - 1).
  const float octagon = 8.0f * (std::sqrt(2.0f) - 1.0f);
  CHECK(ev::footprint_iou(a, ev::Footprint{{0, 0}, 0.785398163f, 2.0f, 2.0f}) ==
        doctest::Approx(octagon / (8.0f - octagon)).epsilon(1e-4));
  // Turned by pi: the same rectangle.
  const ev::Footprint car{{3, 1}, 0.3f, 4.5f, 1.8f};
  CHECK(ev::footprint_iou(car, ev::Footprint{{3, 1}, 0.3f + 3.14159265f, 4.5f, 1.8f}) == doctest::Approx(1.0f));
  CHECK(ev::footprint_iou(car, ev::Footprint{{3, 1}, 0.3f, 0.0f, 1.8f}) == 0.0f);
  CHECK(a.distance_to({0.5f, 0.5f}) == 0.0f);
  CHECK(a.distance_to({3.0f, 0.0f}) == doctest::Approx(2.0f));
  CHECK(a.distance_to({4.0f, 5.0f}) == doctest::Approx(5.0f));
}

TEST_CASE("eval track metrics: perfect tracking, a switch, misses, false positives, ignored objects") {
  SUBCASE("perfect") {
    ev::TrackMetricsAccumulator acc;
    for (int f = 0; f < 10; ++f) {
      const float x = 0.1f * static_cast<float>(f);
      acc.add_frame({truth(1, x, 0, 100, 2.0f), truth(2, 5, 5)}, {report(7, x + 0.2f, 0, 2.1f), report(8, 5, 5, 0.1f)});
    }
    const ev::TrackMetrics m = acc.result();
    CHECK(m.frames == 10);
    CHECK(m.objects == 2);
    CHECK(m.truth == 20);
    CHECK(m.mota == doctest::Approx(1.0));
    CHECK(m.idf1 == doctest::Approx(1.0));
    CHECK(m.id_switches == 0);
    CHECK(m.motp == doctest::Approx(0.1));
    CHECK(m.mean_iou == doctest::Approx((0.8 / 1.2 + 1.0) / 2.0).epsilon(1e-4));
    CHECK(m.velocity_rmse == doctest::Approx(0.1).epsilon(1e-3));
    CHECK(m.velocity_samples == 10);
    CHECK(m.steady_velocity_samples == 10);
    CHECK(m.steady_velocity_rmse == doctest::Approx(0.1).epsilon(1e-3));
    CHECK(m.still_share == doctest::Approx(1.0));
  }
  SUBCASE("one object changes track half way: one switch, IDF1 one half") {
    ev::TrackMetricsAccumulator acc;
    for (int f = 0; f < 10; ++f) acc.add_frame({truth(1, 0, 0)}, {report(f < 5 ? 1u : 2u, 0, 0)});
    const ev::TrackMetrics m = acc.result();
    CHECK(m.id_switches == 1);
    CHECK(m.mota == doctest::Approx(0.9));
    CHECK(m.idf1 == doctest::Approx(2.0 * 5.0 / 20.0));
  }
  SUBCASE("a miss, a false positive, a track on an ignored object, a still share") {
    ev::TrackMetricsAccumulator acc;
    // Frame 1: object 1 matched (reported moving at 0.5 m/s), object 2 missed,
    // a track far from everything, a track on object 3 (5 points: ignored).
    acc.add_frame({truth(1, 0, 0), truth(2, 10, 0), truth(3, 20, 0, 5)},
                  {report(1, 0.3f, 0, 0.5f), report(2, 40, 0), report(3, 20, 0)});
    const ev::TrackMetrics m = acc.result();
    CHECK(m.truth == 2);
    CHECK(m.tracks == 2);
    CHECK(m.matches == 1);
    CHECK(m.misses == 1);
    CHECK(m.false_positives == 1);
    CHECK(m.mota == doctest::Approx(0.0));
    CHECK(m.recall == doctest::Approx(0.5));
    CHECK(m.precision == doctest::Approx(0.5));
    CHECK(m.still_share == doctest::Approx(0.0));
    CHECK(m.static_samples == 1);
  }
  SUBCASE("a track just off a long object's side still matches it; beyond the gate it does not") {
    ev::TrackMetricsAccumulator acc;
    ev::TruthObjectState car = truth(1, 0, 0);
    car.box.length = 4.5f;
    acc.add_frame({car}, {report(1, 2.0f, 0.9f)});   // centre inside the footprint's end, off its centre
    acc.add_frame({car}, {report(1, 0.0f, 2.0f)});   // 1.5 m from the side: a false positive and a miss
    const ev::TrackMetrics m = acc.result();
    CHECK(m.matches == 1);
    CHECK(m.misses == 1);
    CHECK(m.false_positives == 1);
  }
  SUBCASE("a turn: the velocity error counts in the RMSE, not in the steady RMSE") {
    ev::TrackMetricsAccumulator acc;
    ev::TruthObjectState walker = truth(1, 0, 0, 100, -1.0f);
    walker.steady = false;
    acc.add_frame({walker}, {report(1, 0, 0, 1.0f)});
    walker.steady = true;
    acc.add_frame({walker}, {report(1, 0, 0, -1.0f)});
    const ev::TrackMetrics m = acc.result();
    CHECK(m.velocity_rmse == doctest::Approx(std::sqrt(2.0)));
    CHECK(m.steady_velocity_rmse == doctest::Approx(0.0));
    CHECK(m.steady_velocity_samples == 1);
  }
  SUBCASE("a track above the object (heights apart) does not match it; without heights it does") {
    ev::TrackMetricsAccumulator acc;
    ev::TruthObjectState person = truth(1, 0, 0);
    person.bottom = 0.0f;
    person.top = 1.7f;
    ev::TrackReport patch = report(1, 0.1f, 0);
    patch.bottom = 2.95f;
    patch.top = 3.0f;
    acc.add_frame({person}, {patch});
    patch.bottom = patch.top = 0.0f;
    acc.add_frame({person}, {patch});
    const ev::TrackMetrics m = acc.result();
    CHECK(m.matches == 1);
    CHECK(m.misses == 1);
    CHECK(m.false_positives == 1);
  }
  SUBCASE("correspondences are kept while they hold, even when another track comes closer") {
    ev::TrackMetricsAccumulator acc;
    acc.add_frame({truth(1, 0, 0)}, {report(1, 0.4f, 0)});
    acc.add_frame({truth(1, 0, 0)}, {report(1, 0.4f, 0), report(2, 0.0f, 0.1f)});
    const ev::TrackMetrics m = acc.result();
    CHECK(m.id_switches == 0);
    CHECK(m.false_positives == 1);
  }
  CHECK_THROWS_AS(ev::TrackMetricsAccumulator(ev::TrackMetricOptions{0.0f, 50, 0.2f}), std::invalid_argument);
}

TEST_CASE("centroid tracker: follows a walker, confirms, coasts and drops; ignores component ids") {
  streamclust::CentroidTracker tracker;
  double t = 0.0;
  std::uint64_t id = 0;
  for (int k = 0; k < 60; ++k, t += 0.05) {
    const float x = 1.2f * static_cast<float>(t);
    std::vector<tk::ObjectObservation> objects{observe(x, 2.0f), observe(-4.0f, 1.0f)};
    objects[0].id = static_cast<streamclust::ComponentId>(k);  // a new component id every time: no matter
    const std::vector<tk::Track>& tracks = tracker.update(objects, t);
    REQUIRE(tracks.size() == 2);
    if (k == 0) id = tracks[0].id;
    CHECK(tracks[0].id == id);
    CHECK(tracks[0].state == (k < 2 ? tk::TrackState::tentative : tk::TrackState::confirmed));
  }
  const tk::Track walker = tracker.tracks()[0];
  CHECK(walker.velocity.x() == doctest::Approx(1.2f).epsilon(0.05));
  CHECK(std::abs(walker.velocity.y()) < 0.05f);
  CHECK(walker.moving);
  CHECK_FALSE(tracker.tracks()[1].moving);
  // Unseen: coasting along its velocity, dropped after a second.
  t += 0.5;
  const std::vector<tk::Track>& coasting = tracker.update({}, t);
  REQUIRE(coasting.size() == 2);
  CHECK(coasting[0].state == tk::TrackState::coasting);
  CHECK(coasting[0].position.x() == doctest::Approx(1.2f * static_cast<float>(t)).epsilon(0.05));
  CHECK(tracker.update({}, t + 0.6).empty());
  CHECK_THROWS_AS(tracker.update({}, 0.0), std::invalid_argument);
  streamclust::CentroidTracker::Params bad;
  bad.gate_distance = 0.0f;
  CHECK_THROWS_AS(streamclust::CentroidTracker{bad}, std::invalid_argument);
}
