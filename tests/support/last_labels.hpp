// SPDX-License-Identifier: MIT
#pragma once
// The labels an engine's last retrieval gave its window's points.

#include <streamclust/clustering.hpp>

#include <vector>

namespace streamclust::test {

/// Labels of the last retrieval of `engine`, in window order.
template <class Engine>
std::vector<ComponentId> last_labels(const Engine& engine) {
  std::vector<ComponentId> out;
  for (const PointLabel& l : engine.last_result().points) out.push_back(l.label);
  return out;
}

}  // namespace streamclust::test
