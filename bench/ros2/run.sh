#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# The ROS 2 node's figures (docs/performance.md, "ROS 2"): `streamclust ros2`
# against `streamclust replay --to ros2://` (a simulated LiDAR published as
# the Livox driver does), two processes over Cyclone DDS on loopback.
#   bench/ros2/run.sh [STREAMCLUST]      (default build/bench-run/tools/streamclust)
# For each objects preset (Mid-360 at 200 kHz, Avia at 240 kHz) and message
# length (0.1 s: the driver's default 10 Hz; 0.01 s: its 100 Hz), at 1x:
#   latency   the P99 time from a message's arrival to the publication of
#             the first retrieval holding its points, and to the one holding
#             all of them (which waits for the next message); the cycle
#             latency; what was dropped or lost (nothing is the target).
# Then overload (the Mid-360 at OVERLOAD x with a queue of 8 messages):
# what is dropped is counted and resident memory stays bounded.
# Results: each run's report (OUT/NAME.json), resident memory (OUT/NAME.rss,
# kB each second), and the table on stdout and in OUT/table.txt.
#
# Knobs: SECONDS_PER_RUN (default 20), OVERLOAD (default 4), OUT (default build/bench-ros2).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
TOOL=${1:-$ROOT/build/bench-run/tools/streamclust}
SECONDS_PER_RUN=${SECONDS_PER_RUN:-20}
OVERLOAD=${OVERLOAD:-4}
OUT=${OUT:-$ROOT/build/bench-ros2}
DOMAIN=${DOMAIN:-91}
mkdir -p "$OUT"
[[ -x "$TOOL" ]] || { echo "bench/ros2/run.sh: no tool at $TOOL (build it, or pass its path)" >&2; exit 2; }

: > "$OUT/table.txt"
say() { echo "$*" | tee -a "$OUT/table.txt"; }
# run_one NAME SENSOR PRESET MESSAGE_SECONDS SPEED QUEUE: one node against one replay.
run_one() {
  local name=$1 sensor=$2 preset=$3 message=$4 speed=$5 queue=$6
  "$TOOL" ros2 --dds-loopback --domain "$DOMAIN" --preset "$preset" --queue "$queue" --idle-exit 2 --wait 300 \
    --report "$OUT/$name.json" --no-status -q &
  local node_pid=$!
  : > "$OUT/$name.rss"
  ( while kill -0 $node_pid 2>/dev/null; do
      awk '/VmRSS/ {print $2}' /proc/$node_pid/status 2>/dev/null >> "$OUT/$name.rss" || true
      sleep 1
    done ) &
  local rss_pid=$!
  "$TOOL" replay --simulate --sensor "$sensor" --scene office --seconds "$SECONDS_PER_RUN" --speed "$speed" \
    --message-seconds "$message" --to ros2:///livox/lidar --dds-loopback --domain "$DOMAIN" --wait 300 -q
  wait $node_pid
  wait $rss_pid 2>/dev/null || true
}

summary() {  # NAME: one line of the report's figures
  python3 - "$OUT/$1.json" "$OUT/$1.rss" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); r = d["ros2"]; m = r["messages"]; l = r["latency"]
rss = [int(x) for x in open(sys.argv[2]).read().split()] or [0]
print(f'{l["median_ms"]:.1f} {l["p99_ms"]:.1f} {l["complete_median_ms"]:.1f} {l["complete_p99_ms"]:.1f} '
      f'{d["totals"]["latency_us"]["median"]/1000:.2f} {d["totals"]["latency_us"]["p99"]/1000:.2f} '
      f'{m["dropped"] + m["lost"]} {m["received"]} {rss[0]} {max(rss)} {rss[-1]}')
PY
}

say "preset message speed | latency median/P99 ms | complete median/P99 ms | cycle median/P99 ms | dropped+lost / received | RSS first/max/last kB"
row() {  # NAME SENSOR PRESET MESSAGE SPEED QUEUE
  run_one "$@"
  read -r a b c d e f g h i j k < <(summary "$1")
  say "$3 $4s ${5}x | $a / $b | $c / $d | $e / $f | $g / $h | $i / $j / $k"
}
for sensor in mid360 avia; do
  for message in 0.1 0.01; do
    row "objects-$sensor-m$message" "$sensor" "objects-$sensor" "$message" 1 64
  done
done
row "overload-x$OVERLOAD" mid360 objects-mid360 0.1 "$OVERLOAD" 8
