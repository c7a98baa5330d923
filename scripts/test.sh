#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The full test run (this is .ci/run and the README's test command):
#   gcc    Release, g++, C++17       -> build/gcc    all tests (their own files at -O1:
#                                                   STREAMCLUST_TEST_O1), examples, benchmark smoke runs,
#                                                   and the Python module with its pytest suite
#                                                   (CTest python_pytest)
#   clang  Debug (-O1, asserts on), clang++-14, C++20, ASan+UBSan
#                                    -> build/clang  tests and examples
#                                                   (bench- and slow-labelled tests and the
#                                                   doctest cases of test suite "slow" excluded,
#                                                   the oracle on a pairwise cover of the policies;
#                                                   the header self-containment check
#                                                   and the FMA build are the gcc stage's)
#   fuzz   clang++-14, libFuzzer  -> build/fuzz   every fuzz target for 10 s on its seed corpus
#                                                (scripts/fuzz.sh 10; docs/fuzzing.md)
# Each test file is compiled once per compiler: C++17 with g++, C++20 (the
# concepts) with clang, where the sanitizers also run.
#
# Usage:  scripts/test.sh [stage...]          e.g. scripts/test.sh gcc
# Environment:
#   STREAMCLUST_STAGES="gcc clang fuzz"     stages to run (arguments win over it)
#   SKIP_GCC=1 SKIP_CLANG=1 SKIP_FUZZ=1     drop a stage
#   SKIP_DEPS=1                             do not run scripts/install-deps.sh nor install the npm test tools
#   JOBS=2                                  parallel build and test jobs
#   BUILD_ROOT=build                        where the build directories go
#   CMAKE_GENERATOR                         honoured by CMake itself (e.g. Ninja)
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

JOBS=${JOBS:-2}
BUILD_ROOT=${BUILD_ROOT:-build}
if [[ $# -gt 0 ]]; then
  STAGES=("$@")
else
  read -r -a STAGES <<<"${STREAMCLUST_STAGES:-gcc clang fuzz}"
fi

if [[ -z "${SKIP_DEPS:-}" ]]; then
  bash scripts/install-deps.sh
  # The npm packages of the optional mcap_foxglove and foxglove_live tests (the
  # reference MCAP reader, the reference Foxglove WebSocket client): tried once,
  # for at most two minutes, into a scratch folder moved into place only when
  # complete. Without node, npm or the registry the tests report themselves skipped.
  if command -v npm >/dev/null && { [[ ! -d build/npm/node_modules/@mcap/core ]] ||
                                    [[ ! -d build/npm/node_modules/@foxglove/ws-protocol ]]; }; then
    rm -rf build/npm.partial
    if timeout 120 bash scripts/install-npm-tools.sh build/npm.partial >/dev/null 2>&1; then
      rm -rf build/npm && mv build/npm.partial build/npm
    else
      echo "test.sh: the npm packages could not be installed; mcap_foxglove will be skipped"
    fi
  fi
fi

declare -a SUMMARY=()
T_ALL=$SECONDS
CURRENT_STAGE=""

print_summary() {
  local line
  for line in "${SUMMARY[@]}"; do echo "  $line"; done
}
on_exit() {
  local rc=$?
  if [[ $rc -ne 0 ]]; then
    echo
    echo "=== test.sh: FAILED (exit $rc) in stage '${CURRENT_STAGE:-setup}' after $((SECONDS - T_ALL))s ===" >&2
    print_summary >&2
  fi
}
trap on_exit EXIT

# configure + build + ctest. Args: name compiler build_type ctest_args... -- cmake_args...
run_stage() {
  local name=$1 cxx=$2 build_type=$3
  shift 3
  local -a ctest_args=() cmake_args=()
  while [[ $# -gt 0 && "$1" != "--" ]]; do ctest_args+=("$1"); shift; done
  [[ $# -gt 0 ]] && shift
  cmake_args=("$@")

  local dir="$BUILD_ROOT/$name" t0=$SECONDS
  CURRENT_STAGE=$name
  echo
  echo "=== stage $name: $cxx, $build_type, $dir ==="
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE="$build_type" -DCMAKE_CXX_COMPILER="$cxx" "${cmake_args[@]}"
  local t1=$SECONDS
  cmake --build "$dir" -j "$JOBS"
  local t2=$SECONDS
  (cd "$dir" && ctest --output-on-failure -j "$JOBS" "${ctest_args[@]}")
  local t3=$SECONDS
  SUMMARY+=("$(printf '%-6s configure %4ds  build %4ds  test %4ds  total %4ds' \
    "$name" $((t1 - t0)) $((t2 - t1)) $((t3 - t2)) $((t3 - t0)))")
}

# The fuzz targets (scripts/fuzz.sh): configure, build, then each target
# for 10 s on its seed corpus; a crash, leak, timeout or OOM fails the stage.
run_fuzz_stage() {
  local dir="$BUILD_ROOT/fuzz" t0=$SECONDS
  CURRENT_STAGE=fuzz
  echo
  echo "=== stage fuzz: clang++-14, libFuzzer + ASan + UBSan, $dir ==="
  BUILD_DIR="$dir" JOBS="$JOBS" bash scripts/fuzz.sh --phase configure
  local t1=$SECONDS
  BUILD_DIR="$dir" JOBS="$JOBS" bash scripts/fuzz.sh --phase build
  local t2=$SECONDS
  BUILD_DIR="$dir" bash scripts/fuzz.sh --phase run 10
  local t3=$SECONDS
  SUMMARY+=("$(printf '%-6s configure %4ds  build %4ds  test %4ds  total %4ds' \
    fuzz $((t1 - t0)) $((t2 - t1)) $((t3 - t2)) $((t3 - t0)))")
}

# The interpreter the Python module is built for and tested with: the first
# one that has numpy and pytest (a pyenv shim ahead of Debian's python3 may
# have neither).
python_for_module() {
  local py
  for py in python3 /usr/bin/python3; do
    if command -v "$py" >/dev/null 2>&1 && "$py" -c 'import numpy, pytest' >/dev/null 2>&1; then
      command -v "$py"
      return 0
    fi
  done
  echo "test.sh: no python3 with numpy and pytest (scripts/install-deps.sh installs them)" >&2
  return 1
}

for stage in "${STAGES[@]}"; do
  case "$stage" in
    gcc)
      [[ -n "${SKIP_GCC:-}" ]] && continue
      PYTHON_FOR_MODULE=$(python_for_module)
      run_stage gcc g++ Release -- -DSTREAMCLUST_TEST_CXX20=OFF \
        -DSTREAMCLUST_PYTHON=ON -DPython3_EXECUTABLE="$PYTHON_FOR_MODULE"
      ;;
    clang)
      [[ -n "${SKIP_CLANG:-}" ]] && continue
      # Benchmarks are timed in the gcc stage; sanitized they would measure nothing.
      # The slow test files (tests/CMakeLists.txt) run once, in the gcc stage.
      # Header self-containment and FMA contraction are checked once, in the gcc stage.
      # The oracle runs a pairwise cover of the policy combinations (the whole
      # product is the gcc stage's): tests/CMakeLists.txt.
      run_stage clang clang++-14 Debug -LE "bench|slow" -- -DSTREAMCLUST_SANITIZE=ON \
        -DSTREAMCLUST_TEST_ORACLE_COMBOS=pairwise \
        -DSTREAMCLUST_TEST_CXX17=OFF -DSTREAMCLUST_BUILD_BENCH=OFF -DSTREAMCLUST_HEADER_CHECK=OFF \
        -DSTREAMCLUST_TEST_FMA=OFF
      ;;
    fuzz)
      [[ -n "${SKIP_FUZZ:-}" ]] && continue
      run_fuzz_stage
      ;;
    *)
      echo "test.sh: unknown stage '$stage' (known: gcc clang fuzz)" >&2
      exit 2
      ;;
  esac
done

echo
CURRENT_STAGE=""
echo "=== test.sh: all stages passed in $((SECONDS - T_ALL))s ==="
print_summary
