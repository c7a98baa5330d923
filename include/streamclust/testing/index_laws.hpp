// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The laws the engine relies on for a spatial index
/// (concepts/spatial_index.hpp), checked against a brute-force model (one
/// vector per cell in insertion order; a full cell drops its oldest handle)
/// on random operation sequences the engine's way: mostly FIFO removals,
/// some removals out of order, removals of absent handles and from the wrong
/// cell (no-ops), handles across the 32-bit wrap; reset, clear.
///   - insert returns the handle it displaced (or kNoPoint), remove forgets,
///     for_each lists the cell's handles in insertion order, size counts;
///   - a bounded index (max_cell_size) never holds more in a cell, and the
///     model's capacity is that bound;
///   - gather (when present) reports the count and hands over for_each's
///     handles when they fit, nothing past the room;
///   - youngest / gather_older (when present) agree with for_each;
///   - prefetch (when present) changes nothing.
///
/// \code
/// streamclust::testing::IndexLawOptions<MyIndex> options;
/// options.params = {{8}};  // the parameter sets, e.g. a small capacity that fills
/// const auto r = streamclust::testing::check_index<MyIndex>(options);
/// \endcode
/// Cost: O(operations x cell size); 60,000 operations by default. Not thread-safe.

#include <streamclust/concepts/spatial_index.hpp>
#include <streamclust/testing/law_result.hpp>
#include <streamclust/testing/type_name.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::testing {

template <class I>
struct IndexLawOptions {
  std::vector<typename I::Params> params;  ///< parameter sets to test; empty: the defaults
  /// Handles a cell keeps before it displaces its oldest when the index has
  /// no max_cell_size (0: unbounded).
  std::size_t capacity = 0;
  std::size_t operations = 20000;  ///< per grid shape and parameter set
  std::uint32_t seed = 12345;
};

namespace internal {

/// Brute-force index: one vector per cell in insertion order; a full cell
/// drops its oldest handle.
struct IndexModelCells {
  std::vector<std::vector<PointHandle>> cells;
  std::size_t capacity = std::numeric_limits<std::size_t>::max();

  void reset(std::size_t n) { cells.assign(n, {}); }
  PointHandle insert(CellIndex c, PointHandle h) {
    auto& v = cells[c];
    PointHandle displaced = kNoPoint;
    if (v.size() == capacity) {
      displaced = v.front();
      v.erase(v.begin());
    }
    v.push_back(h);
    return displaced;
  }
  void remove(CellIndex c, PointHandle h) {
    auto& v = cells[c];
    const auto it = std::find(v.begin(), v.end(), h);
    if (it != v.end()) v.erase(it);
  }
  std::size_t size() const {
    std::size_t n = 0;
    for (const auto& v : cells) n += v.size();
    return n;
  }
};

template <class I>
std::vector<PointHandle> index_contents(const I& index, CellIndex c) {
  std::vector<PointHandle> out;
  index.for_each(c, [&](PointHandle h) { out.push_back(h); });
  return out;
}

inline std::string handles_text(const std::vector<PointHandle>& v) {
  std::ostringstream os;
  os << "{";
  for (std::size_t k = 0; k < v.size(); ++k) os << (k ? ", " : "") << v[k];
  os << "}";
  return os.str();
}

/// Every law of one cell against the model's contents; "" when they hold.
template <class I>
std::string index_cell_laws(const I& index, CellIndex c, const std::vector<PointHandle>& expected) {
  const std::vector<PointHandle> got = index_contents(index, c);
  if (got != expected)
    return "cell " + std::to_string(c) + ": for_each lists " + handles_text(got) + ", expected " +
           handles_text(expected) + " (insertion order, displaced and removed handles gone)";
  const std::size_t n = got.size();
  if constexpr (has_spatial_index_cell_bound_v<I>) {
    if (n > index.max_cell_size())
      return "cell " + std::to_string(c) + " holds " + std::to_string(n) + " handles, above max_cell_size() = " +
             std::to_string(index.max_cell_size());
  }
  if constexpr (has_spatial_index_gather_v<I>) {
    constexpr PointHandle kGuard = 0xDEADBEEFu;
    for (const std::size_t room : {n, n + 1, std::size_t{4}, std::size_t{6}, std::size_t{64}}) {
      if (room < n) continue;
      std::vector<PointHandle> buffer(room + 1, kGuard);
      const std::size_t count = index.gather(c, buffer.data(), room);
      if (count != n) return "cell " + std::to_string(c) + ": gather reports " + std::to_string(count) +
                             " handles, for_each lists " + std::to_string(n);
      if (buffer.back() != kGuard)
        return "cell " + std::to_string(c) + ": gather wrote past its room " + std::to_string(room);
      buffer.resize(n);
      if (buffer != got)
        return "cell " + std::to_string(c) + ": gather hands over " + handles_text(buffer) + ", for_each lists " +
               handles_text(got);
    }
    if (n > 0) {
      std::vector<PointHandle> short_buffer(n, kGuard);  // room n - 1, guard at [n - 1]
      if (index.gather(c, short_buffer.data(), n - 1) != n || short_buffer.back() != kGuard)
        return "cell " + std::to_string(c) + ": gather with room for one handle less than the cell's " +
               std::to_string(n) + " must report the count and write nothing past the room";
    }
  }
  if constexpr (has_spatial_index_chain_v<I>) {
    if (n > 0) {
      if (index.youngest(c) != got.back())
        return "cell " + std::to_string(c) + ": youngest() = " + std::to_string(index.youngest(c)) +
               ", the last handle for_each lists is " + std::to_string(got.back());
      std::vector<PointHandle> out(n + 1, kNoPoint);
      for (std::size_t k = 0; k <= n; ++k) {
        const PointHandle bound = k < n ? got[k] : got.back() + 1u;
        const std::size_t count = index.gather_older(c, bound, out.data(), n);
        if (count != k || !std::equal(got.begin(), got.begin() + static_cast<std::ptrdiff_t>(k), out.begin()) ||
            out[n] != kNoPoint)
          return "cell " + std::to_string(c) + ": gather_older(bound " + std::to_string(bound) + ") reports " +
                 std::to_string(count) + " handles, expected the " + std::to_string(k) + " before it in " +
                 handles_text(got);
      }
    }
  }
  return {};
}

template <class I>
std::string index_laws(I& index, IndexModelCells& model, CellIndex cells) {
  if (index.size() != model.size())
    return "size() = " + std::to_string(index.size()) + ", the cells hold " + std::to_string(model.size());
  for (CellIndex c = 0; c < cells; ++c) {
    std::string failure = index_cell_laws(index, c, model.cells[c]);
    if (!failure.empty()) return failure;
  }
  return {};
}

}  // namespace internal

/// Every law of a spatial index (see the file comment); the first failure,
/// with the operation that revealed it.
template <class I>
LawResult check_index(const IndexLawOptions<I>& options = {}) {
  static_assert(is_spatial_index_policy_v<I>,
                "check_index: I does not model the spatial index concept (concepts/spatial_index.hpp)");
  const std::string name = "index " + type_name<I>();
  const std::vector<typename I::Params> sets = internal::parameter_sets(options.params);
  std::size_t operations = 0;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const std::string context = name + ", parameter set " + std::to_string(k);
    std::optional<I> holder;
    if (const std::string thrown = internal::construct_from(sets[k], holder); !thrown.empty())
      return law_failed(context + ": the parameters do not construct: " + thrown);
    I& index = *holder;
    internal::IndexModelCells model;
    if constexpr (has_spatial_index_cell_bound_v<I>) {
      model.capacity = 0;  // set per reset: max_cell_size may depend on the grid
    } else if (options.capacity != 0) {
      model.capacity = options.capacity;
    }
    std::mt19937 rng(options.seed + static_cast<std::uint32_t>(k));
    for (const GridShape shape : {GridShape{4, 5, true}, GridShape{2, 3, false}, GridShape{8, 16, true}}) {
      index.reset(shape);
      model.reset(shape.cell_count());
      if constexpr (has_spatial_index_cell_bound_v<I>) model.capacity = index.max_cell_size();
      const auto cells = static_cast<CellIndex>(shape.cell_count());
      std::string op = "reset to " + std::to_string(shape.rows) + "x" + std::to_string(shape.cols);
      const auto fail = [&](const std::string& failure) {
        return law_failed(context + ", grid " + std::to_string(shape.rows) + "x" + std::to_string(shape.cols) +
                          ", after " + op + ": " + failure);
      };
      std::string failure = internal::index_laws(index, model, cells);
      if (!failure.empty()) return fail(failure);
      std::uniform_int_distribution<CellIndex> pick_cell(0, cells - 1);
      std::uniform_int_distribution<int> percent(0, 99);
      std::deque<std::pair<PointHandle, CellIndex>> window;  // live points, oldest first
      PointHandle next = 0xFFFFFF00u;  // near the wrap: handles are opaque to the index
      for (std::size_t step = 0; step < options.operations; ++step, ++operations) {
        const int dice = percent(rng);
        if (dice < 55 || window.empty()) {
          const PointHandle h = next++;
          if (h == kNoPoint) continue;  // the sentinel is never a handle
          const CellIndex c = pick_cell(rng);
          const PointHandle displaced = index.insert(c, h);
          const PointHandle expected = model.insert(c, h);
          op = "insert(cell " + std::to_string(c) + ", handle " + std::to_string(h) + ") at operation " +
               std::to_string(step);
          if (displaced != expected)
            return fail("insert returned " + std::to_string(displaced) + ", expected " +
                        (expected == kNoPoint ? std::string("kNoPoint (the cell had room)")
                                              : std::to_string(expected) + " (the cell's oldest)"));
          window.emplace_back(h, c);
        } else if (dice < 98) {
          // the engine's common case: the oldest leaves (even if displaced
          // earlier); sometimes an arbitrary point of the window
          std::size_t i = 0;
          if (dice >= 92) i = std::uniform_int_distribution<std::size_t>(0, window.size() - 1)(rng);
          const auto [h, c] = window[i];
          window.erase(window.begin() + static_cast<std::ptrdiff_t>(i));
          index.remove(c, h);
          model.remove(c, h);
          op = "remove(cell " + std::to_string(c) + ", handle " + std::to_string(h) + ") at operation " +
               std::to_string(step);
        } else {
          // an absent handle, a handle in the wrong cell: no-ops
          const CellIndex c = pick_cell(rng);
          index.remove(c, next + 1000u);
          op = "remove of an absent handle from cell " + std::to_string(c) + " at operation " + std::to_string(step);
          if (!window.empty()) {
            const auto [h, hc] = window.back();
            const CellIndex other = (hc + 1) % cells;
            index.remove(other, h);
            model.remove(other, h);
          }
        }
        if (index.size() != model.size())
          return fail("size() = " + std::to_string(index.size()) + ", the cells hold " + std::to_string(model.size()));
        if (step % 97 == 0) {
          failure = internal::index_laws(index, model, cells);
          if (!failure.empty()) return fail(failure);
        }
      }
      op = "the random operations";
      failure = internal::index_laws(index, model, cells);
      if (!failure.empty()) return fail(failure);
      if constexpr (has_spatial_index_prefetch_v<I>) {
        for (CellIndex c = 0; c < cells; ++c) index.prefetch(c);
        op = "prefetch of every cell";
        failure = internal::index_laws(index, model, cells);
        if (!failure.empty()) return fail(failure);
      }
      while (!window.empty()) {  // drain in insertion order
        index.remove(window.front().second, window.front().first);
        model.remove(window.front().second, window.front().first);
        window.pop_front();
      }
      op = "removing every handle";
      failure = internal::index_laws(index, model, cells);
      if (!failure.empty()) return fail(failure);
      for (PointHandle h = 0; h < 3 * cells; ++h) {  // refill, then clear
        const PointHandle displaced = index.insert(h % cells, h);
        if (displaced != model.insert(h % cells, h))
          return fail("refilling: insert(cell " + std::to_string(h % cells) + ", handle " + std::to_string(h) +
                      ") returned " + std::to_string(displaced));
      }
      op = "refilling";
      failure = internal::index_laws(index, model, cells);
      if (!failure.empty()) return fail(failure);
      index.clear();
      model.reset(shape.cell_count());
      op = "clear()";
      failure = internal::index_laws(index, model, cells);
      if (!failure.empty()) return fail(failure);
    }
  }
  return law_passed(name + ": " + std::to_string(sets.size()) + " parameter sets, " + std::to_string(operations) +
                    " operations");
}

}  // namespace streamclust::testing
