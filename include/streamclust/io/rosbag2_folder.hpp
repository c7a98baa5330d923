// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// rosbag2 bag folders: `metadata.yaml` names the storage (`sqlite3` or
/// `mcap`) and the bag's files in order (`relative_file_paths`); a bag split
/// into several files reads as one recording (SplitRecording).

#include <streamclust/io/error.hpp>
#include <streamclust/io/recording_source.hpp>

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::io {

/// What a bag folder's metadata.yaml says.
struct Rosbag2Metadata {
  std::string storage_identifier;  ///< "sqlite3" or "mcap"
  std::vector<std::string> files;  ///< paths of the bag's files, in order
};

/// Reads `folder`/metadata.yaml: the keys `storage_identifier` and
/// `relative_file_paths` (a YAML block list); other keys are ignored. Throws
/// InputError naming the line when either is missing or malformed, or a
/// listed file does not exist. O(file).
inline Rosbag2Metadata read_rosbag2_metadata(const std::string& folder) {
  const std::string path = (std::filesystem::path(folder) / "metadata.yaml").string();
  std::ifstream in(path);
  if (!in) throw InputError(folder, "metadata.yaml", "a bag folder needs metadata.yaml: cannot open " + path);
  Rosbag2Metadata m;
  std::string line;
  std::size_t line_no = 0, list_indent = std::string::npos;
  bool in_list = false;
  const auto trim = [](std::string s) {
    const std::size_t a = s.find_first_not_of(" \t\r");
    const std::size_t b = s.find_last_not_of(" \t\r");
    s = a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
    if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front()) s = s.substr(1, s.size() - 2);
    return s;
  };
  while (std::getline(in, line)) {
    ++line_no;
    if (line_no > 100000) throw InputError(path, "line " + std::to_string(line_no), "metadata.yaml longer than 100000 lines");
    const std::size_t indent = line.find_first_not_of(' ');
    if (indent == std::string::npos) continue;
    const std::string body = line.substr(indent);
    if (in_list) {
      if (body.rfind("- ", 0) == 0 && (list_indent == std::string::npos || indent == list_indent)) {
        list_indent = indent;
        const std::string name = trim(body.substr(2));
        if (name.empty() || name.find("..") != std::string::npos || std::filesystem::path(name).is_absolute()) {
          throw InputError(path, "line " + std::to_string(line_no), "relative_file_paths entry \"" + name +
                                                                        "\": expected a file name inside the bag folder");
        }
        m.files.push_back((std::filesystem::path(folder) / name).string());
        continue;
      }
      in_list = false;
    }
    if (body.rfind("storage_identifier:", 0) == 0) {
      m.storage_identifier = trim(body.substr(19));
    } else if (body.rfind("relative_file_paths:", 0) == 0) {
      const std::string rest = trim(body.substr(20));
      if (!rest.empty() && rest != "[]") {
        throw InputError(path, "line " + std::to_string(line_no), "relative_file_paths: expected a block list (\"- file\" lines)");
      }
      in_list = true;
      list_indent = std::string::npos;
    }
  }
  if (m.storage_identifier.empty()) throw InputError(path, "header", "no storage_identifier (expected sqlite3 or mcap)");
  if (m.files.empty()) throw InputError(path, "header", "no relative_file_paths: the bag lists no files");
  for (const std::string& f : m.files) {
    if (!std::filesystem::is_regular_file(f)) throw InputError(path, "relative_file_paths", "listed file " + f + " does not exist");
  }
  return m;
}

/// The files of a split bag read as one recording: topics merged by name and
/// type, messages file after file. Not thread-safe.
class SplitRecording final : public RecordingSource {
 public:
  SplitRecording(std::string path, std::vector<std::unique_ptr<RecordingSource>> parts)
      : RecordingSource(std::move(path)), parts_(std::move(parts)) {
    for (std::size_t p = 0; p < parts_.size(); ++p) {
      for (std::size_t i = 0; i < parts_[p]->topics().size(); ++i) {
        const RecordingTopic& t = parts_[p]->topics()[i];
        const auto key = std::make_pair(t.name, t.type);
        auto it = merged_.find(key);
        if (it == merged_.end()) {
          it = merged_.emplace(key, topics_.size()).first;
          topics_.push_back(t);
        } else if (t.messages && topics_[it->second].messages) {
          *topics_[it->second].messages += *t.messages;
        }
        map_[{p, i}] = it->second;
      }
    }
  }

  const std::vector<RecordingTopic>& topics() override { return topics_; }

  bool next(RecordingMessage& m) override {
    while (part_ < parts_.size()) {
      if (parts_[part_]->next(m)) {
        m.topic = map_.at({part_, m.topic});
        return true;
      }
      ++part_;
    }
    return false;
  }

 private:
  std::vector<std::unique_ptr<RecordingSource>> parts_;
  std::vector<RecordingTopic> topics_;
  std::map<std::pair<std::string, std::string>, std::size_t> merged_;
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> map_;
  std::size_t part_ = 0;
};

}  // namespace streamclust::io
