// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Replays a real Livox firing-order direction table (the files of
/// ../shared/data/livox/patterns, layouts in that folder's README).

#include <streamclust/sensors.hpp>
#include <streamclust/sim/ray.hpp>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace streamclust::sim {

/// A sensor model that replays a recorded direction table in order.
///
/// Slot i of the stream is table row `i mod rows` at time `i / point_rate`:
/// after the table's end it repeats from the first row while time keeps
/// increasing. The laser index is `i mod lasers`.
///
/// Layouts (little-endian, no header):
/// - `Layout::mid360_u16`: uint16 pairs, azimuth_deg = v0 / 100 (0..359.99),
///   elevation_deg = v1 / 100 - 10 (`mid360_u16le.bin`, 200 kHz, 4 lasers).
/// - `Layout::risley_f32`: float32 pairs, azimuth and elevation [rad]
///   (`mid40_f32le.bin`, `mid70_f32le.bin`, 100 kHz, 1 laser).
/// Direction: (cos el cos az, cos el sin az, sin el), x forward, y left, z up.
///
/// Construction reads the whole file: O(rows) time, 12 bytes per row.
/// Throws std::invalid_argument for bad Params, std::runtime_error naming the
/// file (and the byte offset) when it cannot be opened, is empty, has a
/// trailing partial record or holds an out-of-range value. `next()` is O(1)
/// and allocates nothing. Deterministic. Not thread-safe (one replay per
/// thread); copies share nothing.
///
/// \code
/// auto mid360 = streamclust::sim::TableReplay::mid360("../shared/data/livox/patterns/mid360_u16le.bin");
/// auto mid70 = streamclust::sim::TableReplay::risley_f32("../shared/data/livox/patterns/mid70_f32le.bin");
/// const streamclust::sim::Ray r = mid360.next();
/// \endcode
class TableReplay {
 public:
  enum class Layout { mid360_u16, risley_f32 };

  struct Params {
    std::string path;                   ///< the table file
    Layout layout = Layout::mid360_u16;  ///< record layout
    double point_rate = livox_mid360.point_rate_hz;  ///< rows per second [Hz], > 0
    int lasers = livox_mid360.lasers;  ///< lasers interleaved in the table (slot i -> laser i mod lasers), >= 1
  };

  /// Loads the table. See the class comment for what throws.
  explicit TableReplay(const Params& params) : params_(params) {
    if (params.path.empty()) fail("path", "\"\"", "a file name");
    if (!(std::isfinite(params.point_rate) && params.point_rate > 0.0))
      fail("point_rate", std::to_string(params.point_rate), "(0, inf) [Hz]");
    if (params.lasers < 1) fail("lasers", std::to_string(params.lasers), "[1, inf)");
    load();
  }

  /// The official Mid-360 table (`mid360_u16le.bin`): 200 kHz, 4 lasers.
  static TableReplay mid360(const std::string& path) {
    return TableReplay(Params{path, Layout::mid360_u16, livox_mid360.point_rate_hz, livox_mid360.lasers});
  }

  /// A Mid-40 / Mid-70 table (`mid40_f32le.bin`, `mid70_f32le.bin`): one laser.
  static TableReplay risley_f32(const std::string& path, double point_rate = livox_mid40.point_rate_hz) {
    return TableReplay(Params{path, Layout::risley_f32, point_rate, 1});
  }

  /// The next row (cycling), time `i / point_rate`.
  Ray next() {
    const std::size_t row = static_cast<std::size_t>(index_ % dirs_.size());
    Ray r;
    r.direction = dirs_[row];
    r.time = static_cast<double>(index_) / params_.point_rate;
    r.laser = static_cast<int>(index_ % static_cast<std::uint64_t>(params_.lasers));
    ++index_;
    return r;
  }

  /// Rows per second [Hz].
  double point_rate() const { return params_.point_rate; }

  /// Rows in the table (one period of the replay).
  std::size_t rows() const { return dirs_.size(); }

  /// Duration of one period of the table [s].
  double period() const { return static_cast<double>(dirs_.size()) / params_.point_rate; }

  const Params& params() const { return params_; }

 private:
  [[noreturn]] static void fail(const char* name, const std::string& value, const char* range) {
    std::string m = "TableReplay::Params::";
    m.append(name).append(" = ").append(value).append(" is out of range ").append(range);
    throw std::invalid_argument(m);
  }

  [[noreturn]] void bad_file(const std::string& what, std::uint64_t offset) const {
    std::string m = "TableReplay: ";
    m.append(params_.path).append(": ").append(what).append(" at byte offset ").append(std::to_string(offset));
    throw std::runtime_error(m);
  }

  [[noreturn]] void bad_value(const char* what, unsigned value, const char* range, std::uint64_t offset) const {
    std::string m = what;
    m.append(std::to_string(value)).append(range);
    bad_file(m, offset);
  }

  void load() {
    std::ifstream in(params_.path, std::ios::binary);
    if (!in) {
      std::string m = "TableReplay: cannot open ";
      m.append(params_.path);
      throw std::runtime_error(m);
    }
    std::vector<unsigned char> bytes;
    {
      in.seekg(0, std::ios::end);
      const std::streamoff size = in.tellg();
      in.seekg(0, std::ios::beg);
      if (size < 0) bad_file("cannot determine the file size", 0);
      bytes.resize(static_cast<std::size_t>(size));
      if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size))
        bad_file("read error", static_cast<std::uint64_t>(in.gcount()));
    }
    const std::size_t record = params_.layout == Layout::mid360_u16 ? 4 : 8;
    if (bytes.empty()) bad_file("empty table: expected a record", 0);
    if (bytes.size() % record != 0) {
      std::string what = "short file: a partial ";
      what.append(std::to_string(bytes.size() % record))
          .append("-byte record (records are ")
          .append(std::to_string(record))
          .append(" bytes)");
      bad_file(what, bytes.size() - bytes.size() % record);
    }
    const std::size_t n = bytes.size() / record;
    dirs_.resize(n);
    constexpr double kPi = 3.14159265358979323846;
    for (std::size_t i = 0; i < n; ++i) {
      const unsigned char* p = bytes.data() + i * record;
      double az = 0.0;
      double el = 0.0;
      if (params_.layout == Layout::mid360_u16) {
        const unsigned v0 = static_cast<unsigned>(p[0]) | (static_cast<unsigned>(p[1]) << 8);
        const unsigned v1 = static_cast<unsigned>(p[2]) | (static_cast<unsigned>(p[3]) << 8);
        if (v0 >= 36000u) bad_value("azimuth code ", v0, " (1/100 deg) outside 0..35999", i * record);
        if (v1 > 18000u) bad_value("elevation code ", v1, " outside 0..18000", i * record + 2);
        az = static_cast<double>(v0) / 100.0 * kPi / 180.0;
        el = (static_cast<double>(v1) / 100.0 - 10.0) * kPi / 180.0;
      } else {
        const float a = le_float(p);
        const float e = le_float(p + 4);
        if (!std::isfinite(a) || std::fabs(a) > 7.0f) bad_file("azimuth is not a finite angle in radians", i * record);
        if (!std::isfinite(e) || std::fabs(e) > 1.6f)
          bad_file("elevation is not a finite angle in [-pi/2, pi/2] radians", i * record + 4);
        az = static_cast<double>(a);
        el = static_cast<double>(e);
      }
      const double ce = std::cos(el);
      Eigen::Vector3d d(ce * std::cos(az), ce * std::sin(az), std::sin(el));
      dirs_[i] = d.normalized().cast<float>();
    }
  }

  static float le_float(const unsigned char* p) {
    const std::uint32_t u = static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
                            (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
    float f = 0.0f;
    std::memcpy(&f, &u, sizeof f);
    return f;
  }

  Params params_;
  std::vector<Eigen::Vector3f> dirs_;
  std::uint64_t index_ = 0;
};

}  // namespace streamclust::sim
