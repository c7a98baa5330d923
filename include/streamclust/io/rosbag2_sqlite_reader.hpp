// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A reader of rosbag2 SQLite storage (`.db3`, the default up to ROS 2
/// Humble), through Debian's libsqlite3: the `topics` table (id, name,
/// type, serialization_format), the `messages` table (topic_id, timestamp
/// [ns], data: CDR) read in timestamp order as rosbag2 reads it, and, when
/// the bag has it (rosbag2 from Iron on), the `message_definitions` table.
/// Bags without stored definitions get the built-in definitions of the point
/// types this library decodes (ros/known_definitions.hpp).
///
/// The file is opened read-only and immutable; rows stream through one
/// prepared statement (memory: one message).

#include <streamclust/io/error.hpp>
#include <streamclust/io/recording_source.hpp>
#include <streamclust/io/ros/known_definitions.hpp>

#include <sqlite3.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace streamclust::io {

/// Reads a rosbag2 `.db3` file. Throws InputError for a file that is not an
/// SQLite database, lacks the rosbag2 tables, or whose rows are malformed
/// (a message on an unknown topic, a NULL payload, a negative timestamp).
/// Not thread-safe.
class Rosbag2SqliteReader final : public RecordingSource {
 public:
  explicit Rosbag2SqliteReader(const std::string& path) : RecordingSource(path) {
    sqlite3* db = nullptr;
    const std::string uri = "file:" + escape_uri(path) + "?immutable=1";
    const int rc = sqlite3_open_v2(uri.c_str(), &db, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr);
    db_.reset(db);
    if (rc != SQLITE_OK) fail("database", std::string("cannot open as SQLite: ") + sqlite3_errstr(rc));
    read_topics();
    read_definitions();
    messages_ = prepare("SELECT topic_id, timestamp, data FROM messages ORDER BY timestamp, id", "messages");
  }

  const std::vector<RecordingTopic>& topics() override { return topics_; }

  bool next(RecordingMessage& m) override {
    if (done_) return false;  // stepping a finished statement would restart it
    const int rc = sqlite3_step(messages_.get());
    if (rc == SQLITE_DONE) {
      done_ = true;
      return false;
    }
    if (rc != SQLITE_ROW) fail("table messages", std::string("cannot read: ") + sqlite3_errmsg(db_.get()));
    ++row_;
    const std::int64_t topic_id = sqlite3_column_int64(messages_.get(), 0);
    const std::int64_t timestamp = sqlite3_column_int64(messages_.get(), 1);
    const auto it = topic_index_.find(topic_id);
    const std::string where = "table messages, row " + std::to_string(row_);
    if (it == topic_index_.end()) fail(where, "message on topic_id " + std::to_string(topic_id) + ", which table topics does not define");
    if (timestamp < 0) fail(where, "negative timestamp " + std::to_string(timestamp));
    if (sqlite3_column_type(messages_.get(), 2) != SQLITE_BLOB && sqlite3_column_type(messages_.get(), 2) != SQLITE_NULL) {
      fail(where, "data is not a BLOB");
    }
    m.topic = it->second;
    m.log_time_ns = static_cast<std::uint64_t>(timestamp);
    m.data = static_cast<const std::uint8_t*>(sqlite3_column_blob(messages_.get(), 2));
    m.size = static_cast<std::size_t>(sqlite3_column_bytes(messages_.get(), 2));
    static const std::uint8_t empty = 0;
    if (m.data == nullptr) m.data = &empty;
    m.origin = detail::BufferOrigin{path_, "message " + std::to_string(row_) + " on " + topics_[it->second].name + " (" +
                                               where + "), payload byte ", 0};
    return true;
  }

 private:
  struct CloseDb {
    void operator()(sqlite3* db) const noexcept { sqlite3_close(db); }
  };
  struct Finalize {
    void operator()(sqlite3_stmt* s) const noexcept { sqlite3_finalize(s); }
  };
  using Statement = std::unique_ptr<sqlite3_stmt, Finalize>;

  [[noreturn]] void fail(const std::string& where, const std::string& what) const { throw InputError(path_, where, what); }

  static std::string escape_uri(const std::string& path) {
    std::string s;
    for (const char c : path) {
      if (c == '%' || c == '?' || c == '#') {
        static const char* digits = "0123456789ABCDEF";
        s += '%';
        s += digits[(static_cast<unsigned char>(c) >> 4) & 15];
        s += digits[static_cast<unsigned char>(c) & 15];
      } else {
        s += c;
      }
    }
    return s;
  }

  Statement prepare(const std::string& sql, const std::string& table) const {
    sqlite3_stmt* s = nullptr;
    const int rc = sqlite3_prepare_v2(db_.get(), sql.c_str(), -1, &s, nullptr);
    Statement statement(s);
    if (rc != SQLITE_OK) {
      const std::string message = sqlite3_errmsg(db_.get());
      if (rc == SQLITE_NOTADB || rc == SQLITE_CORRUPT) fail("database", "not a valid SQLite database: " + message);
      fail("table " + table, "expected a rosbag2 " + table + " table: " + message);
    }
    return statement;
  }

  static std::string text(sqlite3_stmt* s, int column) {
    const unsigned char* t = sqlite3_column_text(s, column);
    return t == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(t),
                                                      static_cast<std::size_t>(sqlite3_column_bytes(s, column)));
  }

  void read_topics() {
    Statement s = prepare("SELECT id, name, type, serialization_format FROM topics ORDER BY id", "topics");
    for (int rc; (rc = sqlite3_step(s.get())) != SQLITE_DONE;) {
      if (rc != SQLITE_ROW) fail("table topics", std::string("cannot read: ") + sqlite3_errmsg(db_.get()));
      RecordingTopic t;
      const std::int64_t id = sqlite3_column_int64(s.get(), 0);
      t.name = text(s.get(), 1);
      t.type = text(s.get(), 2);
      t.message_encoding = text(s.get(), 3);
      if (topic_index_.count(id) != 0) fail("table topics", "topic id " + std::to_string(id) + " appears twice");
      topic_index_[id] = topics_.size();
      topics_.push_back(std::move(t));
    }
    Statement count = prepare("SELECT topic_id, COUNT(*) FROM messages GROUP BY topic_id", "messages");
    for (auto& t : topics_) t.messages = 0;
    for (int rc; (rc = sqlite3_step(count.get())) != SQLITE_DONE;) {
      if (rc != SQLITE_ROW) fail("table messages", std::string("cannot read: ") + sqlite3_errmsg(db_.get()));
      const auto it = topic_index_.find(sqlite3_column_int64(count.get(), 0));
      if (it != topic_index_.end()) topics_[it->second].messages = static_cast<std::uint64_t>(sqlite3_column_int64(count.get(), 1));
    }
  }

  bool has_table(const char* name) const {
    Statement s = prepare(std::string("SELECT 1 FROM sqlite_master WHERE type='table' AND name='") + name + "'", "sqlite_master");
    return sqlite3_step(s.get()) == SQLITE_ROW;
  }

  void read_definitions() {
    std::map<std::string, std::pair<std::string, std::string>> stored;  // type -> (encoding, text)
    if (has_table("message_definitions")) {
      Statement s = prepare("SELECT topic_type, encoding, encoded_message_definition FROM message_definitions",
                            "message_definitions");
      for (int rc; (rc = sqlite3_step(s.get())) != SQLITE_DONE;) {
        if (rc != SQLITE_ROW) fail("table message_definitions", std::string("cannot read: ") + sqlite3_errmsg(db_.get()));
        stored[text(s.get(), 0)] = {text(s.get(), 1), text(s.get(), 2)};
      }
    }
    for (RecordingTopic& t : topics_) {
      const auto it = stored.find(t.type);
      if (it != stored.end() && !it->second.second.empty()) {
        t.definition_encoding = it->second.first;
        t.definition = it->second.second;
      } else if (const auto known = ros::known_definition(t.type, ros::Encoding::cdr)) {
        t.definition_encoding = "ros2msg";
        t.definition = std::string(*known);
      }
    }
  }

  std::unique_ptr<sqlite3, CloseDb> db_;
  Statement messages_;
  std::map<std::int64_t, std::size_t> topic_index_;
  std::vector<RecordingTopic> topics_;
  std::uint64_t row_ = 0;
  bool done_ = false;
};

}  // namespace streamclust::io
