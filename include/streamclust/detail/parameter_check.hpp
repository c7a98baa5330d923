// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The one message of a parameter outside its range:
/// "OWNER: NAME = VALUE is invalid, expected ALLOWED".

#include <stdexcept>
#include <string>

namespace streamclust::detail {

/// Throws std::invalid_argument "OWNER: NAME = VALUE is invalid, expected
/// ALLOWED" unless `ok`. O(1).
inline void require_parameter(bool ok, const char* owner, const char* name, double value, const char* allowed) {
  if (ok) return;
  std::string msg(owner);
  msg.append(": ");
  msg.append(name);
  msg.append(" = ");
  msg.append(std::to_string(value));
  msg.append(" is invalid, expected ");
  msg.append(allowed);
  throw std::invalid_argument(msg);
}

}  // namespace streamclust::detail
