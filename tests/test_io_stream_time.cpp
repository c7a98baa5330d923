// SPDX-License-Identifier: MIT
// Stream times at epoch scale: the whole-second origin, the exact shift of
// decimal text and integers, the formatting of absolute times, and the
// readers and writers that use them.

#include <doctest/doctest.h>

#include <streamclust/io/reader.hpp>
#include <streamclust/io/stream_time.hpp>
#include <streamclust/io/time_decoder.hpp>
#include <streamclust/io/tum.hpp>
#include <streamclust/io/writers.hpp>

#include "support/temp_dir.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace io = streamclust::io;
namespace fs = std::filesystem;

namespace {

constexpr std::int64_t kEpoch = 1700000000;  // [s] 2023-11-14

std::string shifted(std::string_view s, std::int64_t shift) {
  char out[io::detail::shifted_decimal_capacity];
  const std::size_t n = io::detail::shift_decimal(s, shift, out);
  return std::string(out, n);
}

std::string shortest(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

double parse(std::string_view s) {
  double v = 0;
  std::from_chars(s.data(), s.data() + s.size(), v);
  return v;
}

std::vector<io::Record> read_with_origin(const std::string& path, const io::ReadOptions& options = {},
                                  io::TimeOrigin* origin = nullptr) {
  auto reader = io::open_reader(path, options);
  std::vector<io::Record> out;
  while (reader->read(out, 1000) > 0) {
  }
  if (origin) *origin = reader->time_origin();
  return out;
}

/// Times of a 240 kHz stream with some irregular ones (many decimals).
std::vector<double> stream_times(std::size_t n) {
  std::vector<double> t;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(0.0, 1e-6);
  for (std::size_t i = 0; i < n; ++i) t.push_back(static_cast<double>(i) / 240000.0 + (i % 7 == 3 ? jitter(rng) : 0.0));
  return t;
}

}  // namespace

TEST_CASE("shift_decimal: decimal text minus whole seconds, exactly, in every notation") {
  CHECK(shifted("1700000003.25", kEpoch) == "3.25");
  CHECK(shifted("+1700000003.25", kEpoch) == "3.25");
  CHECK(shifted("1700000000", kEpoch) == "0");
  CHECK(shifted("1700000000.000000001", kEpoch) == "0.000000001");
  CHECK(shifted("1.7000000005e9", kEpoch) == "0.5");
  CHECK(shifted("17000000031234E-4", kEpoch) == "3.1234");
  CHECK(shifted("0.0170000000312e11", kEpoch) == "3.12");
  CHECK(shifted("1700000003.", kEpoch) == "3");
  CHECK(shifted("-2.5", 3) == "-5.5");  // a value below a positive origin keeps its sign
  CHECK(shifted(".5", 0) == "0.5");
  CHECK(shifted("1700000000123456789", 1700000000000000000) == "123456789");  // nanoseconds
  // Not shifted (callers fall back to floating point): below the origin, not a plain number, too large.
  CHECK(shifted("1699999999.9", kEpoch).empty());
  CHECK(shifted("nan", 0).empty());
  CHECK(shifted("inf", 0).empty());
  CHECK(shifted("0x1p3", 0).empty());
  CHECK(shifted("1e", 0).empty());
  CHECK(shifted(".", 0).empty());
  CHECK(shifted("", 0).empty());
  CHECK(shifted("1.5x", 0).empty());
  CHECK(shifted("1e300", 0).empty());
  CHECK(shifted("99999999999999999999", 0).empty());
  CHECK(shifted("1e-999999999", 0).empty());
}

TEST_CASE("origin_of: the whole seconds of the first time, for finite times within the int64 nanosecond range") {
  CHECK(io::origin_of(0.3) == io::TimeOrigin{0});
  CHECK(io::origin_of(1700000000.75) == io::TimeOrigin{kEpoch});
  CHECK(io::origin_of(-0.5) == io::TimeOrigin{-1});
  CHECK_FALSE(io::origin_of(std::numeric_limits<double>::quiet_NaN()));
  CHECK_FALSE(io::origin_of(1e300));
  CHECK_FALSE(io::origin_of(-1e10));
}

TEST_CASE("TimeDecoder: a stream and its copy shifted by whole seconds decode to the same doubles") {
  const std::vector<double> times = stream_times(5000);
  io::TimeDecoder zero, epoch;
  for (const double t : times) {
    const std::string z = shortest(t);
    std::string e;
    io::append_time(e, io::TimeOrigin{kEpoch}, t);
    const double a = zero.from_text(z, parse(z));
    const double b = epoch.from_text(e, parse(e));
    REQUIRE(a == t);  // origin zero: the text's own value
    REQUIRE(b == t);  // shifted exactly, though parse(e) resolves only 0.24 us
  }
  CHECK(zero.origin() == io::TimeOrigin{0});
  CHECK(epoch.origin() == io::TimeOrigin{kEpoch});
  CHECK(epoch.origin_found());

  // Integer nanoseconds, as a ROS stamp or a uint64 field holds them.
  io::TimeDecoder ns_zero(io::TimeUnit::ns), ns_epoch(io::TimeUnit::ns);
  for (std::uint64_t k = 0; k < 3000; ++k) {
    const std::uint64_t offset = k * 4167 + (k % 5);
    REQUIRE(ns_epoch.from_unsigned(static_cast<std::uint64_t>(kEpoch) * 1000000000u + offset) ==
            ns_zero.from_unsigned(offset));
  }
  CHECK(ns_epoch.origin() == io::TimeOrigin{kEpoch});

  // Integer nanoseconds decode to the same double as their decimal text in
  // seconds (a recording and its CSV export): 150000000 ns is 0.15, not the
  // 0.15000000000000002 that 150000000 x 1e-9 gives.
  io::TimeDecoder from_ns(io::TimeUnit::ns), from_text;
  for (std::uint64_t k = 0; k < 20000; ++k) {
    const std::uint64_t ns = k * 5000;  // a 200 kHz stream's 5 us grid
    const std::string text = std::to_string(ns / 1000000000u) + "." + std::string(9 - std::to_string(ns % 1000000000u).size(), '0') +
                             std::to_string(ns % 1000000000u);
    REQUIRE(from_ns.from_unsigned(ns) == from_text.from_text(text, parse(text)));
  }

  // A double at epoch scale keeps what it has (0.24 us): no worse than that.
  io::TimeDecoder real;
  const double first = real.from_real(1700000000.0);
  const double later = real.from_real(1700000000.1);
  CHECK(first == 0.0);
  CHECK(later == doctest::Approx(0.1).epsilon(3e-6));
}

TEST_CASE("TimeDecoder: a given origin is kept; non-finite values do not set one") {
  io::TimeDecoder fixed(io::TimeUnit::s, io::TimeOrigin{kEpoch - 10});
  CHECK(fixed.origin_found());
  CHECK(fixed.from_text("1700000000.5", 1700000000.5) == 10.5);
  io::TimeDecoder found;
  CHECK(std::isnan(found.from_real(std::numeric_limits<double>::quiet_NaN())));
  CHECK_FALSE(found.origin_found());
  CHECK(found.from_text("1e300", 1e300) == 1e300);  // absurd: no origin, the value as it is
  CHECK_FALSE(found.origin_found());
  CHECK(found.from_text("1700000002.25", 1700000002.25) == 0.25);
  CHECK(found.origin() == io::TimeOrigin{1700000002});
  CHECK(found.from_text("1700000001.75", 1700000001.75) == -0.25);  // below the origin: floating point, sign kept
}

TEST_CASE("format_time: origin + t with nanoseconds, composed exactly") {
  CHECK(io::format_time({}, 0.15) == "0.150000000");
  CHECK(io::format_time(io::TimeOrigin{kEpoch}, 0.15) == "1700000000.150000000");
  CHECK(io::format_time(io::TimeOrigin{kEpoch}, 1234.000000001) == "1700001234.000000001");
  CHECK(io::format_time({}, -0.25) == "-0.250000000");
  CHECK(io::format_time(io::TimeOrigin{1}, -1.5) == "-0.500000000");
  CHECK(io::format_time({}, std::numeric_limits<double>::quiet_NaN()) == "nan");
  CHECK(io::format_time({}, -std::numeric_limits<double>::infinity()) == "-inf");
  CHECK(std::stod(io::format_time({}, 1e300)) == 1e300);  // beyond the integer range: still the number
  // The same t at two origins: the texts differ exactly by the origin.
  for (const double t : stream_times(2000)) {
    const std::string a = io::format_time({}, t), b = io::format_time(io::TimeOrigin{kEpoch}, t);
    REQUIRE(a.substr(a.find('.')) == b.substr(b.find('.')));
    REQUIRE(std::stoll(b.substr(0, b.find('.'))) - std::stoll(a.substr(0, a.find('.'))) == kEpoch);
  }
}

TEST_CASE("readers: epoch times in CSV, PCD and PLY read as the same stream shifted to zero") {
  const streamclust::test::TempDir tmp("io", "epoch");
  const std::vector<double> times = stream_times(3000);
  std::vector<io::Record> records;
  for (std::size_t i = 0; i < times.size(); ++i) {
    records.push_back(io::Record{static_cast<float>(i % 17), 1.0f, 2.0f, 3.0f, times[i], static_cast<std::int64_t>(i)});
  }
  SUBCASE("text formats: exact") {
    for (const char* name : {"s.csv", "s.pcd", "s.ply"}) {
      const std::string zero = tmp.path(std::string("zero_") + name), epoch = tmp.path(std::string("epoch_") + name);
      const std::string ext = std::string(name).substr(2);
      if (ext == "csv") {
        io::write_csv_points(zero, records, {});
        io::write_csv_points(epoch, records, {}, io::TimeOrigin{kEpoch});
      } else if (ext == "pcd") {
        io::write_pcd(zero, records, {}, "ascii");
        io::write_pcd(epoch, records, {}, "ascii", io::TimeOrigin{kEpoch});
      } else {
        io::write_ply(zero, records, {}, false);
        io::write_ply(epoch, records, {}, false, io::TimeOrigin{kEpoch});
      }
      io::TimeOrigin origin_zero, origin_epoch;
      const auto a = read_with_origin(zero, {}, &origin_zero);
      const auto b = read_with_origin(epoch, {}, &origin_epoch);
      INFO(name);
      CHECK(origin_zero == io::TimeOrigin{0});
      CHECK(origin_epoch == io::TimeOrigin{kEpoch});
      REQUIRE(a.size() == records.size());
      REQUIRE(b.size() == records.size());
      std::size_t differ = 0;
      for (std::size_t i = 0; i < records.size(); ++i) differ += a[i].t != records[i].t || b[i].t != records[i].t;
      CHECK(differ == 0);
      // Without the origin the epoch text would have rounded to 0.24 us steps.
      std::size_t rounded = 0;
      for (std::size_t i = 0; i < records.size(); ++i) {
        rounded += (parse(io::format_time(io::TimeOrigin{kEpoch}, records[i].t)) - static_cast<double>(kEpoch)) !=
                   records[i].t;
      }
      CHECK(rounded > 0);
    }
  }
  SUBCASE("binary formats: a double, 0.24 us at epoch scale") {
    for (const char* name : {"b.pcd", "b.ply", "c.pcd"}) {
      const std::string path = tmp.path(name);
      if (std::string(name) == "b.pcd") io::write_pcd(path, records, {}, "binary", io::TimeOrigin{kEpoch});
      if (std::string(name) == "c.pcd") io::write_pcd(path, records, {}, "binary_compressed", io::TimeOrigin{kEpoch});
      if (std::string(name) == "b.ply") io::write_ply(path, records, {}, true, io::TimeOrigin{kEpoch});
      io::TimeOrigin origin;
      const auto back = read_with_origin(path, {}, &origin);
      INFO(name);
      CHECK(origin == io::TimeOrigin{kEpoch});
      REQUIRE(back.size() == records.size());
      double worst = 0.0;
      for (std::size_t i = 0; i < records.size(); ++i) worst = std::max(worst, std::fabs(back[i].t - records[i].t));
      CHECK(worst <= 1.2e-7);
    }
  }
  SUBCASE("integer nanoseconds in a PCD field: exact") {
    const std::string zero = tmp.path("ns0.pcd"), epoch = tmp.path("ns.pcd");
    for (const auto& [path, base] : {std::pair{zero, std::uint64_t{0}}, std::pair{epoch, std::uint64_t{kEpoch} * 1000000000u}}) {
      std::ofstream f(path, std::ios::binary);
      f << "VERSION 0.7\nFIELDS x y z timestamp\nSIZE 4 4 4 8\nTYPE F F F U\nCOUNT 1 1 1 1\nWIDTH 1000\nHEIGHT 1\n"
           "POINTS 1000\nDATA binary\n";
      for (std::uint64_t i = 0; i < 1000; ++i) {
        const float p[3] = {1.0f, 2.0f, 3.0f};
        const std::uint64_t ns = base + i * 4167;
        f.write(reinterpret_cast<const char*>(p), sizeof p);
        f.write(reinterpret_cast<const char*>(&ns), sizeof ns);
      }
    }
    io::ReadOptions ns;
    ns.time_unit = io::TimeUnit::ns;
    io::TimeOrigin origin;
    const auto a = read_with_origin(zero, ns), b = read_with_origin(epoch, ns, &origin);
    CHECK(origin == io::TimeOrigin{kEpoch});
    REQUIRE(a.size() == b.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.size(); ++i) differ += a[i].t != b[i].t;
    CHECK(differ == 0);
    CHECK(b[999].t == doctest::Approx(999 * 4167e-9));
  }
  SUBCASE("a given origin applies; find_time_origin finds the reader's") {
    const std::string epoch = tmp.path("given.csv");
    io::write_csv_points(epoch, records, {}, io::TimeOrigin{kEpoch});
    CHECK(io::find_time_origin(epoch) == io::TimeOrigin{kEpoch});
    io::ReadOptions options;
    options.time_origin = io::TimeOrigin{kEpoch - 100};
    const auto back = read_with_origin(epoch, options);
    CHECK(back.front().t == 100.0);
    CHECK(back.back().t == doctest::Approx(100.0 + times.back()));
  }
}

TEST_CASE("read_tum with the stream's origin: epoch poses shift exactly") {
  std::vector<io::TumRecord> poses;
  for (int i = 0; i < 400; ++i) poses.push_back(io::TumRecord{i / 200.0 + (i % 3) * 1e-7, 0.1 * i, 0, 0, 0, 0, 0, 1});
  std::stringstream zero, epoch;
  io::write_tum(zero, poses);
  io::write_tum(epoch, poses, io::TimeOrigin{kEpoch});
  CHECK(epoch.str().find("\n1700000000.000000000 ") != std::string::npos);
  const auto a = io::read_tum(zero, "zero.tum");
  const auto b = io::read_tum(epoch, "epoch.tum", io::TimeOrigin{kEpoch});
  REQUIRE(a.size() == b.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differ += a[i].t != b[i].t;
  CHECK(differ == 0);
}
