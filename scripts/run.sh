#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The main job (the README's run command): build the C-ARC example in Release
# with g++ and run it on its built-in simulated LiDAR stream; it prints
# per-retrieval statistics. Extra arguments are passed to the example.
#   SKIP_DEPS=1  do not run scripts/install-deps.sh
#   JOBS=2       parallel build jobs
#   BUILD_ROOT=build
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

JOBS=${JOBS:-2}
BUILD_ROOT=${BUILD_ROOT:-build}
DIR="$BUILD_ROOT/gcc"
TARGET=example_01_carc_synthetic

if [[ -z "${SKIP_DEPS:-}" ]]; then
  bash scripts/install-deps.sh >&2
fi

cmake -S . -B "$DIR" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=g++ >&2
cmake --build "$DIR" --target "$TARGET" -j "$JOBS" >&2
exec "$DIR/examples/$TARGET" "$@"
