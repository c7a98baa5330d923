#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# CTest live_view: `streamclust live --foxglove --tracks` fed by `streamclust
# replay` over loopback UDP, read by the reference client
# (tests/scripts/check_live_view.mjs): the tracks in the view are the --tracks
# file's. Skipped (exit 77) without node or without the npm packages: install
# them with scripts/install-npm-tools.sh (npm registry needed) or point
# STREAMCLUST_NPM_PREFIX at them.
# Usage: live_view_test.sh TOOL SOURCE_DIR WORK_DIR PORT
set -euo pipefail
tool=$1 src=$2 work=$3 port=$4
prefix=${STREAMCLUST_NPM_PREFIX:-$src/build/npm}
source "$src/tests/scripts/need_npm_packages.sh"
need_npm_packages "$prefix" @foxglove/ws-protocol ws @foxglove/rosmsg2-serialization @foxglove/rosmsg
rm -rf "$work" && mkdir -p "$work"
node "$src/tests/scripts/check_live_view.mjs" "$prefix" "$tool" "$work" "$port"
echo "live_view: ok"
