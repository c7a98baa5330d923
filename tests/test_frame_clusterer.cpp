// SPDX-License-Identifier: MIT
// FrameClusterer: the frame-based driver keeps the engine's window (same
// acceptance, same stream indices, same calibration) and clusters it from
// scratch at every retrieval.

#include <doctest/doctest.h>

#include <streamclust/frame_clusterer.hpp>
#include <streamclust/presets.hpp>
#include <streamclust/sim/synthetic_stream.hpp>

#include "support/partition.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace sc = streamclust;

namespace {

std::vector<sc::SyntheticPoint> synthetic(double seconds, double rate = 40000.0) {
  sc::SyntheticStream::Params p;
  p.point_rate = rate;
  sc::SyntheticStream stream(p);
  std::vector<sc::SyntheticPoint> points;
  while (stream.time() < seconds) points.push_back(stream.next());
  return points;
}

}  // namespace

TEST_CASE("FrameClusterer in insertion order labels every window as the continuous engine does") {
  sc::ClustererParams<sc::CArcFixedConfig> params;
  params.resolution = {32, 256};
  params.window.duration = 0.05;
  sc::StreamClusterer<sc::CArcFixedConfig> engine(params);
  sc::FrameClusterer<sc::CArcFixedConfig> frame(params, sc::BatchMode::insertion_order);
  CHECK_FALSE(frame.calibrating());
  const auto points = synthetic(0.2);
  std::size_t retrievals = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    CHECK(frame.insert(points[i]) == engine.insert(points[i]));
    if (i % 1500 != 1499) continue;
    const sc::Clustering& c = engine.retrieve();
    const sc::BatchResult& b = frame.retrieve();
    REQUIRE(b.labels.size() == c.points.size());
    std::vector<std::uint64_t> engine_labels, engine_index, frame_index;
    for (const sc::PointLabel& p : c.points) {
      engine_labels.push_back(p.label);
      engine_index.push_back(p.stream_index);
    }
    frame.for_each_point([&](const sc::Sample&, std::uint64_t index) { frame_index.push_back(index); });
    CHECK(frame_index == engine_index);
    CHECK(sc::test::partition_mismatch(b.labels, engine_labels) == "");
    CHECK(&frame.last_result() == &b);
    ++retrievals;
  }
  CHECK(retrievals >= 4);
  CHECK(frame.size() == engine.size());
  CHECK(frame.offered() == points.size());
}

TEST_CASE("FrameClusterer calibrates on the first complete window and chooses the engine's grid") {
  sc::ClustererParams<sc::CArcConfig> params;
  params.window.duration = 0.05;
  sc::StreamClusterer<sc::CArcConfig> engine(params);
  sc::FrameClusterer<sc::CArcConfig> frame(params);
  const auto points = synthetic(0.12);
  std::size_t i = 0;
  for (; i < points.size() && points[i].t - points.front().t < 0.04; ++i) {
    frame.insert(points[i]);
    engine.insert(points[i]);
  }
  CHECK(frame.calibrating());
  CHECK(frame.retrieve().labels.empty());  // nothing is labelled before the grid is known
  for (; i < points.size(); ++i) {
    frame.insert(points[i]);
    engine.insert(points[i]);
  }
  REQUIRE_FALSE(frame.calibrating());
  REQUIRE_FALSE(engine.calibrating());
  CHECK(frame.grid().rows == engine.grid().rows);
  CHECK(frame.grid().cols == engine.grid().cols);
  CHECK(frame.grid().wrap_columns == engine.grid().wrap_columns);
  CHECK(frame.size() == engine.size());
  CHECK(frame.retrieve().labels.size() == frame.size());
}

TEST_CASE("FrameClusterer rejects as the engine does and evicts on advance_to") {
  sc::ClustererParams<sc::CArcFixedConfig> params;
  params.resolution = {16, 64};
  params.window.duration = 0.1;
  sc::FrameClusterer<sc::FrameBaselineConfig> unused_default;  // default parameters construct
  sc::FrameClusterer<sc::CArcFixedConfig> frame(params);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  CHECK(frame.insert(sc::SyntheticPoint{5.0f, 0.0f, 0.0f, 1.0f, 0.0, 0}) == sc::RejectReason::accepted);
  CHECK(frame.insert(sc::SyntheticPoint{nan, 0.0f, 0.0f, 1.0f, 0.01, 0}) == sc::RejectReason::non_finite);
  CHECK(frame.insert(sc::SyntheticPoint{0.01f, 0.0f, 0.0f, 1.0f, 0.02, 0}) == sc::RejectReason::too_close);
  CHECK(frame.insert(sc::SyntheticPoint{5.0f, 0.1f, 0.0f, 1.0f, -1.0, 0}) == sc::RejectReason::time_backwards);
  CHECK(frame.insert(sc::SyntheticPoint{5.0f, 0.1f, 0.0f, 1.0f, 0.05, 0}) == sc::RejectReason::accepted);
  CHECK(frame.rejections().rejected() == 3);
  CHECK(frame.size() == 2);
  std::vector<std::uint64_t> indices;
  frame.for_each_point([&](const sc::Sample&, std::uint64_t index) { indices.push_back(index); });
  CHECK(indices == std::vector<std::uint64_t>{0, 4});
  const sc::BatchResult& r = frame.retrieve();
  REQUIRE(r.labels.size() == 2);
  frame.advance_to(0.12);  // the first point (t = 0) has left the 0.1 s window
  CHECK(frame.size() == 1);
  frame.advance_to(1.0);
  CHECK(frame.empty());
}
