// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A streaming reader of MCAP files (the rosbag2 default storage since ROS 2
/// Iron; https://mcap.dev/spec): magic, Header, data records (Schema, Channel,
/// Message, Chunk with "", "lz4" or "zstd" compression), Data End, the
/// optional summary section and the Footer.
///
/// Messages come in file order. Memory holds one chunk (decompressed) at a
/// time. Every CRC the file carries is checked: each chunk's
/// `uncompressed_crc`, the data section's (Data End) and the summary's
/// (Footer); a zero CRC means "not computed" (the specification's rule). The
/// summary's Schema, Channel and Statistics records give the topics and
/// their message counts without reading the data; a file without a summary
/// is scanned once for them.
///
///     streamclust::io::McapReader mcap("run.mcap");
///     for (const auto& t : mcap.topics()) std::cout << t.name << ' ' << t.type << '\n';
///     streamclust::io::RecordingMessage m;
///     while (mcap.next(m)) { /* m.topic, m.log_time_ns, m.data, m.size */ }

#include <streamclust/io/binary_file.hpp>
#include <streamclust/io/byte_cursor.hpp>
#include <streamclust/io/crc32.hpp>
#include <streamclust/io/decompress.hpp>
#include <streamclust/io/error.hpp>
#include <streamclust/io/recording_source.hpp>

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace streamclust::io {

namespace mcap {

/// The 8 bytes at the start and the end of every MCAP file.
inline constexpr std::array<std::uint8_t, 8> magic = {0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};

/// Record opcodes.
enum Opcode : std::uint8_t {
  header = 0x01, footer = 0x02, schema = 0x03, channel = 0x04, message = 0x05, chunk = 0x06,
  message_index = 0x07, chunk_index = 0x08, attachment = 0x09, attachment_index = 0x0A, statistics = 0x0B,
  metadata = 0x0C, metadata_index = 0x0D, summary_offset = 0x0E, data_end = 0x0F
};

/// Bytes of a record's opcode and length.
inline constexpr std::uint64_t record_prefix_bytes = 9;
/// Bytes of the Footer record (prefix included).
inline constexpr std::uint64_t footer_record_bytes = record_prefix_bytes + 20;

}  // namespace mcap

/// Reads an MCAP file. See the file comment. Throws InputError naming the
/// byte offset (or the chunk and its decompressed offset) for a wrong magic,
/// truncation, a length beyond its record or the file, an unknown chunk
/// compression, a CRC mismatch, a message on an undefined channel, or a
/// channel whose schema is undefined. Not thread-safe.
class McapReader final : public RecordingSource {
 public:
  explicit McapReader(const std::string& path) : RecordingSource(path), file_(path) {
    const std::uint64_t size = file_.size();
    if (size < 8) throw InputError(path_, "byte 0", "not an MCAP file: " + std::to_string(size) + " bytes, shorter than the magic");
    std::vector<std::uint8_t> b;
    file_.read_at(0, 8, b, "magic");
    if (!std::equal(b.begin(), b.end(), mcap::magic.begin())) {
      throw InputError(path_, "byte 0", "not an MCAP file: expected the magic 89 4d 43 41 50 30 0d 0a");
    }
    read_footer();
    // The Header record comes first.
    pos_ = 8;
    std::uint8_t op = 0;
    std::uint64_t length = 0;
    read_record(pos_, op, length, record_);
    if (op != mcap::header) throw InputError(path_, "byte 8", "expected the Header record (opcode 0x01), found opcode " + hex(op));
    detail::BufferOrigin origin{path_, "byte ", pos_ + mcap::record_prefix_bytes};
    detail::ByteCursor c(record_.data(), record_.size(), origin);
    profile_ = std::string(c.string32("Header profile"));
    library_ = std::string(c.string32("Header library"));
    data_crc_ = detail::crc32(b.data(), b.size());
    data_crc_ = crc_record(data_crc_, op, length, record_);
    pos_ += mcap::record_prefix_bytes + length;
    if (summary_start_ != 0) read_summary();
  }

  /// The Header's profile ("ros2", "ros1", ...) and writing library.
  const std::string& profile() const noexcept { return profile_; }
  const std::string& library() const noexcept { return library_; }
  /// True when the file has a summary section (topics and counts come from it).
  bool has_summary() const noexcept { return summary_start_ != 0; }

  const std::vector<RecordingTopic>& topics() override {
    if (!topics_known_) scan_topics();
    return table_.topics();
  }

  bool next(RecordingMessage& m) override {
    for (;;) {
      if (chunk_.open) {
        if (next_in_chunk(m)) return true;
        chunk_.open = false;
        continue;
      }
      if (finished_) return false;
      std::uint8_t op = 0;
      std::uint64_t length = 0;
      const std::uint64_t at = pos_;
      if (at == data_end_) {
        throw InputError(path_, "byte " + std::to_string(at),
                         "the data section ends without a Data End record (opcode 0x0f)");
      }
      read_record(at, op, length, record_);
      if (op == mcap::data_end) {
        check_data_end(at, length);
        finished_ = true;
        return false;
      }
      data_crc_ = crc_record(data_crc_, op, length, record_);
      pos_ = at + mcap::record_prefix_bytes + length;
      detail::BufferOrigin origin{path_, "byte ", at + mcap::record_prefix_bytes};
      if (op == mcap::chunk) {
        open_chunk(at, origin);
        continue;
      }
      if (data_record(op, record_.data(), record_.size(), origin, "byte " + std::to_string(at), m)) return true;
    }
  }

 private:
  struct Schema {
    std::string name, encoding, data;
  };

  static std::string hex(std::uint8_t v) {
    static const char* digits = "0123456789abcdef";
    return std::string("0x") + digits[v >> 4] + digits[v & 15];
  }

  /// Reads the record at `at` (opcode, length, content), checking that it fits
  /// before the end of the data section.
  void read_record(std::uint64_t at, std::uint8_t& op, std::uint64_t& length, std::vector<std::uint8_t>& content) {
    std::vector<std::uint8_t>& prefix = prefix_;
    if (!file_.contains(at, mcap::record_prefix_bytes) || at + mcap::record_prefix_bytes > data_end_) {
      throw InputError(path_, "byte " + std::to_string(at),
                       "truncated record: expected an opcode and a length, the data section ends at byte " +
                           std::to_string(data_end_));
    }
    file_.read_at(at, mcap::record_prefix_bytes, prefix, "record");
    op = prefix[0];
    length = 0;
    for (int i = 0; i < 8; ++i) length |= std::uint64_t{prefix[1 + i]} << (8 * i);
    const std::uint64_t content_at = at + mcap::record_prefix_bytes;
    if (length > data_end_ - content_at) {
      throw InputError(path_, "byte " + std::to_string(at),
                       "record (opcode " + hex(op) + ") of " + std::to_string(length) + " bytes runs past the data section's end at byte " +
                           std::to_string(data_end_));
    }
    file_.read_at(content_at, length, content, "record");
  }

  std::uint32_t crc_record(std::uint32_t crc, std::uint8_t op, std::uint64_t length,
                           const std::vector<std::uint8_t>& content) const {
    std::array<std::uint8_t, 9> p{};
    p[0] = op;
    for (int i = 0; i < 8; ++i) p[1 + i] = static_cast<std::uint8_t>(length >> (8 * i));
    crc = detail::crc32(p.data(), p.size(), crc);
    return detail::crc32(content.data(), content.size(), crc);
  }

  /// Reads the Footer (the 29 bytes before the closing magic).
  void read_footer() {
    const std::uint64_t size = file_.size();
    std::vector<std::uint8_t> b;
    if (size < 8 + 9 + mcap::footer_record_bytes + 8) {
      throw InputError(path_, "byte " + std::to_string(size),
                       "truncated MCAP file: " + std::to_string(size) + " bytes cannot hold a Header, a Footer and both magics");
    }
    file_.read_at(size - 8, 8, b, "closing magic");
    if (!std::equal(b.begin(), b.end(), mcap::magic.begin())) {
      throw InputError(path_, "byte " + std::to_string(size - 8),
                       "expected the closing MCAP magic: the file is truncated or was not closed (try `mcap recover`)");
    }
    footer_at_ = size - 8 - mcap::footer_record_bytes;
    file_.read_at(footer_at_, mcap::footer_record_bytes, b, "Footer");
    detail::BufferOrigin origin{path_, "byte ", footer_at_};
    detail::ByteCursor c(b.data(), b.size(), origin);
    const std::uint8_t op = c.u8("Footer opcode");
    const std::uint64_t length = c.u64("Footer length");
    if (op != mcap::footer || length != 20) {
      throw InputError(path_, "byte " + std::to_string(footer_at_),
                       "expected the Footer record (opcode 0x02, 20 bytes) before the closing magic, found opcode " +
                           hex(op) + " of " + std::to_string(length) + " bytes");
    }
    summary_start_ = c.u64("summary_start");
    summary_offset_start_ = c.u64("summary_offset_start");
    summary_crc_ = c.u32("summary_crc");
    if (summary_start_ != 0 && (summary_start_ < 8 + 9 || summary_start_ > footer_at_)) {
      throw InputError(path_, "byte " + std::to_string(footer_at_ + 9),
                       "summary_start " + std::to_string(summary_start_) + " lies outside the file's records (expected 17.." +
                           std::to_string(footer_at_) + ")");
    }
    if (summary_offset_start_ != 0 && (summary_offset_start_ < summary_start_ || summary_offset_start_ > footer_at_)) {
      throw InputError(path_, "byte " + std::to_string(footer_at_ + 17),
                       "summary_offset_start " + std::to_string(summary_offset_start_) + " lies outside the summary section");
    }
    data_end_ = summary_start_ != 0 ? summary_start_ : footer_at_;
  }

  /// Reads Schema, Channel and Statistics records of the summary section.
  void read_summary() {
    std::vector<std::uint8_t> all;
    file_.read_at(summary_start_, footer_at_ - summary_start_, all, "summary section");
    if (summary_crc_ != 0) {
      std::vector<std::uint8_t> footer_head;
      file_.read_at(footer_at_, 1 + 8 + 16, footer_head, "Footer");
      const std::uint32_t crc = detail::crc32(footer_head.data(), footer_head.size(), detail::crc32(all.data(), all.size()));
      if (crc != summary_crc_) {
        throw InputError(path_, "byte " + std::to_string(summary_start_),
                         "summary CRC mismatch: the Footer says " + hex32(summary_crc_) + ", the summary section has " + hex32(crc));
      }
    }
    detail::BufferOrigin origin{path_, "byte ", summary_start_};
    detail::ByteCursor c(all.data(), all.size(), origin);
    std::optional<std::map<std::uint16_t, std::uint64_t>> counts;
    while (!c.at_end()) {
      const std::uint8_t op = c.u8("summary record opcode");
      const std::uint64_t length = c.u64("summary record length");
      const std::size_t content_at = c.position();
      const std::uint8_t* p = c.bytes(length, "summary record");
      detail::BufferOrigin o{path_, "byte ", summary_start_ + content_at};
      detail::ByteCursor r(p, static_cast<std::size_t>(length), o);
      if (op == mcap::schema) {
        schema(r);
      } else if (op == mcap::channel) {
        channel(r);
      } else if (op == mcap::statistics) {
        counts = statistics(r);
      }
    }
    if (counts) {
      for (const auto& [id, topic] : table_.ids()) {
        const auto n = counts->find(static_cast<std::uint16_t>(id));
        table_.topics()[topic].messages = n == counts->end() ? 0 : n->second;
      }
    }
    topics_known_ = true;
  }

  static std::string hex32(std::uint32_t v) {
    static const char* digits = "0123456789abcdef";
    std::string s = "0x";
    for (int i = 7; i >= 0; --i) s += digits[(v >> (4 * i)) & 15];
    return s;
  }

  std::map<std::uint16_t, std::uint64_t> statistics(detail::ByteCursor& r) {
    r.skip(8 + 2 + 4 + 4 + 4 + 4 + 8 + 8, "Statistics counts");
    const std::uint32_t bytes = r.u32("Statistics channel_message_counts length");
    const std::uint8_t* p = r.bytes(bytes, "Statistics channel_message_counts");
    detail::ByteCursor m(p, bytes, r.origin());
    std::map<std::uint16_t, std::uint64_t> counts;
    while (!m.at_end()) {
      const std::uint16_t id = m.u16("channel id");
      counts[id] = m.u64("message count");
    }
    return counts;
  }

  void schema(detail::ByteCursor& r) {
    const std::uint16_t id = r.u16("Schema id");
    Schema s;
    s.name = std::string(r.string32("Schema name"));
    s.encoding = std::string(r.string32("Schema encoding"));
    s.data = std::string(r.string32("Schema data"));
    if (id == 0) r.fail_at(0, "Schema id 0 is reserved (it means \"no schema\")");
    schemas_[id] = std::move(s);
  }

  void channel(detail::ByteCursor& r) {
    const std::uint16_t id = r.u16("Channel id");
    const std::uint16_t schema_id = r.u16("Channel schema_id");
    RecordingTopic t;
    t.name = std::string(r.string32("Channel topic"));
    t.message_encoding = std::string(r.string32("Channel message_encoding"));
    r.skip(r.u32("Channel metadata length"), "Channel metadata");
    if (schema_id != 0) {
      const auto s = schemas_.find(schema_id);
      if (s == schemas_.end()) {
        r.fail_at(0, "channel " + std::to_string(id) + " (" + t.name + ") refers to schema " + std::to_string(schema_id) +
                         ", which no Schema record defined before it");
      }
      t.type = s->second.name;
      t.definition = s->second.data;
      t.definition_encoding = s->second.encoding;
    }
    table_.add(id, std::move(t), r, "channel");
  }

  /// Handles a Schema, Channel or Message record; true (and fills m) for a Message.
  bool data_record(std::uint8_t op, const std::uint8_t* p, std::size_t n, const detail::BufferOrigin& origin,
                   const std::string& where, RecordingMessage& m) {
    detail::ByteCursor r(p, n, origin);
    if (op == mcap::schema) {
      schema(r);
    } else if (op == mcap::channel) {
      channel(r);
    } else if (op == mcap::message) {
      const std::uint16_t id = r.u16("Message channel_id");
      r.skip(4, "Message sequence");
      m.log_time_ns = r.u64("Message log_time");
      r.skip(8, "Message publish_time");
      const auto topic = table_.index(id);
      if (!topic) r.fail_at(0, "message on channel " + std::to_string(id) + ", which no Channel record defined before it");
      if (counting_) {
        ++counted_[*topic];
        return false;
      }
      ++message_index_;
      m.topic = *topic;
      m.data = p + r.position();
      m.size = r.remaining();
      m.origin = detail::BufferOrigin{path_, "message " + std::to_string(message_index_) + " on " +
                                                 table_.topics()[*topic].name + " (record at " + where + "), payload byte ", 0};
      return true;
    }
    return false;
  }

  void open_chunk(std::uint64_t at, const detail::BufferOrigin& origin) {
    detail::ByteCursor c(record_.data(), record_.size(), origin);
    c.skip(16, "Chunk start and end times");
    const std::uint64_t uncompressed_size = c.u64("Chunk uncompressed_size");
    const std::uint32_t crc = c.u32("Chunk uncompressed_crc");
    const std::string_view compression = c.string32("Chunk compression");
    const std::uint64_t records_length = c.u64("Chunk records length");
    const std::size_t records_at = c.position();
    const std::uint8_t* records = c.bytes(records_length, "Chunk records");
    Compression kind = Compression::none;
    if (compression == "lz4") {
      kind = Compression::lz4;
    } else if (compression == "zstd") {
      kind = Compression::zstd;
    } else if (!compression.empty()) {
      c.fail_at(records_at, "unknown chunk compression \"" + std::string(compression) + "\": expected \"\", \"lz4\" or \"zstd\"");
    }
    const std::string where = "byte " + std::to_string(at) + " (chunk)";
    decompress(kind, records, static_cast<std::size_t>(records_length), uncompressed_size, chunk_.bytes, path_, where);
    if (crc != 0) {
      const std::uint32_t actual = detail::crc32(chunk_.bytes.data(), chunk_.bytes.size());
      if (actual != crc) {
        throw InputError(path_, where, "chunk CRC mismatch: the chunk says " + hex32(crc) + ", its records have " + hex32(actual));
      }
    }
    chunk_.start(path_, at);
  }

  bool next_in_chunk(RecordingMessage& m) {
    while (!chunk_.done()) {
      detail::ByteCursor c = chunk_.cursor();
      const std::size_t at = chunk_.next;
      const std::uint8_t op = c.u8("record opcode in chunk");
      const std::uint64_t length = c.u64("record length in chunk");
      const std::uint8_t* p = c.bytes(length, "record in chunk");
      chunk_.next = c.position();
      if (op != mcap::schema && op != mcap::channel && op != mcap::message) {
        c.fail_at(at, "record with opcode " + hex(op) + " inside a chunk: chunks hold only Schema, Channel and Message records");
      }
      detail::BufferOrigin o{path_, chunk_.origin.prefix, at + mcap::record_prefix_bytes};
      if (data_record(op, p, static_cast<std::size_t>(length), o, chunk_.origin.where(at), m))
        return true;
    }
    return false;
  }

  void check_data_end(std::uint64_t at, std::uint64_t length) {
    detail::BufferOrigin origin{path_, "byte ", at + mcap::record_prefix_bytes};
    detail::ByteCursor c(record_.data(), record_.size(), origin);
    const std::uint32_t crc = c.u32("Data End data_section_crc");
    if (crc != 0 && !counting_ && crc != data_crc_) {
      throw InputError(path_, "byte " + std::to_string(at),
                       "data section CRC mismatch: Data End says " + hex32(crc) + ", the data section has " + hex32(data_crc_));
    }
    const std::uint64_t after = at + mcap::record_prefix_bytes + length;
    if (after != data_end_) {
      throw InputError(path_, "byte " + std::to_string(after),
                       std::to_string(data_end_ - after) + " bytes between the Data End record and the " +
                           (summary_start_ != 0 ? "summary section" : "Footer"));
    }
  }

  /// Without a summary: one pass over the data for topics and message counts.
  void scan_topics() {
    const std::uint64_t pos = pos_;
    const std::uint32_t crc = data_crc_;
    counting_ = true;
    RecordingMessage m;
    while (next(m)) {
    }
    counting_ = false;
    for (std::size_t i = 0; i < table_.topics().size(); ++i) table_.topics()[i].messages = counted_[i];
    // Rewind; records met again are checked against what the scan found.
    pos_ = pos;
    data_crc_ = crc;
    finished_ = false;
    chunk_.open = false;
    topics_known_ = true;
  }

  detail::BinaryFile file_;
  std::string profile_, library_;
  std::uint64_t footer_at_ = 0, summary_start_ = 0, summary_offset_start_ = 0, data_end_ = 0;
  std::uint32_t summary_crc_ = 0, data_crc_ = 0;
  std::uint64_t pos_ = 0;
  std::vector<std::uint8_t> prefix_, record_;
  detail::OpenChunk chunk_;
  bool finished_ = false, topics_known_ = false, counting_ = false;
  std::uint64_t message_index_ = 0;
  std::map<std::uint16_t, Schema> schemas_;
  detail::TopicTable table_;
  std::map<std::size_t, std::uint64_t> counted_;
};

}  // namespace streamclust::io
