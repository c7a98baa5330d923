# SPDX-License-Identifier: MIT
# Shared by the evaluation scripts (sourced, from the repository root):
#   evaluation_tool          sets TOOL to the streamclust binary: $TOOL when
#                            given, else one built in Release into $BUILD_DIR
#   evaluation_run_jobs LIST OUT PREFIX
#                            runs `streamclust evaluate` once per line of LIST
#                            (a run's name, then its arguments), JOBS at a time;
#                            each failure's first line goes to OUT/failed.txt and
#                            its whole message to stderr, after PREFIX

evaluation_tool() {
  if [[ -z "${TOOL:-}" ]]; then
    TOOL="$BUILD_DIR/tools/streamclust"
    cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=g++ -DSTREAMCLUST_BUILD_TESTS=OFF \
      -DSTREAMCLUST_BUILD_EXAMPLES=OFF -DSTREAMCLUST_BUILD_BENCH=OFF -DSTREAMCLUST_BUILD_TOOLS=ON >&2
    cmake --build "$BUILD_DIR" --target streamclust_tool -j "$JOBS" >&2
  fi
  TOOL=$(realpath "$TOOL")
}

evaluation_run_jobs() {
  local list=$1 out=$2 prefix=$3
  : >"$out/failed.txt"
  xargs -P "$JOBS" -L 1 bash -c 'name=$0; msg=$("'"$TOOL"'" evaluate "$@" 2>&1) ||
    { echo "$name: $(echo "$msg" | head -1)" >>"'"$out"'/failed.txt"; echo "'"$prefix"': run $name failed: $msg" >&2; }' <"$list"
}
