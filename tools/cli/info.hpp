// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// `streamclust info`: format, fields, point count, bounds and time span of
/// any readable input, read in one streaming pass; an input without a time
/// field is described too (its records get times only from --point-rate),
/// and so is one with a header and no points ("points: 0", exit 0; cluster
/// exits 4 on it). Running out of memory: OutOfMemory (memory_context.hpp).

#include "cli/memory_context.hpp"
#include "cli/options.hpp"

#include <streamclust/io/reader.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <vector>

namespace streamclust::cli {

inline int run_info_reading(const InfoOptions& o, std::ostream& out) {
  // The readers need a point rate to open an input without a time field;
  // without --point-rate, any rate does: no time is reported then.
  io::ReadOptions read = o.read;
  if (!read.point_rate) read.point_rate = 1.0;
  auto reader = io::open_reader(o.input, read);
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
  } else if (o.read.point_rate) {
    out << "time:      no time field; t = index / " << *o.read.point_rate << " Hz (--point-rate)";
  } else {
    out << "time:      no time field (cluster needs --point-rate)";
  }
  if ((info.has_time || o.read.point_rate) && count > 0 && t1 >= t0) {
    const io::TimeOrigin origin = reader->time_origin();
    out << ", " << io::format_time(origin, t0) << " s to " << io::format_time(origin, t1) << " s (span " << t1 - t0
        << " s)";
  }
  out << "\n";
  if (finite > 0) {
    out << "bounds:    x [" << lo[0] << ", " << hi[0] << "] y [" << lo[1] << ", " << hi[1] << "] z [" << lo[2] << ", "
        << hi[2] << "] m\n";
  }
  return kOk;
}

inline int run_info(const InfoOptions& o, std::ostream& out) {
  return with_memory_context("info", o.input, [&](Stage&) { return run_info_reading(o, out); });
}

}  // namespace streamclust::cli
