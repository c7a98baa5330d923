#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# make_long_recordings.sh -- several minutes of a simulated Livox Mid-360 as CSV, ROS 1 bag,
# rosbag2 SQLite bag and MCAP, for measuring the readers' memory (measure_memory.sh).
#
#   bash bench/recordings/make_long_recordings.sh [SECONDS] [OUTDIR]
#        SECONDS  stream length (default 180: 36 M points at 200 kHz)
#        OUTDIR   output folder (default ${TMPDIR:-/tmp}/streamclust-recordings-${SECONDS}s)
#
# Writes into OUTDIR (STEM = office_${SECONDS}s):
#   STEM.csv + STEM.tum   `streamclust simulate --sensor mid360 --scene office --start-time 1700000000`
#                         (x,y,z,intensity,t,label; t in Unix seconds) -- the baseline
#   STEM.bag              ROS 1 bag, livox_ros_driver/CustomMsg on /livox/lidar, lz4 chunks
#   STEM_db3/             rosbag2 bag folder: metadata.yaml + STEM_db3_0.db3 (CDR CustomMsg)
#   STEM.mcap             MCAP, ROS 2 profile, CDR livox_ros_driver2/msg/CustomMsg, zstd chunks
#   make.log              wall time and peak RSS of every step
# One message per 100 ms of stream time; timebase = its first point's time (ns), offset_time =
# point time - timebase (ns), reflectivity = intensity rounded and clamped to 0..255
# (csv_to_recordings.py).  The recordings are written by independent tooling -- Debian's
# python3-rosbag (ROS 1), Python's sqlite3 (rosbag2), @mcap/core 2.2.2 (MCAP) -- never by this
# project's code.  The conversion streams: CSV blocks of 8 MiB, one message at a time.
# Finally every recording is checked to read the CSV's number of points and time span (`streamclust info`).
#
# Needs: the tool built (cmake --build build/dev --target streamclust_tool; or STREAMCLUST=path),
# Debian's /usr/bin/python3 with python3-rosbag, python3-genpy, python3-genmsg, python3-roslz4,
# python3-numpy; node >= 20 + npm with the registry reachable (the npm packages go to a temporary
# folder, deleted at the end).  Disk for 180 s: 3.9 GB (the CSV is 2 GB), 4.6 GB while converting.
# simulate holds the whole stream in memory: 2 GiB for 180 s.
# Runs on one core (nothing in parallel).
set -euo pipefail
export PYTHONDONTWRITEBYTECODE=1 OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
SECONDS_ARG="${1:-180}"
OUTDIR="${2:-${TMPDIR:-/tmp}/streamclust-recordings-${SECONDS_ARG}s}"
START_TIME=1700000000
PY=/usr/bin/python3   # Debian's python: a pyenv python on PATH lacks the ROS modules
STREAMCLUST="${STREAMCLUST:-$ROOT/build/dev/tools/streamclust}"
NPM_PKGS=("@mcap/core@2.2.2" "zstd-codec@0.1.5" "lz4js@0.2.0")

case "$SECONDS_ARG" in ''|*[!0-9]*) echo "make_long_recordings.sh: SECONDS must be whole seconds" >&2; exit 2;; esac
if [ "$SECONDS_ARG" -lt 1 ] || [ "$SECONDS_ARG" -gt 990 ]; then
  echo "make_long_recordings.sh: SECONDS must be in 1..990" >&2; exit 2
fi
[ -x "$STREAMCLUST" ] || {
  echo "make_long_recordings.sh: $STREAMCLUST not found; build it: cmake --build build/dev --target streamclust_tool -j1" >&2
  exit 1
}
"$PY" -c 'import rosbag, genpy, genmsg, roslz4, sqlite3, numpy' || {
  echo "make_long_recordings.sh: $PY lacks rosbag/genpy/genmsg/roslz4/numpy" >&2; exit 1
}
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "make_long_recordings.sh: node + npm needed" >&2; exit 1
fi

mkdir -p "$OUTDIR"
OUTDIR="$(cd "$OUTDIR" && pwd)"
STEM="office_${SECONDS_ARG}s"
LOG="$OUTDIR/make.log"
TMP="$(mktemp -d "${TMPDIR:-/tmp}/long-recordings.XXXXXX")"
trap 'rm -rf "$TMP"; rm -f "$OUTDIR/$STEM".mcap_input.*' EXIT
: > "$LOG"

# step NAME COMMAND...: runs COMMAND, logs its wall time and peak RSS
step() {
  local name="$1"; shift
  echo "== $name"
  /usr/bin/time -o "$TMP/time" -f "%e s wall, %M KB peak RSS" "$@"
  printf '%-28s %s\n' "$name" "$(cat "$TMP/time")" | tee -a "$LOG"
}

step "simulate (CSV)" "$STREAMCLUST" simulate --sensor mid360 --scene office --seconds "$SECONDS_ARG" \
  --start-time "$START_TIME" --out "$OUTDIR/$STEM.csv"
step "convert (bag, db3)" "$PY" "$HERE/csv_to_recordings.py" "$OUTDIR/$STEM.csv" "$OUTDIR" "$STEM"

echo "== npm install ${NPM_PKGS[*]} (into $TMP/npm)"
mkdir -p "$TMP/npm"
echo '{"name":"long-recordings","private":true}' > "$TMP/npm/package.json"
(cd "$TMP/npm" && npm install --no-audit --no-fund --ignore-scripts --save-exact --prefix "$TMP/npm" \
  "${NPM_PKGS[@]}" >/dev/null)
step "write MCAP (zstd)" node "$HERE/write_mcap.mjs" "$TMP/npm" "$OUTDIR/$STEM.mcap_input.json" \
  "$OUTDIR/$STEM.mcap_input.bin" "$OUTDIR/$STEM.mcap" zstd
rm -f "$OUTDIR/$STEM".mcap_input.*

echo "== check: every recording reads the CSV's points"
points_of() { "$STREAMCLUST" info "$1" | awk '$1 == "points:" {print $2; exit}'; }
span_of() { "$STREAMCLUST" info "$1" | awk '$1 == "time:" {print $4 "-" $7; exit}'; }
want="$(points_of "$OUTDIR/$STEM.csv")"
want_span="$(span_of "$OUTDIR/$STEM.csv")"
status=0
for f in "$OUTDIR/$STEM.csv" "$OUTDIR/$STEM.bag" "$OUTDIR/${STEM}_db3" "$OUTDIR/$STEM.mcap"; do
  got="$(points_of "$f")"; span="$(span_of "$f")"
  if [ "$got" = "$want" ] && [ "$span" = "$want_span" ]; then mark=ok; else mark=MISMATCH; status=1; fi
  printf '%-40s %12s points, times %s  %s\n' "$(basename "$f")" "$got" "$span" "$mark" | tee -a "$LOG"
done
echo "== files"
du -sb "$OUTDIR/$STEM.csv" "$OUTDIR/$STEM.bag" "$OUTDIR/${STEM}_db3" "$OUTDIR/$STEM.mcap" | tee -a "$LOG"
exit "$status"
