// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust info`: format, fields, point count, time span and bounds of
/// an input, read in one streaming pass.

#include "cli/options.hpp"

#include <streamclust/io/reader.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <vector>

namespace streamclust::cli {

inline int run_info(const InfoOptions& o, std::ostream& out) {
  auto reader = io::open_reader(o.input, o.read);
  const io::InputInfo& info = reader->info();
  std::uint64_t count = 0, finite = 0;
  double t0 = std::numeric_limits<double>::infinity(), t1 = -t0;
  float lo[3] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                 std::numeric_limits<float>::infinity()};
  float hi[3] = {-lo[0], -lo[1], -lo[2]};
  std::vector<io::Record> chunk;
  for (;;) {
    chunk.clear();
    if (reader->read(chunk, 65536) == 0) break;
    for (const io::Record& r : chunk) {
      ++count;
      if (std::isfinite(r.t)) {
        t0 = std::min(t0, r.t);
        t1 = std::max(t1, r.t);
      }
      const float p[3] = {r.x, r.y, r.z};
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
      ++finite;
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    }
  }
  out << "file:      " << o.input << "\n";
  out << "format:    " << io::to_string(info.format) << (info.encoding.empty() ? "" : " (" + info.encoding + ")") << "\n";
  out << "fields:   ";
  for (const auto& f : info.fields) out << " " << f;
  out << "\n";
  out << "points:    " << count << " (" << finite << " with finite coordinates)";
  if (info.declared_points) out << ", header declares " << *info.declared_points;
  out << "\n";
  if (info.has_time) {
    out << "time:      field '" << info.time_field << "'";
  } else {
    out << "time:      none in the file; assigned as index / point rate";
  }
  if (count > 0 && t1 >= t0) out << ", " << t0 << " s to " << t1 << " s (span " << t1 - t0 << " s)";
  out << "\n";
  if (finite > 0) {
    out << "bounds:    x [" << lo[0] << ", " << hi[0] << "] y [" << lo[1] << ", " << hi[1] << "] z [" << lo[2] << ", "
        << hi[2] << "] m\n";
  }
  return kOk;
}

}  // namespace streamclust::cli
