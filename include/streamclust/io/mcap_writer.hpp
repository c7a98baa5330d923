// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Writing MCAP files (https://mcap.dev/spec) that viewers such as Foxglove
/// open and seek: the magic, a Header, Schema and Channel records as they are
/// added, messages in Zstandard-compressed (or uncompressed) Chunks each
/// followed by its Message Index records, Data End with the data section's
/// CRC-32, and a summary section (Schemas, Channels, Statistics, Chunk
/// Indexes, Summary Offsets) that the Footer points to.
///
///     streamclust::io::McapWriter mcap("out.mcap", {});
///     const auto schema = mcap.add_schema("foxglove_msgs/msg/PointCloud", "ros2msg", definition);
///     const auto channel = mcap.add_channel(schema, "/clusters/points", "cdr");
///     mcap.write(channel, log_time_ns, cdr_bytes.data(), cdr_bytes.size());
///     mcap.close();  // also done by the destructor, which cannot report errors
///
/// Memory: one chunk (about `chunk_bytes`) and the summary (O(chunks +
/// channels)). Not thread-safe.

#include <streamclust/io/crc32.hpp>
#include <streamclust/io/mcap_reader.hpp>

#include <zstd.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace streamclust::io {

/// Writes an MCAP file. Every method throws std::runtime_error naming the file
/// when it cannot be written, std::invalid_argument for an unknown schema or
/// channel id.
class McapWriter {
 public:
  struct Options {
    std::string profile = "ros2";     ///< the Header's profile
    bool compress = true;             ///< Zstandard chunks (else uncompressed)
    std::size_t chunk_bytes = 1 << 20;  ///< a chunk is closed past this many bytes of records
  };

  McapWriter(std::string path, Options options) : path_(std::move(path)), options_(std::move(options)) {
    out_.open(path_, std::ios::binary | std::ios::trunc);
    if (!out_) throw std::runtime_error(path_ + ": cannot open for writing");
    emit(mcap::magic.data(), mcap::magic.size());
    Record header(mcap::header);
    header.string(options_.profile);
    header.string("streamclust");
    emit_record(header);
  }

  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;
  ~McapWriter() {
    try {
      close();
    } catch (...) {  // a destructor cannot report; call close() to see errors
    }
  }

  /// Adds a schema (`encoding` "ros2msg", `data` its definition text); returns its id (from 1).
  std::uint16_t add_schema(std::string_view name, std::string_view encoding, std::string_view data) {
    const auto id = static_cast<std::uint16_t>(schemas_.size() + 1);
    Record r(mcap::schema);
    r.u16(id);
    r.string(name);
    r.string(encoding);
    r.string(data);
    flush_chunk();
    emit_record(r);
    schemas_.push_back(r.content);
    return id;
  }

  /// Adds a channel on `topic` for messages of `schema` in `message_encoding` ("cdr"); returns its id (from 0).
  std::uint16_t add_channel(std::uint16_t schema, std::string_view topic, std::string_view message_encoding) {
    if (schema == 0 || schema > schemas_.size()) throw std::invalid_argument("McapWriter::add_channel: unknown schema id");
    const auto id = static_cast<std::uint16_t>(channels_.size());
    Record r(mcap::channel);
    r.u16(id);
    r.u16(schema);
    r.string(topic);
    r.string(message_encoding);
    r.u32(0);  // no metadata
    flush_chunk();
    emit_record(r);
    channels_.push_back(r.content);
    message_counts_[id] = 0;
    return id;
  }

  /// Writes one message of `channel` recorded at `log_time_ns`.
  void write(std::uint16_t channel, std::uint64_t log_time_ns, const std::uint8_t* data, std::size_t size) {
    if (channel >= channels_.size()) throw std::invalid_argument("McapWriter::write: unknown channel id");
    Record r(mcap::message);
    r.u16(channel);
    r.u32(message_counts_[channel]);
    r.u64(log_time_ns);
    r.u64(log_time_ns);
    r.content.insert(r.content.end(), data, data + size);
    if (chunk_messages_ == 0) {
      chunk_start_ = chunk_end_ = log_time_ns;
    }
    chunk_start_ = std::min(chunk_start_, log_time_ns);
    chunk_end_ = std::max(chunk_end_, log_time_ns);
    message_index_[channel].emplace_back(log_time_ns, chunk_records_.size());
    append(chunk_records_, r);
    ++chunk_messages_;
    ++message_counts_[channel];
    ++messages_;
    if (messages_ == 1) first_time_ = last_time_ = log_time_ns;
    first_time_ = std::min(first_time_, log_time_ns);
    last_time_ = std::max(last_time_, log_time_ns);
    if (chunk_records_.size() >= options_.chunk_bytes) flush_chunk();
  }

  /// Writes the last chunk, Data End, the summary, the Footer and the closing
  /// magic, and closes the file. Idempotent.
  void close() {
    if (closed_) return;
    flush_chunk();
    Record data_end(mcap::data_end);
    data_end.u32(crc_);
    emit_record(data_end);
    // The summary section: groups of records, each remembered for Summary Offsets.
    const std::uint64_t summary_start = offset_;
    std::vector<std::uint8_t> summary;
    std::vector<std::pair<std::uint8_t, std::pair<std::uint64_t, std::uint64_t>>> groups;
    const auto group = [&](std::uint8_t op, const std::vector<std::vector<std::uint8_t>>& contents) {
      if (contents.empty()) return;
      const std::uint64_t start = summary_start + summary.size();
      for (const auto& c : contents) {
        Record r(op);
        r.content = c;
        append(summary, r);
      }
      groups.push_back({op, {start, summary_start + summary.size() - start}});
    };
    group(mcap::schema, schemas_);
    group(mcap::channel, channels_);
    group(mcap::statistics, {statistics()});
    group(mcap::chunk_index, chunk_indexes_);
    const std::uint64_t offsets_start = summary_start + summary.size();
    for (const auto& [op, range] : groups) {
      Record r(mcap::summary_offset);
      r.u8(op);
      r.u64(range.first);
      r.u64(range.second);
      append(summary, r);
    }
    // The Footer; its CRC covers the summary and the Footer up to the CRC field.
    Record footer(mcap::footer);
    footer.u64(summary_start);
    footer.u64(offsets_start);
    footer.u32(0);
    std::vector<std::uint8_t> footer_bytes;
    append(footer_bytes, footer);
    const std::uint32_t crc =
        detail::crc32(footer_bytes.data(), footer_bytes.size() - 4, detail::crc32(summary.data(), summary.size()));
    for (int i = 0; i < 4; ++i) footer_bytes[footer_bytes.size() - 4 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
    emit(summary.data(), summary.size());
    emit(footer_bytes.data(), footer_bytes.size());
    emit(mcap::magic.data(), mcap::magic.size());
    out_.close();
    if (!out_) throw std::runtime_error(path_ + ": cannot write");
    closed_ = true;
  }

  /// Messages written so far.
  std::uint64_t messages() const noexcept { return messages_; }

 private:
  /// A record being built: opcode and content.
  struct Record {
    explicit Record(std::uint8_t opcode) : op(opcode) {}
    std::uint8_t op;
    std::vector<std::uint8_t> content;
    void u8(std::uint8_t v) { content.push_back(v); }
    void u16(std::uint16_t v) { le(v, 2); }
    void u32(std::uint32_t v) { le(v, 4); }
    void u64(std::uint64_t v) { le(v, 8); }
    void string(std::string_view s) {
      u32(static_cast<std::uint32_t>(s.size()));
      content.insert(content.end(), s.begin(), s.end());
    }
    void le(std::uint64_t v, int n) {
      for (int i = 0; i < n; ++i) content.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    }
  };

  static void append(std::vector<std::uint8_t>& out, const Record& r) {
    out.push_back(r.op);
    for (int i = 0; i < 8; ++i) out.push_back(static_cast<std::uint8_t>(std::uint64_t{r.content.size()} >> (8 * i)));
    out.insert(out.end(), r.content.begin(), r.content.end());
  }

  void emit(const std::uint8_t* p, std::size_t n) {
    out_.write(reinterpret_cast<const char*>(p), static_cast<std::streamsize>(n));
    if (!out_) throw std::runtime_error(path_ + ": cannot write");
    if (!in_summary_) crc_ = detail::crc32(p, n, crc_);
    offset_ += n;
  }

  /// A data-section record (counted in the data section's CRC, except Data End itself).
  void emit_record(const Record& r) {
    std::vector<std::uint8_t> bytes;
    append(bytes, r);
    if (r.op == mcap::data_end) in_summary_ = true;  // Data End's own bytes are outside its CRC
    emit(bytes.data(), bytes.size());
  }

  std::vector<std::uint8_t> statistics() const {
    Record r(mcap::statistics);
    r.u64(messages_);
    r.u16(static_cast<std::uint16_t>(schemas_.size()));
    r.u32(static_cast<std::uint32_t>(channels_.size()));
    r.u32(0);  // attachments
    r.u32(0);  // metadata
    r.u32(static_cast<std::uint32_t>(chunk_indexes_.size()));
    r.u64(messages_ ? first_time_ : 0);
    r.u64(messages_ ? last_time_ : 0);
    r.u32(static_cast<std::uint32_t>(message_counts_.size() * 10));
    for (const auto& [channel, n] : message_counts_) {
      r.u16(channel);
      r.u64(n);
    }
    return r.content;
  }

  /// Writes the open chunk (if any), its Message Index records, and remembers its Chunk Index.
  void flush_chunk() {
    if (chunk_messages_ == 0) return;
    const std::uint32_t crc = detail::crc32(chunk_records_.data(), chunk_records_.size());
    std::vector<std::uint8_t> stored;
    std::string compression;
    if (options_.compress) {
      stored.resize(ZSTD_compressBound(chunk_records_.size()));
      const std::size_t n = ZSTD_compress(stored.data(), stored.size(), chunk_records_.data(), chunk_records_.size(), 3);
      if (ZSTD_isError(n)) throw std::runtime_error(path_ + ": zstd: " + ZSTD_getErrorName(n));
      stored.resize(n);
      compression = "zstd";
    } else {
      stored = chunk_records_;
    }
    Record chunk(mcap::chunk);
    chunk.u64(chunk_start_);
    chunk.u64(chunk_end_);
    chunk.u64(chunk_records_.size());
    chunk.u32(crc);
    chunk.string(compression);
    chunk.u64(stored.size());
    chunk.content.insert(chunk.content.end(), stored.begin(), stored.end());
    const std::uint64_t chunk_at = offset_;
    emit_record(chunk);
    const std::uint64_t chunk_length = offset_ - chunk_at;
    // Message Index records, one per channel with messages in the chunk.
    Record index(mcap::chunk_index);
    index.u64(chunk_start_);
    index.u64(chunk_end_);
    index.u64(chunk_at);
    index.u64(chunk_length);
    Record offsets(0);
    const std::uint64_t indexes_at = offset_;
    for (const auto& [channel, entries] : message_index_) {
      Record m(mcap::message_index);
      m.u16(channel);
      m.u32(static_cast<std::uint32_t>(entries.size() * 16));
      for (const auto& [time, at] : entries) {
        m.u64(time);
        m.u64(at);
      }
      offsets.u16(channel);
      offsets.u64(offset_);
      emit_record(m);
    }
    index.u32(static_cast<std::uint32_t>(offsets.content.size()));
    index.content.insert(index.content.end(), offsets.content.begin(), offsets.content.end());
    index.u64(offset_ - indexes_at);
    index.string(compression);
    index.u64(stored.size());
    index.u64(chunk_records_.size());
    chunk_indexes_.push_back(index.content);
    chunk_records_.clear();
    message_index_.clear();
    chunk_messages_ = 0;
  }

  std::string path_;
  Options options_;
  std::ofstream out_;
  std::uint64_t offset_ = 0;
  std::uint32_t crc_ = 0;
  bool in_summary_ = false, closed_ = false;
  std::vector<std::vector<std::uint8_t>> schemas_, channels_, chunk_indexes_;
  std::map<std::uint16_t, std::uint32_t> message_counts_;
  std::vector<std::uint8_t> chunk_records_;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> message_index_;
  std::uint64_t chunk_messages_ = 0, chunk_start_ = 0, chunk_end_ = 0;
  std::uint64_t messages_ = 0, first_time_ = 0, last_time_ = 0;
};

}  // namespace streamclust::io
