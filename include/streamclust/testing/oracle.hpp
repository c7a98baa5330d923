// SPDX-License-Identifier: MIT
#pragma once
// The oracle comparison: the engine's last retrieval against a from-scratch
// batch run on the same window.

#include <streamclust/batch_clusterer.hpp>
#include <streamclust/stream_clusterer.hpp>

#include <streamclust/testing/partition.hpp>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace streamclust::testing {

/// Clusters `window` (the points the engine labelled `continuous`, in
/// order) with `batch` on the engine's grid and compares the partitions and
/// the component count. Returns an empty string on agreement.
template <class Config, class P>
std::string compare_window_with_batch(const StreamClusterer<Config>& engine, BatchClusterer<Config>& batch,
                                      const std::vector<P>& window, const std::vector<ComponentId>& continuous) {
  batch.set_grid({engine.grid().rows, engine.grid().cols});
  const BatchResult& reference = batch.cluster(window);
  if (reference.rejections.rejected() != 0) return "batch rejected a point the engine accepted";
  std::string mismatch = partition_mismatch(continuous, reference.labels);
  if (!mismatch.empty()) return mismatch;
  std::set<ComponentId> ids(continuous.begin(), continuous.end());
  if (ids.size() != engine.last_result().components.size()) return "component summaries do not match the labels";
  return {};
}

/// Compares the engine's last retrieval with a from-scratch batch run on the
/// same window (same grid). Returns an empty string on agreement, else what
/// differs. O(window) plus the batch run.
template <class Config>
std::string compare_with_batch(const StreamClusterer<Config>& engine, BatchClusterer<Config>& batch) {
  std::vector<Sample> window;
  std::vector<std::uint64_t> indices;
  engine.for_each_point([&](const Sample& s, std::uint64_t i) {
    window.push_back(s);
    indices.push_back(i);
  });
  const Clustering& result = engine.last_result();
  if (result.points.size() != window.size()) return "engine labelled a different number of points than its window";
  std::vector<ComponentId> continuous;
  for (std::size_t i = 0; i < window.size(); ++i) {
    if (result.points[i].stream_index != indices[i]) return "stream index mismatch";
    continuous.push_back(result.points[i].label);
  }
  return compare_window_with_batch(engine, batch, window, continuous);
}

}  // namespace streamclust::testing
