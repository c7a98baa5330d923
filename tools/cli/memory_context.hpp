// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Running out of memory, reported with its context: the command, the input
/// and the stage it was in (reading, clustering, writing); exit code 5
/// (kOutOfMemory, docs/cli.md). A command runs its work through
/// `with_memory_context` and moves `stage` along as it goes.

#include <new>
#include <stdexcept>
#include <string>
#include <utility>

namespace streamclust::cli {

/// What a command was doing when an allocation failed.
enum class Stage { reading, clustering, writing };

inline const char* to_string(Stage s) noexcept {
  switch (s) {
    case Stage::reading: return "reading";
    case Stage::clustering: return "clustering";
    case Stage::writing: return "writing";
  }
  return "running";
}

/// An allocation failure (std::bad_alloc) with its context; `what()` reads
/// "COMMAND INPUT: out of memory while STAGE".
class OutOfMemory : public std::runtime_error {
 public:
  OutOfMemory(const std::string& command, const std::string& input, Stage stage)
      : std::runtime_error(command + " " + input + ": out of memory while " + to_string(stage)), stage_(stage) {}
  Stage stage() const noexcept { return stage_; }

 private:
  Stage stage_;
};

/// Returns `f(stage)`; `f` moves `stage` (starting at `reading`) along. A
/// std::bad_alloc leaving `f` becomes OutOfMemory(command, input, stage).
template <class F>
auto with_memory_context(const char* command, const std::string& input, F&& f) {
  Stage stage = Stage::reading;
  try {
    return std::forward<F>(f)(stage);
  } catch (const std::bad_alloc&) {
    throw OutOfMemory(command, input, stage);
  }
}

}  // namespace streamclust::cli
