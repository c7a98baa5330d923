// SPDX-License-Identifier: MIT
// KalmanTracker on observations with known truth: velocities converge,
// static objects stay still, ids survive renumbered components, merges,
// occlusions and shuffled ids; tentative tracks and coasting end as their
// rules say; NullTracker tracks nothing.

#include <doctest/doctest.h>

#include <streamclust/tracking/kalman_tracker.hpp>
#include <streamclust/tracking/null_tracker.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace sc = streamclust;
namespace tr = streamclust::tracking;

namespace {

constexpr double kCycle = 0.05;  // 20 Hz retrievals

/// An observed object at `centre` with component id `id`: a two-sided box
/// of 100 points, and a window velocity `v` of standard error `v_error`
/// when `v_error` > 0.
tr::ObjectObservation observed(sc::ComponentId id, Eigen::Vector2f centre, Eigen::Vector2f v = {0, 0},
                               float v_error = 0.0f, double time = 0.0) {
  tr::ObjectObservation o;
  o.id = id;
  o.time = time;
  o.box.center = Eigen::Vector3f(centre.x(), centre.y(), -0.2f);
  o.box.length = 4.0f;
  o.box.width = 1.8f;
  o.box.height = 1.6f;
  o.box.yaw = 0.3f;
  o.box.quality = tr::BoxQuality::two_sides;
  o.box.points = 100;
  if (v_error > 0.0f) {
    o.velocity.valid = true;
    o.velocity.velocity = v;
    o.velocity.error = v_error;
    o.velocity.slices = 5;
  }
  return o;
}

/// Two draws of `d`, x first (an argument list would leave the order to the compiler).
template <class Distribution>
Eigen::Vector2f draw2(Distribution& d, std::mt19937& rng) {
  const float x = d(rng);
  const float y = d(rng);
  return Eigen::Vector2f(x, y);
}

const tr::Track* find_track(const std::vector<tr::Track>& tracks, std::uint64_t id) {
  for (const tr::Track& t : tracks) {
    if (t.id == id) return &t;
  }
  return nullptr;
}

}  // namespace

TEST_CASE("KalmanTracker: a moving object's velocity converges; it moves and faces its way; its id holds") {
  std::mt19937 rng(1);
  std::normal_distribution<float> pos_noise(0.0f, 0.1f), vel_noise(0.0f, 0.2f);
  sc::KalmanTracker tracker;
  const Eigen::Vector2f start(5.0f, 2.0f), v(1.0f, -0.5f);
  std::uint64_t id = 0;
  int moving = 0, cycles = 0;
  double sq_error = 0.0;
  for (int c = 0; c < 80; ++c) {
    const double t = c * kCycle;
    const Eigen::Vector2f truth = start + v * static_cast<float>(t);
    const Eigen::Vector2f seen = truth + draw2(pos_noise, rng);
    const Eigen::Vector2f seen_v = v + draw2(vel_noise, rng);
    const auto& tracks = tracker.update({observed(7, seen, seen_v, 0.2f, t)}, t);
    REQUIRE(tracks.size() == 1);
    const tr::Track& track = tracks.front();
    if (c == 0) id = track.id;
    CHECK(track.id == id);
    CHECK(track.cluster_id == 7);
    CHECK(track.state == (c < 2 ? tr::TrackState::tentative : tr::TrackState::confirmed));
    if (c >= 20) {
      ++cycles;
      moving += track.moving;
      const float error = (track.velocity.head<2>() - v).norm();
      CHECK(error < 0.3f);
      sq_error += static_cast<double>(error * error);
      CHECK((track.position.head<2>() - truth).norm() < 0.15f);
      CHECK(std::abs(track.yaw - std::atan2(v.y(), v.x())) < 0.2f);
      CHECK(track.length == doctest::Approx(4.0f));
      CHECK(track.height == doctest::Approx(1.6f));
    }
  }
  CHECK(moving == cycles);
  CHECK(std::sqrt(sq_error / cycles) < 0.15);
}

TEST_CASE("KalmanTracker: a fast object starts at the speed its window shows and keeps its track as its ids change") {
  // A car at 10 m/s whose component is renumbered every third retrieval
  // (a fast mover's points break into pieces over the window): started at
  // rest, the track would fall behind by 0.5 m a retrieval and lose it.
  std::mt19937 rng(4);
  std::normal_distribution<float> pos_noise(0.0f, 0.15f), vel_noise(0.0f, 0.3f);
  sc::KalmanTracker tracker;
  const Eigen::Vector2f start(-5.0f, -2.0f), v(-10.0f, 0.0f);
  std::uint64_t id = 0;
  for (int c = 0; c < 40; ++c) {
    const double t = c * kCycle;
    const Eigen::Vector2f truth = start + v * static_cast<float>(t);
    const auto component = static_cast<sc::ComponentId>(100 + c / 3);
    const auto& tracks =
        tracker.update({observed(component, truth + draw2(pos_noise, rng), v + draw2(vel_noise, rng), 0.3f, t)}, t);
    REQUIRE(tracks.size() == 1);
    const tr::Track& track = tracks.front();
    if (c == 0) id = track.id;
    CHECK(track.id == id);
    CHECK((track.position.head<2>() - truth).norm() < 0.5f);
    if (track.state == tr::TrackState::confirmed) {
      CHECK(track.moving);
      CHECK((track.velocity.head<2>() - v).norm() < 1.0f);
    }
  }
}

TEST_CASE("KalmanTracker: a static object with a wandering centre is reported still") {
  std::mt19937 rng(2);
  std::normal_distribution<float> pos_noise(0.0f, 0.15f), vel_noise(0.0f, 0.15f);
  sc::KalmanTracker tracker;
  int still = 0, cycles = 0;
  for (int c = 0; c < 200; ++c) {
    const double t = c * kCycle;
    const Eigen::Vector2f centre = Eigen::Vector2f(-8.0f, 3.0f) + draw2(pos_noise, rng);
    const Eigen::Vector2f window_v = draw2(vel_noise, rng);
    tr::ObjectObservation o = observed(3, centre, window_v, 0.15f, t);
    o.box.quality = c % 3 == 0 ? tr::BoxQuality::one_side : tr::BoxQuality::two_sides;
    const auto& tracks = tracker.update({o}, t);
    REQUIRE(tracks.size() == 1);
    if (tracks.front().state != tr::TrackState::confirmed) continue;
    ++cycles;
    still += tracks.front().velocity.norm() < 0.2f && !tracks.front().moving;
  }
  CAPTURE(still);
  CHECK(still >= cycles * 95 / 100);
}

TEST_CASE("KalmanTracker: a desk going out of view, its centre and window velocity following the view's edge, "
          "stays static") {
  // The edge of the field of view sweeps over a standing desk at 1.2 m/s:
  // what shows of it, and its centre, move along x at 0.6 m/s, a tight
  // window velocity; its far end stands (the ends differ by 1.2 m/s).
  // The same observations with ends that agree are a mover.
  for (const bool ends_agree : {false, true}) {
    sc::KalmanTracker tracker;
    bool moved = false;
    for (int c = 0; c < 20; ++c) {
      const double t = c * kCycle;
      const Eigen::Vector2f centre(3.0f + 0.6f * static_cast<float>(t), -1.5f);
      tr::ObjectObservation o = observed(7, centre, {0.6f, 0.0f}, 0.08f, t);
      o.velocity.end_difference = ends_agree ? 0.1f : 1.2f;
      const auto& tracks = tracker.update({o}, t);
      REQUIRE(tracks.size() == 1);
      moved = moved || tracks.front().moving;
    }
    CAPTURE(ends_agree);
    CHECK(moved == ends_agree);
  }
}

TEST_CASE("KalmanTracker: new component ids, a merge and an occlusion keep each object's track") {
  sc::KalmanTracker tracker;
  // A moves along +x past B, 2.5 m beside it; for 0.5 s they are one
  // component (B's id: the larger part keeps it; one box around both), then
  // A is hidden for 0.6 s, then both come back with new ids.
  const Eigen::Vector2f a0(-6.0f, -1.0f), va(1.5f, 0.0f), b(0.0f, 1.5f);
  std::uint64_t track_a = 0, track_b = 0;
  sc::ComponentId next_id = 100;
  sc::ComponentId id_a = next_id++, id_b = next_id++;
  for (int c = 0; c < 120; ++c) {
    const double t = c * kCycle;
    const Eigen::Vector2f a = a0 + va * static_cast<float>(t);
    std::vector<tr::ObjectObservation> objects;
    const bool merged = t >= 3.0 && t < 3.5, hidden = t >= 3.5 && t < 4.1;
    if (c % 25 == 24) id_a = next_id++;  // renumbered now and then (splits elsewhere)
    if (t >= 4.1 && id_b < 102) {
      id_a = next_id++;
      id_b = next_id++;
    }
    if (merged) {
      tr::ObjectObservation both = observed(id_b, 0.5f * (a + b), va * 0.5f, 0.2f, t);
      both.box.yaw = 0.0f;
      both.box.length = 4.0f + std::abs(a.x() - b.x());
      both.box.width = 1.8f + std::abs(a.y() - b.y());
      objects.push_back(both);
    } else {
      if (!hidden) objects.push_back(observed(id_a, a, va, 0.2f, t));
      objects.push_back(observed(id_b, b, {0, 0}, 0.2f, t));
    }
    std::sort(objects.begin(), objects.end(), [](const auto& x, const auto& y) { return x.id < y.id; });
    const auto& tracks = tracker.update(objects, t);
    CAPTURE(t);
    if (c == 10) {
      REQUIRE(tracks.size() == 2);
      for (const tr::Track& tk : tracks) (tk.cluster_id == id_a ? track_a : track_b) = tk.id;
      REQUIRE(track_a != track_b);
    }
    if (c <= 10) continue;
    const tr::Track* ta = find_track(tracks, track_a);
    const tr::Track* tb = find_track(tracks, track_b);
    REQUIRE(ta != nullptr);
    REQUIRE(tb != nullptr);
    CHECK((tb->position.head<2>() - b).norm() < 0.6f);
    CHECK_FALSE(tb->moving);
    if (hidden) {
      CHECK(ta->state == tr::TrackState::coasting);
      CHECK(ta->cluster_id == sc::kNoComponent);
    }
    if (!merged && !hidden) {
      CHECK(ta->state == tr::TrackState::confirmed);
      CHECK(ta->cluster_id == id_a);
      CHECK((ta->position.head<2>() - a).norm() < 0.5f);
    }
    // No track is born of the merge or the return.
    CHECK(tracks.size() == 2);
  }
}

TEST_CASE("KalmanTracker: a standing object unseen with nothing in front of it coasts for out_of_sight_seconds") {
  // Seen from a sensor at the origin: a desk 8 m ahead along x and a cabinet
  // off to the side, both standing. At 1 s the desk is no longer seen: out of
  // the field of view (nothing in front of it), or hidden behind a person
  // who stands 4 m ahead from then on.
  const auto unseen_for = [](bool hidden_behind, bool with_viewpoint) {
    sc::KalmanTracker tracker;  // coast_seconds 1, out_of_sight_seconds 0.4
    std::uint64_t desk = 0;
    double last_listed = 0.0;
    for (int c = 0; c <= 60; ++c) {
      const double t = c * kCycle;
      std::vector<tr::ObjectObservation> seen{observed(1, {-5.0f, 5.0f}, {0, 0}, 0.1f, t)};
      if (t < 1.0) seen.push_back(observed(2, {8.0f, 0.0f}, {0, 0}, 0.1f, t));
      if (t >= 1.0 && hidden_behind) {
        tr::ObjectObservation person = observed(3, {4.0f, 0.0f}, {0, 0}, 0.1f, t);
        person.box.length = person.box.width = 0.5f;
        seen.push_back(person);
      }
      for (tr::ObjectObservation& o : seen) {
        if (with_viewpoint) o.viewpoint = Eigen::Vector3f(0.0f, 0.0f, 1.0f);
      }
      for (const tr::Track& tk : tracker.update(seen, t)) {
        if (tk.cluster_id == 2 && desk == 0) desk = tk.id;
        if (desk != 0 && tk.id == desk) last_listed = t;
      }
    }
    REQUIRE(desk != 0);
    return last_listed - 0.95;  // unseen since its last sighting at 0.95 s
  };
  CHECK(unseen_for(false, true) == doctest::Approx(0.4).epsilon(0.01));
  CHECK(unseen_for(true, true) == doctest::Approx(1.0).epsilon(0.01));
  CHECK(unseen_for(false, false) == doctest::Approx(1.0).epsilon(0.01));  // no viewpoint: no rule
  sc::KalmanTracker::Params bad;
  bad.out_of_sight_seconds = -1.0;
  CHECK_THROWS_WITH_AS(sc::KalmanTracker{bad}, doctest::Contains("out_of_sight_seconds"), std::invalid_argument);
}

TEST_CASE("KalmanTracker: many objects under shuffled component ids keep their tracks (association by position)") {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> place(-40.0f, 40.0f), speed(-2.0f, 2.0f);
  std::normal_distribution<float> noise(0.0f, 0.08f);
  struct Truth {
    Eigen::Vector2f p, v;
  };
  std::vector<Truth> truths;
  while (truths.size() < 25) {  // 25 objects at least 5 m apart
    const Eigen::Vector2f p = draw2(place, rng);
    const Truth cand{p, draw2(speed, rng)};
    const bool apart = std::all_of(truths.begin(), truths.end(),
                                   [&](const Truth& t) { return (t.p - cand.p).norm() > 5.0f && (t.v - cand.v).norm() > 0.6f; });
    if (apart) truths.push_back(cand);
  }
  sc::KalmanTracker tracker;
  std::map<std::size_t, std::uint64_t> track_of_truth;
  sc::ComponentId next_id = 1;
  int switches = 0;
  for (int c = 0; c < 40; ++c) {  // 2 s: objects close in by at most 2 x 2.8 x 2 m
    const double t = c * kCycle;
    std::vector<tr::ObjectObservation> objects;
    std::vector<std::size_t> truth_of_id;
    for (std::size_t k = 0; k < truths.size(); ++k) {
      const Eigen::Vector2f p = truths[k].p + truths[k].v * static_cast<float>(t);
      objects.push_back(observed(next_id++, p + draw2(noise, rng), truths[k].v, 0.2f, t));
    }
    const auto& tracks = tracker.update(objects, t);
    REQUIRE(tracks.size() == truths.size());
    for (const tr::Track& tk : tracks) {
      const std::size_t k = static_cast<std::size_t>(tk.cluster_id - objects.front().id);
      REQUIRE(k < truths.size());
      const auto [it, fresh] = track_of_truth.emplace(k, tk.id);
      if (!fresh && it->second != tk.id) {
        ++switches;
        it->second = tk.id;
      }
    }
  }
  CHECK(switches == 0);
  CHECK(track_of_truth.size() == truths.size());
}

TEST_CASE("KalmanTracker: births, tentative tracks and coasting end by their rules") {
  sc::KalmanTracker::Params params;
  params.birth_points = 20;
  sc::KalmanTracker tracker(params);
  tr::ObjectObservation small = observed(1, {3, 3});
  small.box.points = 19;
  CHECK(tracker.update({small}, 0.0).empty());
  // One sighting: tentative, dropped once unseen for more than 0.2 s.
  CHECK(tracker.update({observed(2, {3, 3})}, 0.05).size() == 1);
  CHECK(tracker.update({}, 0.2).size() == 1);
  CHECK(tracker.update({}, 0.3).empty());
  // Confirmed after three sightings, coasting up to 1 s, then gone.
  for (int c = 0; c < 3; ++c) tracker.update({observed(3, {5, 5})}, 1.0 + c * kCycle);
  REQUIRE(tracker.tracks().size() == 1);
  CHECK(tracker.tracks().front().state == tr::TrackState::confirmed);
  CHECK(tracker.update({}, 1.6).front().state == tr::TrackState::coasting);
  CHECK(tracker.update({}, 2.05).size() == 1);
  CHECK(tracker.update({}, 2.2).empty());
  CHECK_THROWS_WITH_AS(tracker.update({}, 2.0), doctest::Contains("before the last"), std::invalid_argument);
  sc::KalmanTracker::Params bad;
  bad.gate_distance = 0.0f;
  CHECK_THROWS_WITH_AS(sc::KalmanTracker{bad}, doctest::Contains("KalmanTracker: gate_distance"),
                       std::invalid_argument);
}

TEST_CASE("KalmanTracker: what floats above the ground or lies in a tracked object's box starts no track") {
  sc::KalmanTracker tracker;  // birth_clearance 1 m, group_margin 0.3 m
  // A car standing on the ground (its box's bottom at z = -1), confirmed.
  const auto standing = [](sc::ComponentId id, Eigen::Vector2f centre) {
    tr::ObjectObservation o = observed(id, centre);
    o.ground_z = -1.0f;
    o.box.on_ground = true;
    return o;
  };
  for (int c = 0; c < 3; ++c) tracker.update({standing(1, {0, 0})}, c * kCycle);
  REQUIRE(tracker.tracks().size() == 1);
  // Something 3 m above the ground (its bottom; a lamp hung from the
  // ceiling); the same 0.5 m above it.
  tr::ObjectObservation ceiling = observed(2, {10, 10});
  ceiling.ground_z = -1.0f;
  ceiling.box.center.z() = 2.3f;
  ceiling.box.height = 0.6f;
  tr::ObjectObservation low = ceiling;
  low.id = 3;
  low.box.center = Eigen::Vector3f(-10.0f, 10.0f, -0.2f);
  // A piece of the car beside its component (centre inside its 4 x 1.8 m
  // box), and one 1 m beyond the box's end.
  tr::ObjectObservation part = observed(4, {1.5f, 0.4f});
  part.box.length = part.box.width = 0.5f;
  tr::ObjectObservation beyond = part;
  beyond.id = 5;
  beyond.box.center.head<2>() = Eigen::Vector2f(2.0f * std::cos(0.3f), 2.0f * std::sin(0.3f)) +
                                Eigen::Vector2f(1.3f * std::cos(0.3f), 1.3f * std::sin(0.3f));
  // The ground unknown: no rule.
  tr::ObjectObservation unknown = ceiling;
  unknown.id = 6;
  unknown.box.center.head<2>() = Eigen::Vector2f(-10.0f, -10.0f);
  unknown.ground_z.reset();
  for (int c = 3; c < 6; ++c) tracker.update({standing(1, {0, 0}), ceiling, low, part, beyond, unknown}, c * kCycle);
  std::map<sc::ComponentId, std::size_t> tracks_of;
  for (const tr::Track& t : tracker.tracks()) ++tracks_of[t.cluster_id];
  CHECK(tracks_of[1] == 1);
  CHECK(tracks_of.count(2) == 0);  // floats 3 m above the ground
  CHECK(tracks_of[3] == 1);        // 0.5 m: within the clearance
  CHECK(tracks_of.count(4) == 0);  // a part of the car
  CHECK(tracks_of[5] == 1);
  CHECK(tracks_of[6] == 1);
  CHECK(tracker.tracks().size() == 4);
  sc::KalmanTracker::Params bad;
  bad.birth_clearance = 0.0f;
  CHECK_THROWS_WITH_AS(sc::KalmanTracker{bad}, doctest::Contains("birth_clearance"), std::invalid_argument);
}

TEST_CASE("KalmanTracker: where the ground is unknown, a crown above its trunk's foot starts no track") {
  sc::KalmanTracker tracker;  // birth_clearance 1 m, birth_neighbourhood 3 m
  const auto piece = [](sc::ComponentId id, Eigen::Vector2f centre, float bottom, float height) {
    tr::ObjectObservation o = observed(id, centre);
    o.box.length = o.box.width = 1.0f;
    o.box.height = height;
    o.box.center.z() = bottom + 0.5f * height;
    return o;  // ground_z unknown
  };
  // A tree seen as two components 25 m out: its trunk from the foot up, its
  // crown 2 m to the side from 2.5 m up; a second crown alone 10 m away.
  const std::vector<tr::ObjectObservation> seen{piece(1, {25, 0}, -1.0f, 3.0f), piece(2, {25, 2}, 1.5f, 4.0f),
                                                 piece(3, {25, 12}, 1.5f, 4.0f)};
  for (int c = 0; c < 3; ++c) tracker.update(seen, c * kCycle);
  std::map<sc::ComponentId, std::size_t> tracks_of;
  for (const tr::Track& t : tracker.tracks()) ++tracks_of[t.cluster_id];
  CHECK(tracks_of[1] == 1);
  CHECK(tracks_of.count(2) == 0);  // 2.5 m above the trunk's foot 2 m away
  CHECK(tracks_of[3] == 1);        // nothing near to stand for the ground
  sc::KalmanTracker::Params bad;
  bad.birth_neighbourhood = -1.0f;
  CHECK_THROWS_WITH_AS(sc::KalmanTracker{bad}, doctest::Contains("birth_neighbourhood"), std::invalid_argument);
}

TEST_CASE("KalmanTracker: by position, an observation pairs with a track only at its height") {
  sc::KalmanTracker tracker;  // gate_height 0.5 m
  // A desk (box 0-0.75 m high) confirmed under component 1.
  const auto box_at = [](sc::ComponentId id, Eigen::Vector2f centre, float bottom, float height) {
    tr::ObjectObservation o = observed(id, centre);
    o.box.length = 1.6f;
    o.box.width = 0.8f;
    o.box.height = height;
    o.box.center.z() = bottom + 0.5f * height;
    return o;
  };
  for (int c = 0; c < 3; ++c) tracker.update({box_at(1, {0, 0}, 0.0f, 0.75f)}, c * kCycle);
  REQUIRE(tracker.tracks().size() == 1);
  const std::uint64_t desk = tracker.tracks()[0].id;
  // Its component is gone; 0.3 m away, 1.4-1.5 m up, a few points under
  // a new id (a lamp's, a passer-by's arm): not the desk, which coasts.
  tracker.update({box_at(2, {0.3f, 0.0f}, 1.4f, 0.1f)}, 3 * kCycle);
  const tr::Track* coasting = find_track(tracker.tracks(), desk);
  REQUIRE(coasting);
  CHECK(coasting->cluster_id == sc::kNoComponent);
  CHECK(coasting->position.z() == doctest::Approx(0.375f));
  // The desk again under a new id, its top 0.4 m lower (its far half in a
  // shadow): the same track.
  tracker.update({box_at(3, {0.1f, 0.0f}, 0.0f, 0.35f)}, 4 * kCycle);
  const tr::Track* again = find_track(tracker.tracks(), desk);
  REQUIRE(again);
  CHECK(again->cluster_id == 3);
  sc::KalmanTracker::Params bad;
  bad.gate_height = -1.0f;
  CHECK_THROWS_WITH_AS(sc::KalmanTracker{bad}, doctest::Contains("gate_height"), std::invalid_argument);
}

TEST_CASE("KalmanTracker: what reaches the ceiling starts no track unless shaped like a pillar") {
  sc::KalmanTracker tracker;  // birth_ceiling_gap 0.3 m
  // Boxes standing on the floor (z = 0) or hanging, under a ceiling at 3 m.
  const auto seen_at = [](sc::ComponentId id, float x, float bottom, float length, float height) {
    tr::ObjectObservation o = observed(id, {x, 0.0f});
    o.box.length = length;
    o.box.width = std::min(length, 0.5f);
    o.box.height = height;
    o.box.center.z() = bottom + 0.5f * height;
    o.ceiling_z = 3.0f;
    return o;
  };
  std::vector<tr::ObjectObservation> seen{
      seen_at(1, 0, 2.85f, 0.4f, 0.15f),   // a patch of ceiling the ground policy left
      seen_at(2, 10, 2.3f, 0.6f, 0.6f),    // a lamp hung from it
      seen_at(3, 20, 0.0f, 9.0f, 3.0f),    // a wall up to it
      seen_at(4, 30, 0.0f, 0.5f, 3.0f),    // a pillar
      seen_at(5, 40, 0.0f, 0.5f, 1.75f),   // a person below it
      seen_at(6, 50, 0.0f, 3.0f, 2.8f),    // a row of shelves 0.2 m below it
  };
  // The same lamp where no ceiling is known: no rule.
  tr::ObjectObservation unknown = seen_at(7, 60, 2.3f, 0.6f, 0.6f);
  unknown.ceiling_z.reset();
  unknown.ground_z = 2.0f;
  seen.push_back(unknown);
  for (int c = 0; c < 3; ++c) tracker.update(seen, c * kCycle);
  std::map<sc::ComponentId, std::size_t> tracks_of;
  for (const tr::Track& t : tracker.tracks()) ++tracks_of[t.cluster_id];
  for (const sc::ComponentId id : {1, 2, 3, 6}) CHECK(tracks_of.count(id) == 0);
  for (const sc::ComponentId id : {4, 5, 7}) CHECK(tracks_of[id] == 1);
  // With no gap only what reaches the ceiling's height counts.
  sc::KalmanTracker::Params exact;
  exact.birth_ceiling_gap = 0.0f;
  sc::KalmanTracker strict(exact);
  for (int c = 0; c < 3; ++c) strict.update(seen, c * kCycle);
  tracks_of.clear();
  for (const tr::Track& t : strict.tracks()) ++tracks_of[t.cluster_id];
  CHECK(tracks_of.count(3) == 0);
  CHECK(tracks_of[6] == 1);
  sc::KalmanTracker::Params bad;
  bad.birth_ceiling_gap = -0.1f;
  CHECK_THROWS_WITH_AS(sc::KalmanTracker{bad}, doctest::Contains("birth_ceiling_gap"), std::invalid_argument);
}

TEST_CASE("KalmanTracker: a static track whose box grows to the ceiling is set aside until its object comes apart") {
  // Under a ceiling at 3 m: a cabinet (1 x 0.5 x 2 m) whose component merges
  // with the wall behind it (4 x 0.5 x 3 m, up to the ceiling, its centre
  // 1.5 m off the cabinet's), for a moment, for good, or for ten updates; a
  // pillar; a lamp first seen before the ceiling was known.
  const auto box_at = [](sc::ComponentId id, float x, float length, float height, float bottom) {
    tr::ObjectObservation o = observed(id, {x, 0.0f});
    o.box.length = length;
    o.box.width = 0.5f;
    o.box.height = height;
    o.box.center.z() = bottom + 0.5f * height;
    o.ceiling_z = 3.0f;
    return o;
  };
  const auto cabinet = [&](sc::ComponentId id, float x, bool merged) {
    return merged ? box_at(id, x + 1.5f, 4.0f, 3.0f, 0.0f) : box_at(id, x, 1.0f, 2.0f, 0.0f);
  };
  struct Seen {
    std::vector<int> present = std::vector<int>(5, 0);  // per object: updates tracked in after the merge began
    std::map<sc::ComponentId, std::set<std::uint64_t>> ids;  // per object: the track ids reported
    bool back_at_cabinet = false;  // the third cabinet's track, back, has the cabinet's box
  };
  const auto run = [&](const sc::KalmanTracker::Params& params) {
    sc::KalmanTracker tracker(params);
    Seen seen;
    for (int c = 0; c < 30; ++c) {
      const bool merged = c >= 10;
      tr::ObjectObservation lamp = box_at(4, 30.0f, 0.6f, 0.6f, 2.3f);
      if (c < 10) lamp.ceiling_z.reset();
      const std::vector<tr::ObjectObservation> now{cabinet(1, 0.0f, merged && c < 12), cabinet(2, 10.0f, merged),
                                                   box_at(3, 20.0f, 0.5f, 3.0f, 0.0f), lamp,
                                                   cabinet(5, 40.0f, merged && c < 20)};
      for (const tr::Track& t : tracker.update(now, c * kCycle)) {
        seen.ids[t.cluster_id].insert(t.id);
        if (c >= 10) ++seen.present[static_cast<std::size_t>(t.cluster_id) - 1];
        if (t.cluster_id == 5 && c == 20) {
          seen.back_at_cabinet = std::abs(t.position.x() - 40.0f) < 0.01f && std::abs(t.length - 1.0f) < 0.01f;
        }
      }
    }
    return seen;
  };
  const Seen seen = run({});
  CHECK(seen.present[0] == 20);  // merged for two updates: kept
  CHECK(seen.present[1] >= 3);   // merged for good: set aside once its smoothed top reaches 2.7 m three times in a row
  CHECK(seen.present[1] <= 8);
  CHECK(seen.present[2] == 20);  // the pillar
  CHECK(seen.present[3] == 2);   // the lamp: set aside at the third update that knows the ceiling, for good
  // Merged for ten updates: set aside, then back at the cabinet's place and
  // box from its first update apart, under the id it had.
  CHECK(seen.present[4] >= 3 + 10);
  CHECK(seen.present[4] <= 8 + 10);
  CHECK(seen.back_at_cabinet);
  for (const sc::ComponentId id : {1, 2, 3, 4, 5}) CHECK(seen.ids.at(id).size() == 1);
  sc::KalmanTracker::Params never;
  never.ceiling_hide_updates = 0;
  CHECK(run(never).present == std::vector<int>{20, 20, 20, 20, 20});
  sc::KalmanTracker::Params bad;
  bad.ceiling_hide_updates = 1001;
  CHECK_THROWS_WITH_AS(sc::KalmanTracker{bad}, doctest::Contains("ceiling_hide_updates"), std::invalid_argument);
}

TEST_CASE("KalmanTracker: a static track whose windows show clear motion in successive updates starts moving") {
  // A bicycle stands for 1 s, then rides off along x at 5 m/s: its windows
  // show the motion from the first update on, its ends agreeing. The static
  // prior holds the track back; restart_updates such windows restart it.
  // A standing object whose windows show the same motion twice, then none,
  // stays still.
  std::mt19937 rng(5);
  std::normal_distribution<float> pos_noise(0.0f, 0.05f), vel_noise(0.0f, 0.1f);
  const Eigen::Vector2f start(5.0f, 1.0f), v(5.0f, 0.0f);
  const auto ride = [&](const sc::KalmanTracker::Params& params, int motion_updates) {
    sc::KalmanTracker tracker(params);
    std::vector<float> speed_error;  // per update from the start of the ride
    bool ever_moved = false;
    for (int c = 0; c < 20 + 8; ++c) {
      const double t = c * kCycle;
      const int riding = c - 20;  // updates since the ride began
      const bool rides = riding >= 0 && riding < motion_updates;
      const Eigen::Vector2f velocity = rides ? v : Eigen::Vector2f::Zero();
      Eigen::Vector2f centre = start;
      if (riding >= 0 && motion_updates > 8) centre += v * static_cast<float>(riding * kCycle);
      const Eigen::Vector2f window_v = velocity + draw2(vel_noise, rng);
      const auto& tracks = tracker.update({observed(7, centre + draw2(pos_noise, rng), window_v, 0.1f, t)}, t);
      REQUIRE(tracks.size() == 1);
      ever_moved = ever_moved || tracks.front().moving;
      if (riding >= 0) speed_error.push_back((tracks.front().velocity.head<2>() - velocity).norm());
    }
    return std::make_pair(speed_error, ever_moved);
  };
  const auto [restarted, moved] = ride({}, 100);
  CHECK(moved);
  for (std::size_t k = 3; k < restarted.size(); ++k) {
    CAPTURE(k);
    CHECK(restarted[k] < 1.0f);  // from the third update on, within 1 m/s
  }
  sc::KalmanTracker::Params late;
  late.restart_updates = 1000;
  const auto [held, held_moved] = ride(late, 100);
  CHECK(held[7] > 1.0f);  // without the restart, the static prior holds it back
  const auto [twice, twice_moved] = ride({}, 2);
  CHECK_FALSE(twice_moved);
  sc::KalmanTracker::Params bad;
  bad.restart_speed = 0.0f;
  CHECK_THROWS_WITH_AS(sc::KalmanTracker{bad}, doctest::Contains("restart_speed"), std::invalid_argument);
  bad = {};
  bad.restart_updates = 0;
  CHECK_THROWS_WITH_AS(sc::KalmanTracker{bad}, doctest::Contains("restart_updates"), std::invalid_argument);
}

TEST_CASE("KalmanTracker: what is shaped like structure starts no track; what is shaped like an object does") {
  sc::KalmanTracker tracker;  // birth_max_length 10 m, birth_flatness 0.1
  const auto shaped = [](sc::ComponentId id, float x, float length, float width, float height) {
    tr::ObjectObservation o = observed(id, {x, 0.0f});
    o.box.length = length;
    o.box.width = width;
    o.box.height = height;
    return o;
  };
  const std::vector<tr::ObjectObservation> seen{
      shaped(1, 0, 12.0f, 0.3f, 3.0f),   // a stretch of wall: too long
      shaped(2, 20, 6.0f, 4.0f, 0.3f),   // a patch of ground or ceiling: flat
      shaped(3, 40, 4.8f, 1.8f, 1.5f),   // a car
      shaped(4, 60, 0.5f, 0.4f, 1.7f),   // a person
      shaped(5, 80, 3.0f, 0.3f, 0.35f),  // a fallen log, barely not flat
      shaped(6, 100, 9.5f, 2.5f, 3.5f),  // a bus under 10 m
      shaped(7, 120, 0.6f, 0.05f, 1.2f),  // a piece of facade seen flat
      shaped(8, 140, 0.15f, 0.06f, 2.5f),  // a post seen from one side
      shaped(9, 160, 0.3f, 0.1f, 1.7f),   // a person seen from the side
  };
  for (int c = 0; c < 3; ++c) tracker.update(seen, c * kCycle);
  std::map<sc::ComponentId, std::size_t> tracks_of;
  for (const tr::Track& t : tracker.tracks()) ++tracks_of[t.cluster_id];
  CHECK(tracks_of.count(1) == 0);
  CHECK(tracks_of.count(2) == 0);
  CHECK(tracks_of.count(7) == 0);
  for (const sc::ComponentId id : {3, 4, 5, 6, 8, 9}) CHECK(tracks_of[id] == 1);
  for (const tr::Track& t : tracker.tracks()) CHECK(t.state == tr::TrackState::confirmed);
  sc::KalmanTracker::Params bad;
  bad.birth_flatness = 1.5f;
  CHECK_THROWS_WITH_AS(sc::KalmanTracker{bad}, doctest::Contains("birth_flatness"), std::invalid_argument);
  bad = {};
  bad.birth_min_width = -0.1f;
  CHECK_THROWS_WITH_AS(sc::KalmanTracker{bad}, doctest::Contains("birth_min_width"), std::invalid_argument);
  bad = {};
  bad.birth_max_length = -1.0f;
  CHECK_THROWS_WITH_AS(sc::KalmanTracker{bad}, doctest::Contains("birth_max_length"), std::invalid_argument);
}

TEST_CASE("NullTracker tracks nothing") {
  static_assert(!sc::NullTracker::enabled);
  static_assert(sc::is_tracker_policy_v<sc::NullTracker> && sc::is_tracker_policy_v<sc::KalmanTracker>);
  sc::NullTracker none;
  CHECK(none.update({observed(1, {0, 0})}, 0.0).empty());
  CHECK(none.tracks().empty());
}
