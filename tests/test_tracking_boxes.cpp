// SPDX-License-Identifier: MIT
// Oriented boxes and in-window velocities: the L-shape fit against an
// exhaustive search of its criterion and against the true boxes of random
// rectangles seen from one, two and four sides; the velocity from capture
// times against the true motion; ObjectBoxes on an objects engine watching
// a moving box on the ground.

#include <doctest/doctest.h>

#include <streamclust/objects_presets.hpp>
#include <streamclust/stream_clusterer.hpp>
#include <streamclust/tracking/object_boxes.hpp>
#include <streamclust/tracking/oriented_box.hpp>
#include <streamclust/tracking/window_velocity.hpp>

#include <Eigen/Geometry>

#include "support/constants.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace sc = streamclust;
namespace tr = streamclust::tracking;

namespace {

using streamclust::test::kPi;

/// Difference of two headings of lines (period pi) [rad], in [0, pi/2].
float heading_error(float a, float b) {
  float d = std::fmod(std::abs(a - b), kPi);
  return std::min(d, kPi - d);
}

/// A rectangle in the ground plane: centre, length along yaw, width across.
struct Rect {
  Eigen::Vector2f centre;
  float length, width, yaw;
  /// The point at (u, v) in the rectangle's frame, u along its length.
  Eigen::Vector2f at(float u, float v) const {
    const float c = std::cos(yaw), s = std::sin(yaw);
    return centre + Eigen::Vector2f(c * u - s * v, s * u + c * v);
  }
};

Rect random_rect(std::mt19937& rng) {
  std::uniform_real_distribution<float> pos(-30.0f, 30.0f), len(1.0f, 5.0f), ratio(0.3f, 0.8f),
      yaw(-0.5f * kPi, 0.5f * kPi);
  Rect r;
  const float x = pos(rng), y = pos(rng);
  r.centre = Eigen::Vector2f(x, y);
  r.length = len(rng);
  r.width = r.length * ratio(rng);
  r.yaw = yaw(rng);
  return r;
}

/// Points on the given sides of `r` (0: u = -L/2, 1: u = +L/2, 2: v = -W/2,
/// 3: v = +W/2), heights in [z0, z0 + h], noise `sigma` across the side.
std::vector<Eigen::Vector3f> points_on_sides(const Rect& r, const std::vector<int>& sides, int per_side, float z0,
                                             float h, float sigma, std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(-0.5f, 0.5f), up(0.0f, 1.0f);
  std::normal_distribution<float> noise(0.0f, sigma);
  std::vector<Eigen::Vector3f> out;
  for (int side : sides) {
    for (int i = 0; i < per_side; ++i) {
      const float along = unit(rng), across = noise(rng), z = z0 + h * up(rng);
      Eigen::Vector2f p;
      if (side < 2) {
        p = r.at((side == 0 ? -0.5f : 0.5f) * r.length + across, along * r.width);
      } else {
        p = r.at(along * r.length, (side == 2 ? -0.5f : 0.5f) * r.width + across);
      }
      out.emplace_back(p.x(), p.y(), z);
    }
  }
  return out;
}

/// The tightest box of `pts` at the rectangle's own heading: what a perfect
/// heading gives (the sides' sampled ends fall short of the corners).
/// A point captured at `t`: on side `side` of `r` (`bottom` to 1.5 m above
/// it) when `r` is given, else on level ground (z = -1 m) at a range drawn
/// from `ground_range` [m] in any direction.
sc::Point side_or_ground(double t, const Rect* r, int side, float bottom,
                         std::uniform_real_distribution<float>& ground_range, std::mt19937& rng) {
  sc::Point p;
  p.t = t;
  if (r != nullptr) {
    const Eigen::Vector3f q = points_on_sides(*r, {side}, 1, bottom, 1.5f, 0.01f, rng).front();
    p.x = q.x();
    p.y = q.y();
    p.z = q.z();
  } else {
    std::uniform_real_distribution<float> direction(-kPi, kPi);
    const float range = ground_range(rng), a = direction(rng);
    p.x = range * std::cos(a);
    p.y = range * std::sin(a);
    p.z = -1.0f;
  }
  return p;
}

Rect tight_at_heading(const std::vector<Eigen::Vector3f>& pts, const Rect& r) {
  const float c = std::cos(r.yaw), s = std::sin(r.yaw);
  float lo1 = 1e9f, hi1 = -1e9f, lo2 = 1e9f, hi2 = -1e9f;
  for (const auto& p : pts) {
    const float a = c * p.x() + s * p.y(), b = c * p.y() - s * p.x();
    lo1 = std::min(lo1, a);
    hi1 = std::max(hi1, a);
    lo2 = std::min(lo2, b);
    hi2 = std::max(hi2, b);
  }
  const float m1 = 0.5f * (lo1 + hi1), m2 = 0.5f * (lo2 + hi2);
  return Rect{Eigen::Vector2f(c * m1 - s * m2, s * m1 + c * m2), hi1 - lo1, hi2 - lo2, r.yaw};
}

/// The fitted box is the rectangle's (heading within 4 deg: the criterion's
/// own scatter at 2 cm of noise; extent within 0.1 m of the points' own
/// extent at the true heading, its long side either way).
bool matches(const tr::OrientedBox& b, const std::vector<Eigen::Vector3f>& pts, const Rect& r) {
  const Rect t = tight_at_heading(pts, r);
  const float long_side = std::max(t.length, t.width), short_side = std::min(t.length, t.width);
  return heading_error(b.yaw, t.length >= t.width ? r.yaw : r.yaw + 0.5f * kPi) < 4.0f * kPi / 180.0f &&
         std::abs(b.length - long_side) < 0.1f && std::abs(b.width - short_side) < 0.1f &&
         (b.center.head<2>() - t.centre).norm() < 0.1f;
}

/// The closeness criterion's best score over every heading in 0.05 deg
/// steps: the exhaustive search the fit's coarse-to-fine search stands for.
double exhaustive_best_score(const std::vector<Eigen::Vector2f>& xy, float floor) {
  double best = 0.0;
  for (int i = 0; i < 1800; ++i) {
    best = std::max(best, tr::detail::closeness_score(xy, static_cast<float>(i) * 0.05f * kPi / 180.0f, floor));
  }
  return best;
}

}  // namespace

TEST_CASE("fit_oriented_box: the heading search finds the exhaustive search's best score") {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 40; ++trial) {
    const Rect r = random_rect(rng);
    const std::vector<int> sides = trial % 2 == 0 ? std::vector<int>{0, 2} : std::vector<int>{1, 2, 3};
    const std::vector<Eigen::Vector3f> pts = points_on_sides(r, sides, 30, 0.0f, 1.0f, 0.02f, rng);
    Eigen::Vector2f mean = Eigen::Vector2f::Zero();
    for (const auto& p : pts) mean += p.head<2>();
    mean /= static_cast<float>(pts.size());
    std::vector<Eigen::Vector2f> xy;
    for (const auto& p : pts) xy.push_back(p.head<2>() - mean);
    const float theta = tr::detail::best_heading(xy, 0.01f);
    const double found = tr::detail::closeness_score(xy, theta, 0.01f);
    const double best = exhaustive_best_score(xy, 0.01f);
    CAPTURE(trial);
    CHECK(found >= 0.97 * best);
  }
}

TEST_CASE("fit_oriented_box: random rectangles seen as an L, whole and from one side") {
  std::mt19937 rng(11);
  tr::BoxFitParams params;
  tr::BoxFitScratch scratch;
  int l_within = 0, whole_within = 0, side_within = 0;
  constexpr int kTrials = 60;
  for (int trial = 0; trial < kTrials; ++trial) {
    const Rect r = random_rect(rng);
    CAPTURE(trial);
    // Two adjacent sides: heading, extent and centre are the rectangle's.
    {
      const auto pts = points_on_sides(r, {trial % 2, 2 + (trial / 2) % 2}, 40, -1.0f, 1.5f, 0.02f, rng);
      const tr::OrientedBox b = tr::fit_oriented_box(pts, std::nullopt, params, scratch);
      CHECK(b.quality == tr::BoxQuality::two_sides);
      l_within += matches(b, pts, r);
      CHECK(b.yaw >= -0.5f * kPi);
      CHECK(b.yaw < 0.5f * kPi);
      CHECK(b.length >= b.width);
      CHECK(b.center.z() == doctest::Approx(-0.25f).epsilon(0.05));
      CHECK(b.points == pts.size());
    }
    // All four sides.
    {
      const auto pts = points_on_sides(r, {0, 1, 2, 3}, 25, 0.0f, 1.0f, 0.02f, rng);
      const tr::OrientedBox b = tr::fit_oriented_box(pts, std::nullopt, params, scratch);
      whole_within += matches(b, pts, r);
    }
    // One long side: its heading, its length; the width is what shows.
    {
      const auto pts = points_on_sides(r, {2 + trial % 2}, 60, 0.0f, 1.0f, 0.02f, rng);
      const tr::OrientedBox b = tr::fit_oriented_box(pts, std::nullopt, params, scratch);
      CHECK(b.quality == tr::BoxQuality::one_side);
      side_within += matches(b, pts, r) && b.width < 0.2f;
    }
  }
  // Random draws can put few points near a corner: nearly all, not all.
  CHECK(l_within >= kTrials - 2);
  CHECK(whole_within >= kTrials - 2);
  CHECK(side_within >= kTrials - 2);
}

TEST_CASE("fit_oriented_box: the bottom is the ground under the object when it is near its lowest point") {
  std::mt19937 rng(3);
  const Rect r{Eigen::Vector2f(10.0f, 5.0f), 4.0f, 1.8f, 0.3f};
  const auto car = points_on_sides(r, {0, 2}, 50, -0.75f, 1.25f, 0.01f, rng);  // feet 0.25 m above the ground
  tr::BoxFitParams params;
  tr::BoxFitScratch scratch;
  const tr::OrientedBox standing = tr::fit_oriented_box(car, -1.0f, params, scratch);
  CHECK(standing.on_ground);
  CHECK(standing.bottom() == doctest::Approx(-1.0f).epsilon(0.001));
  CHECK(standing.height == doctest::Approx(1.5f).epsilon(0.02));
  // A crown 2 m above the ground keeps its own bottom.
  const auto crown = points_on_sides(r, {0, 2}, 50, 1.0f, 1.0f, 0.01f, rng);
  const tr::OrientedBox hanging = tr::fit_oriented_box(crown, -1.0f, params, scratch);
  CHECK_FALSE(hanging.on_ground);
  CHECK(hanging.bottom() == doctest::Approx(1.0f).epsilon(0.01));
  CHECK(hanging.height == doctest::Approx(1.0f).epsilon(0.02));
  // No ground known: the lowest point.
  const tr::OrientedBox unknown = tr::fit_oriented_box(car, std::nullopt, params, scratch);
  CHECK_FALSE(unknown.on_ground);
  const float lowest = std::min_element(car.begin(), car.end(), [](const auto& a, const auto& b) {
                         return a.z() < b.z();
                       })->z();
  CHECK(unknown.bottom() == doctest::Approx(lowest).epsilon(0.001));
}

TEST_CASE("fit_oriented_box: few and scattered points are flagged; a single point is a minimal box") {
  std::mt19937 rng(5);
  tr::BoxFitParams params;
  tr::BoxFitScratch scratch;
  const Rect r{Eigen::Vector2f(3.0f, -2.0f), 2.0f, 1.0f, 0.0f};
  const auto few = points_on_sides(r, {0, 2}, 3, 0.0f, 1.0f, 0.01f, rng);
  CHECK(tr::fit_oriented_box(few, std::nullopt, params, scratch).quality == tr::BoxQuality::few_points);
  // A ball of points (a bush): no side holds a quarter of them.
  std::normal_distribution<float> blob(0.0f, 0.5f);
  std::vector<Eigen::Vector3f> bush;
  for (int i = 0; i < 400; ++i) {
    const float bx = blob(rng), by = blob(rng), bz = blob(rng);
    bush.emplace_back(bx, by, bz);
  }
  CHECK(tr::fit_oriented_box(bush, std::nullopt, params, scratch).quality == tr::BoxQuality::scattered);
  const tr::OrientedBox one = tr::fit_oriented_box({Eigen::Vector3f(1, 2, 3)}, std::nullopt, params, scratch);
  CHECK(one.points == 1);
  CHECK(one.length == params.min_size);
  CHECK(one.center.x() == doctest::Approx(1.0f));
  CHECK(one.center.y() == doctest::Approx(2.0f));
  CHECK(tr::fit_oriented_box({}, std::nullopt, params, scratch).points == 0);
}

TEST_CASE("box, velocity and object settings out of range name themselves") {
  tr::BoxFitParams fit;
  fit.side_share = 0.0f;
  CHECK_THROWS_WITH_AS(fit.validate(), doctest::Contains("BoxFitParams: side_share"), std::invalid_argument);
  tr::WindowVelocityParams velocity;
  velocity.min_slices = 2;
  CHECK_THROWS_WITH_AS(velocity.validate(), doctest::Contains("WindowVelocityParams: min_slices"),
                       std::invalid_argument);
  tr::ObjectBoxParams objects;
  objects.ground_margin = -1.0f;
  CHECK_THROWS_WITH_AS(tr::ObjectBoxes{objects}, doctest::Contains("ObjectBoxParams: ground_margin"),
                       std::invalid_argument);
  tr::ObjectBoxParams reuse;
  reuse.lookup_reuse_seconds = -0.1;
  CHECK_THROWS_WITH_AS(tr::ObjectBoxes{reuse}, doctest::Contains("ObjectBoxParams: lookup_reuse_seconds"),
                       std::invalid_argument);
  reuse.lookup_reuse_seconds = 0.0;  // at every retrieval: allowed
  reuse.lookup_reuse_shift = 11.0f;
  CHECK_THROWS_WITH_AS(tr::ObjectBoxes{reuse}, doctest::Contains("ObjectBoxParams: lookup_reuse_shift"),
                       std::invalid_argument);
  reuse.lookup_reuse_shift = 0.0f;
  CHECK_NOTHROW(tr::ObjectBoxes{reuse});
}

namespace {

/// Points of a 1.8 x 0.8 x 1.7 m box moving at `v` [m/s], seen from its
/// sides at random over `seconds`, each side's points at random heights:
/// the parts of an object show at different times, as in a scan.
struct MovingBox {
  Eigen::Vector2f start, v;
  std::vector<Eigen::Vector3f> xyz;
  std::vector<double> t;
};

MovingBox moving_box(Eigen::Vector2f v, double seconds, int points, std::mt19937& rng) {
  MovingBox m{Eigen::Vector2f(12.0f, -3.0f), v, {}, {}};
  std::uniform_real_distribution<double> time(0.0, seconds);
  std::uniform_int_distribution<int> side(0, 3);
  for (int i = 0; i < points; ++i) {
    const double ti = time(rng);
    const Rect r{m.start + v * static_cast<float>(ti), 1.8f, 0.8f, 0.4f};
    const auto p = points_on_sides(r, {side(rng)}, 1, -1.0f, 1.7f, 0.02f, rng);
    m.xyz.push_back(p.front());
    m.t.push_back(100.0 + ti);
  }
  return m;
}

}  // namespace

TEST_CASE("window_velocity: the motion within one window from the points' capture times") {
  std::mt19937 rng(19);
  tr::WindowVelocityParams params;
  tr::WindowVelocityScratch scratch;
  double sq_moving = 0.0, sq_static = 0.0;
  int within_error = 0;
  constexpr int kTrials = 40;
  for (int trial = 0; trial < kTrials; ++trial) {
    std::uniform_real_distribution<float> speed(0.5f, 3.0f), dir(-kPi, kPi);
    const float s = speed(rng), d = dir(rng);
    const Eigen::Vector2f v(s * std::cos(d), s * std::sin(d));
    const MovingBox m = moving_box(v, 0.5, 400, rng);
    const tr::WindowVelocity w = tr::window_velocity(m.xyz, m.t, params, scratch);
    REQUIRE(w.valid);
    CHECK(w.slices == 5);
    const float e = (w.velocity - v).norm();
    sq_moving += static_cast<double>(e * e);
    within_error += e <= 3.0f * std::sqrt(2.0f) * w.error;
    const MovingBox still = moving_box(Eigen::Vector2f::Zero(), 0.5, 400, rng);
    const tr::WindowVelocity ws = tr::window_velocity(still.xyz, still.t, params, scratch);
    REQUIRE(ws.valid);
    sq_static += static_cast<double>(ws.velocity.squaredNorm());
  }
  const double rmse_moving = std::sqrt(sq_moving / kTrials), rmse_static = std::sqrt(sq_static / kTrials);
  CAPTURE(rmse_moving);
  CAPTURE(rmse_static);
  CHECK(rmse_moving < 0.35);
  CHECK(rmse_static < 0.3);
  // The standard error covers the error (3 sigma) nearly always.
  CHECK(within_error >= kTrials - 3);
  // Too short for three slices: no measurement.
  const MovingBox brief = moving_box(Eigen::Vector2f(1.0f, 0.0f), 0.15, 100, rng);
  CHECK_FALSE(tr::window_velocity(brief.xyz, brief.t, params, scratch).valid);
  CHECK_THROWS_AS(tr::window_velocity(brief.xyz, {}, params, scratch), std::invalid_argument);
}

TEST_CASE("window_velocity: a standing object going out of view is no clear motion; a moving one is") {
  // A desk 1.6 m long along x, standing; the edge of the field of view
  // sweeps over it at 1.5 m/s, so at time t only x >= 2.4 + 1.5 t shows.
  // Its centroid moves; its far end does not.
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> time(0.0, 0.5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> noise(0.0f, 0.02f);
  std::vector<Eigen::Vector3f> xyz;
  std::vector<double> t;
  for (int i = 0; i < 2000; ++i) {
    const double ti = time(rng);
    const float edge = 2.4f + 1.5f * static_cast<float>(ti);
    const float x = edge + (4.0f - edge) * unit(rng);
    xyz.emplace_back(x + noise(rng), -1.5f + 0.8f * unit(rng), 0.75f + noise(rng));
    t.push_back(10.0 + ti);
  }
  tr::WindowVelocityParams params;
  tr::WindowVelocityScratch scratch;
  const tr::WindowVelocity sweep = tr::window_velocity(xyz, t, params, scratch);
  REQUIRE(sweep.valid);
  CAPTURE(sweep.velocity.transpose());
  CAPTURE(sweep.error);
  CAPTURE(sweep.end_difference);
  // The centroid follows the edge, tightly: by its error alone it would be motion.
  CHECK(sweep.velocity.x() > 0.5f);
  CHECK(sweep.velocity.norm() > 3.0f * sweep.error);
  // Its near end moves at the edge's 1.5 m/s, its far end stands.
  CHECK(sweep.end_difference == doctest::Approx(1.5f).epsilon(0.2));
  CHECK(sweep.end_difference > sweep.velocity.norm());
  // A box moving at 1.5 m/s, seen whole: both ends move with it.
  const MovingBox m = moving_box(Eigen::Vector2f(1.5f, 0.0f), 0.5, 2000, rng);
  const tr::WindowVelocity moving = tr::window_velocity(m.xyz, m.t, params, scratch);
  REQUIRE(moving.valid);
  CAPTURE(moving.end_difference);
  CHECK(moving.velocity.norm() > 5.0f * moving.error);
  CHECK(moving.end_difference < 0.3f);
}

TEST_CASE("ObjectBoxes: a box moving past an objects engine: its velocity, its box undone of the motion, on the "
          "ground") {
  // Sensor 1 m above level ground, at rest (world = sensor frame, ground at
  // z = -1); a 1.8 x 0.8 x 1.7 m box 12 m out moving at 1.2 m/s; ground
  // returns beyond 9 m, where a level Mid-360 sees the ground.
  sc::ObjectsSetup setup;
  setup.sensor_height = 1.0f;
  sc::StreamClusterer<sc::ObjectsConfig> engine(sc::objects_mid360_params(setup));
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> ground_r(9.0f, 20.0f);
  std::uniform_int_distribution<int> side(0, 1);
  const Eigen::Vector2f start(12.0f, -2.0f), v(0.0f, 1.2f);
  constexpr float kYaw = 0.4f;
  tr::ObjectBoxes boxes;
  int checked = 0;
  const double rate = 100000.0;  // points per second
  double next_retrieval = 0.55;
  for (int i = 0; i < 120000; ++i) {
    const double t = static_cast<double>(i) / rate;
    const Rect r{start + v * static_cast<float>(t), 1.8f, 0.8f, kYaw};
    const bool on_box = i % 4 == 0;  // the box's two sides facing the sensor
    engine.insert(side_or_ground(t, on_box ? &r : nullptr, on_box && side(rng) == 0 ? 0 : 2, -0.8f, ground_r, rng));
    if (i == 20000) {  // 0.2 s: the engine still calibrates; its result holds no point
      REQUIRE(engine.calibrating());
      CHECK(boxes.update(engine, engine.retrieve()).empty());
    }
    if (t < next_retrieval) continue;
    next_retrieval += 0.05;
    const sc::Clustering& result = engine.retrieve();
    const auto& objects = boxes.update(engine, result);
    // The box's component: the one whose box holds the box's true centre now.
    const Eigen::Vector2f truth = Rect{start + v * static_cast<float>(result.time), 1.8f, 0.8f, kYaw}.centre;
    const tr::ObjectObservation* seen = nullptr;
    for (const auto& o : objects) {
      if ((o.box.center.head<2>() - truth).norm() < 0.5f) seen = &o;
    }
    REQUIRE(seen != nullptr);
    const auto summary = std::find_if(result.components.begin(), result.components.end(),
                                      [&](const sc::ComponentSummary& c) { return c.id == seen->id; });
    REQUIRE(summary != result.components.end());
    CHECK(seen->box.points == summary->size);
    CHECK(seen->velocity.valid);
    CHECK((seen->velocity.velocity - v).norm() < 0.3f);
    CHECK(seen->compensated);
    // Undone of 0.5 s of motion (0.6 m), the box is the box.
    CHECK(seen->box.length == doctest::Approx(1.8f).epsilon(0.1));
    CHECK(seen->box.width == doctest::Approx(0.8f).epsilon(0.15));
    CHECK(heading_error(seen->box.yaw, kYaw) < 3.0f * kPi / 180.0f);
    CHECK(seen->box.on_ground);
    CHECK(seen->box.bottom() == doctest::Approx(-1.0f).epsilon(0.05));
    CHECK(seen->time == result.time);
    ++checked;
  }
  CHECK(checked >= 10);
  // A stale result is refused.
  sc::Clustering stale = engine.last_result();
  engine.insert(sc::Point{15.0f, 0.0f, 0.5f, 0.0f, 1.3});
  engine.retrieve();
  CHECK_THROWS_AS(boxes.update(engine, stale), std::logic_error);
}

TEST_CASE("ObjectBoxes: every observation is seen from the sensor's position in the world") {
  // A standing box 10 m out, the sensor mounted 2 m ahead and 1 m to the
  // right of the world's origin (level): each observation's viewpoint is
  // the mount's place; before any point is boxed, none is known.
  sc::ObjectsSetup setup;
  setup.sensor_height = 1.0f;
  setup.mount.translation = Eigen::Vector3d(2.0, -1.0, 0.0);
  sc::StreamClusterer<sc::ObjectsConfig> engine(sc::objects_mid360_params(setup));
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> ground_r(9.0f, 20.0f);
  const Rect r{{10.0f, 1.0f}, 1.0f, 0.6f, 0.2f};
  tr::ObjectBoxes boxes;
  int seen = 0;
  for (int i = 0; i < 70000; ++i) {
    const double t = static_cast<double>(i) / 100000.0;
    engine.insert(side_or_ground(t, i % 4 == 0 ? &r : nullptr, i % 8 == 0 ? 0 : 3, -0.8f, ground_r, rng));
    if (i % 5000 != 4999 || t < 0.55) continue;
    for (const tr::ObjectObservation& o : boxes.update(engine, engine.retrieve())) {
      REQUIRE(o.viewpoint);
      CHECK((*o.viewpoint - Eigen::Vector3f(2.0f, -1.0f, 0.0f)).norm() < 1e-3f);
      ++seen;
    }
  }
  CHECK(seen >= 3);
  tr::ObjectObservation unseen;
  CHECK_FALSE(unseen.viewpoint);
}

TEST_CASE("ObjectBoxes: a standing object's ground is looked up again after lookup_reuse_seconds") {
  // Sensor 1 m above level ground, at rest; a 1 x 1 x 1.5 m box standing
  // 16 m out, where the ground stays unknown until its returns (9-14.5 m out,
  // apart from the box) begin at 1 s. Three ObjectBoxes read the same retrievals: one looks the
  // ground up at every retrieval, one reuses a lookup for 0.5 s, one for 10 s.
  sc::ObjectsSetup setup;
  setup.sensor_height = 1.0f;
  sc::StreamClusterer<sc::ObjectsConfig> engine(sc::objects_mid360_params(setup));
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> ground_r(9.0f, 14.5f);
  std::uniform_int_distribution<int> side(0, 1);
  const Rect box{Eigen::Vector2f(16.0f, 1.0f), 1.0f, 1.0f, 0.3f};
  tr::ObjectBoxParams fresh_params, reuse_params, long_params;
  fresh_params.lookup_reuse_seconds = 0.0;
  long_params.lookup_reuse_seconds = 10.0;
  tr::ObjectBoxes fresh(fresh_params), reuse(reuse_params), stale(long_params);
  auto ground_of_box = [&](const std::vector<tr::ObjectObservation>& objects) {
    for (const auto& o : objects) {
      if ((o.box.center.head<2>() - box.centre).norm() < 0.5f) return std::optional<std::optional<float>>{o.ground_z};
    }
    return std::optional<std::optional<float>>{};
  };
  const double rate = 100000.0;  // points per second
  double next_retrieval = 0.55, fresh_found = -1.0, reuse_found = -1.0;
  int compared = 0;
  for (int i = 0; i < 250000; ++i) {
    const double t = static_cast<double>(i) / rate;
    const bool on_box = i % 4 == 0 || t < 1.0;
    engine.insert(side_or_ground(t, on_box ? &box : nullptr, on_box && side(rng) == 0 ? 0 : 2, -1.0f, ground_r, rng));
    if (t < next_retrieval) continue;
    next_retrieval += 0.05;
    const sc::Clustering& result = engine.retrieve();
    const auto a = ground_of_box(fresh.update(engine, result));
    const auto b = ground_of_box(reuse.update(engine, result));
    const auto c = ground_of_box(stale.update(engine, result));
    REQUIRE(a);
    REQUIRE(b);
    REQUIRE(c);
    CAPTURE(result.time);
    if (result.time < 1.0) {
      CHECK_FALSE(*a);  // no ground in view yet
      CHECK_FALSE(*b);
    }
    if (*a && fresh_found < 0.0) fresh_found = result.time;
    if (*b && reuse_found < 0.0) reuse_found = result.time;
    CHECK_FALSE(*c);  // looked up once, before the ground came, and never again
    if (*a && *b) {
      CHECK(**b == doctest::Approx(**a).epsilon(0.05));
      ++compared;
    }
  }
  REQUIRE(fresh_found > 0.0);
  REQUIRE(reuse_found >= fresh_found);
  CHECK(reuse_found - fresh_found <= 0.5 + 1e-6);
  CHECK(compared >= 10);
}

TEST_CASE("ObjectBoxes: a fast mover seen in pieces one after another is one object with its velocity") {
  // A 1.0 x 0.6 x 1.5 m box at 15 m/s, 20 m out, seen only in bursts of
  // 0.1 s every 0.25 s (a scan pattern coming back to it): each burst is a
  // piece of its own component 1.25 m from the next, too short in time for
  // a window velocity of its own. Linked, the pieces are one object at the
  // box's place now, moving at its velocity; unlinked, pieces without one.
  // The same box hanging 2.2 m above the ground is the top of a structure
  // the view passes over: not linked unless the clearance allows it.
  sc::ObjectsSetup setup;
  setup.sensor_height = 1.0f;
  const Eigen::Vector2f start(20.0f, -6.0f), v(0.0f, 15.0f);
  constexpr float kYaw = 1.5707963f;  // along its motion
  struct Outcome {
    int retrievals = 0;       // retrievals checked
    int linked_right = 0;     // one linked object at the box's place with its velocity
    int one_on_path = 0;      // exactly one object along the box's path over the window
    int several_pieces = 0;   // objects of two or more pieces
  };
  const auto run = [&](const tr::ObjectBoxParams& params, float bottom) {
    sc::StreamClusterer<sc::ObjectsConfig> engine(sc::objects_mid360_params(setup));
    tr::ObjectBoxes boxes(params);
    std::mt19937 rng(29);
    std::uniform_real_distribution<float> ground_r(9.0f, 30.0f);
    std::uniform_int_distribution<int> side(0, 1);
    const double rate = 100000.0;
    double next_retrieval = 0.6;
    Outcome out;
    for (int i = 0; i < 120000; ++i) {
      const double t = static_cast<double>(i) / rate;
      const bool on_box = std::fmod(t, 0.25) < 0.1 && i % 4 == 0;  // in a burst
      const Rect r{start + v * static_cast<float>(t), 1.0f, 0.6f, kYaw};
      engine.insert(side_or_ground(t, on_box ? &r : nullptr, on_box && side(rng) == 0 ? 1 : 2, bottom, ground_r, rng));
      if (t < next_retrieval) continue;
      next_retrieval += 0.05;
      const sc::Clustering& result = engine.retrieve();
      const Eigen::Vector2f truth = start + v * static_cast<float>(result.time);
      int on_path = 0;
      for (const auto& o : boxes.update(engine, result)) {
        const Eigen::Vector2f c = o.box.center.head<2>();
        if (std::abs(c.x() - truth.x()) > 1.0f || c.y() < truth.y() - 9.0f || c.y() > truth.y() + 2.0f) continue;
        ++on_path;
        if (o.pieces >= 2) ++out.several_pieces;
        if (o.pieces >= 2 && o.compensated && (c - truth).norm() < 1.0f &&
            (o.velocity.velocity - v).norm() < 1.5f) {
          ++out.linked_right;
        }
      }
      if (on_path == 1) ++out.one_on_path;
      ++out.retrievals;
    }
    return out;
  };
  tr::ObjectBoxParams linking;
  tr::ObjectBoxParams unlinked;
  unlinked.link_pieces = false;
  tr::ObjectBoxParams any_clearance;
  any_clearance.piece_max_clearance = 100.0f;

  const Outcome on_ground = run(linking, -0.8f);
  CHECK(on_ground.retrievals >= 10);
  CHECK(on_ground.linked_right == on_ground.retrievals);
  CHECK(on_ground.one_on_path == on_ground.retrievals);
  const Outcome off = run(unlinked, -0.8f);
  CHECK(off.several_pieces == 0);
  CHECK(off.one_on_path < off.retrievals);  // the pieces were separate objects

  const Outcome hanging = run(linking, 1.2f);
  CHECK(hanging.retrievals >= 10);
  CHECK(hanging.several_pieces == 0);
  const Outcome hanging_allowed = run(any_clearance, 1.2f);
  CHECK(hanging_allowed.linked_right == hanging_allowed.retrievals);
}
