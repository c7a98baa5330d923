// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// What the engine counts between two retrievals, and the phase clock that
/// times its phases only for configurations that ask for it.

#include <chrono>
#include <cstdint>

namespace streamclust {

/// Wall time spent per phase [microseconds]; measured only for configs with
/// `static constexpr bool timed = true`, zero otherwise.
struct PhaseTimes {
  double placement = 0.0;         ///< motion compensation and projection (motion policy)
  double ground = 0.0;            ///< structure removal: the ground model's update and decision
  double insertion = 0.0;         ///< neighbour search, edges, isolation/expansion/bridging
  double eviction = 0.0;          ///< removing points that left the window
  double validation = 0.0;        ///< BFS over pending clusters, splits
  double component_update = 0.0;  ///< BFS over the component graph, stable ids
  double labelling = 0.0;         ///< labels and summaries of every window point
};

/// Counters of the work done since the previous retrieval.
struct RetrievalStats {
  std::uint64_t inserted = 0;           ///< points inserted into the graph
  std::uint64_t evicted = 0;            ///< points that left the window
  std::uint64_t ground = 0;             ///< accepted points classed ground (ground policy)
  std::uint64_t ceiling = 0;            ///< accepted points classed ceiling (ground policy)
  std::uint64_t wall = 0;               ///< accepted points classed wall (ground policy)
  std::uint64_t clusters_validated = 0; ///< pending clusters checked by BFS
  std::uint64_t points_validated = 0;   ///< points of the clusters checked (validation work)
  std::uint64_t clusters_split = 0;     ///< new clusters created by splits
  std::uint64_t forest_folds = 0;       ///< spanning_forest: folds without labelling (new edges past the threshold)
  std::uint64_t edges_found = 0;        ///< spanning_forest: edges of the inserted points to older neighbours
  std::uint64_t edges_pruned = 0;       ///< spanning_forest: of those, dropped as redundant (prune_witnesses)
  std::uint64_t candidates_skipped = 0; ///< crowded cells: chain points not tested (engine/cell_chains.hpp)
  std::uint64_t forest_displaced = 0;   ///< spanning_forest: kept forest edges a fold moved aside (detail::merge_forest)
  std::uint64_t edges_folded = 0;       ///< spanning_forest: new edges the folds read (those still live at their fold)
  std::uint64_t edges_accepted = 0;     ///< spanning_forest: of those, accepted into the forest (the rest closed cycles)
  std::uint64_t forest_edges = 0;       ///< spanning_forest: edges of the forest after this retrieval (window points - components)
  PhaseTimes phase_us{};                ///< timed configs only
};

namespace detail {

/// Start times and elapsed-time sums for the phases; with `Timed` false
/// every call compiles to nothing. Stateless, thread-safe.
template <bool Timed>
struct PhaseClock {
  struct NoTime {};
  /// The current time, or nothing.
  static auto now() {
    if constexpr (Timed) {
      return std::chrono::steady_clock::now();
    } else {
      return NoTime{};
    }
  }
  /// Adds the time since `since` to `microseconds`.
  template <class T>
  static void add_since(double& microseconds, const T& since) {
    if constexpr (Timed) {
      microseconds += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - since).count();
    } else {
      (void)microseconds;
      (void)since;
    }
  }
};

}  // namespace detail
}  // namespace streamclust
