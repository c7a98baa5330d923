// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A streaming reader of ROS 1 bags, format 2.0 (http://wiki.ros.org/Bags/Format/2.0):
/// the magic `#ROSBAG V2.0\n`, then records of `u32 header_len | header |
/// u32 data_len | data`, the header being `u32 len | name=value` fields with
/// `op` giving the record type. Chunks (compression `none`, `bz2` or `lz4`)
/// hold Connection and Message Data records; the index section after
/// `index_pos` holds every Connection and the Chunk Info records with
/// message counts per connection.
///
/// Messages come in file order, one chunk decompressed at a time. Topics come
/// from the index section; a bag without one (index_pos 0: a recording that
/// was not closed) is scanned once for them.
///
///     streamclust::io::Ros1BagReader bag("run.bag");
///     streamclust::io::RecordingMessage m;
///     while (bag.next(m)) { /* m.topic, m.log_time_ns, m.data (ROS 1 serialized) */ }

#include <streamclust/io/binary_file.hpp>
#include <streamclust/io/byte_cursor.hpp>
#include <streamclust/io/decompress.hpp>
#include <streamclust/io/error.hpp>
#include <streamclust/io/recording_source.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace streamclust::io {

namespace ros1_bag {

inline constexpr std::string_view magic = "#ROSBAG V2.0\n";

/// Record op codes.
enum Op : std::uint8_t { message_data = 0x02, bag_header = 0x03, index_data = 0x04, chunk = 0x05, chunk_info = 0x06,
                         connection = 0x07 };

/// The `name=value` fields of a record header.
class HeaderFields {
 public:
  /// Parses `n` bytes at `p`; errors located through `c`'s origin at `at`.
  HeaderFields(const std::uint8_t* p, std::size_t n, const detail::ByteCursor& errors, std::size_t at) {
    detail::ByteCursor c(p, n, errors.origin());
    while (!c.at_end()) {
      const std::size_t field_at = c.position();
      const std::uint32_t len = c.u32("header field length");
      const auto* f = reinterpret_cast<const char*>(c.bytes(len, "header field"));
      const std::string_view field(f, len);
      const std::size_t eq = field.find('=');
      if (eq == std::string_view::npos) {
        errors.fail_at(at + field_at, "header field without '=' (expected name=value)");
      }
      fields_.emplace_back(field.substr(0, eq), field.substr(eq + 1));
    }
  }

  std::optional<std::string_view> get(std::string_view name) const {
    for (const auto& f : fields_)
      if (f.first == name) return f.second;
    return std::nullopt;
  }

  /// The field `name` as a little-endian integer of sizeof(T) bytes.
  template <class T>
  T integer(std::string_view name, const detail::ByteCursor& errors, std::size_t at) const {
    const auto v = get(name);
    if (!v || v->size() != sizeof(T)) {
      errors.fail_at(at, "record header field " + std::string(name) + ": expected " + std::to_string(sizeof(T)) +
                             " bytes" + (v ? ", found " + std::to_string(v->size()) : std::string(", field missing")));
    }
    T x = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) x = static_cast<T>(x | (static_cast<T>(static_cast<std::uint8_t>((*v)[i])) << (8 * i)));
    return x;
  }

 private:
  std::vector<std::pair<std::string_view, std::string_view>> fields_;
};

}  // namespace ros1_bag

/// Reads a ROS 1 bag. See the file comment. Throws InputError naming the
/// byte offset (or the chunk and its decompressed offset) for a wrong magic,
/// truncation, lengths beyond their record or the file, unknown op codes or
/// compressions, and messages on undefined connections. Not thread-safe.
class Ros1BagReader final : public RecordingSource {
 public:
  explicit Ros1BagReader(const std::string& path) : RecordingSource(path), file_(path) {
    std::vector<std::uint8_t> b;
    if (file_.size() < ros1_bag::magic.size()) {
      throw InputError(path_, "byte 0", "not a ROS 1 bag: expected \"#ROSBAG V2.0\" and a newline");
    }
    file_.read_at(0, ros1_bag::magic.size(), b, "magic");
    if (std::string_view(reinterpret_cast<const char*>(b.data()), b.size()) != ros1_bag::magic) {
      const bool v1 = std::string_view(reinterpret_cast<const char*>(b.data()), b.size()).rfind("#ROSBAG V1", 0) == 0;
      throw InputError(path_, "byte 0", v1 ? "ROS bag format 1.x: expected format 2.0 (convert it with `rosbag fix`)"
                                           : "not a ROS 1 bag: expected \"#ROSBAG V2.0\" and a newline");
    }
    pos_ = ros1_bag::magic.size();
    Record r = read_record(pos_, "bag header");
    if (r.op != ros1_bag::bag_header) fail(pos_, "expected the bag header record (op 0x03), found op " + std::to_string(r.op));
    index_pos_ = r.fields->integer<std::uint64_t>("index_pos", *r.cursor, 0);
    pos_ = r.end;
    if (index_pos_ != 0 && (index_pos_ < pos_ || index_pos_ > file_.size())) {
      fail(ros1_bag::magic.size(), "index_pos " + std::to_string(index_pos_) + " lies outside the file's records (" +
                                       std::to_string(pos_) + ".." + std::to_string(file_.size()) + ")");
    }
    data_end_ = index_pos_ != 0 ? index_pos_ : file_.size();
    if (index_pos_ != 0) read_index();
  }

  const std::vector<RecordingTopic>& topics() override {
    if (!topics_known_) scan_topics();
    return table_.topics();
  }

  bool next(RecordingMessage& m) override {
    for (;;) {
      if (chunk_.open) {
        if (next_in_chunk(m)) return true;
        chunk_.open = false;
      }
      if (pos_ >= data_end_) return false;
      const std::uint64_t at = pos_;
      Record r = read_record(at, "record");
      pos_ = r.end;
      if (r.op == ros1_bag::chunk) {
        open_chunk(at, r);
      } else if (r.op == ros1_bag::connection) {
        connection(r);
      } else if (r.op == ros1_bag::message_data) {
        if (message(r, "byte " + std::to_string(at), m)) return true;
      } else if (r.op != ros1_bag::index_data && r.op != ros1_bag::chunk_info) {
        fail(at, "unknown record op " + std::to_string(r.op) + " (expected 0x02..0x07)");
      }
    }
  }

 private:
  /// A parsed record: op, fields, data, and where the next record starts.
  struct Record {
    std::uint8_t op = 0;
    std::optional<ros1_bag::HeaderFields> fields;
    std::optional<detail::ByteCursor> cursor;  // over the header, for errors
    const std::uint8_t* data = nullptr;
    std::size_t data_size = 0;
    std::uint64_t end = 0;
    std::uint64_t data_at = 0;
  };

  [[noreturn]] void fail(std::uint64_t at, const std::string& what) const {
    throw InputError(path_, "byte " + std::to_string(at), what);
  }

  /// Parses the record at file offset `at` (its header and data read into buffers).
  Record read_record(std::uint64_t at, const char* what) {
    std::vector<std::uint8_t> len;
    if (!file_.contains(at, 4) || at + 4 > data_end_or_size()) {
      fail(at, std::string("truncated ") + what + ": expected a header length, the file ends");
    }
    file_.read_at(at, 4, len, what);
    const std::uint32_t header_len = load32(len.data());
    if (!file_.contains(at + 4, std::uint64_t{header_len} + 4)) {
      fail(at, std::string("truncated ") + what + ": header of " + std::to_string(header_len) +
                   " bytes and a data length run past the end of the file at byte " + std::to_string(file_.size()));
    }
    file_.read_at(at + 4, header_len + 4, header_, what);
    const std::uint32_t data_len = load32(header_.data() + header_len);
    const std::uint64_t data_at = at + 8 + header_len;
    if (!file_.contains(data_at, data_len)) {
      fail(at, std::string("truncated ") + what + ": data of " + std::to_string(data_len) +
                   " bytes runs past the end of the file at byte " + std::to_string(file_.size()));
    }
    file_.read_at(data_at, data_len, data_, what);
    header_origin_ = detail::BufferOrigin{path_, "byte ", at + 4};
    return parse(header_.data(), header_len, data_.data(), data_len, header_origin_, data_at);
  }

  std::uint64_t data_end_or_size() const noexcept { return data_end_ != 0 ? data_end_ : file_.size(); }

  static std::uint32_t load32(const std::uint8_t* p) noexcept {
    return std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 | std::uint32_t{p[3]} << 24;
  }

  static Record parse(const std::uint8_t* header, std::size_t header_len, const std::uint8_t* data, std::size_t data_len,
                      const detail::BufferOrigin& origin, std::uint64_t data_at) {
    Record r;
    r.cursor.emplace(header, header_len, origin);
    r.fields.emplace(header, header_len, *r.cursor, 0);
    r.op = r.fields->integer<std::uint8_t>("op", *r.cursor, 0);
    r.data = data;
    r.data_size = data_len;
    r.data_at = data_at;
    r.end = data_at + data_len;
    return r;
  }

  void connection(const Record& r) {
    const std::uint32_t id = r.fields->integer<std::uint32_t>("conn", *r.cursor, 0);
    detail::BufferOrigin origin{path_, header_origin_.prefix, r.data_at};
    detail::ByteCursor data(r.data, r.data_size, origin);
    const ros1_bag::HeaderFields fields(r.data, r.data_size, data, 0);
    RecordingTopic t;
    const auto topic = r.fields->get("topic");
    t.name = std::string(topic ? *topic : fields.get("topic").value_or(""));
    t.type = std::string(fields.get("type").value_or(""));
    t.message_encoding = "ros1";
    t.definition_encoding = "ros1msg";
    if (const auto d = fields.get("message_definition")) t.definition = std::string(*d);
    if (t.type.empty()) data.fail_at(0, "connection " + std::to_string(id) + " (" + t.name + ") without a type field");
    table_.add(id, std::move(t), data, "connection");
  }

  bool message(const Record& r, const std::string& where, RecordingMessage& m) {
    const std::uint32_t id = r.fields->integer<std::uint32_t>("conn", *r.cursor, 0);
    const std::uint64_t time = r.fields->integer<std::uint64_t>("time", *r.cursor, 0);
    const auto topic = table_.index(id);
    if (!topic) {
      r.cursor->fail_at(0, "message on connection " + std::to_string(id) + ", which no connection record defined before it");
    }
    const std::uint64_t sec = time & 0xFFFFFFFFu, nsec = time >> 32;
    if (counting_) {
      ++counted_[*topic];
      return false;
    }
    ++message_index_;
    m.topic = *topic;
    m.log_time_ns = sec * 1000000000u + nsec;
    m.data = r.data;
    m.size = r.data_size;
    m.origin = detail::BufferOrigin{path_, "message " + std::to_string(message_index_) + " on " + table_.topics()[*topic].name +
                                               " (record at " + where + "), payload byte ", 0};
    return true;
  }

  void open_chunk(std::uint64_t at, const Record& r) {
    const auto compression = r.fields->get("compression");
    const std::uint32_t size = r.fields->integer<std::uint32_t>("size", *r.cursor, 0);
    Compression kind = Compression::none;
    if (!compression) r.cursor->fail_at(0, "chunk without a compression field");
    if (*compression == "bz2") {
      kind = Compression::bz2;
    } else if (*compression == "lz4") {
      kind = Compression::lz4;
    } else if (*compression != "none") {
      r.cursor->fail_at(0, "unknown chunk compression \"" + std::string(*compression) + "\": expected none, bz2 or lz4");
    }
    const std::string where = "byte " + std::to_string(at) + " (chunk)";
    decompress(kind, r.data, r.data_size, size, chunk_.bytes, path_, where);
    chunk_.start(path_, at);
  }

  bool next_in_chunk(RecordingMessage& m) {
    while (!chunk_.done()) {
      detail::ByteCursor c = chunk_.cursor();
      const std::size_t at = chunk_.next;
      const std::uint32_t header_len = c.u32("record header length in chunk");
      const std::uint8_t* header = c.bytes(header_len, "record header in chunk");
      const std::uint32_t data_len = c.u32("record data length in chunk");
      const std::size_t data_at = c.position();
      const std::uint8_t* data = c.bytes(data_len, "record data in chunk");
      chunk_.next = c.position();
      chunk_header_origin_ = detail::BufferOrigin{path_, chunk_.origin.prefix, at + 4};
      Record r = parse(header, header_len, data, data_len, chunk_header_origin_, data_at);
      if (r.op == ros1_bag::connection) {
        connection(r);
      } else if (r.op == ros1_bag::message_data) {
        if (message(r, chunk_.origin.where(at), m)) return true;
      } else {
        c.fail_at(at, "record op " + std::to_string(r.op) + " inside a chunk: chunks hold connection (0x07) and message (0x02) records");
      }
    }
    return false;
  }

  /// The index section: connection records, then chunk info records.
  void read_index() {
    std::uint64_t at = index_pos_;
    const std::uint64_t saved_end = data_end_;
    data_end_ = file_.size();
    std::map<std::uint32_t, std::uint64_t> counts;
    while (at < file_.size()) {
      Record r = read_record(at, "index record");
      if (r.op == ros1_bag::connection) {
        connection(r);
      } else if (r.op == ros1_bag::chunk_info) {
        detail::BufferOrigin origin{path_, "byte ", r.data_at};
        detail::ByteCursor c(r.data, r.data_size, origin);
        const std::uint32_t n = r.fields->integer<std::uint32_t>("count", *r.cursor, 0);
        for (std::uint32_t k = 0; k < n; ++k) {
          const std::uint32_t conn = c.u32("chunk info connection");
          counts[conn] += c.u32("chunk info count");
        }
      } else {
        fail(at, "record op " + std::to_string(r.op) + " in the index section: expected connection (0x07) or chunk info (0x06)");
      }
      at = r.end;
    }
    data_end_ = saved_end;
    for (const auto& [conn, topic] : table_.ids()) {
      auto& messages = table_.topics()[topic].messages;
      const auto it = counts.find(conn);
      messages = messages.value_or(0) + (it == counts.end() ? 0 : it->second);
    }
    topics_known_ = true;
  }

  void scan_topics() {
    const std::uint64_t pos = pos_;
    counting_ = true;
    RecordingMessage m;
    while (next(m)) {
    }
    counting_ = false;
    for (std::size_t i = 0; i < table_.topics().size(); ++i) table_.topics()[i].messages = counted_[i];
    pos_ = pos;
    chunk_.open = false;
    topics_known_ = true;
  }

  detail::BinaryFile file_;
  std::uint64_t pos_ = 0, index_pos_ = 0, data_end_ = 0;
  std::vector<std::uint8_t> header_, data_;
  detail::OpenChunk chunk_;
  detail::BufferOrigin header_origin_, chunk_header_origin_;
  bool topics_known_ = false, counting_ = false;
  std::uint64_t message_index_ = 0;
  detail::TopicTable table_;
  std::map<std::size_t, std::uint64_t> counted_;
};

}  // namespace streamclust::io
