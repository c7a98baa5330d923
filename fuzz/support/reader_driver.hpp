// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The body of the reader targets: one fuzz input as a point file, read the
/// way `streamclust cluster` and `streamclust info` read it. io::InputError
/// is the documented outcome of bad input; anything else (another exception
/// type, a crash, undefined behaviour, a leak, unbounded memory or time)
/// is a bug. O(input size) per input. Compiled once (reader_driver.cpp) and
/// linked into every reader target: each opens every format.

#include "temp_input.hpp"

#include <cstddef>
#include <cstdint>

namespace streamclust::fuzz {

/// One fuzz input as the file `file` (whose name sets the format by
/// extension): read in chunks, the time origin found as the CLI finds it,
/// `streamclust info`'s pass, and format detection by content on `bare` (a
/// name without an extension).
void drive_reader(const std::uint8_t* data, std::size_t size, TempInput& file, TempInput& bare);

}  // namespace streamclust::fuzz
