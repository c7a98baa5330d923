// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The one place where a reader's record time becomes the time the Python
/// module hands out (`read()["t"]`). Today io::Record::t is already stream
/// time in seconds; when the readers report a whole-second origin for
/// epoch-scale timestamps, this function is what changes.

#include <streamclust/io/record.hpp>

namespace streamclust::python {

/// The Python time [s] of record `r` read from an input described by `info`.
/// O(1).
inline double python_time(const io::Record& r, const io::InputInfo& info) {
  (void)info;
  return r.t;
}

}  // namespace streamclust::python
