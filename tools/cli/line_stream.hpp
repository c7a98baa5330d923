// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// An output stream for one of several threads that share a terminal: it
/// writes whole lines, each with a prefix, to a shared stream under a
/// shared mutex, so two threads' messages never interleave mid-line.
/// Thread-safety: one LineStream per thread; the shared stream is written
/// only under the mutex. A last partial line is written on destruction.

#include <mutex>
#include <ostream>
#include <streambuf>
#include <string>

namespace streamclust::cli {

class LinePrefixBuffer : public std::streambuf {
 public:
  LinePrefixBuffer(std::ostream& target, std::mutex& mutex, std::string prefix)
      : target_(target), mutex_(mutex), prefix_(std::move(prefix)) {}
  ~LinePrefixBuffer() override { write_line(); }
  LinePrefixBuffer(const LinePrefixBuffer&) = delete;
  LinePrefixBuffer& operator=(const LinePrefixBuffer&) = delete;

 protected:
  int_type overflow(int_type ch) override {
    if (traits_type::eq_int_type(ch, traits_type::eof())) return traits_type::not_eof(ch);
    line_.push_back(traits_type::to_char_type(ch));
    if (ch == '\n') write_line();
    return ch;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    for (std::streamsize i = 0; i < n; ++i) overflow(traits_type::to_int_type(s[i]));
    return n;
  }

 private:
  void write_line() {
    if (line_.empty()) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    target_ << prefix_ << line_ << std::flush;
    line_.clear();
  }

  std::ostream& target_;
  std::mutex& mutex_;
  std::string prefix_;
  std::string line_;
};

/// An ostream over a LinePrefixBuffer.
class LineStream : public std::ostream {
 public:
  LineStream(std::ostream& target, std::mutex& mutex, std::string prefix)
      : std::ostream(nullptr), buffer_(target, mutex, std::move(prefix)) {
    rdbuf(&buffer_);
  }

 private:
  LinePrefixBuffer buffer_;
};

}  // namespace streamclust::cli
