// SPDX-License-Identifier: MIT
// The extension module `streamclust._streamclust`: numpy in, numpy out, over
// the library's continuous engine configured by the CLI's own option parser.
// The pure-Python package `streamclust` (python/streamclust/) wraps it with
// keyword arguments; docs/python.md is the user's documentation.
//
// Copies: insert() reads the caller's arrays in place (zero copy; checked
// C-contiguous); every retrieval is copied once into new numpy arrays (the
// engine reuses its result buffers at the next retrieval, so a view could
// not outlive it). The GIL is released while the engine works.

#include "array_checks.hpp"
#include "erased_clusterer.hpp"
#include "live_run.hpp"
#include "options_bridge.hpp"
#include "retrieval_arrays.hpp"
#include "scheduled_run.hpp"
#include "window_rows.hpp"

#include "cli/evaluate.hpp"
#include "cli/simulate.hpp"

#include <streamclust/eval/average.hpp>
#include <streamclust/eval/report.hpp>
#include <streamclust/io/error.hpp>
#include <streamclust/io/reader.hpp>
#include <streamclust/tracking/kalman_tracker.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace streamclust::python {

namespace {

std::optional<double> optional_time(const py::object& time, const char* name) {
  if (time.is_none()) return std::nullopt;
  double t = 0.0;
  try {
    t = time.cast<double>();
  } catch (const py::cast_error&) {
    throw py::value_error(std::string(name) + ": expected seconds as a float or None");
  }
  if (!std::isfinite(t)) throw py::value_error(std::string(name) + ": expected finite seconds, got " + std::to_string(t));
  return t;
}

/// A StreamSession shared with Python: every call releases the GIL, then
/// takes the session's mutex (so calls from several Python threads run one
/// at a time, never concurrently in the engine). Lock order: mutex, then
/// GIL (retrieve copies its rows under both); never the mutex with the GIL.
class Clusterer {
 public:
  /// `first_xyz`, `first_t`: None, or the stream's beginning, from which the
  /// mount and sensor height are estimated as the CLI does from its input's
  /// first window (ground without mount or sensor height).
  /// `tracks`: each retrieval also fits the objects' boxes and updates a
  /// KalmanTracker (continuous mode only: ValueError otherwise).
  Clusterer(const std::vector<std::string>& args, const py::handle& first_xyz, const py::handle& first_t, bool tracks)
      : session_(make_engine(args, first_xyz, first_t)) {
    if (!tracks) return;
    if (!session_.engine().continuous()) {
      throw py::value_error("tracks: tracking follows the continuous engine's components; not with mode=\"frame\"");
    }
    tracker_.emplace();
  }

  py::object insert(const py::handle& xyz, const py::handle& t, const py::handle& intensity, bool want_reasons) {
    const PointBuffers points = point_buffers(xyz, t, intensity);
    std::optional<py::array_t<std::uint8_t>> reasons;  // allocated only when asked for
    std::uint8_t* reasons_out = nullptr;
    if (want_reasons) {
      reasons.emplace(static_cast<py::ssize_t>(points.size));
      reasons_out = reasons->mutable_data();
    }
    std::size_t accepted = 0;
    {
      py::gil_scoped_release release;
      const std::lock_guard<std::mutex> lock(mutex_);
      accepted = session_.insert(points, reasons_out);
    }
    if (reasons) return py::make_tuple(accepted, *reasons);
    return py::int_(accepted);
  }

  void advance_to(const py::object& time_obj) {
    if (time_obj.is_none()) throw py::value_error("time: expected seconds, got None");
    const double time = *optional_time(time_obj, "time");
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(mutex_);
    session_.advance_to(time);
  }

  void complete_calibration() {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(mutex_);
    session_.complete_calibration();
  }

  py::tuple retrieve(const py::object& time_obj) {
    const std::optional<double> time = optional_time(time_obj, "time");
    py::tuple out;
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(mutex_);
    if (time) session_.advance_to(*time);
    const Clustering& result = session_.retrieve(rows_);
    const std::uint64_t cycle = cycles_++;
    const std::vector<tracking::Track>* tracks = nullptr;
    if (tracker_) tracks = &tracker_->update(*session_.engine().objects(result), result.time);
    py::gil_scoped_acquire acquire;
    out = retrieval_tuple(cycle, time ? *time : result.time, rows_, result);
    if (tracks) out = py::make_tuple(out[0], out[1], out[2], out[3], out[4], tracks_array(*tracks));
    return out;
  }

  // Every accessor releases the GIL before it takes the mutex: retrieve()
  // takes the GIL while holding the mutex, so waiting for the mutex with the
  // GIL held could deadlock.
  bool calibrating() {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(mutex_);
    return session_.calibrating();
  }
  std::uint64_t offered() {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(mutex_);
    return session_.engine().offered();
  }
  std::size_t size() {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(mutex_);
    return session_.engine().size();
  }
  py::tuple grid() {
    GridShape g;
    {
      py::gil_scoped_release release;
      const std::lock_guard<std::mutex> lock(mutex_);
      g = session_.engine().grid();
    }
    return py::make_tuple(g.rows, g.cols, g.wrap_columns);
  }

 private:
  static std::unique_ptr<ErasedClusterer> make_engine(const std::vector<std::string>& args,
                                                      const py::handle& first_xyz, const py::handle& first_t) {
    cli::ClusterOptions o = parse_python_options(args);
    if (first_xyz.is_none() && first_t.is_none()) {
      resolve_setup(o, nullptr);
    } else {
      const PointBuffers first = point_buffers(first_xyz, first_t, py::none(), "first_window xyz", "first_window t");
      std::vector<double> times;
      const std::vector<Eigen::Vector3f> window = first_window_of(o, first, &times);
      resolve_setup(o, &window, &times);
    }
    return make_erased_clusterer(o);
  }

  StreamSession session_;
  std::mutex mutex_;
  WindowRows rows_;
  std::uint64_t cycles_ = 0;
  std::optional<KalmanTracker> tracker_;  ///< with tracks=True
};

/// cluster_stream: the CLI driver's schedule (tools/cli/cluster_driver.hpp)
/// over arrays. Cycle k here is the CLI's cycle k on the same stream.
/// `args` include the retrieval rate (--rate).
py::list cluster_stream(const std::vector<std::string>& args, const py::handle& xyz, const py::handle& t,
                        const py::handle& intensity, const std::optional<std::vector<std::uint64_t>>& cycles,
                        bool tracks) {
  const PointBuffers points = point_buffers(xyz, t, intensity);
  if (points.size == 0) throw py::value_error("xyz: no points (the CLI refuses an empty input too)");
  cli::ClusterOptions o = parse_python_options(args);
  std::vector<std::uint64_t> wanted = cycles.value_or(std::vector<std::uint64_t>{});
  std::sort(wanted.begin(), wanted.end());
  const bool all = !cycles.has_value();

  py::list out;
  py::gil_scoped_release release;
  if (needs_first_window(o)) {
    std::vector<double> times;
    const std::vector<Eigen::Vector3f> first = first_window_of(o, points, &times);
    resolve_setup(o, &first, &times);
  } else {
    resolve_setup(o, nullptr);
  }
  std::optional<ScheduledRun> run_holder;
  try {
    run_holder.emplace(o, tracks);
  } catch (const std::invalid_argument& e) {
    py::gil_scoped_acquire acquire;
    throw py::value_error(e.what());
  }
  ScheduledRun& run = *run_holder;
  auto keep = [&](std::uint64_t cycle, double time, const WindowRows& rows, const Clustering& result,
                  const std::vector<tracking::Track>* cycle_tracks) {
    if (all || std::binary_search(wanted.begin(), wanted.end(), cycle)) {
      py::gil_scoped_acquire acquire;
      py::tuple r = retrieval_tuple(cycle, time, rows, result);
      if (cycle_tracks) r = py::make_tuple(r[0], r[1], r[2], r[3], r[4], tracks_array(*cycle_tracks));
      out.append(r);
    }
  };
  run.feed(points, keep);
  if (run.valid_times() == 0) {
    py::gil_scoped_acquire acquire;
    throw py::value_error("t: no usable time (finite, within +-9e9 s, not a jump; the CLI exits 4 on such a stream)");
  }
  run.finish(keep);
  py::gil_scoped_acquire acquire;
  return out;
}

/// The records of `path` through the library's readers, as arrays.
py::dict read_file(const std::string& path, const std::vector<std::string>& args) {
  io::ReadOptions read_options;
  for (cli::ArgCursor c(args); !c.done(); c.next()) {
    if (!cli::parse_input_option(c, read_options)) throw cli::UsageError("unknown read option '" + c.option() + "'");
  }
  std::vector<io::Record> records;
  io::InputInfo info;
  io::TimeOrigin origin;
  {
    py::gil_scoped_release release;
    auto reader = io::open_reader(path, read_options);
    info = reader->info();
    while (reader->read(records, 65536) > 0) {
    }
    origin = reader->time_origin();
  }
  const auto n = static_cast<py::ssize_t>(records.size());
  py::array_t<float> x(n), y(n), z(n), intensity(n);
  py::array_t<double> t(n);
  py::array_t<std::int64_t> label(n);
  float *px = x.mutable_data(), *py_ = y.mutable_data(), *pz = z.mutable_data(), *pi = intensity.mutable_data();
  double* pt = t.mutable_data();
  std::int64_t* pl = label.mutable_data();
  for (std::size_t i = 0; i < records.size(); ++i) {
    const io::Record& r = records[i];
    px[i] = r.x;
    py_[i] = r.y;
    pz[i] = r.z;
    pi[i] = r.intensity;
    pt[i] = r.t;  // seconds since the origin, exact at epoch scale (io/stream_time.hpp)
    pl[i] = r.label;
  }
  py::dict d;
  d["x"] = x;
  d["y"] = y;
  d["z"] = z;
  d["intensity"] = intensity;
  d["t"] = t;
  d["time_origin"] = origin.seconds;
  if (info.has_label) d["label"] = label;
  return d;
}

/// A simulated stream: (xyz (N, 3) float32, t float64, intensity float32,
/// truth int64 instance ids (0 structure), surface uint8 SurfaceClass).
py::tuple simulate(const std::vector<std::string>& args) {
  cli::SimulateOptions o;
  for (cli::ArgCursor c(args); !c.done(); c.next()) {
    if (!cli::parse_simulation_option(c, o)) throw cli::UsageError("unknown simulation option '" + c.option() + "'");
  }
  cli::validate_simulation_options(o);
  cli::SimulatedStream stream;
  {
    py::gil_scoped_release release;
    stream = cli::simulate_stream(o);
  }
  const auto n = static_cast<py::ssize_t>(stream.records.size());
  py::array_t<float> xyz({n, py::ssize_t{3}});
  py::array_t<float> intensity(n);
  py::array_t<double> t(n);
  py::array_t<std::int64_t> truth(n);
  py::array_t<std::uint8_t> surface(n);
  float* pxyz = xyz.mutable_data();
  for (std::size_t i = 0; i < stream.records.size(); ++i) {
    const io::Record& r = stream.records[i];
    pxyz[3 * i] = r.x;
    pxyz[3 * i + 1] = r.y;
    pxyz[3 * i + 2] = r.z;
    intensity.mutable_data()[i] = r.intensity;
    t.mutable_data()[i] = r.t;
    truth.mutable_data()[i] = r.label;
    surface.mutable_data()[i] = static_cast<std::uint8_t>(stream.classes[i]);
  }
  return py::make_tuple(xyz, t, intensity, truth, surface);
}

std::vector<std::int64_t> int64_vector(const py::handle& obj, const char* name) {
  const py::array a = require_ndarray(obj, name);
  if (a.ndim() != 1) throw py::value_error(std::string(name) + ": expected shape (N,), got " + shape_of(a));
  if (a.dtype().kind() != 'i' && a.dtype().kind() != 'u') {
    throw py::value_error(std::string(name) + ": expected an integer dtype, got " + std::string(py::str(a.dtype())));
  }
  const auto v = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
  return std::vector<std::int64_t>(v.data(), v.data() + v.size());
}

/// The metrics of one window: eval::evaluate as a dict named like the CLI's
/// `evaluate --json` quality fields.
py::dict evaluate(const py::handle& labels_obj, const py::handle& truth_obj, std::size_t min_points) {
  const std::vector<std::int64_t> labels = int64_vector(labels_obj, "labels");
  const std::vector<std::int64_t> truth = int64_vector(truth_obj, "truth");
  if (labels.size() != truth.size()) {
    throw py::value_error("labels: " + std::to_string(labels.size()) + " labels for " + std::to_string(truth.size()) +
                          " truth ids; expected one per point");
  }
  if (min_points == 0) throw py::value_error("min_points: expected a whole number >= 1");
  eval::MeanQuality q;
  {
    py::gil_scoped_release release;
    eval::MetricOptions m;
    m.min_points = min_points;
    q = eval::to_mean_quality(eval::evaluate(truth, labels, m));
  }
  py::dict d;
  const char* const* names = cli::mean_quality_names();
  std::size_t k = 0;
  for (const auto field : eval::kMeanQualityFields) d[names[k++]] = q.*field;
  return d;
}

}  // namespace
}  // namespace streamclust::python

PYBIND11_MODULE(_streamclust, m) {
  namespace sp = streamclust::python;
  m.doc() = "streamclust's extension module; use the `streamclust` package (docs/python.md).";
  PYBIND11_NUMPY_DTYPE(sp::ComponentRecord, id, size, centroid, min, max, t_min, t_max);
  PYBIND11_NUMPY_DTYPE(sp::TrackRecord, track_id, cluster_id, position, velocity, length, width, height, yaw, points,
                       state, moving);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const streamclust::cli::UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const streamclust::io::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const streamclust::live::ConnectionError& e) {
      PyErr_SetString(PyExc_ConnectionError, e.what());
    } catch (const sp::LiveTimeout& e) {
      PyErr_SetString(PyExc_TimeoutError, e.what());
    }
  });

  py::tuple reasons(streamclust::kRejectReasonCount);
  for (std::size_t r = 0; r < streamclust::kRejectReasonCount; ++r) {
    reasons[r] = streamclust::to_string(static_cast<streamclust::RejectReason>(r));
  }
  m.attr("REJECT_REASONS") = reasons;

  py::class_<sp::Clusterer>(m, "Clusterer")
      .def(py::init<const std::vector<std::string>&, const py::handle&, const py::handle&, bool>(), py::arg("args"),
           py::arg("first_xyz") = py::none(), py::arg("first_t") = py::none(), py::arg("tracks") = false)
      .def("insert", &sp::Clusterer::insert, py::arg("xyz"), py::arg("t"), py::arg("intensity") = py::none(),
           py::arg("reasons") = false)
      .def("advance_to", &sp::Clusterer::advance_to, py::arg("time"))
      .def("complete_calibration", &sp::Clusterer::complete_calibration)
      .def("retrieve", &sp::Clusterer::retrieve, py::arg("time") = py::none())
      .def_property_readonly("calibrating", &sp::Clusterer::calibrating)
      .def_property_readonly("offered", &sp::Clusterer::offered)
      .def_property_readonly("size", &sp::Clusterer::size)
      .def_property_readonly("grid", &sp::Clusterer::grid);
  m.def("cluster_stream", &sp::cluster_stream, py::arg("args"), py::arg("xyz"), py::arg("t"), py::arg("intensity"),
        py::arg("cycles"), py::arg("tracks") = false);
  py::class_<sp::LiveRun>(m, "LiveRun")
      .def(py::init([](const std::vector<std::string>& args, const std::string& source,
                       const std::vector<std::string>& lidars, bool configure,
                       const std::optional<std::string>& discovery_address, double wait, double duration,
                       double idle_exit, std::size_t queue, std::size_t reorder, bool tracks) {
             return std::make_unique<sp::LiveRun>(
                 args,
                 sp::live_source_options(source, lidars, configure, discovery_address, wait, duration, idle_exit,
                                         queue, reorder),
                 tracks);
           }),
           py::arg("args"), py::arg("source"), py::arg("lidars"), py::arg("configure"), py::arg("discovery_address"),
           py::arg("wait"), py::arg("duration"), py::arg("idle_exit"), py::arg("queue"), py::arg("reorder"),
           py::arg("tracks") = false)
      .def("next", &sp::LiveRun::next)
      .def("close", &sp::LiveRun::close)
      .def("counters", &sp::LiveRun::counters)
      .def_property_readonly("time_origin", &sp::LiveRun::time_origin);
  m.def("read", &sp::read_file, py::arg("path"), py::arg("args"));
  m.def("simulate", &sp::simulate, py::arg("args"));
  m.def("evaluate", &sp::evaluate, py::arg("labels"), py::arg("truth"), py::arg("min_points"));
  // The registered policies' options (cli/tool_policies.hpp): the package's
  // keywords for them (python/streamclust/_options.py).
  m.def("policy_options", [] {
    std::vector<std::pair<std::string, std::string>> options;  // (keyword, CLI option), each once
    for (const auto& o : streamclust::cli::ToolRegistry::options()) {
      const bool seen = std::any_of(options.begin(), options.end(), [&](const auto& k) { return k.first == o.keyword; });
      if (!seen) options.emplace_back(o.keyword, o.name);
    }
    return options;
  });
  m.def("policy_names", [](const std::string& slot) {
    using streamclust::registry::Slot;
    const Slot s = slot == "linkage" ? Slot::linkage
                   : slot == "index" ? Slot::spatial_index
                   : slot == "connectivity" ? Slot::connectivity
                   : slot == "projection" ? Slot::projection
                                          : throw streamclust::cli::UsageError("policy_names: expected linkage, index, "
                                                                               "connectivity or projection, got '" +
                                                                               slot + "'");
    return streamclust::cli::ToolRegistry::names(s);
  });
}
