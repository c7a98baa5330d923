#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The main job (the README's run command): build the demo (examples/00_livox_demo.cpp)
# in Release with g++ and run it: a simulated Livox Mid-360 in an office,
# clustered continuously by C-ARC for 10 s of stream; it prints per-cycle
# lines, a summary (P99 cycle latency, ARI and objects correct against the
# simulator's ground truth) and writes a bird's-eye PNG of the last window to
# $BUILD_ROOT/streamclust_demo.png. Extra arguments go to the demo, e.g.
# `bash scripts/run.sh --seconds 30` or `--every 1` (every cycle).
#   SKIP_DEPS=1  do not run scripts/install-deps.sh
#   JOBS=2       parallel build jobs
#   BUILD_ROOT=build
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

JOBS=${JOBS:-2}
BUILD_ROOT=${BUILD_ROOT:-build}
DIR="$BUILD_ROOT/gcc"
TARGET=example_00_livox_demo

if [[ -z "${SKIP_DEPS:-}" ]]; then
  bash scripts/install-deps.sh >&2
fi

cmake -S . -B "$DIR" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=g++ >&2
cmake --build "$DIR" --target "$TARGET" -j "$JOBS" >&2
exec "$DIR/examples/$TARGET" --png "$BUILD_ROOT/streamclust_demo.png" "$@"
