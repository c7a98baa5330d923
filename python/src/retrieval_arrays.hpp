// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A retrieval as new numpy arrays: what streamclust.Retrieval wraps. One
/// copy out of the engine's buffers, which it reuses at the next retrieval.
/// Every function needs the GIL.

#include "window_rows.hpp"

#include <streamclust/clustering.hpp>
#include <streamclust/tracking/track.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <cstring>
#include <vector>

namespace streamclust::python {

namespace py = pybind11;

/// One row of Retrieval.components (a numpy structured array; its dtype is
/// registered when the module loads).
struct ComponentRecord {
  std::int64_t id;      ///< stable component id
  std::int64_t size;    ///< points in the window
  float centroid[3];    ///< mean position [m]
  float min[3];         ///< box, lower corner [m]
  float max[3];         ///< box, upper corner [m]
  double t_min;         ///< oldest point [s]
  double t_max;         ///< newest point [s]
};

/// One row of Retrieval.tracks (a numpy structured array; its dtype is
/// registered when the module loads). The tracks CSV's columns.
struct TrackRecord {
  std::int64_t track_id;    ///< the track's own id
  std::int64_t cluster_id;  ///< the component seen, -1 when none was
  float position[3];        ///< box centre [m]
  float velocity[3];        ///< [m/s]; 0 while static
  float length, width, height;  ///< [m]
  float yaw;                ///< [rad]
  std::int64_t points;      ///< of the component seen (0 when none)
  std::int8_t state;        ///< 0 tentative, 1 confirmed, 2 coasting
  bool moving;
};

template <class T>
py::array_t<T> copy_to_array(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(T));
  return a;
}

inline py::array_t<ComponentRecord> components_array(const std::vector<ComponentSummary>& components) {
  py::array_t<ComponentRecord> a(static_cast<py::ssize_t>(components.size()));
  ComponentRecord* out = a.mutable_data();
  for (const ComponentSummary& c : components) {
    ComponentRecord r{};
    r.id = static_cast<std::int64_t>(c.id);
    r.size = static_cast<std::int64_t>(c.size);
    for (int k = 0; k < 3; ++k) {
      r.centroid[k] = c.centroid[k];
      r.min[k] = c.min[k];
      r.max[k] = c.max[k];
    }
    r.t_min = c.time_begin;
    r.t_max = c.time_end;
    *out++ = r;
  }
  return a;
}

inline py::array_t<TrackRecord> tracks_array(const std::vector<tracking::Track>& tracks) {
  py::array_t<TrackRecord> a(static_cast<py::ssize_t>(tracks.size()));
  TrackRecord* out = a.mutable_data();
  for (const tracking::Track& t : tracks) {
    TrackRecord r{};
    r.track_id = static_cast<std::int64_t>(t.id);
    r.cluster_id = t.cluster_id == kNoComponent ? -1 : static_cast<std::int64_t>(t.cluster_id);
    for (int k = 0; k < 3; ++k) {
      r.position[k] = t.position[k];
      r.velocity[k] = t.velocity[k];
    }
    r.length = t.length;
    r.width = t.width;
    r.height = t.height;
    r.yaw = t.yaw;
    r.points = static_cast<std::int64_t>(t.points);
    r.state = static_cast<std::int8_t>(t.state);
    r.moving = t.moving;
    *out++ = r;
  }
  return a;
}

/// (cycle, time, index, labels, components). O(rows + components).
inline py::tuple retrieval_tuple(std::uint64_t cycle, double time, const WindowRows& rows, const Clustering& result) {
  return py::make_tuple(cycle, time, copy_to_array(rows.index), copy_to_array(rows.label),
                        components_array(result.components));
}

}  // namespace streamclust::python
