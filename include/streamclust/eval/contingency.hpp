// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// ContingencyTable: the sparse (truth label x predicted label) point-count
/// table every clustering-quality metric is computed from.

#include <streamclust/eval/options.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace streamclust {
namespace eval {

/// Sparse contingency table n(g, d) = number of points with truth label g and
/// predicted label d, over the EVALUATED points: those with truth >= 0
/// (ignored points, truth < 0, are dropped). Every negative predicted id is
/// folded into the single label kUnlabelled (-1).
///
/// Layout: truth labels sorted ascending (structure label 0 first when
/// present), predicted labels sorted ascending (kUnlabelled first when
/// present); non-zero cells sorted by (truth index, predicted index), so the
/// cells of truth label i are `cells()[row_begin(i) .. row_end(i))`.
///
/// Build it once and pass it to several metrics (`evaluate` does) instead of
/// letting each metric rebuild it from the label vectors.
///
/// Example:
/// \code
///   std::vector<std::int64_t> truth{0, 0, 1, 1, 2};
///   std::vector<std::int64_t> pred{-1, -1, 7, 7, 7};
///   streamclust::eval::ContingencyTable t{truth, pred};
///   // t.truth_labels() == {0, 1, 2}, t.predicted_labels() == {-1, 7}
///   // cells: (0,-1):2, (1,7):2, (2,7):1
/// \endcode
///
/// Complexity: construction O(n log n) time (one sort of the n evaluated
/// (truth, predicted) pairs) and O(n) transient memory (16 bytes per point);
/// the table itself is O(cells + labels). Thread safety: immutable after
/// construction; const members may be called concurrently.
class ContingencyTable {
 public:
  struct Cell {
    std::size_t truth_index = 0;      ///< index into truth_labels()
    std::size_t predicted_index = 0;  ///< index into predicted_labels()
    std::uint64_t count = 0;          ///< n(g, d) > 0
  };

  /// Empty table (no points).
  ContingencyTable() { row_begin_.push_back(0); }

  /// Builds the table; throws std::invalid_argument when the sizes differ.
  ContingencyTable(const std::vector<std::int64_t>& truth, const std::vector<std::int64_t>& predicted) {
    detail::check_same_size(truth.size(), predicted.size());
    input_points_ = truth.size();
    std::vector<std::pair<std::int64_t, std::int64_t>> pairs;
    pairs.reserve(truth.size());
    for (std::size_t i = 0; i < truth.size(); ++i) {
      if (truth[i] < 0) continue;
      pairs.emplace_back(truth[i], predicted[i] < 0 ? kUnlabelled : predicted[i]);
    }
    evaluated_points_ = pairs.size();
    std::sort(pairs.begin(), pairs.end());

    // Run-length encode into cells, keeping the raw predicted label for now.
    std::vector<std::int64_t> cell_pred;
    row_begin_.push_back(0);
    for (std::size_t i = 0; i < pairs.size();) {
      std::size_t j = i + 1;
      while (j < pairs.size() && pairs[j] == pairs[i]) ++j;
      if (truth_labels_.empty() || truth_labels_.back() != pairs[i].first) {
        if (!truth_labels_.empty()) row_begin_.push_back(cells_.size());
        truth_labels_.push_back(pairs[i].first);
        truth_sizes_.push_back(0);
      }
      const auto count = static_cast<std::uint64_t>(j - i);
      cells_.push_back(Cell{truth_labels_.size() - 1, 0, count});
      cell_pred.push_back(pairs[i].second);
      truth_sizes_.back() += count;
      i = j;
    }
    if (!truth_labels_.empty()) row_begin_.push_back(cells_.size());

    predicted_labels_ = cell_pred;
    std::sort(predicted_labels_.begin(), predicted_labels_.end());
    predicted_labels_.erase(std::unique(predicted_labels_.begin(), predicted_labels_.end()), predicted_labels_.end());
    predicted_sizes_.assign(predicted_labels_.size(), 0);
    for (std::size_t c = 0; c < cells_.size(); ++c) {
      const auto it = std::lower_bound(predicted_labels_.begin(), predicted_labels_.end(), cell_pred[c]);
      cells_[c].predicted_index = static_cast<std::size_t>(it - predicted_labels_.begin());
      predicted_sizes_[cells_[c].predicted_index] += cells_[c].count;
    }
  }

  /// Distinct truth labels (all >= 0), ascending.
  const std::vector<std::int64_t>& truth_labels() const { return truth_labels_; }
  /// Points per truth label, parallel to truth_labels().
  const std::vector<std::uint64_t>& truth_sizes() const { return truth_sizes_; }
  /// Distinct predicted labels (kUnlabelled or >= 0), ascending.
  const std::vector<std::int64_t>& predicted_labels() const { return predicted_labels_; }
  /// Evaluated points per predicted label (structure points included,
  /// ignored points excluded), parallel to predicted_labels().
  const std::vector<std::uint64_t>& predicted_sizes() const { return predicted_sizes_; }
  /// Non-zero cells, sorted by (truth_index, predicted_index).
  const std::vector<Cell>& cells() const { return cells_; }
  /// Cells of truth label index i: [row_begin(i), row_end(i)).
  std::size_t row_begin(std::size_t i) const { return row_begin_[i]; }
  std::size_t row_end(std::size_t i) const { return row_begin_[i + 1]; }

  bool is_structure(std::size_t truth_index) const { return truth_labels_[truth_index] == 0; }
  bool is_object(std::size_t truth_index) const { return truth_labels_[truth_index] > 0; }
  bool is_unlabelled(std::size_t predicted_index) const { return predicted_labels_[predicted_index] < 0; }

  /// Length of the input vectors.
  std::size_t input_points() const { return input_points_; }
  /// Points with truth >= 0.
  std::size_t evaluated_points() const { return evaluated_points_; }
  /// Points with truth < 0.
  std::size_t ignored_points() const { return input_points_ - evaluated_points_; }

 private:
  std::vector<std::int64_t> truth_labels_;
  std::vector<std::uint64_t> truth_sizes_;
  std::vector<std::int64_t> predicted_labels_;
  std::vector<std::uint64_t> predicted_sizes_;
  std::vector<Cell> cells_;
  std::vector<std::size_t> row_begin_;
  std::size_t input_points_ = 0;
  std::size_t evaluated_points_ = 0;
};

}  // namespace eval
}  // namespace streamclust
