// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// TUM trajectory files: one pose per line, `t tx ty tz qx qy qz qw`
/// (time [s], position [m], unit quaternion of world from sensor), separated
/// by spaces; lines starting with `#` are comments. Standard library only:
/// the records are plain numbers (motion/trajectory.hpp makes poses of them).

#include <cstdio>
#include <ostream>
#include <vector>

namespace streamclust::io {

/// One line of a TUM trajectory.
struct TumRecord {
  double t = 0.0;                     ///< [s]
  double tx = 0.0, ty = 0.0, tz = 0.0;  ///< position [m]
  double qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;  ///< rotation, unit quaternion (x, y, z, w)
};

/// Writes `records` as a TUM trajectory with a `#` header line: times with
/// nanosecond resolution (%.9f, exact at epoch scale within a double's
/// precision), positions and quaternions with 9 decimals. O(records).
inline void write_tum(std::ostream& out, const std::vector<TumRecord>& records) {
  out << "# t tx ty tz qx qy qz qw\n";
  char line[256];
  for (const TumRecord& r : records) {
    std::snprintf(line, sizeof line, "%.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n", r.t, r.tx, r.ty, r.tz, r.qx, r.qy,
                  r.qz, r.qw);
    out << line;
  }
}

}  // namespace streamclust::io
