// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The `--report` JSON, the `--labels` CSV rows and the one-line summary.

#include <streamclust/resolution/adaptive.hpp>
#include <streamclust/stream_clusterer.hpp>
#include <streamclust/types.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::cli {

/// One retrieval cycle as reported.
struct CycleReport {
  std::uint64_t cycle = 0;
  double time = 0.0;          ///< scheduled stream time of the retrieval [s]
  std::size_t window = 0;     ///< clustered points in the window
  std::uint64_t inserted = 0; ///< points inserted since the previous cycle
  std::uint64_t evicted = 0;  ///< points evicted since the previous cycle (continuous mode)
  std::size_t components = 0;
  PhaseTimes phase{};         ///< continuous mode [us]
  double batch_us = 0.0;      ///< frame mode: the batch clustering of the window [us]
  double total_us = 0.0;      ///< the retrieval itself [us] (continuous: validation + components + labelling)
};

struct Report {
  std::string input, format, mode;
  std::string connectivity;  ///< continuous mode: "lazy-bfs" or "forest"; empty in frame mode
  std::uint32_t grid_rows = 0, grid_cols = 0;
  bool grid_wraps = false;
  bool adaptive = false;
  std::vector<AdaptiveStep> trace;
  AdaptiveStop stop = AdaptiveStop::not_run;
  std::vector<CycleReport> cycles;
  std::uint64_t records = 0;
  RejectionCounts rejections{};
};

/// Cost of one cycle [us]: everything done for it since the previous one.
inline double cycle_cost_us(const CycleReport& c) {
  return c.phase.insertion + c.phase.eviction + c.phase.validation + c.phase.component_update + c.phase.labelling +
         c.batch_us;
}

inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(k, v.size() - 1)];
}

inline std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

template <class Rows>
void write_label_rows(std::ostream& out, const Rows& w) {
  for (std::size_t i = 0; i < w.index.size(); ++i) {
    out << w.cycle << ',' << w.time << ',' << w.index[i] << ',' << w.label[i] << '\n';
  }
}

inline void write_report(std::ostream& o, const Report& r) {
  o.precision(9);
  o << "{\n  \"input\": " << json_string(r.input) << ",\n  \"format\": " << json_string(r.format)
    << ",\n  \"mode\": " << json_string(r.mode);
  if (!r.connectivity.empty()) o << ", \"connectivity\": " << json_string(r.connectivity);
  o << ",\n";
  o << "  \"grid\": {\"rows\": " << r.grid_rows << ", \"cols\": " << r.grid_cols
    << ", \"wrap_columns\": " << (r.grid_wraps ? "true" : "false") << ", \"adaptive\": " << (r.adaptive ? "true" : "false")
    << ", \"stop\": " << json_string(to_string(r.stop)) << ", \"trace\": [";
  for (std::size_t i = 0; i < r.trace.size(); ++i) {
    const AdaptiveStep& s = r.trace[i];
    o << (i ? ", " : "") << "{\"rows\": " << s.grid.rows << ", \"cols\": " << s.grid.cols
      << ", \"density_v\": " << s.density_v << ", \"density_h\": " << s.density_h << ", \"gap_v\": " << s.gap_v
      << ", \"gap_h\": " << s.gap_h << ", \"mean_multiplicity\": " << s.mean_multiplicity << "}";
  }
  o << "]},\n  \"cycles\": [\n";
  std::vector<double> costs;
  std::uint64_t inserted = 0, evicted = 0;
  for (std::size_t i = 0; i < r.cycles.size(); ++i) {
    const CycleReport& c = r.cycles[i];
    costs.push_back(cycle_cost_us(c));
    inserted += c.inserted;
    evicted += c.evicted;
    o << "    {\"cycle\": " << c.cycle << ", \"time\": " << c.time << ", \"window_size\": " << c.window
      << ", \"inserted\": " << c.inserted << ", \"evicted\": " << c.evicted << ", \"components\": " << c.components
      << ", \"latency_us\": {\"insertion\": " << c.phase.insertion << ", \"eviction\": " << c.phase.eviction
      << ", \"validation\": " << c.phase.validation << ", \"component_update\": " << c.phase.component_update
      << ", \"labelling\": " << c.phase.labelling << ", \"batch\": " << c.batch_us << ", \"total\": " << costs.back()
      << "}}" << (i + 1 < r.cycles.size() ? "," : "") << "\n";
  }
  o << "  ],\n  \"totals\": {\"records\": " << r.records << ", \"inserted\": " << inserted << ", \"evicted\": " << evicted
    << ", \"cycles\": " << r.cycles.size() << ", \"rejected\": {";
  for (std::size_t k = 1; k < kRejectReasonCount; ++k) {
    o << (k > 1 ? ", " : "") << json_string(to_string(static_cast<RejectReason>(k))) << ": " << r.rejections.by_reason[k];
  }
  o << "}, \"latency_us\": {\"median\": " << percentile(costs, 0.5) << ", \"p99\": " << percentile(costs, 0.99)
    << ", \"max\": " << percentile(costs, 1.0) << "}}\n}\n";
}

inline void write_report_file(const std::string& path, const Report& r) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("--report: cannot write '" + path + "'");
  write_report(f, r);
  f.flush();
  if (!f) throw std::runtime_error("--report: writing '" + path + "' failed");
}

inline std::string summary_line(const Report& r) {
  std::vector<double> costs;
  for (const CycleReport& c : r.cycles) costs.push_back(cycle_cost_us(c));
  std::ostringstream s;
  s.precision(3);
  s << std::fixed << "streamclust: " << r.records << " records, " << r.rejections[RejectReason::accepted]
    << " clustered, " << r.rejections.rejected() << " rejected, " << r.cycles.size() << " cycles, grid " << r.grid_rows
    << "x" << r.grid_cols << ", cycle cost median " << percentile(costs, 0.5) / 1000.0 << " ms, P99 "
    << percentile(costs, 0.99) / 1000.0 << " ms";
  return s.str();
}

}  // namespace streamclust::cli
