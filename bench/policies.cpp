// SPDX-License-Identifier: MIT
// Microbenchmarks of the policies, one family at a time, each reporting
// points (or pairs) per second through SetItemsProcessed (items_per_second),
// written with the installed benchmark kit (<streamclust/benchmarking/...>,
// docs/performance.md): what a researcher's own policy is measured with.
// Engine-level benchmarks (insertion per preset, retrieval) live in
// bench/engine.cpp; the end-to-end latency is bench/latency/.
//
// The policies measured are the lists of tests/support/policy_lists.hpp
// (Projections, SpatialIndexes, Linkages, Windows, Resolutions), each with its
// default Params: adding a policy to its list there adds its benchmark here
// (and its tests), with no line in this file. Benchmark names are
// BM_<family><PolicyType>, e.g. BM_Linkage<AngularLinkage>. A linkage is
// measured by each path it has (sample, payload, link_many: the engine's
// one-call path) on two sets of candidate pairs: each point of 0.1 s of the
// simulated Mid-360 office stream against the 16 points fired before it
// (mid360_office_back16), and against what a 5 x 5 mask offers it
// (mid360_office_mask5). BM_LinkageCompare<RangeAdaptiveLinkage> times it
// against the Euclidean linkage alternately (the kit's comparison, ratio
// `over_reference`), BM_LinkageCompare<ScanAdaptiveLinkage> the
// scan-adaptive linkage (its table from the sensor model, T_B 0.5 s) against
// the range-adaptive one on the Mid-360 and Avia office mask pairs, and
// BM_LinkagePayload the per-point cost of making the payload (the
// scan-adaptive radius: a table read and, with poses, a rotation). The motion policy PosedMotion is measured on its
// own (BM_PosedMotion, ns per point). Inputs and counters: the kit's headers.
//
// Measure with (numbers: docs/performance.md):
//   build/bench-run/bench/bench_policies --benchmark_min_time=0.5 --benchmark_repetitions=3
//       --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <streamclust/benchmarking/linkage_benchmarks.hpp>
#include <streamclust/benchmarking/policy_benchmarks.hpp>
#include <streamclust/index/bucket_grid.hpp>
#include <streamclust/index/capped_grid.hpp>
#include <streamclust/index/overwrite_grid.hpp>
#include <streamclust/linkage/angular.hpp>
#include <streamclust/linkage/combinators.hpp>
#include <streamclust/linkage/euclidean.hpp>
#include <streamclust/linkage/range_adaptive.hpp>
#include <streamclust/linkage/runtime_linkage.hpp>
#include <streamclust/linkage/scan_adaptive.hpp>
#include <streamclust/motion/posed_motion.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/projection/cylindrical.hpp>
#include <streamclust/projection/spherical.hpp>
#include <streamclust/resolution/adaptive.hpp>
#include <streamclust/sim/sensors/avia_model.hpp>
#include <streamclust/sim/sensors/mid360_model.hpp>
#include <streamclust/window/count_window.hpp>
#include <streamclust/window/time_window.hpp>

#include "../tests/support/policy_lists.hpp"
#include "../tests/support/type_name.hpp"
#include "../tests/support/type_product.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sc = streamclust;
namespace bk = streamclust::benchmarking;

namespace {

// ------------------------------------------------------------------ motion

/// PosedMotion::place over one second of a 200 kHz stream (the positions of
/// the 0.1 s office stream, repeated, at times every 5 us) on a 100 Hz
/// trajectory driving at 10 m/s and yawing at 1 rad/s, the sensor pitched
/// 15 degrees on the vehicle. Argument: 0 a fixed mount (no trajectory),
/// 1 the trajectory, 2 the same pose per point from PoseTrajectory::at (a
/// slerp per point, double; what the per-segment cache saves).
void BM_PosedMotion(benchmark::State& state) {
  const auto& points = bk::simulated_points({bk::Sensor::mid360, "office"}, 0.1);
  std::vector<sc::StampedPose> poses;
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.01 * i;
    sc::Pose pose = sc::mount_from_roll_pitch_yaw_deg(0.0, 0.0, t * 57.29577951308232);
    pose.translation = Eigen::Vector3d(10.0 * t, 0.5 * t * t, 0.0);
    poses.push_back(sc::StampedPose{1700000000.0 + t, pose});
  }
  sc::PosedMotion::Params params;
  params.mount = sc::mount_from_roll_pitch_yaw_deg(0.0, 15.0, 0.0);
  if (state.range(0) != 0) params.trajectory = std::make_shared<const sc::PoseTrajectory>(poses);
  constexpr std::size_t kPoints = 200000;
  std::vector<Eigen::Vector3f> positions(kPoints);
  std::vector<double> times(kPoints);
  for (std::size_t i = 0; i < kPoints; ++i) {
    const auto& p = points[i % points.size()];
    positions[i] = Eigen::Vector3f(p.x, p.y, p.z);
    times[i] = 1700000000.0 + static_cast<double>(i) * 5e-6;
  }
  float sum = 0.0f;
  for (auto _ : state) {
    sc::PosedMotion motion(params);  // a fresh cursor: the stream starts at the trajectory's start
    if (state.range(0) == 2) {
      sc::PoseTrajectory::Cursor cursor;
      for (std::size_t i = 0; i < kPoints; ++i) {
        const sc::Pose pose = *params.trajectory->at(times[i], cursor) * params.mount;
        sum += static_cast<float>((pose * positions[i].cast<double>()).x());
      }
    } else {
      sc::PlacedPoint placed;
      for (std::size_t i = 0; i < kPoints; ++i) {
        benchmark::DoNotOptimize(motion.place(positions[i], times[i], placed));
        sum += placed.world.x() + placed.ray.y();
      }
    }
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(kPoints));
}
BENCHMARK(BM_PosedMotion)->ArgName("trajectory")->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

// ----------------------------------------------------------- scan-adaptive

/// ScanAdaptiveLinkage's defaults with the table of `sensor`'s model over
/// 0.5 s (the objects presets' T_B). About 0.5 s to build.
sc::ScanAdaptiveLinkage::Params scan_adaptive_params(bk::Sensor sensor) {
  sc::ScanAdaptiveLinkage::Params p;
  if (sensor == bk::Sensor::mid360) {
    sc::sim::Mid360Model model;
    p.spacing = sc::ScanSpacing::from_sensor_model(model, 0.5);
  } else {
    sc::sim::AviaModel model;
    p.spacing = sc::ScanSpacing::from_sensor_model(model, 0.5);
  }
  return p;
}

/// make_payload over the 0.1 s Mid-360 office stream (as Samples, times
/// every 5 us over a 100 Hz trajectory). Argument: 0 RangeAdaptiveLinkage
/// (a copy), 1 ScanAdaptiveLinkage with a fixed mount (pitched 15 deg),
/// 2 ScanAdaptiveLinkage with the trajectory (a slerp per point).
void BM_LinkagePayload(benchmark::State& state) {
  const auto& points = bk::simulated_points({bk::Sensor::mid360, "office"}, 0.1);
  std::vector<sc::Sample> samples;
  samples.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f p(points[i].x, points[i].y, points[i].z);
    samples.push_back(sc::make_sample(p, p.norm(), 0.0f, 0.001 * static_cast<double>(i) / static_cast<double>(points.size())));
  }
  static const sc::ScanAdaptiveLinkage::Params table = scan_adaptive_params(bk::Sensor::mid360);
  sc::ScanAdaptiveLinkage::Params params = table;
  params.mount = sc::mount_from_roll_pitch_yaw_deg(0.0, 15.0, 0.0);
  if (state.range(0) == 2) {
    std::vector<sc::StampedPose> poses;
    for (int i = 0; i <= 100; ++i) {
      const double t = 0.01 * i;
      sc::Pose pose = sc::mount_from_roll_pitch_yaw_deg(0.0, 0.0, t * 57.29577951308232);
      pose.translation = Eigen::Vector3d(10.0 * t, 0.0, 0.0);
      poses.push_back(sc::StampedPose{t, pose});
    }
    params.trajectory = std::make_shared<const sc::PoseTrajectory>(std::move(poses));
  }
  const sc::ScanAdaptiveLinkage scan{params};
  const sc::RangeAdaptiveLinkage range{{}};
  float sum = 0.0f;
  for (auto _ : state) {
    if (state.range(0) == 0) {
      for (const sc::Sample& s : samples) sum += range.make_payload(s).range;
    } else {
      for (const sc::Sample& s : samples) sum += scan.make_payload(s).radius;
    }
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(samples.size()));
}
BENCHMARK(BM_LinkagePayload)->ArgName("linkage")->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

/// Registers one benchmark per policy of each list (support/policy_lists.hpp).
bool register_policy_benchmarks() {
  namespace st = sc::test;
  // "BM_<family><Policy>", e.g. BM_Linkage<AngularLinkage>
  const auto name = [](const char* family, auto tag) {
    return std::string(family) + "<" + st::type_name<typename decltype(tag)::type>() + ">";
  };
  const std::vector<bk::PairSource> pairs{
      {"mid360_office_back16", []() -> const bk::CandidatePairs& { return bk::firing_order_candidates({bk::Sensor::mid360, "office"}); }},
      {"mid360_office_mask5", []() -> const bk::CandidatePairs& { return bk::mask_candidates({bk::Sensor::mid360, "office"}); }}};
  st::for_each_type<st::Projections>([&](auto tag) {
    bk::register_projection<typename decltype(tag)::type>(name("BM_Project", tag));
  });
  st::for_each_type<st::SpatialIndexes>([&](auto tag) {
    bk::register_index<typename decltype(tag)::type>(name("BM_Index", tag));
  });
  st::for_each_type<st::Linkages>([&](auto tag) {
    bk::register_linkage<typename decltype(tag)::type>(name("BM_Linkage", tag), {}, pairs);
  });
  // The kit's comparison, as a researcher runs it on their own linkage: the
  // range-adaptive linkage against the Euclidean one on the pairs a 5 x 5
  // mask offers in the Mid-360 and Avia office streams.
  bk::register_linkage_comparison<sc::RangeAdaptiveLinkage, sc::EuclideanLinkage>("BM_LinkageCompare<RangeAdaptiveLinkage>");
  // The scan-adaptive linkage against the range-adaptive one, each sensor's
  // pairs with that sensor's table.
  for (const bk::PairSource& source : bk::mask_pair_sources()) {
    const bk::Sensor sensor = source.name.rfind("mid360", 0) == 0 ? bk::Sensor::mid360 : bk::Sensor::avia;
    bk::register_linkage_comparison<sc::ScanAdaptiveLinkage, sc::RangeAdaptiveLinkage>(
        "BM_LinkageCompare<ScanAdaptiveLinkage>", scan_adaptive_params(sensor), {}, {source});
  }
  st::for_each_type<st::Windows>([&](auto tag) {
    bk::register_window<typename decltype(tag)::type>(name("BM_Window", tag));
  });
  st::for_each_type<st::Resolutions>([&](auto tag) {
    bk::register_resolution<typename decltype(tag)::type>(name("BM_Calibrate", tag));
  });
  return true;
}

[[maybe_unused]] const bool registered = register_policy_benchmarks();

}  // namespace

BENCHMARK_MAIN();
