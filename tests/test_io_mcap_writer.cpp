// SPDX-License-Identifier: MIT
// The MCAP writer and the CDR writer: what they write reads back through the
// MCAP reader (every CRC checked), message for message and point for point,
// and the summary's indexes point at the records they name.

#include "support/bad_files.hpp"
#include "support/temp_dir.hpp"

#include <streamclust/io/cdr_writer.hpp>
#include <streamclust/io/mcap_reader.hpp>
#include <streamclust/io/mcap_writer.hpp>
#include <streamclust/io/reader.hpp>
#include <streamclust/io/ros/known_definitions.hpp>

#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace io = streamclust::io;
using streamclust::test::file_bytes;
using streamclust::test::TempDir;

namespace {

constexpr std::uint64_t kEpochNs = 1700000000ull * 1000000000ull;

/// A PointCloud2 (x, y, z float32, t uint32 ns) of `n` points for message `k`.
std::vector<std::uint8_t> cloud(int k, std::uint32_t n) {
  io::CdrWriter m;
  m.i32(1700000000 + k / 10);
  m.u32(static_cast<std::uint32_t>(k % 10) * 100000000u);
  m.string("lidar");
  m.u32(1);
  m.u32(n);
  m.count(4);
  const char* names[] = {"x", "y", "z", "t"};
  for (std::uint32_t f = 0; f < 4; ++f) {
    m.string(names[f]);
    m.u32(4 * f);
    m.u8(f == 3 ? 6 : 7);
    m.u32(1);
  }
  m.boolean(false);
  m.u32(16);
  m.u32(16 * n);
  std::vector<std::uint8_t> data(16 * n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const float v[3] = {static_cast<float>(i), static_cast<float>(k), 0.5f};
    const std::uint32_t t = i * 1000u;
    std::memcpy(&data[16 * i], v, 12);
    std::memcpy(&data[16 * i + 12], &t, 4);
  }
  m.bytes(data.data(), data.size());
  m.boolean(true);
  return m.bytes();
}

std::uint64_t u64_at(const std::string& b, std::size_t at) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < 8; ++i) v |= std::uint64_t{static_cast<std::uint8_t>(b[at + i])} << (8 * i);
  return v;
}

}  // namespace

TEST_CASE("CdrWriter aligns from the encapsulation header, as the reader expects") {
  io::CdrWriter w;
  w.u8(1);
  w.u32(2);       // 3 pad bytes before it
  w.string("ab");  // length 3 with the NUL
  w.f64(1.5);     // 1 pad byte: aligned to 8 from byte 4
  const std::vector<std::uint8_t>& b = w.bytes();
  REQUIRE(b.size() == 4 + 1 + 3 + 4 + 4 + 3 + 1 + 8);
  CHECK(b[0] == 0x00);
  CHECK(b[1] == 0x01);
  CHECK(b[8] == 2);
  CHECK(b[12] == 3);
  CHECK(b[16] == 'a');
  double d = 0;
  std::memcpy(&d, &b[20], 8);
  CHECK(d == 1.5);
}

TEST_CASE("an MCAP written here reads back: messages, points, topics, counts, CRCs") {
  TempDir dir("mcap_writer", "round_trip");
  for (const bool compress : {true, false}) {
    INFO("compress " << compress);
    const std::string path = dir.path(compress ? "z.mcap" : "plain.mcap");
    std::vector<std::vector<std::uint8_t>> sent;
    {
      io::McapWriter w(path, {"ros2", compress, 8192});  // small chunks: many of them
      const std::string def = *io::ros::known_definition("sensor_msgs/msg/PointCloud2", io::ros::Encoding::cdr);
      const auto schema = w.add_schema("sensor_msgs/msg/PointCloud2", "ros2msg", def);
      const auto points = w.add_channel(schema, "/points", "cdr");
      const auto other = w.add_channel(schema, "/other", "cdr");
      for (int k = 0; k < 25; ++k) {
        sent.push_back(cloud(k, 200));
        w.write(points, kEpochNs + static_cast<std::uint64_t>(k) * 100000000u, sent.back().data(), sent.back().size());
        if (k % 5 == 0) {
          const auto small = cloud(k, 3);
          w.write(other, kEpochNs + static_cast<std::uint64_t>(k) * 100000000u, small.data(), small.size());
        }
      }
      CHECK(w.messages() == 30);
      w.close();
    }
    io::McapReader mcap(path);
    CHECK(mcap.has_summary());
    CHECK(mcap.profile() == "ros2");
    REQUIRE(mcap.topics().size() == 2);
    CHECK(mcap.topics()[0].name == "/points");
    CHECK(mcap.topics()[0].messages == std::uint64_t{25});
    CHECK(mcap.topics()[1].messages == std::uint64_t{5});
    std::size_t k = 0;
    io::RecordingMessage m;
    while (mcap.next(m)) {
      if (m.topic != 0) continue;
      REQUIRE(k < sent.size());
      CHECK(std::vector<std::uint8_t>(m.data, m.data + m.size) == sent[k]);
      CHECK(m.log_time_ns == kEpochNs + k * 100000000u);
      ++k;
    }
    CHECK(k == 25);
    io::ReadOptions o;
    o.topic = "/points";
    auto reader = io::open_reader(path, o);
    std::vector<io::Record> records;
    while (reader->read(records, 1000) > 0) {
    }
    REQUIRE(records.size() == 25 * 200);
    CHECK(records[201].x == 1.0f);
    CHECK(records[201].y == 1.0f);
    CHECK(records[201].t == doctest::Approx(0.1 + 1e-6).epsilon(1e-12));
  }
}

TEST_CASE("the summary's chunk indexes and offsets point at the records they name") {
  TempDir dir("mcap_writer", "indexes");
  const std::string path = dir.path("i.mcap");
  {
    io::McapWriter w(path, {"ros2", true, 4096});
    const auto schema = w.add_schema("sensor_msgs/msg/PointCloud2", "ros2msg",
                                     *io::ros::known_definition("sensor_msgs/msg/PointCloud2", io::ros::Encoding::cdr));
    const auto channel = w.add_channel(schema, "/points", "cdr");
    for (int k = 0; k < 12; ++k) {
      const auto c = cloud(k, 100);
      w.write(channel, kEpochNs + static_cast<std::uint64_t>(k), c.data(), c.size());
    }
  }  // the destructor closes
  const std::string b = file_bytes(path);
  const std::uint64_t summary_start = u64_at(b, b.size() - 8 - 20);
  const std::uint64_t offsets_start = u64_at(b, b.size() - 8 - 12);
  REQUIRE(summary_start > 0);
  REQUIRE(offsets_start > summary_start);
  std::size_t chunks = 0, groups = 0;
  for (std::size_t at = summary_start; at < b.size() - 8 - 29;) {
    const auto op = static_cast<std::uint8_t>(b[at]);
    const std::uint64_t length = u64_at(b, at + 1);
    const std::size_t c = at + 9;
    if (op == io::mcap::chunk_index) {
      ++chunks;
      const std::uint64_t chunk_at = u64_at(b, c + 16);
      CHECK(static_cast<std::uint8_t>(b[chunk_at]) == io::mcap::chunk);
      const std::uint64_t first_index = u64_at(b, c + 32 + 4 + 2);  // the map's first entry: u16 channel, u64 offset
      CHECK(static_cast<std::uint8_t>(b[first_index]) == io::mcap::message_index);
    }
    if (op == io::mcap::summary_offset) {
      ++groups;
      CHECK(at >= offsets_start);
      const std::uint64_t group_start = u64_at(b, c + 1);
      CHECK(static_cast<std::uint8_t>(b[group_start]) == static_cast<std::uint8_t>(b[c]));
    }
    at = c + length;
  }
  CHECK(chunks > 3);
  CHECK(groups == 4);  // schemas, channels, statistics, chunk indexes
}
