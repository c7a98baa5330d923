// SPDX-License-Identifier: MIT
#pragma once
// Substring checks on messages and reports.

#include <string>

namespace streamclust::test {

/// True when `part` occurs in `text`.
inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace streamclust::test
