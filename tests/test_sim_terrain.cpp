// SPDX-License-Identifier: MIT
// The terrain height field (values, validation, ray casting against a
// brute-force march), surface classes of every ready-made scene, and the
// hills scene (contents, objects standing on the terrain, determinism).

#include <doctest/doctest.h>

#include <streamclust/sim/scene.hpp>
#include <streamclust/sim/scenes.hpp>
#include <streamclust/sim/terrain.hpp>

#include <Eigen/Core>

#include "support/constants.hpp"
#include "support/directions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace sc = streamclust;
namespace sim = streamclust::sim;

using streamclust::test::kInf;
using streamclust::test::kPi;
using streamclust::test::spherical;

/// A terrain with every kind of term: two waves, a ramp, a strip and a single step.
sim::Terrain::Params busy_params() {
  sim::Terrain::Params p;
  p.lo = {-40.0f, -40.0f};
  p.hi = {40.0f, 40.0f};
  p.base_height = 0.2f;
  p.waves = {{0.6f, 0.15f, 0.05f, 0.3f}, {0.25f, -0.1f, 0.2f, 1.0f}};
  p.ramps = {{{1.0f, 1.0f}, 10.0f, 8.0f, 0.8f}};
  p.steps = {{{0.0f, 1.0f}, 5.0f, 9.0f, 0.15f}, {{-1.0f, 0.0f}, 12.0f, kInf, -0.2f}};
  return p;
}

/// True when `p` lies on the terrain: on the surface, or on the vertical face of a step edge.
bool on_terrain(const sim::Terrain& t, const Eigen::Vector3f& p, float tol) {
  if (std::abs(p.z() - t.height(p.x(), p.y())) <= tol) return true;
  for (const sim::TerrainStep& s : t.params().steps) {
    const float u = s.direction.dot(p.head<2>());
    for (const float edge : {s.from, s.to}) {
      if (!std::isfinite(edge) || std::abs(u - edge) > tol) continue;
      const Eigen::Vector2f below = p.head<2>() - 2.0f * tol * s.direction;
      const Eigen::Vector2f above = p.head<2>() + 2.0f * tol * s.direction;
      const float h0 = t.height(below.x(), below.y());
      const float h1 = t.height(above.x(), above.y());
      if (p.z() >= std::min(h0, h1) - tol && p.z() <= std::max(h0, h1) + tol) return true;
    }
  }
  return false;
}

/// The first crossing found by a fine fixed-step march (the oracle), or nothing.
std::optional<float> brute_force(const sim::Terrain& t, const Eigen::Vector3f& o, const Eigen::Vector3f& d, float step,
                                 float t_end) {
  for (float s = step; s <= t_end; s += step) {
    const Eigen::Vector3f q = o + s * d;
    if (!t.contains(q.x(), q.y())) continue;
    if (q.z() <= t.height(q.x(), q.y())) return s;
  }
  return std::nullopt;
}

}  // namespace

TEST_CASE("sim terrain: heights of waves, ramps and steps; bounds and slope") {
  sim::Terrain::Params p;
  p.base_height = 1.0f;
  p.waves = {{0.3f, 0.2f, 0.0f, 0.0f}};
  p.ramps = {{{2.0f, 0.0f}, 10.0f, 10.0f, 2.0f}};  // direction normalized by Terrain
  p.steps = {{{0.0f, 1.0f}, 3.0f, 6.0f, 0.15f}};
  const sim::Terrain t(p);
  CHECK(t.height(0.0f, 0.0f) == doctest::Approx(1.0f));
  CHECK(t.height(2.5f * kPi, 0.0f) == doctest::Approx(1.3f));         // wave crest (0.2 x = pi / 2)
  CHECK(t.height(15.0f, 0.0f) == doctest::Approx(1.0f + 0.3f * std::sin(3.0f) + 1.0f));  // half-way up the ramp
  CHECK(t.height(30.0f, 0.0f) == doctest::Approx(1.0f + 0.3f * std::sin(6.0f) + 2.0f));  // above the ramp
  CHECK(t.height(0.0f, 3.0f) == doctest::Approx(1.15f));              // on the strip: from is inside
  CHECK(t.height(0.0f, 5.99f) == doctest::Approx(1.15f));
  CHECK(t.height(0.0f, 6.0f) == doctest::Approx(1.0f));               // to is outside
  CHECK(t.step_height(0.0f, 4.0f) == doctest::Approx(0.15f));
  CHECK(t.max_slope() == doctest::Approx(0.3f * 0.2f + 0.2f));
  CHECK(t.max_slope_deg() == doctest::Approx(std::atan(0.26) * 180.0 / 3.14159265358979).epsilon(1e-6));
  const sim::Aabb b = t.bounds();
  CHECK(b.lo.z() <= 0.7f);
  CHECK(b.hi.z() >= 1.0f + 0.3f + 2.0f + 0.15f);
  CHECK(b.lo.x() == -50.0f);
  CHECK(b.hi.y() == 50.0f);
  CHECK(t.contains(49.0f, -49.0f));
  CHECK_FALSE(t.contains(51.0f, 0.0f));
}

TEST_CASE("sim terrain: invalid params throw std::invalid_argument naming the parameter") {
  const auto message = [](const sim::Terrain::Params& p) -> std::string {
    try {
      const sim::Terrain t{p};
      (void)t;
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  sim::Terrain::Params p;
  p.waves = {{2.0f, 0.2f, 0.0f, 0.0f}};  // slope 0.4 > tan 15 deg
  CHECK(message(p).find("slope bound") != std::string::npos);
  p.waves = {{1.0f, 0.2f, 0.0f, 0.0f}};  // 0.2: fine alone
  CHECK(message(p).empty());
  p.ramps = {{{1.0f, 0.0f}, 0.0f, 10.0f, 1.0f}};  // + 0.1: 0.3 > 0.268
  CHECK(message(p).find("slope bound") != std::string::npos);
  p = sim::Terrain::Params{};
  p.ramps = {{{1.0f, 0.0f}, 0.0f, 10.0f, 2.6f}};  // 14.6 deg alone: fine
  CHECK(message(p).empty());
  p.ramps = {{{1.0f, 0.0f}, 0.0f, 0.0f, 0.1f}};
  CHECK(message(p).find("ramps length") != std::string::npos);
  p.ramps = {{{0.0f, 0.0f}, 0.0f, 1.0f, 0.1f}};
  CHECK(message(p).find("ramps direction") != std::string::npos);
  p = sim::Terrain::Params{};
  p.steps = {{{1.0f, 0.0f}, 0.0f, 5.0f, 0.6f}};
  CHECK(message(p).find("steps height") != std::string::npos);
  p.steps = {{{1.0f, 0.0f}, 5.0f, 5.0f, 0.1f}};
  CHECK(message(p).find("steps to") != std::string::npos);
  p.steps.assign(9, sim::TerrainStep{});
  CHECK(message(p).find("steps (count)") != std::string::npos);
  p = sim::Terrain::Params{};
  p.hi = {-60.0f, 10.0f};
  CHECK(message(p).find("hi") != std::string::npos);
  p = sim::Terrain::Params{};
  p.min_step = 0.0f;
  CHECK(message(p).find("min_step") != std::string::npos);
  p = sim::Terrain::Params{};
  p.tolerance = 0.1f;  // > min_step
  CHECK(message(p).find("tolerance") != std::string::npos);
  p = sim::Terrain::Params{};
  p.base_height = std::numeric_limits<float>::quiet_NaN();
  CHECK(message(p).find("base_height") != std::string::npos);
}

TEST_CASE("sim terrain: known intersections, kerb faces, inside, t_max") {
  sim::Terrain::Params p;
  p.steps = {{{1.0f, 0.0f}, 5.0f, 8.0f, 0.15f}};
  const sim::Terrain flat(p);
  // Straight down onto the flat part and onto the strip.
  CHECK(flat.intersect({0, 0, 1}, {0, 0, -1}).value_or(-1.0f) == doctest::Approx(1.0f).epsilon(1e-4));
  CHECK(flat.intersect({6, 0, 1}, {0, 0, -1}).value_or(-1.0f) == doctest::Approx(0.85f).epsilon(1e-4));
  // Horizontal at 0.1 m: the kerb face at x = 5, exactly.
  CHECK(flat.intersect({0, 0, 0.1f}, {1, 0, 0}).value_or(-1.0f) == doctest::Approx(5.0f).epsilon(1e-6));
  // Horizontal at 0.2 m: over the strip, nothing.
  CHECK_FALSE(flat.intersect({0, 0, 0.2f}, {1, 0, 0}));
  // From the far side at 0.1 m going -x: the face at x = 8.
  CHECK(flat.intersect({20, 0, 0.1f}, {-1, 0, 0}).value_or(-1.0f) == doctest::Approx(12.0f).epsilon(1e-6));
  // Slanted: from 1 m, 45 deg down: z = 0 at 1 m along x.
  const Eigen::Vector3f down45 = Eigen::Vector3f(1, 0, -1).normalized();
  CHECK(flat.intersect({0, 0, 1}, down45).value_or(-1.0f) == doctest::Approx(std::sqrt(2.0f)).epsilon(1e-4));
  // Not normalized: t in units of |direction|.
  CHECK(flat.intersect({0, 0, 1}, {0, 0, -4}).value_or(-1.0f) == doctest::Approx(0.25f).epsilon(1e-4));
  // Looking up, below the surface (inside the solid), beyond t_max, outside the rectangle.
  CHECK_FALSE(flat.intersect({0, 0, 1}, {0, 0, 1}));
  CHECK_FALSE(flat.intersect({0, 0, -0.5f}, {1, 0, 0}));
  CHECK_FALSE(flat.intersect({0, 0, -0.5f}, {0, 0, -1}));
  CHECK_FALSE(flat.intersect({0, 0, 1}, {0, 0, -1}, 0.9f));
  CHECK_FALSE(flat.intersect({60, 0, 1}, {0, 0, -1}));
  CHECK_FALSE(flat.intersect({0, 0, 1}, {0, 0, 0}));
  CHECK_FALSE(flat.intersect({0, 0, std::numeric_limits<float>::quiet_NaN()}, {0, 0, -1}));

  // In a ShapeSet: the nearer of a box and the terrain.
  sim::ShapeSet set;
  set.add(flat).add(sim::Box::aligned({2, -1, 0}, {3, 1, 1}));
  CHECK(set.size() == 2);
  CHECK_FALSE(set.unbounded());
  CHECK(set.nearest({0, 0, 0.5f}, {1, 0, 0}) == doctest::Approx(2.0f));
  CHECK(set.nearest({0, 0, 0.5f}, {0, 0, -1}) == doctest::Approx(0.5f).epsilon(1e-4));
}

TEST_CASE("sim terrain: every hit lies on the terrain and matches a fine brute-force march") {
  const sim::Terrain t(busy_params());
  sim::detail::SplitMix64 rng(42);
  int hits = 0;
  int faces = 0;
  int mismatches = 0;
  for (int i = 0; i < 400; ++i) {
    const float x = rng.uniform(-30.0f, 30.0f);
    const float y = rng.uniform(-30.0f, 30.0f);
    const float above = rng.uniform(0.3f, 3.0f);
    const Eigen::Vector3f o(x, y, t.height(x, y) + above);
    const float az = rng.uniform(0.0f, 2.0f * kPi);
    const float el = rng.uniform(-1.4f, -0.06f);
    const Eigen::Vector3f d = spherical(az, el);
    const std::optional<float> hit = t.intersect(o, d);
    const std::optional<float> oracle = brute_force(t, o, d, 0.002f, 120.0f);
    REQUIRE(hit.has_value() == oracle.has_value());
    if (!hit) continue;
    ++hits;
    const Eigen::Vector3f p = o + *hit * d;
    CAPTURE(i);
    CHECK(on_terrain(t, p, 1e-3f));
    faces += std::abs(p.z() - t.height(p.x(), p.y())) > 1e-3f;
    // The oracle's first sample below the surface is at most one step past the crossing.
    mismatches += !(*hit <= *oracle + 1e-3f && *hit >= *oracle - 0.002f - 1e-3f);
  }
  CHECK(hits > 300);
  CHECK(faces > 0);  // some rays met a kerb face
  CHECK(mismatches == 0);
}

TEST_CASE("sim scenes: surface classes of office, forest and street structure") {
  const auto scan = [](const sim::Scene& scene, const Eigen::Vector3f& o,
                       std::map<sc::SurfaceClass, int>& seen) {
    for (int i = 0; i < 7200; ++i) {
      const float az = 2.0f * kPi * static_cast<float>(i % 120) / 120.0f;
      const float el = -1.5f + 3.0f * static_cast<float>(i / 120) / 59.0f;
      const Eigen::Vector3f d = spherical(az, el);
      const std::optional<sim::Hit> hit = scene.cast(o, d, 0.0);
      if (!hit || hit->range > 60.0f) continue;
      ++seen[hit->surface];
      if (hit->instance > 0) {
        CHECK(hit->surface == sc::SurfaceClass::object);
        continue;
      }
      CHECK(hit->surface != sc::SurfaceClass::object);
    }
  };
  {
    const sim::Scene office = sim::office_scene(4);
    std::map<sc::SurfaceClass, int> seen;
    scan(office, {0, 0, 1.2f}, seen);
    int checked = 0;
    for (int i = 0; i < 7200; ++i) {
      const float az = 2.0f * kPi * static_cast<float>(i % 120) / 120.0f;
      const float el = -1.5f + 3.0f * static_cast<float>(i / 120) / 59.0f;
      const Eigen::Vector3f d = spherical(az, el);
      const Eigen::Vector3f o(0, 0, 1.2f);
      const std::optional<sim::Hit> hit = office.cast(o, d, 0.0);
      if (!hit || hit->instance > 0) continue;
      const Eigen::Vector3f p = o + hit->range * d;
      const bool wall = std::abs(std::abs(p.x()) - 10.0f) < 1e-3f || std::abs(std::abs(p.y()) - 6.0f) < 1e-3f;
      const sc::SurfaceClass expected = std::abs(p.z()) < 1e-3f          ? sc::SurfaceClass::ground
                                        : std::abs(p.z() - 3.0f) < 1e-3f ? sc::SurfaceClass::ceiling
                                        : wall                           ? sc::SurfaceClass::wall
                                                                         : sc::SurfaceClass::object;
      CHECK(hit->surface == expected);
      ++checked;
    }
    CHECK(checked > 3000);
    CHECK(seen[sc::SurfaceClass::ground] > 100);
    CHECK(seen[sc::SurfaceClass::wall] > 100);
    CHECK(seen[sc::SurfaceClass::ceiling] > 100);
    CHECK(seen[sc::SurfaceClass::object] > 100);
  }
  {
    const sim::Scene forest = sim::forest_scene(4);
    std::map<sc::SurfaceClass, int> seen;
    scan(forest, {0, 0, 1.0f}, seen);
    CHECK(seen[sc::SurfaceClass::ground] > 1000);
    CHECK(seen[sc::SurfaceClass::object] > 100);
    CHECK(seen.count(sc::SurfaceClass::wall) == 0);
    CHECK(seen.count(sc::SurfaceClass::ceiling) == 0);
  }
  {
    const sim::Scene street = sim::street_scene(4);
    std::map<sc::SurfaceClass, int> seen;
    const Eigen::Vector3f o(0, 0, 1.5f);
    scan(street, o, seen);
    int kerbs = 0;
    for (int i = 0; i < 20000; ++i) {
      const float az = 2.0f * kPi * static_cast<float>(i % 400) / 400.0f;
      const float el = -0.6f + 0.9f * static_cast<float>(i / 400) / 49.0f;
      const Eigen::Vector3f d = spherical(az, el);
      const std::optional<sim::Hit> hit = street.cast(o, d, 0.0);
      if (!hit || hit->instance > 0) continue;
      const Eigen::Vector3f p = o + hit->range * d;
      // Road (also seen through alleys), sidewalk tops and kerb faces are ground; building blocks are walls.
      const float ay = std::abs(p.y());
      const bool road = std::abs(p.z()) < 1e-3f;
      const bool sidewalk = std::abs(p.z() - 0.15f) < 1e-3f && ay >= 7.0f - 1e-3f && ay <= 12.0f + 1e-3f;
      const bool kerb = std::abs(ay - 7.0f) < 1e-3f && p.z() > -1e-3f && p.z() < 0.15f + 1e-3f;
      CHECK(hit->surface == (road || sidewalk || kerb ? sc::SurfaceClass::ground : sc::SurfaceClass::wall));
      kerbs += kerb && !road && !sidewalk;
    }
    CHECK(kerbs > 0);
    CHECK(seen[sc::SurfaceClass::ground] > 1000);
    CHECK(seen[sc::SurfaceClass::wall] > 100);
    CHECK(seen.count(sc::SurfaceClass::ceiling) == 0);
  }
}

TEST_CASE("sim scenes: make_scene knows every name") {
  for (const char* name : sim::kSceneNames) {
    CAPTURE(name);
    const sim::Scene scene = sim::make_scene(name, 2);
    CHECK(scene.object_count() > 10);
  }
  CHECK(sim::make_scene("forest", 3).object_count() == sim::forest_scene(3).object_count());
  CHECK_THROWS_AS(sim::make_scene("mars", 1), std::invalid_argument);
  CHECK_FALSE(sim::office_scene(1).ground_height(0.0f, 0.0f));
  CHECK(sim::hills_scene(1).ground_height(0.0f, 0.0f).value_or(9.0f) == doctest::Approx(0.0f).epsilon(1e-5));
}

TEST_CASE("sim hills: contents, ground-only structure, objects on the terrain, clear start") {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    CAPTURE(seed);
    const sim::Scene scene = sim::hills_scene(seed);
    std::map<std::string, int> labels;
    std::set<int> ids;
    for (const sim::ObjectInfo& info : scene.objects()) {
      ++labels[info.label];
      ids.insert(info.instance);
    }
    CHECK(ids.size() == scene.object_count());
    CHECK(labels["tree"] >= 8);
    CHECK(labels["tree"] <= 14);
    CHECK(labels["car"] >= 3);
    CHECK(labels["car"] <= 5);
    CHECK(labels["box"] >= 4);
    CHECK(labels["pole"] >= 4);
    CHECK(labels["person"] >= 5);
    CHECK(labels["person"] <= 9);
    CHECK(labels.size() == 5);
    CHECK(scene.object_count() >= 24);

    // Objects stand on the terrain: the bottom touches the ground under them.
    for (const sim::ObjectInfo& info : scene.objects()) {
      CAPTURE(info.label);
      if (info.moving) {
        for (double time : {0.0, 1.7, 5.3, 11.1}) {
          const Eigen::Vector3f q = scene.position(info.instance, time);
          CHECK(std::abs(q.z() - *scene.ground_height(q.x(), q.y())) < 0.02f);  // sampled every <= 1 m
        }
        continue;
      }
      const Eigen::Vector3f c = info.bounds.center();
      const float r = 0.5f * std::hypot(info.bounds.hi.x() - info.bounds.lo.x(), info.bounds.hi.y() - info.bounds.lo.y());
      float lowest = *scene.ground_height(c.x(), c.y());
      for (int k = 0; k < 16; ++k) {
        const float a = 2.0f * kPi * static_cast<float>(k) / 16.0f;
        lowest = std::min(lowest, *scene.ground_height(c.x() + r * std::cos(a), c.y() + r * std::sin(a)));
      }
      CHECK(info.bounds.lo.z() <= *scene.ground_height(c.x(), c.y()) + 1e-3f);  // not floating at its center
      CHECK(info.bounds.lo.z() >= lowest - 0.05f);                                 // not buried
      CHECK(std::abs(c.x()) <= 40.0f);
      CHECK(std::abs(c.y()) <= 40.0f);
      CHECK(std::abs(c.y()) >= 2.5f);  // the driving lane stays clear
    }

    // A scan from 1 m above the origin: structure is ground only, nothing closer than the ground.
    std::map<sc::SurfaceClass, int> seen;
    std::set<int> objects;
    float closest = kInf;
    for (int i = 0; i < 12000; ++i) {
      const float az = 2.0f * kPi * static_cast<float>(i % 240) / 240.0f;
      const float el = -1.5f + 1.9f * static_cast<float>(i / 240) / 49.0f;
      const std::optional<sim::Hit> hit = scene.cast({0, 0, 1}, spherical(az, el), 0.0);
      if (!hit) continue;
      ++seen[hit->surface];
      closest = std::min(closest, hit->range);
      if (hit->instance > 0) objects.insert(hit->instance);
      CHECK((hit->instance > 0) == (hit->surface == sc::SurfaceClass::object));
    }
    CHECK(seen[sc::SurfaceClass::ground] > 3000);
    CHECK(seen.count(sc::SurfaceClass::wall) == 0);
    CHECK(seen.count(sc::SurfaceClass::ceiling) == 0);
    CHECK(objects.size() >= 8);
    CHECK(closest >= 0.9f);
  }
}

TEST_CASE("sim hills: every structure point lies on the terrain; deterministic; golden fingerprint") {
  const sim::Scene a = sim::hills_scene(5);
  const sim::Scene b = sim::hills_scene(5);
  const sim::Scene c = sim::hills_scene(6);
  // Structure hits against the scene's ground height (on a kerb face: between its two sides).
  int same = 0;
  int differ = 0;
  int checked = 0;
  const Eigen::Vector3f o(0.3f, -0.2f, 1.4f);
  for (int i = 0; i < 6000; ++i) {
    const float az = 2.0f * kPi * static_cast<float>(i % 150) / 150.0f;
    const float el = -1.4f + 1.5f * static_cast<float>(i / 150) / 39.0f;
    const Eigen::Vector3f d = spherical(az, el);
    const auto ha = a.cast(o, d, 0.01 * i);
    const auto hb = b.cast(o, d, 0.01 * i);
    const auto hc = c.cast(o, d, 0.01 * i);
    same += ha.has_value() == hb.has_value() &&
            (!ha || (ha->range == hb->range && ha->instance == hb->instance && ha->surface == hb->surface));
    differ += ha.has_value() != hc.has_value() || (ha && ha->range != hc->range);
    if (!ha || ha->instance > 0) continue;
    const Eigen::Vector3f p = o + ha->range * d;
    const float h = *a.ground_height(p.x(), p.y());
    const float h_lo = std::min({h, *a.ground_height(p.x() - 0.002f, p.y()), *a.ground_height(p.x() + 0.002f, p.y()),
                                 *a.ground_height(p.x(), p.y() - 0.002f), *a.ground_height(p.x(), p.y() + 0.002f)});
    const float h_hi = std::max({h, *a.ground_height(p.x() - 0.002f, p.y()), *a.ground_height(p.x() + 0.002f, p.y()),
                                 *a.ground_height(p.x(), p.y() - 0.002f), *a.ground_height(p.x(), p.y() + 0.002f)});
    CAPTURE(p.transpose());
    CHECK(p.z() >= h_lo - 2e-3f);
    CHECK(p.z() <= h_hi + 2e-3f);
    ++checked;
  }
  CHECK(same == 6000);
  CHECK(differ > 500);
  CHECK(checked > 2000);

  // Seed 1, pinned like the other scenes' fingerprints (test_sim_scenes.cpp).
  const sim::Scene golden = sim::hills_scene(1);
  double range_sum = 0.0;
  long id_sum = 0;
  for (int i = 0; i < 3600; ++i) {
    const float az = 2.0f * 3.14159265f * static_cast<float>(i % 60) / 60.0f;
    const float el = -0.5f + static_cast<float>(i / 60) / 59.0f * 1.2f;
    const auto hit = golden.cast({0, 0, 1}, spherical(az, el), 0.01 * i);
    if (!hit) continue;
    range_sum += static_cast<double>(hit->range);
    id_sum += hit->instance;
  }
  CHECK(golden.object_count() == 36);
  CHECK(range_sum == doctest::Approx(12834.347788).epsilon(1e-6));
  CHECK(id_sum == 621);
}
