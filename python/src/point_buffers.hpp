// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// PointBuffers: the caller's numpy arrays as raw, already checked C buffers,
/// and ArrayPointIterator, which reads them as streamclust::Point values so
/// the engine's `insert_batch` runs straight over them (zero copy: no packet
/// of Points is built).

#include <streamclust/point_traits.hpp>

#include <cstddef>
#include <iterator>

namespace streamclust::python {

/// The points of one `insert` call: C-contiguous buffers owned by numpy
/// arrays that outlive the call. Exactly one of `xyz32` / `xyz64` is set
/// (N x 3, row-major [m]); `t` has N stream times [s]; at most one of
/// `intensity32` / `intensity64` is set (none: intensity 0).
struct PointBuffers {
  const float* xyz32 = nullptr;
  const double* xyz64 = nullptr;
  const double* t = nullptr;
  const float* intensity32 = nullptr;
  const double* intensity64 = nullptr;
  std::size_t size = 0;

  /// The buffers of points [from, to) (no copy).
  PointBuffers slice(std::size_t from, std::size_t to) const {
    PointBuffers s = *this;
    if (xyz32) s.xyz32 += 3 * from;
    if (xyz64) s.xyz64 += 3 * from;
    s.t += from;
    if (intensity32) s.intensity32 += from;
    if (intensity64) s.intensity64 += from;
    s.size = to - from;
    return s;
  }

  /// Point i as the library's Point (float coordinates, as the engine stores
  /// them). O(1); two predictable branches on the dtypes.
  Point operator[](std::size_t i) const {
    Point p;
    if (xyz32) {
      p.x = xyz32[3 * i];
      p.y = xyz32[3 * i + 1];
      p.z = xyz32[3 * i + 2];
    } else {
      p.x = static_cast<float>(xyz64[3 * i]);
      p.y = static_cast<float>(xyz64[3 * i + 1]);
      p.z = static_cast<float>(xyz64[3 * i + 2]);
    }
    if (intensity32) p.intensity = intensity32[i];
    if (intensity64) p.intensity = static_cast<float>(intensity64[i]);
    p.t = t[i];
    return p;
  }
};

/// A forward iterator over PointBuffers yielding Point by value: what
/// `StreamClusterer::insert_batch(first, last, reasons)` reads.
class ArrayPointIterator {
 public:
  using iterator_category = std::forward_iterator_tag;
  using value_type = Point;
  using difference_type = std::ptrdiff_t;
  using pointer = const Point*;
  using reference = Point;

  ArrayPointIterator() = default;
  ArrayPointIterator(const PointBuffers* buffers, std::size_t i) : buffers_(buffers), i_(i) {}
  Point operator*() const { return (*buffers_)[i_]; }
  ArrayPointIterator& operator++() {
    ++i_;
    return *this;
  }
  ArrayPointIterator operator++(int) {
    ArrayPointIterator old = *this;
    ++i_;
    return old;
  }
  friend bool operator==(const ArrayPointIterator& a, const ArrayPointIterator& b) { return a.i_ == b.i_; }
  friend bool operator!=(const ArrayPointIterator& a, const ArrayPointIterator& b) { return a.i_ != b.i_; }

 private:
  const PointBuffers* buffers_ = nullptr;
  std::size_t i_ = 0;
};

}  // namespace streamclust::python
