#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the libFuzzer targets (fuzz/, clang-14, -DSTREAMCLUST_FUZZ=ON) and
# runs each for SECONDS on a copy of its seed corpus, with its dictionary
# (docs/fuzzing.md). Exits non-zero when any target finds a crash, a leak,
# a timeout or an out-of-memory input; the inputs are collected in
# $BUILD_DIR/artifacts/<target>/ and named in the summary.
#
# Usage:  scripts/fuzz.sh [--phase configure|build|run] [SECONDS] [TARGET...]
#         e.g. scripts/fuzz.sh 10 fuzz_csv fuzz_pcd
#         SECONDS per target (default 60); default targets: all of them;
#         --phase: only that step (default: configure, build, run).
# Environment:
#   JOBS=2               parallel build jobs
#   RUN_JOBS=JOBS        targets fuzzed at once (each is one thread)
#   BUILD_DIR=build/fuzz where the targets, corpora and artifacts go
#   CXX_FUZZ=clang++-14  the compiler (clang with libFuzzer)
#   KEEP_CORPUS=1        keep each target's working corpus from earlier runs
#                        (a campaign in several runs); default: a fresh copy of the seeds
#   SKIP_BUILD=1         run the targets already built
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

ALL_TARGETS=(fuzz_csv fuzz_pcd fuzz_ply fuzz_kitti fuzz_lvx fuzz_bag fuzz_mcap fuzz_db3 fuzz_ros_message fuzz_lzf fuzz_tum
             fuzz_cli_options fuzz_engine fuzz_livox_sdk2_packet fuzz_livox_sdk2_control fuzz_livox_sdk1_packet
             fuzz_livox_sdk1_control)
PHASE=all
if [[ $# -gt 1 && "$1" == "--phase" ]]; then
  PHASE=$2
  shift 2
fi
case "$PHASE" in
  all | configure | build | run) ;;
  *) echo "fuzz.sh: unknown phase '$PHASE' (known: configure build run)" >&2; exit 2 ;;
esac
SECONDS_PER_TARGET=60
if [[ $# -gt 0 && "$1" =~ ^[0-9]+$ ]]; then
  SECONDS_PER_TARGET=$1
  shift
fi
TARGETS=("$@")
EVERY_TARGET=
[[ ${#TARGETS[@]} -eq 0 ]] && TARGETS=("${ALL_TARGETS[@]}") && EVERY_TARGET=1
for t in "${TARGETS[@]}"; do
  if [[ ! " ${ALL_TARGETS[*]} " =~ " $t " ]]; then
    echo "fuzz.sh: unknown target '$t' (known: ${ALL_TARGETS[*]})" >&2
    exit 2
  fi
done

JOBS=${JOBS:-2}
BUILD_DIR=${BUILD_DIR:-build/fuzz}
CXX_FUZZ=${CXX_FUZZ:-clang++-14}

# Per target: the dictionary (fuzz/dict/, none for binary-only inputs) and
# the longest input [bytes]: a few seeds' worth, so that executions stay short.
dict_of() {
  case "$1" in
    fuzz_csv) echo fuzz/dict/csv.dict ;;
    fuzz_pcd) echo fuzz/dict/pcd.dict ;;
    fuzz_ply) echo fuzz/dict/ply.dict ;;
    fuzz_lvx) echo fuzz/dict/lvx.dict ;;
    fuzz_bag) echo fuzz/dict/bag.dict ;;
    fuzz_mcap) echo fuzz/dict/mcap.dict ;;
    fuzz_tum) echo fuzz/dict/tum.dict ;;
    fuzz_cli_options) echo fuzz/dict/cli.dict ;;
    fuzz_livox_sdk2_packet) echo fuzz/dict/livox_sdk2_packet.dict ;;
    fuzz_livox_sdk2_control) echo fuzz/dict/livox_sdk2_control.dict ;;
    fuzz_livox_sdk1_packet) echo fuzz/dict/livox_sdk1_packet.dict ;;
    fuzz_livox_sdk1_control) echo fuzz/dict/livox_sdk1_control.dict ;;
    *) echo "" ;;
  esac
}
max_len_of() {
  case "$1" in
    fuzz_kitti) echo 4096 ;;
    fuzz_lvx) echo 8192 ;;  # a few packages of about 1.4 KB
    fuzz_bag | fuzz_mcap | fuzz_db3) echo 40960 ;;  # the seed recordings (15-38 KB)
    fuzz_ros_message) echo 8192 ;;  # one message (2.3-6 KB)
    fuzz_tum) echo 8192 ;;
    fuzz_cli_options) echo 2048 ;;
    fuzz_livox_sdk1_packet) echo 2048 ;;  # one datagram (42-1362 bytes)
    fuzz_livox_sdk1_control) echo 512 ;;  # one frame (15-34 bytes in a session)
    fuzz_engine) echo 12288 ;;  # ~2048 points, the scenario's own cap
    fuzz_livox_sdk2_packet | fuzz_livox_sdk2_control) echo 2048 ;;  # one datagram (1380 B; control <= 1400 B)
    *) echo 16384 ;;
  esac
}

T_ALL=$SECONDS
wants() { [[ "$PHASE" == all || "$PHASE" == "$1" ]]; }
if [[ -z "${SKIP_BUILD:-}" ]] && wants configure; then
  echo "=== fuzz.sh: configuring $BUILD_DIR ($CXX_FUZZ) ==="
  cmake -S . -B "$BUILD_DIR" -DCMAKE_CXX_COMPILER="$CXX_FUZZ" -DCMAKE_BUILD_TYPE=Debug -DSTREAMCLUST_FUZZ=ON \
    -DSTREAMCLUST_BUILD_TESTS=OFF -DSTREAMCLUST_BUILD_EXAMPLES=OFF -DSTREAMCLUST_BUILD_BENCH=OFF \
    -DSTREAMCLUST_BUILD_TOOLS=OFF -DSTREAMCLUST_PYTHON=OFF >/dev/null
fi
if [[ -z "${SKIP_BUILD:-}" ]] && wants build; then
  echo "=== fuzz.sh: building ${TARGETS[*]} ==="
  # All of them as one goal (fuzz/CMakeLists.txt: streamclust_fuzz_all), so
  # that the Makefile generator builds them in parallel.
  if [[ -n "$EVERY_TARGET" ]]; then
    cmake --build "$BUILD_DIR" -j "$JOBS" --target streamclust_fuzz_all
  else
    cmake --build "$BUILD_DIR" -j "$JOBS" --target "${TARGETS[@]}"
  fi
fi
T_BUILD=$((SECONDS - T_ALL))
wants run || exit 0

# One target's run; its summary line goes to logs/<target>.summary.
run_target() {
  local t=$1
  local exe="$BUILD_DIR/fuzz/$t" corpus="$BUILD_DIR/corpus/$t" artifacts="$BUILD_DIR/artifacts/$t"
  local log="$BUILD_DIR/logs/$t.log"
  [[ -z "${KEEP_CORPUS:-}" ]] && rm -rf "$corpus"
  mkdir -p "$corpus" "$artifacts"
  cp -n fuzz/corpus/"$t"/* "$corpus"/ 2>/dev/null || true
  rm -f "$artifacts"/crash-* "$artifacts"/leak-* "$artifacts"/timeout-* "$artifacts"/oom-*
  local -a args=(-max_total_time="$SECONDS_PER_TARGET" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048
                 -max_len="$(max_len_of "$t")" -print_final_stats=1 -artifact_prefix="$artifacts/")
  local dict
  dict=$(dict_of "$t")
  [[ -n "$dict" ]] && args+=(-dict="$dict")
  echo "=== $t: ${SECONDS_PER_TARGET}s, corpus $corpus ==="
  local rc=0 execs final cov ft units result found
  "$exe" "${args[@]}" "$corpus" >"$log" 2>&1 || rc=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  final=$(grep -E '^#[0-9]+.*(DONE|cov:)' "$log" | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$final")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$final")
  units=$(find "$corpus" -type f | wc -l)
  if [[ $rc -eq 0 ]]; then
    result=ok
  else
    found=$(find "$artifacts" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | head -3 | tr '\n' ' ')
    result="FAILED (exit $rc): ${found:-no artifact, see $log}"
    grep -E 'ERROR|fuzz: |SUMMARY|runtime error|Test unit written' "$log" | head -8 >&2 || true
  fi
  printf '%-17s %4ds  execs %9s  cov %6s  ft %7s  corpus %5s  %s\n' \
    "$t" "$SECONDS_PER_TARGET" "${execs:-?}" "${cov:-?}" "${ft:-?}" "$units" "$result" >"$BUILD_DIR/logs/$t.summary"
}

# The targets run RUN_JOBS at a time (each fuzzer is one thread).
RUN_JOBS=${RUN_JOBS:-$JOBS}
mkdir -p "$BUILD_DIR/logs"
for t in "${TARGETS[@]}"; do
  rm -f "$BUILD_DIR/logs/$t.summary"
  while [[ $(jobs -rp | wc -l) -ge $RUN_JOBS ]]; do wait -n || true; done
  run_target "$t" &
done
wait
declare -a SUMMARY=() FAILED=()
for t in "${TARGETS[@]}"; do
  line=$(cat "$BUILD_DIR/logs/$t.summary" 2>/dev/null || printf '%-17s no summary: the run was interrupted' "$t")
  SUMMARY+=("$line")
  [[ "$line" == *" ok" ]] || FAILED+=("$t")
done

echo
BUILT=""
[[ $T_BUILD -gt 0 ]] && BUILT="build ${T_BUILD}s, "
echo "=== fuzz.sh: ${BUILT}${#TARGETS[@]} targets x ${SECONDS_PER_TARGET}s, total $((SECONDS - T_ALL))s (logs: $BUILD_DIR/logs) ==="
for line in "${SUMMARY[@]}"; do echo "  $line"; done
if [[ ${#FAILED[@]} -gt 0 ]]; then
  echo "fuzz.sh: ${#FAILED[@]} target(s) failed: ${FAILED[*]} (inputs in $BUILD_DIR/artifacts/<target>/; rerun one with" \
       "$BUILD_DIR/fuzz/<target> <input>)" >&2
  exit 1
fi
