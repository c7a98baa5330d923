// SPDX-License-Identifier: MIT
// The ground policy's parts against brute force, and its decisions on
// shapes whose answer is known: a floor with boxes, a 15 degree slope, a
// kerb, a flat ceiling and a tree crown.

#include <doctest/doctest.h>

#include <streamclust/ground/cell_table.hpp>
#include <streamclust/ground/height_column.hpp>
#include <streamclust/ground/height_map_ground.hpp>
#include <streamclust/ground/no_ground.hpp>

#include "support/invalid_argument.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <random>
#include <utility>
#include <vector>

namespace sc = streamclust;

namespace {

/// Lowest/highest bin of a multiset of bins with `support` points in it and
/// its upper/lower neighbour: the layer rules of HeightColumn by brute force.
std::optional<std::int32_t> lowest_brute(const std::map<std::int32_t, std::uint32_t>& bins, std::uint32_t support) {
  for (const auto& [bin, count] : bins) {
    const auto above = bins.find(bin + 1);
    if (count + (above == bins.end() ? 0u : above->second) >= support) return bin;
  }
  return std::nullopt;
}
std::optional<std::int32_t> highest_brute(const std::map<std::int32_t, std::uint32_t>& bins, std::uint32_t support) {
  for (auto it = bins.rbegin(); it != bins.rend(); ++it) {
    const auto below = bins.find(it->first - 1);
    if (it->second + (below == bins.end() ? 0u : below->second) >= support) return it->first;
  }
  return std::nullopt;
}

/// The classification rule of HeightMapGround computed from the list of
/// live points, without its data structures.
class BruteGround {
 public:
  explicit BruteGround(const sc::HeightMapGround::Params& p) : p_(p) {}
  sc::SurfaceClass classify(const Eigen::Vector3f& world, const Eigen::Vector3f& ray) {
    live_.push_back(world);
    classes_.push_back(sc::SurfaceClass::object);
    classes_.back() = decide(world, ray);
    return classes_.back();
  }
  void forget_oldest() {
    live_.pop_front();
    classes_.pop_front();
  }

 private:
  sc::SurfaceClass decide(const Eigen::Vector3f& world, const Eigen::Vector3f& ray) const {
    const auto [ix, iy] = key(world);
    if (p_.detect_ceiling && ray.z() >= p_.ceiling_clearance) {
      const std::optional<float> top = highest(ix, iy);
      if (top && world.z() >= *top - p_.ceiling_tolerance && peaked(ix, iy)) {
        int agreeing = 0;
        for (int dy = -2; dy <= 2; ++dy) {
          for (int dx = -2; dx <= 2; ++dx) {
            if (dx == 0 && dy == 0) continue;
            const std::optional<float> other = highest(ix + dx, iy + dy);
            if (other && std::fabs(*other - *top) <= p_.ceiling_flatness) ++agreeing;
          }
        }
        if (static_cast<float>(agreeing) >= p_.ceiling_min_agreement * 24.0f) return sc::SurfaceClass::ceiling;
      }
    }
    std::optional<float> bound = lowest(ix, iy);
    const float rise = std::tan(p_.max_slope_deg * 0.01745329252f) * p_.cell_size;
    const int rings = static_cast<int>(std::ceil(p_.search_radius / p_.cell_size));
    bool neighbour = false;
    for (int ring = 1; ring <= std::max(1, rings) && !neighbour; ++ring) {
      for (int dy = -ring; dy <= ring; ++dy) {
        for (int dx = -ring; dx <= ring; ++dx) {
          if (std::max(std::abs(dx), std::abs(dy)) != ring) continue;
          const std::optional<float> layer = lowest(ix + dx, iy + dy);
          neighbour = neighbour || layer.has_value();
          if (layer && (!bound || *layer + rise * static_cast<float>(ring) < *bound)) {
            bound = *layer + rise * static_cast<float>(ring);
          }
        }
      }
    }
    if (bound && p_.surface_evidence) {
      // Ground needs a solid surface: in the 3 x 3 cells, else in the nearest
      // ring holding one (whose layers bound it too).
      bool evidence = false;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) evidence = evidence || (lowest(ix + dx, iy + dy) && solid(ix + dx, iy + dy));
      }
      for (int ring = 2; ring <= rings && !evidence; ++ring) {
        for (int dy = -ring; dy <= ring; ++dy) {
          for (int dx = -ring; dx <= ring; ++dx) {
            if (std::max(std::abs(dx), std::abs(dy)) != ring) continue;
            const std::optional<float> layer = lowest(ix + dx, iy + dy);
            if (!layer || !solid(ix + dx, iy + dy)) continue;
            evidence = true;
            bound = std::min(*bound, *layer + rise * static_cast<float>(ring));
          }
        }
      }
      if (!evidence) return sc::SurfaceClass::object;
    }
    if (!bound) return sc::SurfaceClass::object;
    if (p_.sensor_height > 0.0f) {
      const float sensor_z = world.z() - ray.z();
      const float d = std::hypot(ray.x(), ray.y());
      if (p_.lowest_ray_elevation_deg > -89.9f &&
          *bound <= reach(sensor_z, d) + p_.blind_margin) {
        bound = std::min(*bound, sensor_z - p_.sensor_height);
      }
      bound = std::min(*bound, sensor_z - p_.sensor_height + std::tan(p_.max_slope_deg * 0.01745329252f) * d);
      if (world.z() > top(ix, iy, *bound) + p_.ground_tolerance) return sc::SurfaceClass::object;
      return rises_from_view(world, ray, sensor_z, d) ? sc::SurfaceClass::ground : sc::SurfaceClass::object;
    }
    return world.z() <= top(ix, iy, *bound) + p_.ground_tolerance ? sc::SurfaceClass::ground
                                                                            : sc::SurfaceClass::object;
  }
  /// The highest ground of cell (ix, iy) for ground bound `bound`: the slope's
  /// rise, or a neighbouring surface up to step_height above the bound.
  float top(int ix, int iy, float bound) const {
    float t = bound + slope_rise(ix, iy);
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const std::optional<float> layer = lowest(ix + dx, iy + dy);
        if (layer && *layer > t && *layer <= bound + p_.step_height && surface(ix + dx, iy + dy)) t = *layer;
      }
    }
    return t;
  }
  /// Points in the lowest supported bin and the one above, and in the 10 bins above them.
  std::pair<double, double> peak_and_above(int ix, int iy) const {
    const auto all = bins(ix, iy);
    const auto b = lowest_brute(all, p_.support);
    auto count = [&all](std::int32_t bin) {
      const auto it = all.find(bin);
      return it == all.end() ? 0.0 : static_cast<double>(it->second);
    };
    double above = 0.0;
    for (std::int32_t i = *b + 2; i < *b + 12; ++i) above += count(i);
    return {count(*b) + count(*b + 1), above};
  }
  /// The step rule's peak test on the lowest supported bin.
  bool surface(int ix, int iy) const {
    const auto [peak, above] = peak_and_above(ix, iy);
    return peak / 2.0 >= p_.step_peak_ratio * above / 10.0;
  }
  /// The surface evidence rule: a surface with enough points, more than above it.
  bool solid(int ix, int iy) const {
    const auto [peak, above] = peak_and_above(ix, iy);
    return surface(ix, iy) && peak >= p_.surface_min_points && peak > above;
  }
  /// Height the lowest ray reaches at horizontal distance d [m].
  float reach(float sensor_z, float d) const {
    if (p_.lowest_ray_elevation_deg <= -89.9f) return -1e30f;
    return sensor_z + std::tan(p_.lowest_ray_elevation_deg * 0.01745329252f) * d;
  }
  /// Ground out of view of level ground rises from where it came into view:
  /// a straight rise from the foot is out of view one cell nearer, or the
  /// nearer cell holds a ground point.
  bool rises_from_view(const Eigen::Vector3f& world, const Eigen::Vector3f& ray, float sensor_z, float d) const {
    const float foot = sensor_z - p_.sensor_height;
    if (foot >= reach(sensor_z, d)) return true;
    const float nearer = d - p_.cell_size;
    if (nearer <= 0.0f || foot + (world.z() - foot) * nearer / d <= reach(sensor_z, nearer)) return true;
    const std::pair<int, int> here = key(world);
    for (const float steps : {1.0f, 1.5f}) {
      const float scale = steps * p_.cell_size / d;
      const auto in = key(Eigen::Vector3f(world.x() - ray.x() * scale, world.y() - ray.y() * scale, world.z()));
      if (in == here) continue;
      for (std::size_t i = 0; i + 1 < live_.size(); ++i) {
        if (classes_[i] == sc::SurfaceClass::ground && key(live_[i]) == in) return true;
      }
      return false;
    }
    return false;
  }

  std::pair<int, int> key(const Eigen::Vector3f& w) const {
    return {static_cast<int>(std::floor(w.x() * (1.0f / p_.cell_size))),
            static_cast<int>(std::floor(w.y() * (1.0f / p_.cell_size)))};
  }
  std::map<std::int32_t, std::uint32_t> bins(int ix, int iy) const {
    std::map<std::int32_t, std::uint32_t> b;
    for (const Eigen::Vector3f& w : live_) {
      if (key(w) == std::make_pair(ix, iy)) ++b[static_cast<std::int32_t>(std::floor(w.z() * (1.0f / p_.bin_height)))];
    }
    return b;
  }
  std::uint32_t support(int, int) const { return p_.support; }
  float slope_rise(int ix, int iy) const {
    const auto centre = lowest(ix, iy);
    if (!centre) return 0.0f;
    auto gradient = [&](int dx, int dy) {
      const auto before = lowest(ix - dx, iy - dy), after = lowest(ix + dx, iy + dy);
      if (!before || !after) return 0.0f;
      const float d1 = *centre - *before, d2 = *after - *centre;
      return d1 * d2 <= 0.0f ? 0.0f : std::min(std::fabs(d1), std::fabs(d2));
    };
    const float gx = gradient(1, 0), gy = gradient(0, 1);
    return std::min(std::tan(p_.max_slope_deg * 0.01745329252f) * p_.cell_size, std::sqrt(gx * gx + gy * gy));
  }
  /// The ceiling's peak test on the highest supported bin.
  bool peaked(int ix, int iy) const {
    const auto all = bins(ix, iy);
    const auto b = highest_brute(all, support(ix, iy));
    auto count = [&all](std::int32_t bin) {
      const auto it = all.find(bin);
      return it == all.end() ? 0.0 : static_cast<double>(it->second);
    };
    double below = 0.0;
    for (std::int32_t i = *b - 12; i < *b - 2; ++i) below += count(i);
    return (count(*b) + count(*b - 1)) / 2.0 >= p_.ceiling_peak_ratio * below / 10.0;
  }
  /// Mean height [m] of the live points of cell (ix, iy) in the densest bin
  /// of [first, last] (the lowest of equals), in HeightColumn's units.
  float densest_mean(int ix, int iy, std::int32_t first, std::int32_t last) const {
    const auto all = bins(ix, iy);
    std::int32_t best = first;
    auto count = [&all](std::int32_t bin) {
      const auto it = all.find(bin);
      return it == all.end() ? 0u : it->second;
    };
    for (std::int32_t b = first + 1; b <= last; ++b) {
      if (count(b) > count(best)) best = b;
    }
    double sum = 0.0;
    std::uint64_t n = 0;
    for (const Eigen::Vector3f& w : live_) {
      if (key(w) != std::make_pair(ix, iy)) continue;
      const float scaled = w.z() * (1.0f / p_.bin_height);
      const float bin = std::floor(scaled);
      if (static_cast<std::int32_t>(bin) != best) continue;
      const auto fraction = std::clamp(static_cast<std::int32_t>((scaled - bin) * 1024), 0, 1023);
      sum += static_cast<double>(bin) + static_cast<double>(fraction) / 1024;
      ++n;
    }
    return static_cast<float>(sum / static_cast<double>(n)) * p_.bin_height;
  }
  std::int32_t layer_bins() const {
    return std::max<std::int32_t>(1, static_cast<std::int32_t>(std::lround(p_.layer_thickness / p_.bin_height)));
  }
  std::optional<float> lowest(int ix, int iy) const {
    const auto b = lowest_brute(bins(ix, iy), support(ix, iy));
    if (!b) return std::nullopt;
    return densest_mean(ix, iy, *b, *b + layer_bins() - 1);
  }
  std::optional<float> highest(int ix, int iy) const {
    const auto b = highest_brute(bins(ix, iy), support(ix, iy));
    if (!b) return std::nullopt;
    return densest_mean(ix, iy, *b - layer_bins() + 1, *b);
  }

  sc::HeightMapGround::Params p_;
  std::deque<Eigen::Vector3f> live_;
  std::deque<sc::SurfaceClass> classes_;  ///< of live_ (the newest still undecided while deciding)
};

}  // namespace

TEST_CASE("HeightColumn's layers equal brute force under adds, removals and a moving span") {
  std::mt19937_64 rng(11);
  for (int round = 0; round < 50; ++round) {
    sc::HeightColumn column;
    std::map<std::int32_t, std::uint32_t> bins;
    std::deque<std::pair<std::int32_t, std::int32_t>> fifo;  // bin, fraction
    const std::uint32_t support = 1 + static_cast<std::uint32_t>(rng() % 3);
    const std::int32_t spread = 20 + static_cast<std::int32_t>(rng() % 100);  // bins; < 128 after the first lowering
    for (int step = 0; step < 400; ++step) {
      if (!fifo.empty() && rng() % 3 == 0) {
        column.remove(fifo.front().first, fifo.front().second);
        if (--bins[fifo.front().first] == 0) bins.erase(fifo.front().first);
        fifo.pop_front();
      } else {
        const std::int32_t bin = static_cast<std::int32_t>(rng() % static_cast<std::uint64_t>(spread)) - spread / 2;
        const auto fraction = static_cast<std::int32_t>(rng() % 1024);
        column.add(bin, fraction);
        ++bins[bin];
        fifo.emplace_back(bin, fraction);
      }
      INFO("round " << round << ", step " << step);
      REQUIRE(column.points() == fifo.size());
      REQUIRE(column.lowest_supported(support) == lowest_brute(bins, support));
      REQUIRE(column.highest_supported(support) == highest_brute(bins, support));
      if (!fifo.empty()) {  // the mean position over a range of bins, against the points
        const std::int32_t from = fifo.back().first - 3, to = fifo.back().first + 2;
        double sum = 0.0;
        std::size_t n = 0;
        for (const auto& [b, f] : fifo) {
          if (b < from || b > to) continue;
          sum += b + f / 1024.0;
          ++n;
        }
        REQUIRE(column.mean_bin(from, to).has_value());
        REQUIRE(*column.mean_bin(from, to) == doctest::Approx(sum / static_cast<double>(n)).epsilon(1e-12));
        REQUIRE(column.count(fifo.back().first) == bins[fifo.back().first]);
      }
    }
  }
}

TEST_CASE("HeightColumn: with points spread wider than its span no count is lost and no layer is too high") {
  // Points above the span count in its top bin: a layer may then read lower
  // than the truth (the conservative side: a lower ground bound), never higher.
  std::mt19937_64 rng(12);
  for (int round = 0; round < 50; ++round) {
    sc::HeightColumn column;
    std::map<std::int32_t, std::uint32_t> bins;
    std::deque<std::pair<std::int32_t, std::int32_t>> fifo;  // bin, fraction
    const std::uint32_t support = 1;
    const std::int32_t spread = 100 + static_cast<std::int32_t>(rng() % 400);
    for (int step = 0; step < 600; ++step) {
      if (!fifo.empty() && rng() % 3 == 0) {
        column.remove(fifo.front().first, fifo.front().second);
        if (--bins[fifo.front().first] == 0) bins.erase(fifo.front().first);
        fifo.pop_front();
      } else {
        const std::int32_t bin = static_cast<std::int32_t>(rng() % static_cast<std::uint64_t>(spread)) - spread / 2;
        const auto fraction = static_cast<std::int32_t>(rng() % 1024);
        column.add(bin, fraction);
        ++bins[bin];
        fifo.emplace_back(bin, fraction);
      }
      INFO("round " << round << ", step " << step);
      REQUIRE(column.points() == fifo.size());
      const auto low = column.lowest_supported(support);
      const auto top = column.highest_supported(support);
      REQUIRE(low.has_value() == !fifo.empty());
      REQUIRE(top.has_value() == !fifo.empty());
      if (low) REQUIRE(*low <= bins.begin()->first);
      if (top) REQUIRE(*top <= bins.rbegin()->first);
    }
    while (!fifo.empty()) {
      column.remove(fifo.front().first, fifo.front().second);
      fifo.pop_front();
    }
    REQUIRE(column.points() == 0);
    REQUIRE_FALSE(column.highest_supported(1).has_value());  // no count left behind
  }
}

TEST_CASE("HeightColumn: points beyond its span count in the top bin and leave from there") {
  sc::HeightColumn column;
  column.add(0, 0);    // span [-64, 64)
  column.add(500, 0);  // the span moves up as far as bin 0 allows, [0, 128): 500 counts in the top bin
  CHECK(column.lowest_supported(1) == std::optional<std::int32_t>(0));
  CHECK(column.highest_supported(1) == std::optional<std::int32_t>(127));
  column.add(-100, 0);  // the span moves down to [-100, 28): 500 stays in the top bin
  CHECK(column.lowest_supported(1) == std::optional<std::int32_t>(-100));
  CHECK(column.highest_supported(1) == std::optional<std::int32_t>(27));
  column.remove(500, 0);
  CHECK(column.highest_supported(1) == std::optional<std::int32_t>(0));
  column.remove(0, 0);
  CHECK(column.highest_supported(1) == std::optional<std::int32_t>(-100));
  column.remove(-100, 0);
  CHECK(column.points() == 0);
  CHECK_FALSE(column.lowest_supported(1).has_value());
  column.add(1000, 0);  // an empty column starts afresh around its first point
  CHECK(column.highest_supported(1) == std::optional<std::int32_t>(1000));
}

TEST_CASE("CellTable finds, creates and releases like a map, through growth and backward shifts") {
  std::mt19937_64 rng(5);
  sc::CellTable<int> table;
  std::map<std::pair<int, int>, int> reference;
  for (int step = 0; step < 20000; ++step) {
    const int ix = static_cast<int>(rng() % 40) - 20;
    const int iy = static_cast<int>(rng() % 40) - 20;
    const auto it = reference.find({ix, iy});
    if (it != reference.end() && rng() % 2 == 0) {
      table.release(ix, iy);
      reference.erase(it);
    } else {
      const std::uint32_t c = table.find_or_create(ix, iy);
      if (it == reference.end()) {
        REQUIRE(table[c] == 0);  // a new column is value-initialised, even a recycled one
        table[c] = step + 1;
        reference[{ix, iy}] = step + 1;
      } else {
        REQUIRE(table[c] == it->second);
      }
    }
    if (step % 97 == 0) {
      for (int x = -20; x < 20; ++x) {
        for (int y = -20; y < 20; ++y) {
          const std::uint32_t c = table.find(x, y);
          const auto r = reference.find({x, y});
          REQUIRE((c == sc::CellTable<int>::kNone) == (r == reference.end()));
          if (r != reference.end()) REQUIRE(table[c] == r->second);
        }
      }
    }
  }
  CHECK(table.size() == reference.size());
}

TEST_CASE("HeightMapGround decides as its rule computed from the live points (a sliding window)") {
  std::mt19937_64 rng(21);
  for (int round = 0; round < 12; ++round) {
    sc::HeightMapGround::Params p;
    p.cell_size = round % 3 == 0 ? 0.3f : 0.6f;
    p.support = 1 + static_cast<std::uint32_t>(round % 3);
    p.search_radius = static_cast<float>(round % 4);
    p.ceiling_min_agreement = 0.3f;
    p.sensor_height = round % 2 == 0 ? 0.0f : 1.0f;
    p.layer_thickness = round % 3 == 2 ? 0.05f : 0.15f;
    p.lowest_ray_elevation_deg = round % 4 == 1 ? -7.0f : -90.0f;
    p.step_height = round % 4 == 3 ? 0.0f : 0.2f;
    p.step_peak_ratio = round % 3 == 1 ? 0.5f : 2.0f;
    p.surface_evidence = round % 5 != 2;
    p.surface_min_points = 1 + static_cast<std::uint32_t>(round % 3);  // a sparse window: 300 points on 16 m^2
    p.detect_walls = false;  // the ground rule alone (walls: the test cases below)
    // Even rounds: the floor has a kerb 0.12 m high at x = 0.3.
    const float kerb = round % 2 == 0 ? 0.12f : 0.0f;
    sc::HeightMapGround model(p);
    BruteGround brute(p);
    std::deque<std::pair<Eigen::Vector3f, sc::SurfaceClass>> window;
    std::uniform_real_distribution<float> xy(-2.0f, 2.0f);
    int classes[3] = {0, 0, 0};
    for (int step = 0; step < 1500; ++step) {
      // A floor near -1 m, boxes up to 1 m, a ceiling at 1.5 m: within one span.
      float x = xy(rng);
      const float y = xy(rng);
      const int kind = static_cast<int>(rng() % 4);
      // With the field of view's cut-off the floor shows on one side only:
      // points beyond it find no ground nearer the sensor.
      if (round % 4 == 1 && kind >= 2) x = -std::fabs(x);
      const float floor = x > 0.3f ? -1.0f + kerb : -1.0f;
      const float unit = std::uniform_real_distribution<float>(0, 1)(rng);
      float z = kind == 0   ? 1.5f
                : kind == 1 ? -1.0f + 2.0f * unit
                            : floor + 0.02f * std::uniform_real_distribution<float>(-1, 1)(rng);
      Eigen::Vector3f w(x, y, z);
      if (kind == 1 && step % 2 == 0) {
        // A post on a 0.1 m plinth: its lowest layer is no surface.
        const float px = step % 4 == 0 ? 0.9f : -0.7f;
        w = Eigen::Vector3f(px + 0.1f * unit, 0.4f + 0.1f * (1.0f - unit), floor + 0.1f + 1.4f * unit);
      }
      const Eigen::Vector3f sensor(0.5f, -0.25f, 0.0f);
      const sc::SurfaceClass expected = brute.classify(w, w - sensor);
      const sc::SurfaceClass got = model.classify(w, w - sensor);
      INFO("round " << round << ", step " << step);
      REQUIRE(got == expected);
      ++classes[static_cast<int>(got) == 3 ? 2 : static_cast<int>(got)];
      window.emplace_back(w, got);
      if (window.size() > 300) {
        model.forget(window.front().first, window.front().second);
        brute.forget_oldest();
        window.pop_front();
      }
    }
    CHECK(classes[0] > 0);
    CHECK(classes[1] > 0);
  }
}

namespace {

/// Feeds `points` (world, sensor at the origin) and returns their classes.
std::vector<sc::SurfaceClass> classify_all(sc::HeightMapGround& model, const std::vector<Eigen::Vector3f>& points) {
  std::vector<sc::SurfaceClass> out;
  for (const Eigen::Vector3f& p : points) out.push_back(model.classify(p, p));
  return out;
}

/// Points on a surface z = f(x, y) over [x0, x1] x [y0, y1], interleaved
/// with points of boxes standing on it (returned with their truth).
struct SurfaceWithPosts {
  std::vector<Eigen::Vector3f> points;
  std::vector<bool> is_ground;
};

template <class Height>
SurfaceWithPosts surface_with_posts(Height height, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  SurfaceWithPosts s;
  for (int i = 0; i < 20000; ++i) {
    if (i % 5 == 4) {
      // A post 0.4 x 0.4 m, 1.5 m tall, at one of four places.
      const float px = -4.0f + 2.5f * static_cast<float>(i % 4);
      const float py = 3.0f;
      const float x = px + 0.4f * u(rng), y = py + 0.4f * u(rng);
      const float z = height(px, py) + 1.5f * u(rng);
      s.points.emplace_back(x, y, z);
      s.is_ground.push_back(false);
    } else {
      const float x = -6.0f + 12.0f * u(rng), y = -6.0f + 12.0f * u(rng);
      s.points.emplace_back(x, y, height(x, y) + 0.01f * (u(rng) - 0.5f));
      s.is_ground.push_back(true);
    }
  }
  return s;
}

/// Fraction of ground points classed ground, and of post points above
/// `above` m over the ground classed object, after the first `warm` points.
std::pair<double, double> rates(const SurfaceWithPosts& s, const std::vector<sc::SurfaceClass>& classes,
                                std::size_t warm) {
  std::size_t g = 0, g_ok = 0, o = 0, o_ok = 0;
  for (std::size_t i = warm; i < s.points.size(); ++i) {
    if (s.is_ground[i]) {
      ++g;
      g_ok += classes[i] == sc::SurfaceClass::ground;
    } else {
      ++o;
      o_ok += classes[i] == sc::SurfaceClass::object;
    }
  }
  return {static_cast<double>(g_ok) / static_cast<double>(g), static_cast<double>(o_ok) / static_cast<double>(o)};
}

}  // namespace

TEST_CASE("HeightMapGround on a flat floor, a 15 degree slope and a kerb: ground stays ground, posts stay objects") {
  const float slope = std::tan(15.0f * 0.01745329252f);
  // Fractions after a warm-up of 2,000 points; measured: flat 1.00 / 0.96,
  // slope 0.99 / 0.86, kerb 1.00 / 0.96 (ground / posts).
  auto run = [](auto height, const std::string& name, double min_ground) {
    sc::HeightMapGround model;
    const SurfaceWithPosts s = surface_with_posts(height, 3);
    const auto classes = classify_all(model, s.points);
    const std::pair<double, double> r = rates(s, classes, 2000);
    const double ground_rate = r.first, object_rate = r.second;
    const std::string what = name + ": ground " + std::to_string(ground_rate) + ", posts " + std::to_string(object_rate);
    INFO(what);
    CHECK(ground_rate > min_ground);
    // A post loses at most its bottom (tolerance + slope allowance or step) of 1.5 m.
    CHECK(object_rate > 0.83);
  };
  run([](float, float) { return -1.0f; }, "flat", 0.98);
  run([slope](float x, float) { return -1.0f + slope * x; }, "slope 15 degrees", 0.94);
  run([](float x, float) { return x > 0.3f ? -0.85f : -1.0f; }, "kerb 0.15 m", 0.98);
}

TEST_CASE("HeightMapGround where a level sensor cannot see level ground: a desk top stays an object, a ramp is ground") {
  // A sensor 1 m above the floor (z = -1) whose lowest ray points 7 deg
  // down: level floor shows only from 8.1 m on. Points in random order.
  sc::HeightMapGround::Params p;
  p.sensor_height = 1.0f;
  p.lowest_ray_elevation_deg = -7.0f;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  auto ground_fraction = [&](auto&& make_point, std::size_t warm) {
    sc::HeightMapGround model(p);
    std::vector<Eigen::Vector3f> points;
    for (int i = 0; i < 6000; ++i) points.push_back(make_point());
    const std::vector<sc::SurfaceClass> classes = classify_all(model, points);
    const auto ground = std::count(classes.begin() + static_cast<std::ptrdiff_t>(warm), classes.end(), sc::SurfaceClass::ground);
    return static_cast<double>(ground) / static_cast<double>(classes.size() - warm);
  };
  // A desk top 0.75 m high at 5-6 m: within the 15 deg cone from the
  // sensor's foot, but nothing nearer shows a rising ground.
  const double desk = ground_fraction([&] { return Eigen::Vector3f(5.0f + u(rng), u(rng) - 0.5f, -0.25f + 0.01f * u(rng)); }, 0);
  // A ramp rising 10 deg from the foot, in view from 3.4 m on.
  const double ramp = ground_fraction([&] {
    const float x = 3.4f + 5.0f * u(rng);
    return Eigen::Vector3f(x, 2.0f * u(rng) - 1.0f, -1.0f + std::tan(10.0f * 0.01745329252f) * x);
  }, 2000);
  // Measured: desk 0.00 (0.5 without the rise-from-view rule), ramp 0.91.
  INFO("desk top classed ground " << desk << ", ramp " << ramp);
  CHECK(desk < 0.05);
  CHECK(ramp > 0.85);
}

TEST_CASE("HeightMapGround::ground_height_near: only cells holding ground; where it cannot see level ground, the ground under it") {
  // A sensor at the origin 1 m above the floor (z = -1), lowest ray 7 deg
  // down: level floor shows from 8.1 m on. Overhead, 1.2-1.8 m and
  // 4.0-4.6 m out, patches of ceiling 2 m up: the only layer of their cells.
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Eigen::Vector3f> patch;
  for (const float near_edge : {1.2f, 4.0f}) {
    for (int i = 0; i < 3000; ++i) patch.emplace_back(near_edge + 0.6f * u(rng), 0.6f * u(rng) - 0.3f, 2.0f + 0.01f * u(rng));
  }
  sc::HeightMapGround::Params p;
  p.sensor_height = 1.0f;
  p.lowest_ray_elevation_deg = -7.0f;
  sc::HeightMapGround model(p);
  classify_all(model, patch);
  // A ceiling is no ground, even bounded by the 15 deg cone from the foot
  // (which would allow -0.52 m at 1.8 m and 0.23 m at 4.6 m): under both
  // patches, in the blind zone, the floor under the sensor.
  for (const float x : {1.5f, 4.3f}) {
    const std::optional<float> under_patch = model.ground_height_near(x, 0.0f, 0.3f);
    INFO("patch at " << x << " m");
    REQUIRE(under_patch);
    CHECK(*under_patch == doctest::Approx(-1.0f));
  }
  // Nothing seen 4.2 m out, inside the blind zone: the floor under the sensor.
  const std::optional<float> blind = model.ground_height_near(3.0f, 3.0f, 0.5f);
  REQUIRE(blind);
  CHECK(*blind == doctest::Approx(-1.0f));
  // Nothing seen 20 m out, where the floor would show: unknown.
  CHECK_FALSE(model.ground_height_near(20.0f, 0.0f, 0.5f));

  // Without the sensor's height the layer is all there is.
  sc::HeightMapGround unplaced;
  classify_all(unplaced, patch);
  const std::optional<float> layer = unplaced.ground_height_near(1.5f, 0.0f, 0.3f);
  REQUIRE(layer);
  CHECK(*layer == doctest::Approx(2.0f).epsilon(0.02));
  CHECK_FALSE(unplaced.ground_height_near(3.0f, 3.0f, 0.5f));
}

TEST_CASE("HeightMapGround with surface evidence: a far object with its foot out of view keeps its bottom, sparse ground stays ground") {
  // 33 m out, ground 1.5 m below the sensor: a box's face 1 m wide and 1.6 m
  // tall, 200 points in the window (3 per 5 cm bin of a cell); and sparse
  // ground, 6 points per 0.5 m cell, on its own or around the box.
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  struct Outcome {
    double ground_as_ground, box_as_ground, box_bottom_as_ground;
  };
  auto run = [&](bool evidence, bool ground_in_view) {
    std::vector<Eigen::Vector3f> points;
    std::vector<int> kind;  // 0 ground, 1 box
    for (int i = 0; i < 200; ++i) {
      const float y = u(rng) - 0.5f;  // drawn in order: argument order is unspecified
      const float z = -1.5f + 1.6f * u(rng);
      points.emplace_back(33.0f, y, z);
      kind.push_back(1);
    }
    if (ground_in_view) {
      for (int i = 0; i < 6 * 144; ++i) {  // [30, 36] x [-3, 3] m: 144 cells
        const float x = 30.0f + 6.0f * u(rng), y = 6.0f * u(rng) - 3.0f;
        if (x > 32.9f && x < 33.1f && std::fabs(y) < 0.5f) continue;  // under the box
        points.emplace_back(x, y, -1.5f + 0.02f * (u(rng) - 0.5f));
        kind.push_back(0);
      }
    }
    std::vector<std::size_t> order(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    sc::HeightMapGround::Params p;
    p.surface_evidence = evidence;
    sc::HeightMapGround model(p);
    // Ground measured on the second half (the first builds the map); the
    // box's bottom 0.1 m, 12 points or so, on all of it.
    std::size_t counts[2] = {0, 0}, as_ground[2] = {0, 0}, bottom = 0, bottom_as_ground = 0;
    for (std::size_t n = 0; n < order.size(); ++n) {
      const std::size_t i = order[n];
      const bool ground = model.classify(points[i], points[i]) == sc::SurfaceClass::ground;
      if (kind[i] == 1 && points[i].z() < -1.4f) {
        ++bottom;
        bottom_as_ground += ground;
      }
      if (2 * n < order.size()) continue;
      ++counts[kind[i]];
      as_ground[kind[i]] += ground;
    }
    return Outcome{counts[0] ? static_cast<double>(as_ground[0]) / static_cast<double>(counts[0]) : 1.0,
                   static_cast<double>(as_ground[1]) / static_cast<double>(counts[1]),
                   static_cast<double>(bottom_as_ground) / static_cast<double>(bottom)};
  };
  // Means over 8 draws (a dozen bottom points a draw).
  auto mean_of = [&](bool evidence, bool ground_in_view) {
    Outcome sum{0.0, 0.0, 0.0};
    for (int draw = 0; draw < 8; ++draw) {
      const Outcome o = run(evidence, ground_in_view);
      sum = Outcome{sum.ground_as_ground + o.ground_as_ground / 8, sum.box_as_ground + o.box_as_ground / 8,
                    sum.box_bottom_as_ground + o.box_bottom_as_ground / 8};
    }
    return sum;
  };
  const Outcome hidden_off = mean_of(false, false), hidden_on = mean_of(true, false);
  const Outcome shown_off = mean_of(false, true), shown_on = mean_of(true, true);
  INFO("foot out of view: box bottom 0.1 m as ground " << hidden_off.box_bottom_as_ground << " without evidence, "
       << hidden_on.box_bottom_as_ground << " with; ground in view: ground as ground " << shown_off.ground_as_ground
       << " / " << shown_on.ground_as_ground << ", box as ground " << shown_off.box_as_ground << " / "
       << shown_on.box_as_ground);
  // Without evidence the box's own bottom bounds the ground under it; with
  // it, only where a few of its points happen to pile up like a surface.
  CHECK(hidden_off.box_bottom_as_ground > 0.5);
  CHECK(hidden_on.box_bottom_as_ground < 0.15);
  // Sparse ground in view is ground either way, and the box above its foot an object.
  CHECK(shown_on.ground_as_ground > 0.9);
  CHECK(shown_on.ground_as_ground > shown_off.ground_as_ground - 0.05);
  CHECK(shown_on.box_as_ground < 0.1);  // its bottom 0.1 m of 1.6 at most
}

TEST_CASE("HeightMapGround: a flat ceiling overhead is ceiling, a tree crown is not; "
          "ceiling_height_near finds the first") {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  sc::HeightMapGround ceiling_model;
  std::vector<Eigen::Vector3f> ceiling;
  for (int i = 0; i < 20000; ++i) ceiling.emplace_back(5.0f * u(rng), 5.0f * u(rng), 1.8f + 0.01f * u(rng));
  // Also where the sensor sees no floor: the ceiling is then its cells' only layer, and still ceiling.
  const auto c = classify_all(ceiling_model, ceiling);
  std::size_t inner = 0, as_ceiling = 0;  // away from the edges, where fewer cells can agree
  for (std::size_t i = 2000; i < c.size(); ++i) {
    if (std::fabs(ceiling[i].x()) > 4.0f || std::fabs(ceiling[i].y()) > 4.0f) continue;
    ++inner;
    as_ceiling += c[i] == sc::SurfaceClass::ceiling;
  }
  CHECK(static_cast<double>(as_ceiling) / static_cast<double>(inner) > 0.95);
  // Its height where it is seen, anywhere under it; nothing beyond it.
  for (const Eigen::Vector2f& at : {Eigen::Vector2f(0.0f, 0.0f), Eigen::Vector2f(-3.0f, 2.5f)}) {
    const std::optional<float> over = ceiling_model.ceiling_height_near(at.x(), at.y(), 0.5f);
    INFO("at " << at.transpose());
    REQUIRE(over);
    CHECK(*over == doctest::Approx(1.8f).epsilon(0.03));
  }
  // Over a wide square (its layers looked up cell by cell, not tabled), and
  // at its edge, where the cells beyond hold nothing.
  for (const float radius : {4.0f, 9.0f}) {
    const std::optional<float> wide = ceiling_model.ceiling_height_near(0.0f, 0.0f, radius);
    INFO("radius " << radius);
    REQUIRE(wide);
    CHECK(*wide == doctest::Approx(1.8f).epsilon(0.03));
  }
  const std::optional<float> edge = ceiling_model.ceiling_height_near(4.9f, 0.0f, 0.5f);
  REQUIRE(edge);
  CHECK(*edge == doctest::Approx(1.8f).epsilon(0.03));
  CHECK_FALSE(ceiling_model.ceiling_height_near(20.0f, 0.0f, 1.0f));
  sc::HeightMapGround::Params without;
  without.detect_ceiling = false;
  sc::HeightMapGround blind_to_ceilings(without);
  classify_all(blind_to_ceilings, ceiling);
  CHECK_FALSE(blind_to_ceilings.ceiling_height_near(0.0f, 0.0f, 0.5f));

  // The underside of a crown: a sphere of radius 2 m centred 4 m up.
  sc::HeightMapGround crown_model;
  std::vector<Eigen::Vector3f> crown;
  for (int i = 0; i < 20000; ++i) {
    Eigen::Vector3f d(u(rng), u(rng), -std::fabs(u(rng)) - 0.05f);
    d.normalize();
    crown.push_back(Eigen::Vector3f(3.0f, 0.0f, 4.0f) + 2.0f * d);
  }
  const auto k = classify_all(crown_model, crown);
  std::size_t crown_ceiling = 0;
  for (const auto cls : k) crown_ceiling += cls == sc::SurfaceClass::ceiling;
  CHECK(static_cast<double>(crown_ceiling) / 20000.0 < 0.1);
  CHECK_FALSE(crown_model.ceiling_height_near(3.0f, 0.0f, 0.5f));
}

TEST_CASE("HeightMapGround forgets every point: after the window passes no cell is live") {
  sc::HeightMapGround model;
  std::vector<Eigen::Vector3f> points;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  for (int i = 0; i < 5000; ++i) points.emplace_back(u(rng), u(rng), 0.1f * u(rng));
  const std::vector<sc::SurfaceClass> classes = classify_all(model, points);
  CHECK(model.live_cells() > 100);
  CHECK(model.heap_bytes() > 0);
  for (std::size_t i = 0; i < points.size(); ++i) model.forget(points[i], classes[i]);
  CHECK(model.live_cells() == 0);
  CHECK(model.live_wall_voxels() == 0);
}

TEST_CASE("HeightMapGround rejects parameters outside their ranges, naming them") {
  auto bad = [](auto change) {
    sc::HeightMapGround::Params p;
    change(p);
    return p;
  };
  auto message = [](const sc::HeightMapGround::Params& p) {
    return streamclust::test::invalid_argument_message([&p] { sc::HeightMapGround model{p}; });
  };
  CHECK(message(bad([](auto& p) { p.cell_size = 0.0f; })).find("cell_size = 0") != std::string::npos);
  CHECK(message(bad([](auto& p) { p.ground_tolerance = -0.1f; })).find("ground_tolerance") != std::string::npos);
  CHECK(message(bad([](auto& p) { p.max_slope_deg = 80.0f; })).find("max_slope_deg = 80") != std::string::npos);
  CHECK(message(bad([](auto& p) { p.support = 0; })).find("support") != std::string::npos);
  CHECK(message(bad([](auto& p) { p.surface_min_points = 0; })).find("surface_min_points = 0") != std::string::npos);
  CHECK(message(bad([](auto& p) { p.ceiling_min_agreement = 0.0f; })).find("ceiling_min_agreement") !=
        std::string::npos);
  CHECK(message(bad([](auto& p) { p.walls.max_rms = 0.0f; })).find("WallModel: max_rms = 0") != std::string::npos);
  CHECK(message(bad([](auto& p) { p.walls.voxel_size = 8.0f; })).find("voxel_size = 8") != std::string::npos);
  CHECK(message(bad([](auto& p) { p.walls.min_points = 1; })).find("min_points = 1") != std::string::npos);
  CHECK(message(sc::HeightMapGround::Params{}).empty());
  CHECK(sc::NoGround{}.classify(Eigen::Vector3f(0, 0, -5), Eigen::Vector3f(0, 0, -5)) == sc::SurfaceClass::object);
}

namespace {

/// What a surface point belongs to, in the walls test below.
enum class Part { floor, wall, cabinet_front, cabinet_side, pillar, car_side, trunk };

/// Random points on a room's floor (z = -1, the sensor at the origin), a
/// wall 3 m tall at x = 6, a cabinet 2 m tall 2 cm in front of it, a
/// pillar, a car's side and a trunk; the faces the sensor sees, shuffled.
std::vector<std::pair<Eigen::Vector3f, Part>> wall_room(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  std::vector<std::pair<Eigen::Vector3f, Part>> out;
  const auto add = [&](Part part, int n, auto&& make) {
    for (int i = 0; i < n; ++i) out.emplace_back(make() + Eigen::Vector3f(noise(rng), noise(rng), noise(rng)), part);
  };
  add(Part::floor, 40000, [&] { return Eigen::Vector3f(-8.0f + 14.0f * u(rng), -8.0f + 16.0f * u(rng), -1.0f); });
  add(Part::wall, 30000, [&] {
    Eigen::Vector3f p(6.0f, -7.0f + 14.0f * u(rng), -1.0f + 3.0f * u(rng));
    while (p.y() > 0.98f && p.y() < 2.02f && p.z() < 1.0f) p = Eigen::Vector3f(6.0f, -7.0f + 14.0f * u(rng), -1.0f + 3.0f * u(rng));
    return p;
  });
  add(Part::cabinet_front, 3000, [&] { return Eigen::Vector3f(5.43f, 1.0f + u(rng), -1.0f + 2.0f * u(rng)); });
  add(Part::cabinet_side, 1500, [&] { return Eigen::Vector3f(5.43f + 0.55f * u(rng), 1.0f, -1.0f + 2.0f * u(rng)); });
  add(Part::pillar, 3000, [&] {
    const float a = 1.5f + 1.6f * u(rng);  // the half that faces the sensor
    return Eigen::Vector3f(2.0f + 0.3f * std::cos(a), -3.0f + 0.3f * std::sin(a), -1.0f + 3.0f * u(rng));
  });
  add(Part::car_side, 4000, [&] { return Eigen::Vector3f(-3.0f + 4.5f * u(rng), -4.1f, -0.7f + 1.2f * u(rng)); });
  add(Part::trunk, 2000, [&] {
    const float a = -0.4f + 1.6f * u(rng);
    return Eigen::Vector3f(-4.0f + 0.2f * std::cos(a), 3.0f + 0.2f * std::sin(a), -1.0f + 4.0f * u(rng));
  });
  std::shuffle(out.begin(), out.end(), rng);
  return out;
}

}  // namespace

TEST_CASE("HeightMapGround walls: a wall is wall; a cabinet against it, a pillar, a car's side and a trunk are not") {
  const auto points = wall_room(3);
  sc::HeightMapGround model;
  std::map<Part, std::pair<std::size_t, std::size_t>> wall_rate;  // part -> (points, classed wall)
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f& p = points[i].first;
    const sc::SurfaceClass c = model.classify(p, p);
    if (i < points.size() / 3) continue;  // the model warms up on the first third
    auto& r = wall_rate[points[i].second];
    ++r.first;
    r.second += c == sc::SurfaceClass::wall;
  }
  const auto rate = [&](Part part) {
    const auto& r = wall_rate[part];
    return static_cast<double>(r.second) / static_cast<double>(r.first);
  };
  INFO("classed wall: wall " << rate(Part::wall) << ", floor " << rate(Part::floor) << ", cabinet front "
                             << rate(Part::cabinet_front) << ", side " << rate(Part::cabinet_side) << ", pillar "
                             << rate(Part::pillar) << ", car side " << rate(Part::car_side) << ", trunk "
                             << rate(Part::trunk));
  CHECK(rate(Part::wall) > 0.95);
  CHECK(rate(Part::floor) < 0.02);          // a strip along the wall's foot
  CHECK(rate(Part::cabinet_front) < 0.01);  // 0.55 m in front of the wall
  CHECK(rate(Part::cabinet_side) < 0.25);   // the back 10 cm of its 55
  CHECK(rate(Part::pillar) == 0.0);
  CHECK(rate(Part::car_side) == 0.0);       // long, but 1.2 m tall
  CHECK(rate(Part::trunk) == 0.0);

  // Without the wall stage nothing is wall.
  sc::HeightMapGround::Params off;
  off.detect_walls = false;
  sc::HeightMapGround no_walls(off);
  std::size_t walls = 0;
  for (const auto& [p, part] : points) walls += no_walls.classify(p, p) == sc::SurfaceClass::wall;
  CHECK(walls == 0);
}
