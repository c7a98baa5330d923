// SPDX-License-Identifier: MIT
#pragma once
// The oracle of an engine with a ground or motion policy: the batch
// clusterer, given the engine's object points as they were offered (sensor
// frame, in stream order), places, projects and clusters them from scratch;
// the partitions must be equal. The ground decisions are the engine's,
// replayed: the batch sees only the points the engine kept as objects.

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <streamclust/testing/oracle.hpp>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace streamclust::testing {

/// Compares the engine's last retrieval with a batch run on the offered
/// points `stream` (stream index = position + first_stream_index) of the
/// window's object points, on the engine's grid. Also checks that the
/// result's object and structure points are the window's, disjoint.
/// Returns an empty string on agreement, else what differs. O(window) plus
/// the batch run.
template <class Config, class P>
std::string compare_with_batch_on_input(const StreamClusterer<Config>& engine, BatchClusterer<Config>& batch,
                                        const std::vector<P>& stream) {
  const Clustering& result = engine.last_result();
  if (result.structure.size() != engine.structure_size()) return "structure list differs from the structure ring";
  if (engine.calibrating()) return result.points.empty() ? "" : "labels while the first window is buffered";
  if (result.points.size() != engine.size()) return "engine labelled a different number of points than its window";
  std::set<std::uint64_t> seen;
  std::vector<P> window;
  std::vector<ComponentId> continuous;
  const std::uint64_t first = engine.params().first_stream_index;
  for (const PointLabel& p : result.points) {
    if (!seen.insert(p.stream_index).second) return "a stream index appears twice among the object points";
    if (p.stream_index < first || p.stream_index - first >= stream.size()) return "stream index outside the stream";
    window.push_back(stream[static_cast<std::size_t>(p.stream_index - first)]);
    continuous.push_back(p.label);
  }
  for (const StructurePoint& s : result.structure) {
    if (!seen.insert(s.stream_index).second) return "a structure point is also an object point, or appears twice";
    if (s.surface == SurfaceClass::object) return "a structure point classed object";
  }
  if (window.empty()) return {};
  return compare_window_with_batch(engine, batch, window, continuous);
}

}  // namespace streamclust::testing
