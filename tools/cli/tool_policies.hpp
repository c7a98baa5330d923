// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The policies this build of the tool offers: cli::ToolRegistry, a
/// registry::PolicyRegistry. The stock `streamclust` offers the stock
/// policies; a tool built by streamclust_add_tool (cmake/StreamclustAddTool.cmake)
/// defines STREAMCLUST_TOOL_POLICIES_HEADER, a generated header that
/// includes the researcher's policy headers and defines ToolRegistry with
/// the stock policies and theirs.

#ifdef STREAMCLUST_TOOL_POLICIES_HEADER
#include STREAMCLUST_TOOL_POLICIES_HEADER
#else
#include <streamclust/registry/stock.hpp>

namespace streamclust::cli {
using ToolRegistry = registry::StockRegistry;
}  // namespace streamclust::cli
#endif
