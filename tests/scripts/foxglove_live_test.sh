#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# CTest foxglove_live: the live view's Foxglove WebSocket server
# (tools/live/foxglove_server.hpp) against the reference client
# (tests/scripts/check_foxglove_live.mjs: @foxglove/ws-protocol over ws, messages
# decoded by @foxglove/rosmsg2-serialization). Skipped (exit 77) without node or
# without the npm packages: install them with scripts/install-npm-tools.sh (npm
# registry needed) or point STREAMCLUST_NPM_PREFIX at them.
# Usage: foxglove_live_test.sh SERVE SOURCE_DIR
set -euo pipefail
serve=$1 src=$2
prefix=${STREAMCLUST_NPM_PREFIX:-$src/build/npm}
source "$src/tests/scripts/need_npm_packages.sh"
need_npm_packages "$prefix" @foxglove/ws-protocol ws @foxglove/rosmsg2-serialization @foxglove/rosmsg
node "$src/tests/scripts/check_foxglove_live.mjs" "$prefix" "$serve"
echo "foxglove_live: ok"
