// SPDX-License-Identifier: MIT
// The recording readers (ROS 1 bags, rosbag2 SQLite, MCAP) on fixtures written
// by reference implementations (tests/data/recordings/README.md): points and
// times equal the source stream point for point; topic choice; and every kind
// of damage ends in an InputError that names the file and the place.

#include "support/bad_files.hpp"
#include "support/same_float.hpp"
#include "support/temp_dir.hpp"

#include <streamclust/io/mcap_reader.hpp>
#include <streamclust/io/reader.hpp>
#include <streamclust/io/ros/message_decoder.hpp>
#include <streamclust/io/ros1_bag_reader.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace io = streamclust::io;
using streamclust::test::expect_error;
using streamclust::test::file_bytes;
using streamclust::test::same_float;
using streamclust::test::TempDir;

namespace {

/// A file of tests/data/recordings.
std::string fixture(const std::string& name) {
  return (std::filesystem::path(__FILE__).parent_path() / "data" / "recordings" / name).string();
}

std::vector<io::Record> read_recording(const std::string& path, const io::ReadOptions& options = {}) {
  auto reader = io::open_reader(path, options);
  std::vector<io::Record> out;
  while (reader->read(out, 97) > 0) {
  }
  CHECK(reader->read(out, 97) == 0);  // the end stays the end
  return out;
}

/// The expected records: x,y,z,intensity and t in integer nanoseconds.
std::vector<io::Record> expected(const std::string& name) {
  io::ReadOptions o;
  o.time_unit = io::TimeUnit::ns;
  return read_recording(fixture(name), o);
}

void check_equal(const std::vector<io::Record>& got, const std::vector<io::Record>& want) {
  REQUIRE(got.size() == want.size());
  std::size_t bad = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    const io::Record& g = got[i];
    const io::Record& w = want[i];
    if (!(same_float(g.x, w.x) && same_float(g.y, w.y) && same_float(g.z, w.z) && g.intensity == w.intensity &&
          g.t == w.t)) {
      if (++bad <= 3) {
        INFO("record " << i << ": got " << g.x << " " << g.y << " " << g.z << " " << g.intensity << " t " << g.t
                       << ", expected " << w.x << " " << w.y << " " << w.z << " " << w.intensity << " t " << w.t);
        CHECK(false);
      }
    }
  }
  CHECK(bad == 0);
}

/// The InputError of reading all of `path` ("" when it reads cleanly).
std::string recording_error(const std::string& path, const io::ReadOptions& options = {}) {
  try {
    read_recording(path, options);
  } catch (const io::InputError& e) {
    CHECK(e.file().find(std::filesystem::path(path).filename().string()) != std::string::npos);
    return e.where() + ": " + e.what_expected();
  }
  return "";
}

std::uint64_t load_u64(const std::string& b, std::size_t at) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < 8; ++i) v |= std::uint64_t{static_cast<std::uint8_t>(b[at + i])} << (8 * i);
  return v;
}
void store_u32(std::string& b, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) b[at + i] = static_cast<char>((v >> (8 * i)) & 0xFF);
}
void store_u64(std::string& b, std::size_t at, std::uint64_t v) {
  for (std::size_t i = 0; i < 8; ++i) b[at + i] = static_cast<char>((v >> (8 * i)) & 0xFF);
}

/// The top-level records of MCAP bytes: offset and opcode.
std::vector<std::pair<std::size_t, int>> mcap_records(const std::string& b) {
  std::vector<std::pair<std::size_t, int>> r;
  std::size_t at = 8;
  while (at + 9 <= b.size() - 8) {
    const int op = static_cast<std::uint8_t>(b[at]);
    r.emplace_back(at, op);
    at += 9 + static_cast<std::size_t>(load_u64(b, at + 1));
  }
  return r;
}

std::size_t first_record(const std::string& b, int op) {
  for (const auto& [at, o] : mcap_records(b))
    if (o == op) return at;
  FAIL("no record with opcode " << op);
  return 0;
}

}  // namespace

TEST_CASE("each recording reads as its source stream, point for point") {
  struct Case {
    const char* file;
    const char* expected;
    io::Format format;
    const char* topic;
  };
  const Case cases[] = {
      {"ros1_custom.bag", "custom.expected.csv", io::Format::ros1_bag, nullptr},
      {"ros1_custom_bz2.bag", "custom.expected.csv", io::Format::ros1_bag, nullptr},
      {"ros1_custom_lz4.bag", "custom.expected.csv", io::Format::ros1_bag, nullptr},
      {"ros1_pc2_livox.bag", "pc2_livox.expected.csv", io::Format::ros1_bag, nullptr},
      {"ros1_pc2_two_topics.bag", "pc2_livox.expected.csv", io::Format::ros1_bag, "/lidar_front"},
      {"ros2_custom_lz4.mcap", "custom.expected.csv", io::Format::mcap, nullptr},
      {"ros2_custom_zstd.mcap", "custom.expected.csv", io::Format::mcap, nullptr},
      {"ros2_pc2_converter.mcap", "pc2_offset_u32.expected.csv", io::Format::mcap, nullptr},
      {"ros2_pc2_ouster.mcap", "pc2_ouster.expected.csv", io::Format::mcap, nullptr},
      {"ros2_pc2_velodyne.mcap", "pc2_velodyne.expected.csv", io::Format::mcap, nullptr},
      {"ros2_pc2_bigendian.mcap", "pc2_offset_u32.expected.csv", io::Format::mcap, nullptr},
      {"ros2_custom_db3", "custom.expected.csv", io::Format::rosbag2_sqlite, nullptr},
      {"ros2_custom_db3/ros2_custom_db3_0.db3", "custom.expected.csv", io::Format::rosbag2_sqlite, nullptr},
      {"ros2_pc2_old.db3", "pc2_livox.expected.csv", io::Format::rosbag2_sqlite, nullptr},
  };
  for (const Case& c : cases) {
    INFO(c.file);
    io::ReadOptions o;
    if (c.topic) o.topic = c.topic;
    CHECK(io::detect_format(fixture(c.file)) == c.format);
    auto reader = io::open_reader(fixture(c.file), o);
    CHECK(reader->info().format == c.format);
    CHECK(reader->info().has_time);
    check_equal(read_recording(fixture(c.file), o), expected(c.expected));
    // Times count from the same whole second as the source's.
    CHECK(io::find_time_origin(fixture(c.file), o).seconds == 1700000000);
  }
}

TEST_CASE("a recording's time field and fields are reported") {
  auto custom = io::open_reader(fixture("ros2_custom_lz4.mcap"));
  CHECK(custom->info().time_field == "offset_time");
  CHECK(custom->info().encoding == "cdr");
  auto livox = io::open_reader(fixture("ros1_pc2_livox.bag"));
  CHECK(livox->info().time_field == "timestamp");
  CHECK(livox->info().encoding == "ros1");
  CHECK(livox->info().fields == std::vector<std::string>{"x", "y", "z", "intensity", "tag", "line", "timestamp"});
  auto velodyne = io::open_reader(fixture("ros2_pc2_velodyne.mcap"));
  CHECK(velodyne->info().time_field == "time");
}

TEST_CASE("topic choice: the only point-cloud topic, --topic, or an error listing them") {
  const std::string two = fixture("ros1_pc2_two_topics.bag");
  const std::string e = recording_error(two);
  CHECK(e.rfind("topics: 2 point-cloud topics: /lidar_front (sensor_msgs/PointCloud2, 4 messages), /lidar_rear "
                "(sensor_msgs/PointCloud2, 4 messages); choose one (--topic NAME)",
                0) == 0);
  io::ReadOptions o;
  o.topic = "lidar_front";  // without the leading slash too
  CHECK(read_recording(two, o).size() == 480);
  o.topic = "/lidar_rear";
  CHECK(read_recording(two, o).size() == 48);
  o.topic = "/livox/imu";
  CHECK(recording_error(two, o).find("topic /livox/imu has type sensor_msgs/Imu, which holds no points") != std::string::npos);
  o.topic = "/nope";
  CHECK(recording_error(two, o).find("no topic /nope; topics: ") != std::string::npos);
  // Other topics (IMU) are skipped without a choice when one cloud topic exists.
  CHECK(read_recording(fixture("ros2_custom_lz4.mcap")).size() == 480);
}

TEST_CASE("a topic without a message definition is an input error") {
  const std::string path = fixture("ros2_no_schema.mcap");
  CHECK(recording_error(path).find("without a schema (message type and definition missing): /livox/lidar (no schema, 2 messages)") !=
        std::string::npos);
  io::ReadOptions o;
  o.topic = "/livox/lidar";
  CHECK(recording_error(path, o) ==
        "topic /livox/lidar: the recording has no schema for this topic: its message type and definition are missing");

  // A ROS 1 bag whose connections lost their message_definition field.
  TempDir dir("recordings", "no_definition");
  std::string b = file_bytes(fixture("ros1_custom.bag"));
  for (std::size_t at = 0; (at = b.find("message_definition=", at)) != std::string::npos;) b[at + 17] = 'X';
  CHECK(recording_error(dir.file("a.bag", b)) ==
        "topic /livox/lidar: the message definition of livox_ros_driver/CustomMsg is missing from the recording: "
        "expected it to decode the messages");
}

TEST_CASE("MCAP: wrong magic, truncation, CRCs, lengths, compression, channels") {
  TempDir dir("recordings", "mcap");
  const std::string good = file_bytes(fixture("ros2_custom_lz4.mcap"));

  std::string b = good;
  b[1] = 'X';
  CHECK(recording_error(dir.file("magic.mcap", b)) == "byte 0: not an MCAP file: expected the magic 89 4d 43 41 50 30 0d 0a");

  b = good.substr(0, good.size() - 3);
  CHECK(recording_error(dir.file("cut.mcap", b)) ==
        "byte " + std::to_string(b.size() - 8) +
            ": expected the closing MCAP magic: the file is truncated or was not closed (try `mcap recover`)");

  // The first chunk's uncompressed_crc.
  const std::size_t chunk = first_record(good, io::mcap::chunk);
  b = good;
  b[chunk + 9 + 24] = static_cast<char>(b[chunk + 9 + 24] ^ 0x01);
  CHECK(recording_error(dir.file("chunk_crc.mcap", b)).rfind("byte " + std::to_string(chunk) + " (chunk): chunk CRC mismatch", 0) == 0);

  // A byte of a Message Index record (never decoded): the data section CRC.
  b = good;
  const std::size_t index = first_record(good, io::mcap::message_index);
  b[index + 9 + 2] = static_cast<char>(b[index + 9 + 2] ^ 0x40);
  CHECK(recording_error(dir.file("data_crc.mcap", b)).find("data section CRC mismatch") != std::string::npos);

  // The summary section.
  b = good;
  const std::uint64_t summary = load_u64(good, good.size() - 8 - 20);
  b[summary + 12] = static_cast<char>(b[summary + 12] ^ 0x01);
  CHECK(recording_error(dir.file("summary_crc.mcap", b)).rfind("byte " + std::to_string(summary) + ": summary CRC mismatch", 0) == 0);

  // A record length running past the data section.
  b = good;
  store_u64(b, chunk + 1, std::uint64_t{1} << 40);
  CHECK(recording_error(dir.file("length.mcap", b)).rfind("byte " + std::to_string(chunk) + ": record (opcode 0x06) of 1099511627776 bytes runs past", 0) == 0);

  // A chunk whose uncompressed size lies: larger than the data gives.
  b = good;
  store_u64(b, chunk + 9 + 16, load_u64(good, chunk + 9 + 16) + 1000);
  CHECK(recording_error(dir.file("size.mcap", b)).find("chunk decompresses to") != std::string::npos);
  b = good;
  store_u64(b, chunk + 9 + 16, std::uint64_t{1} << 50);
  CHECK(recording_error(dir.file("huge.mcap", b)).find("expected at most 1073741824") != std::string::npos);

  // Unknown compression.
  b = good;
  const std::size_t lz4 = b.find("lz4", chunk);
  b[lz4 + 2] = 'z';
  CHECK(recording_error(dir.file("codec.mcap", b)).find("unknown chunk compression \"lzz\": expected \"\", \"lz4\" or \"zstd\"") !=
        std::string::npos);

  // Corrupt compressed data: the codec or the CRC catches it.
  b = good;
  b[lz4 + 3 + 8 + 40] = static_cast<char>(b[lz4 + 3 + 8 + 40] ^ 0x5A);
  const std::string corrupt = recording_error(dir.file("corrupt.mcap", b));
  CHECK((corrupt.find("corrupt lz4 data") != std::string::npos || corrupt.find("CRC mismatch") != std::string::npos ||
         corrupt.find("decompresses to") != std::string::npos));

  // A message on a channel no Channel record defined (unchunked file).
  const std::string plain = file_bytes(fixture("ros2_pc2_converter.mcap"));
  b = plain;
  const std::size_t message = first_record(plain, io::mcap::message);
  b[message + 9] = 99;
  CHECK(recording_error(dir.file("channel.mcap", b)) ==
        "byte " + std::to_string(message + 9) + ": message on channel 99, which no Channel record defined before it");
}

TEST_CASE("MCAP: a summary gives topics and counts; a file without one is scanned") {
  io::McapReader summarized(fixture("ros2_custom_lz4.mcap"));
  CHECK(summarized.has_summary());
  CHECK(summarized.profile() == "ros2");
  REQUIRE(summarized.topics().size() == 2);
  io::McapReader plain(fixture("ros2_pc2_converter.mcap"));
  CHECK_FALSE(plain.has_summary());
  const auto& topics = plain.topics();
  REQUIRE(topics.size() == 2);
  for (const auto* reader : {&summarized.topics(), &topics}) {
    for (const io::RecordingTopic& t : *reader) {
      if (t.name == "/livox/lidar") CHECK(t.messages == std::uint64_t{4});
      if (t.name == "/livox/imu") CHECK(t.messages == std::uint64_t{3});
    }
  }
  // The scan rewinds: every message is still read.
  std::size_t n = 0;
  io::RecordingMessage m;
  while (plain.next(m)) ++n;
  CHECK(n == 7);
  CHECK_FALSE(plain.next(m));
}

TEST_CASE("ROS 1 bags: magic, version, truncation, compression, chunk size, counts") {
  TempDir dir("recordings", "bag");
  const std::string good = file_bytes(fixture("ros1_custom.bag"));

  std::string b = good;
  b.replace(0, 13, "#ROSBAG V1.2\n");
  CHECK(recording_error(dir.file("v1.bag", b)) == "byte 0: ROS bag format 1.x: expected format 2.0 (convert it with `rosbag fix`)");
  b = good;
  b[2] = 'X';
  CHECK(recording_error(dir.file("magic.bag", b)) == "byte 0: not a ROS 1 bag: expected \"#ROSBAG V2.0\" and a newline");

  b = good.substr(0, good.size() - 10);
  CHECK(recording_error(dir.file("cut.bag", b)).find("truncated index record") != std::string::npos);
  b = good.substr(0, 5000);
  CHECK(recording_error(dir.file("short.bag", b)).find("index_pos") != std::string::npos);

  b = good;
  const std::size_t none = b.find("compression=none");
  b.replace(none + 12, 4, "nope");
  CHECK(recording_error(dir.file("codec.bag", b)).find("unknown chunk compression \"nope\": expected none, bz2 or lz4") !=
        std::string::npos);

  // The chunk's declared size.
  b = good;
  const std::size_t size = b.find("size=", none - 40) + 5;
  store_u32(b, size, 12);
  CHECK(recording_error(dir.file("size.bag", b)).find("its header says 12") != std::string::npos);

  // A lying point_num in the first CustomMsg (the chunk is uncompressed, so
  // the message is in the file verbatim; the decoder finds the field).
  io::Ros1BagReader bag(fixture("ros1_custom.bag"));
  io::RecordingMessage m;
  do {
    REQUIRE(bag.next(m));
  } while (bag.topics()[m.topic].name != "/livox/lidar");
  const std::string payload(reinterpret_cast<const char*>(m.data), m.size);
  const std::size_t at = good.find(payload);
  REQUIRE(at != std::string::npos);
  io::ros::MessageDefinitions defs(bag.topics()[m.topic].type, *bag.topics()[m.topic].definition);
  io::ros::MessageDecoder decoder(defs, io::ros::Encoding::ros1);
  io::ros::DecodedMessage decoded;
  decoder.decode(m.data, m.size, m.origin, decoded);
  const io::ros::Leaf* point_num = decoded.find("point_num");
  REQUIRE(point_num != nullptr);
  b = good;
  store_u32(b, at + point_num->offset, 121);
  CHECK(recording_error(dir.file("count.bag", b)).find("point_num says 121 points, the points array holds 120") !=
        std::string::npos);
  // The points array's count: more points than bytes.
  const io::ros::StructArray* points = decoded.find_array("points");
  REQUIRE(points != nullptr);
  b = good;
  store_u32(b, at + points->offset - 4, 1000000);
  CHECK(recording_error(dir.file("array.bag", b)).find("array points of 1000000 elements of 19 bytes: the message has 2280 bytes left") !=
        std::string::npos);
}

TEST_CASE("rosbag2 SQLite: not a database, missing tables, unknown topic ids") {
  TempDir dir("recordings", "db3");
  const std::string good = file_bytes(fixture("ros2_pc2_old.db3"));
  std::string b = good;
  b[0] = 'X';
  CHECK(recording_error(dir.file("magic.db3", b)).rfind("database: not a valid SQLite database", 0) == 0);
  CHECK(recording_error(dir.file("text.db3", "SQLite format 3")).find("SQLite") != std::string::npos);
  b = good.substr(0, 3000);
  CHECK_FALSE(recording_error(dir.file("cut.db3", b)).empty());

  // A bag folder whose metadata.yaml lists a missing file.
  const std::filesystem::path folder = dir.dir / "bag";
  std::filesystem::create_directories(folder);
  dir.file("bag/metadata.yaml", "rosbag2_bagfile_information:\n  storage_identifier: sqlite3\n  relative_file_paths:\n    - bag_0.db3\n");
  CHECK(recording_error(folder.string()).find("listed file") != std::string::npos);
  dir.file("bag/metadata.yaml", "rosbag2_bagfile_information:\n  storage_identifier: rosbag_v2\n  relative_file_paths:\n    - x\n");
  CHECK_FALSE(recording_error(folder.string()).empty());
  const std::filesystem::path empty = dir.dir / "empty";
  std::filesystem::create_directories(empty);
  CHECK(recording_error(empty.string()).find("expected metadata.yaml") != std::string::npos);
}

TEST_CASE("every truncation and many byte flips of every recording end cleanly") {
  TempDir dir("recordings", "damage");
  const char* files[] = {"ros1_custom.bag", "ros1_custom_bz2.bag", "ros1_custom_lz4.bag", "ros2_custom_lz4.mcap",
                         "ros2_custom_zstd.mcap", "ros2_pc2_converter.mcap", "ros2_pc2_ouster.mcap",
                         "ros2_pc2_old.db3"};
  for (const char* name : files) {
    INFO(name);
    const std::string good = file_bytes(fixture(name));
    const std::string ext = std::filesystem::path(name).extension().string();
    std::size_t errors = 0, clean = 0;
    // Truncations: a bag or an MCAP cut anywhere is an error; SQLite may
    // still find every row it needs in the first pages.
    for (std::size_t n = 0; n < good.size(); n += 1 + n / 32) {
      const std::string path = dir.file("cut" + ext, good.substr(0, n));
      (recording_error(path).empty() ? clean : errors)++;
      if (ext != ".db3") CHECK_MESSAGE(!recording_error(path).empty(), "cut at " << n);
    }
    // Flips: an error or a clean read, never anything else (a crash, a
    // hang or another exception fails the test run).
    for (std::size_t at = 0; at < good.size(); at += 31) {
      std::string b = good;
      b[at] = static_cast<char>(b[at] ^ 0xA5);
      const std::string path = dir.file("flip" + ext, b);
      try {
        (recording_error(path).empty() ? clean : errors)++;
      } catch (const std::exception& e) {
        FAIL("flip at " << at << ": " << e.what());
      }
    }
    CHECK(errors > 0);
  }
}

TEST_CASE("message definitions: comments, constants, defaults, arrays, nested types, errors") {
  namespace ros = io::ros;
  const ros::MessageDefinitions d("pkg/msg/Scan",
                                  "# a scan\n"
                                  "uint8 MODE_A=1   # a constant\n"
                                  "int32 LIMIT = -5\n"
                                  "Header header\n"
                                  "Point[] points   # unbounded\n"
                                  "float64[3] origin\n"
                                  "uint16[<=8] flags\n"
                                  "string<=10 name\n"
                                  "uint8 level 3    # ROS 2 default value\n"
                                  "================================================================================\n"
                                  "MSG: std_msgs/Header\n"
                                  "uint32 seq\ntime stamp\nstring frame_id\n"
                                  "================================================================================\n"
                                  "MSG: pkg/Point\n"
                                  "float32 x\nfloat32 y\n");
  const auto& f = d.main().fields;
  REQUIRE(f.size() == 6);
  CHECK(d.main().name == "pkg/Scan");
  CHECK(f[0].type_name == "std_msgs/Header");
  CHECK(f[1].type_name == "pkg/Point");
  CHECK(f[1].array == ros::FieldDefinition::Array::sequence);
  CHECK(f[2].array == ros::FieldDefinition::Array::fixed);
  CHECK(f[2].fixed_length == 3);
  CHECK(f[3].array == ros::FieldDefinition::Array::sequence);
  CHECK(f[4].primitive == ros::Primitive::string);
  CHECK(f[5].name == "level");
  CHECK(d.type("pkg/Point").fields.size() == 2);

  CHECK_THROWS_WITH_AS(ros::MessageDefinitions("a/B", "Missing m\n"),
                       "message definition of a/B: type a/Missing (field a/B.m) is used but not defined",
                       std::invalid_argument);
  CHECK_THROWS_WITH_AS(ros::MessageDefinitions("a/B", "B inner\n"), "message definition of a/B: type a/B contains itself",
                       std::invalid_argument);
  CHECK_THROWS_WITH_AS(ros::MessageDefinitions("a/B", "uint8\n"),
                       "message definition line 1: expected \"TYPE NAME\", found \"uint8\"", std::invalid_argument);
  CHECK_THROWS_AS(ros::MessageDefinitions("a/B", "uint8[x] v\n"), std::invalid_argument);
}

TEST_CASE("message definitions: nested fixed arrays that unroll beyond the bound are refused, quickly") {
  namespace ros = io::ros;
  // 1000 x (1 + 1000 x (1 + 1)) fields: the decoder would visit 2 million per message.
  CHECK_THROWS_WITH_AS(ros::MessageDefinitions("a/A", "B[1000] b\nMSG: a/B\nC[1000] c\nMSG: a/C\nuint8 x\n"),
                       "message definition of a/A: type a/A has more than 65536 fields with its fixed arrays of "
                       "messages unrolled",
                       std::invalid_argument);
  // A primitive array is one field, however long.
  CHECK_NOTHROW(ros::MessageDefinitions("a/A", "B[100] b\nMSG: a/B\nfloat32[100000000] v\n"));
  // Forty types, each holding the next twice: 2^40 fields, found without
  // visiting them (each type is counted once).
  std::string text = "T1 a\nT1 b\n";
  for (int k = 1; k < 40; ++k)
    text += "MSG: a/T" + std::to_string(k) + "\nT" + std::to_string(k + 1) + " a\nT" + std::to_string(k + 1) + " b\n";
  text += "MSG: a/T40\nuint8 x\n";
  CHECK_THROWS_WITH_AS(ros::MessageDefinitions("a/T0", text),
                       "message definition of a/T0: type a/T25 has more than 65536 fields with its fixed arrays of "
                       "messages unrolled",
                       std::invalid_argument);
}

TEST_CASE("message decoder: an array element with more than 4096 primitive fields is an input error") {
  namespace ros = io::ros;
  // A primitive array inside an array element is unrolled into the
  // element's layout, once per message.
  const ros::MessageDefinitions defs("a/Cloud", "P[] points\nMSG: a/P\nfloat32[5000] v\n");
  ros::MessageDecoder decoder(defs, ros::Encoding::ros1);
  const std::uint8_t payload[4] = {0, 0, 0, 0};  // no points
  io::detail::BufferOrigin origin;
  origin.file = "cloud.bag";
  ros::DecodedMessage decoded;
  CHECK_THROWS_WITH_AS(decoder.decode(payload, sizeof payload, origin, decoded),
                       "cloud.bag: byte 4: array points: an element of a/P has more than 4096 primitive fields "
                       "(fixed arrays unrolled): not a point type",
                       io::InputError);
  const ros::MessageDefinitions small("a/Cloud", "P[] points\nMSG: a/P\nfloat32[4096] v\n");
  ros::MessageDecoder fits(small, ros::Encoding::ros1);
  CHECK_NOTHROW(fits.decode(payload, sizeof payload, origin, decoded));
}

TEST_CASE("CDR: the points of a CustomMsg start where the frame_id length puts them") {
  namespace ros = io::ros;
  // The first lidar message of each CustomMsg fixture, decoded in place: the
  // first point's offset follows the frame_id (formats.md: 48 for
  // "livox_frame" and "lidar", 56 for "mid360_front"), stride 20.
  const std::pair<const char*, std::size_t> cases[] = {
      {"ros2_custom_lz4.mcap", 48}, {"ros2_custom_zstd.mcap", 48}, {"ros2_custom_db3", 56}};
  for (const auto& test_case : cases) {
    const char* const name = test_case.first;
    const std::size_t first = test_case.second;
    INFO(name);
    auto source = io::detail::open_recording(fixture(name), io::detect_format(fixture(name)));
    io::RecordingMessage m;
    do {
      REQUIRE(source->next(m));
    } while (source->topics()[m.topic].name != "/livox/lidar");
    const io::RecordingTopic& t = source->topics()[m.topic];
    ros::MessageDefinitions defs(t.type, *t.definition);
    ros::MessageDecoder decoder(defs, ros::Encoding::cdr);
    ros::DecodedMessage decoded;
    decoder.decode(m.data, m.size, m.origin, decoded);
    const ros::StructArray* points = decoded.find_array("points");
    REQUIRE(points != nullptr);
    std::vector<std::size_t> starts;
    points->for_each([&](std::size_t at, const ros::ElementLayout&) { starts.push_back(at); });
    REQUIRE(starts.size() == 120);
    CHECK(starts[0] == first);
    CHECK(starts[1] - starts[0] == 20);
    CHECK(m.size == starts.back() + 19);  // the last point without padding
  }
}
