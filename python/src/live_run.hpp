// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// LiveRun: `streamclust.live` in C++. A LiveSource's returns become points
/// (xyz [m], t [s] since a whole-second time origin, intensity = the
/// reflectivity), are clustered on the retrieval schedule of
/// `cluster_stream` (ScheduledRun) and come out as retrievals with the
/// window's points and the points received since the previous retrieval,
/// as numpy arrays. Exactness: the cycles equal `cluster_stream` over the
/// concatenation of the received points.
///
/// The GIL is released while waiting for packets and while the engine
/// works; waits are cut into 50 ms slices, between which pending signals
/// are handled (Ctrl-C raises KeyboardInterrupt). No signal handler is
/// installed.
///
/// Thread safety: one call at a time (a mutex; `next` from a second thread
/// while one waits raises RuntimeError). Lock order: mutex, then GIL.

#include "live_source.hpp"
#include "options_bridge.hpp"
#include "retrieval_arrays.hpp"
#include "scheduled_run.hpp"

#include <streamclust/live/live_counters.hpp>
#include <streamclust/live/livox_returns.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::python {

/// No packet within `wait` after the connection (Python: TimeoutError).
class LiveTimeout : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The source's options from `streamclust.live`'s keywords; ValueError
/// (py::value_error) naming the keyword, with the CLI's message for a bad
/// source string.
inline LiveSourceOptions live_source_options(const std::string& source, const std::vector<std::string>& lidars,
                                             bool configure, const std::optional<std::string>& discovery_address,
                                             double wait, double duration, double idle_exit, std::size_t queue,
                                             std::size_t reorder) {
  LiveSourceOptions o;
  live::LivoxConnectionOptions& c = o.connection;
  try {
    c.source = live::parse_livox_source_url(source);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  o.source_text = source;
  for (const std::string& l : lidars) {
    if (l.empty()) throw py::value_error("lidar: expected a serial number or an IPv4 address");
  }
  c.lidars = lidars;
  c.configure = configure;
  if (c.source.protocol == live::LivoxProtocol::sdk1 && configure)
    throw py::value_error("configure: an SDK2 option (SDK1 always handshakes)");
  if (discovery_address) {
    c.discovery_address = live::parse_address(*discovery_address);
    if (!c.discovery_address)
      throw py::value_error("discovery_address: expected a dotted IPv4 address (e.g. 192.168.1.50), got '" +
                            *discovery_address + "'");
  }
  auto positive = [](const char* name, double s, bool zero_ok) {
    if (!std::isfinite(s) || s < 0.0 || (!zero_ok && s == 0.0) || s > 1e9)
      throw py::value_error(std::string(name) + ": expected " + (zero_ok ? "None or " : "") + "seconds > 0, got " +
                            std::to_string(s));
    return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
  };
  c.wait = positive("wait", wait, false);
  o.duration = positive("duration", duration, true);
  o.idle_exit = positive("idle_exit", idle_exit, true);
  if (queue < 2 || queue > (1u << 20)) throw py::value_error("queue: expected 2 to 1048576 packets, got " + std::to_string(queue));
  if (reorder > 1024) throw py::value_error("reorder: expected 0 to 1024 packets, got " + std::to_string(reorder));
  c.queue_packets = queue;
  o.reorder_packets = reorder;
  return o;
}

class LiveRun {
 public:
  /// `args`: policy arguments with --rate; parsed before connecting, so a
  /// bad option raises ValueError without touching the network. `tracks`:
  /// each retrieval also carries the tracker's tracks (as Clusterer's).
  LiveRun(const std::vector<std::string>& args, LiveSourceOptions source, bool tracks = false)
      : options_(parse_python_options(args)), tracks_(tracks) {
    if (tracks_ && options_.mode == cli::Mode::frame)
      throw py::value_error("tracks: tracking follows the continuous engine's components; not with mode=\"frame\"");
    // Poses count from the time origin and ground estimates need the first
    // window: those runs are set up when the first points come.
    if (options_.poses_path.empty() && !needs_first_window(options_)) {
      resolve_setup(options_, nullptr);
      run_.emplace(options_, tracks_);
    }
    py::gil_scoped_release release;
    source_ = std::make_unique<LiveSource>(source);
  }

  ~LiveRun() {
    if (source_) source_->close();
  }
  LiveRun(const LiveRun&) = delete;
  LiveRun& operator=(const LiveRun&) = delete;

  /// The next retrieval as a tuple (cycle, time, index, labels, components,
  /// xyz, t, intensity, new_xyz, new_t, new_intensity, counters, tracks
  /// (None without tracking)), or None
  /// when the stream ended. GIL held on entry.
  py::object next() {
    const std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock()) throw std::runtime_error("live: next() is already running in another thread");
    while (ready_.empty()) {
      if (done_) return py::none();
      {
        py::gil_scoped_release release;
        step();
      }
      if (!source_->started() && !done_ && source_->elapsed() > source_->options().connection.wait) {
        const live::LiveCounters counters = source_->counters();
        const bool sdk2 = source_->options().connection.source.protocol == live::LivoxProtocol::sdk2;
        throw LiveTimeout("live: no " + std::string(sdk2 ? "SDK2" : "SDK1") + " point packet on UDP " +
                          source_->endpoint() + " within " + seconds_text(source_->options().connection.wait) + " s (" +
                          std::to_string(counters.foreign) + " datagrams from other addresses" +
                          (sdk2 && !source_->options().connection.configure ? "; is the LiDAR's destination this host? try configure=True" : "") +
                          ")");
      }
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
    py::object r = ready_.front();
    ready_.pop_front();
    return r;
  }

  /// Stops the receiver and the LiDAR; later `next` calls return None.
  void close() {
    {
      py::gil_scoped_release release;  // the mutex before the GIL (next() may hold it while it waits)
      const std::lock_guard<std::mutex> lock(mutex_);
      source_->close();
      done_ = true;
    }
    ready_.clear();  // retrievals not taken (the GIL again)
  }

  /// The connection's counters now (see docs/python.md, "Live sources").
  py::dict counters() {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(mutex_);
    py::gil_scoped_acquire acquire;
    return counters_dict();
  }

  /// Whole seconds of the host clock the times count from; None before the first packet.
  py::object time_origin() {
    std::optional<std::int64_t> origin;
    {
      py::gil_scoped_release release;
      const std::lock_guard<std::mutex> lock(mutex_);
      origin = origin_s_;
    }
    if (!origin) return py::none();
    return py::int_(*origin);
  }

 private:
  // One slice: up to 50 ms of waiting for returns, then the cycles they
  // make due. GIL released.
  void step() {
    returns_.clear();
    source_->pull(returns_, std::chrono::steady_clock::now() + std::chrono::milliseconds(50));
    if (!returns_.empty()) append(returns_);
    const bool ended = source_->end() != LiveSourceEnd::running;
    if (source_->end() == LiveSourceEnd::receiver_failed) {
      done_ = true;
      throw live::ConnectionError("live: the receiver failed: " + source_->failure());
    }
    if (ended && source_->end() == LiveSourceEnd::closed) {
      done_ = true;
      return;
    }
    feed(ended);
    if (ended) {
      if (run_) run_->finish([this](auto&&... a) { on_cycle(a...); });
      done_ = true;
    }
  }

  void append(const std::vector<live::LivoxReturn>& returns) {
    if (!origin_s_) {
      origin_s_ = static_cast<std::int64_t>(returns.front().time_ns / 1'000'000'000u);
      options_.read.time_origin = io::TimeOrigin{*origin_s_};
    }
    const std::int64_t origin_ns = *origin_s_ * 1'000'000'000;
    for (const live::LivoxReturn& r : returns) {
      xyz_.insert(xyz_.end(), {r.x, r.y, r.z});
      t_.push_back(static_cast<double>(static_cast<std::int64_t>(r.time_ns) - origin_ns) * 1e-9);
      intensity_.push_back(static_cast<float>(r.reflectivity));
    }
  }

  // The points [first, last) of the store (global stream indices) as buffers.
  PointBuffers buffers(std::uint64_t first, std::uint64_t last) const {
    PointBuffers b;
    const std::size_t at = static_cast<std::size_t>(first - base_);
    b.xyz32 = xyz_.data() + 3 * at;
    b.t = t_.data() + at;
    b.intensity32 = intensity_.data() + at;
    b.size = static_cast<std::size_t>(last - first);
    return b;
  }
  std::uint64_t stored_end() const { return base_ + t_.size(); }

  // Hands the stored points not yet fed to the engine; first sets the run
  // up (after the first window when the ground estimate needs it).
  void feed(bool ended) {
    if (!run_) {
      if (t_.empty()) return;
      if (needs_first_window(options_)) {
        const bool window_complete = options_.window_is_count ? t_.size() > options_.window_count
                                                              : t_.back() - t_.front() >= options_.window_seconds;
        if (!window_complete && !ended && t_.size() < 400000) return;
        std::vector<double> times;
        const std::vector<Eigen::Vector3f> first = first_window_of(options_, buffers(base_, stored_end()), &times);
        resolve_setup(options_, &first, &times);
      } else {
        resolve_setup(options_, nullptr);
      }
      run_.emplace(options_, tracks_);
    }
    if (fed_ == stored_end()) return;
    run_->feed(buffers(fed_, stored_end()), [this](auto&&... a) { on_cycle(a...); });
    fed_ = stored_end();
    // Forget what no later retrieval shows: before the window's first row
    // and before the points not yet handed out.
    if (keep_from_ > base_ + 65536) {
      const std::size_t drop = static_cast<std::size_t>(keep_from_ - base_);
      xyz_.erase(xyz_.begin(), xyz_.begin() + static_cast<std::ptrdiff_t>(3 * drop));
      t_.erase(t_.begin(), t_.begin() + static_cast<std::ptrdiff_t>(drop));
      intensity_.erase(intensity_.begin(), intensity_.begin() + static_cast<std::ptrdiff_t>(drop));
      base_ = keep_from_;
    }
  }

  // A cycle of the schedule: the retrieval with its points, queued for
  // next(). Called with the GIL released; takes it.
  void on_cycle(std::uint64_t cycle, double time, const WindowRows& rows, const Clustering& result,
                const std::vector<tracking::Track>* tracks) {
    const std::uint64_t offered = run_->offered();
    if (!rows.index.empty() && static_cast<std::uint64_t>(rows.index.front()) < base_)
      throw std::logic_error("live: a window row before the kept points");
    py::gil_scoped_acquire acquire;
    const py::tuple retrieval = retrieval_tuple(cycle, time, rows, result);
    const auto m = static_cast<py::ssize_t>(rows.index.size());
    py::array_t<float> xyz({m, py::ssize_t{3}}), intensity(m);
    py::array_t<double> t(m);
    float* px = xyz.mutable_data();
    float* pi = intensity.mutable_data();
    double* pt = t.mutable_data();
    for (std::size_t k = 0; k < rows.index.size(); ++k) {
      const std::size_t at = static_cast<std::size_t>(static_cast<std::uint64_t>(rows.index[k]) - base_);
      std::memcpy(px + 3 * k, xyz_.data() + 3 * at, 3 * sizeof(float));
      pt[k] = t_[at];
      pi[k] = intensity_[at];
    }
    const PointBuffers fresh = buffers(new_from_, offered);
    const auto n = static_cast<py::ssize_t>(fresh.size);
    py::array_t<float> new_xyz({n, py::ssize_t{3}}), new_intensity(n);
    py::array_t<double> new_t(n);
    if (n > 0) {
      std::memcpy(new_xyz.mutable_data(), fresh.xyz32, 3 * fresh.size * sizeof(float));
      std::memcpy(new_t.mutable_data(), fresh.t, fresh.size * sizeof(double));
      std::memcpy(new_intensity.mutable_data(), fresh.intensity32, fresh.size * sizeof(float));
    }
    ready_.push_back(py::make_tuple(retrieval[0], retrieval[1], retrieval[2], retrieval[3], retrieval[4], xyz, t,
                                    intensity, new_xyz, new_t, new_intensity, counters_dict(),
                                    tracks ? py::object(tracks_array(*tracks)) : py::none()));
    new_from_ = offered;
    keep_from_ = rows.index.empty() ? offered : std::min<std::uint64_t>(offered, static_cast<std::uint64_t>(rows.index.front()));
  }

  // GIL held.
  py::dict counters_dict() const {
    const live::LivoxStreamCounters& sc = source_->stream().counters();
    py::dict d;
    d["lidar"] = source_->lidar_name();
    live::for_each_counter(source_->counters(), [&d](const char* name, std::uint64_t value) { d[name] = value; });
    if (!d.contains("kernel_drops")) d["kernel_drops"] = py::none();  // the OS does not say
    d["clock_epochs"] = sc.epochs;
    d["time_sync"] = live::describe(source_->stream().clock().sync());
    d["end"] = describe(source_->end());
    return d;
  }

  static std::string seconds_text(std::chrono::steady_clock::duration d) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", std::chrono::duration<double>(d).count());
    return text;
  }

  cli::ClusterOptions options_;
  bool tracks_ = false;  ///< retrievals carry the tracker's tracks
  std::optional<ScheduledRun> run_;
  std::unique_ptr<LiveSource> source_;
  std::mutex mutex_;
  bool done_ = false;
  std::deque<py::object> ready_;  // retrievals not yet returned (touched with the GIL only)
  std::vector<live::LivoxReturn> returns_;
  std::optional<std::int64_t> origin_s_;
  // The points from stream index base_ on: xyz (3 floats a point), t [s], intensity.
  std::vector<float> xyz_, intensity_;
  std::vector<double> t_;
  std::uint64_t base_ = 0, fed_ = 0, new_from_ = 0, keep_from_ = 0;
};

}  // namespace streamclust::python
