#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# The live pipeline's figures (docs/performance.md, "Live"): `streamclust
# live` on loopback against `streamclust replay` (the emulated LiDAR), both
# real processes with real UDP sockets.
#   bench/live/run.sh [STREAMCLUST]      (default build/bench-run/tools/streamclust)
# For each sensor and preset (Mid-360 at 200 kHz, Avia at 240 kHz; carc and
# objects presets):
#   latency   at the sensor's rate: the P99 time from a packet's arrival to
#             the first retrieval that holds its points (steady state), the
#             cycle latency, and what was dropped (nothing is the target);
#   rate      the replay's speed raised (1x, 2x, ...) until the run drops or
#             loses a packet or falls behind: the highest sustained multiple;
#   soak      (SOAK_SECONDS > 0) the Mid-360 objects preset at 1x for that
#             long: resident memory every second, drops.
# Results: each run's live report (OUT/NAME.json) and resident memory
# (OUT/NAME.rss, kB each second), and the table on stdout and in OUT/table.txt.
#
# Knobs: SECONDS_PER_RUN (default 20), SPEEDS (default "1 2 3 4 5 6 8"),
#        SOAK_SECONDS (default 0), OUT (default build/bench-live).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
TOOL=${1:-$ROOT/build/bench-run/tools/streamclust}
SECONDS_PER_RUN=${SECONDS_PER_RUN:-20}
SPEEDS=${SPEEDS:-"1 2 3 4 5 6 8"}
SOAK_SECONDS=${SOAK_SECONDS:-0}
OUT=${OUT:-$ROOT/build/bench-live}
mkdir -p "$OUT"
[[ -x "$TOOL" ]] || { echo "bench/live/run.sh: no tool at $TOOL (build it, or pass its path)" >&2; exit 2; }

PORT=47901
: > "$OUT/table.txt"
say() { echo "$*" | tee -a "$OUT/table.txt"; }
# run_one NAME SENSOR PRESET SPEED SECONDS: one live run against one replay;
# writes $OUT/NAME.json (the live report) and $OUT/NAME.rss (kB per second).
run_one() {
  local name=$1 sensor=$2 preset=$3 speed=$4 seconds=$5
  local url="livox-sdk2://127.0.0.1:$PORT" protocol=sdk2 device=127.0.0.2
  if [[ $sensor == avia ]]; then url="livox-sdk1://127.0.0.1:$((PORT + 100))"; device=127.0.0.3; fi
  "$TOOL" live "$url" --preset "$preset" --idle-exit 1 --wait 300 --report "$OUT/$name.json" --no-status -q &
  local live_pid=$!
  sleep 0.5
  : > "$OUT/$name.rss"
  ( while kill -0 $live_pid 2>/dev/null; do
      awk '/VmRSS/ {print $2}' /proc/$live_pid/status 2>/dev/null >> "$OUT/$name.rss" || true
      sleep 1
    done ) &
  local rss_pid=$!
  "$TOOL" replay --simulate --sensor "$sensor" --scene office --seconds "$seconds" --to "$url" \
    --device-address $device --speed "$speed" -q
  wait $live_pid
  wait $rss_pid 2>/dev/null || true
}

summary() {  # NAME: one line of the report's figures
  python3 - "$OUT/$1.json" "$OUT/$1.rss" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); l = d["live"]; p = l["packets"]
rss = [int(x) for x in open(sys.argv[2]).read().split()] or [0]
dropped = p["queue_drops"] + p.get("kernel_drops", 0) + p["lost"]
print(f'{l["latency"]["median_ms"]:.1f} {l["latency"]["p99_ms"]:.1f} {d["totals"]["latency_us"]["median"]/1000:.2f} '
      f'{d["totals"]["latency_us"]["p99"]/1000:.2f} {dropped} {p["returns"]} {rss[0]} {max(rss)} {rss[-1]}')
PY
}

say "sensor preset speed | latency median/P99 ms | cycle median/P99 ms | dropped+lost | returns | RSS first/max/last kB"
for sensor in mid360 avia; do
  for family in carc objects; do
    preset="$family-$sensor"
    for speed in $SPEEDS; do
      name="$preset-x$speed"
      run_one "$name" "$sensor" "$preset" "$speed" "$SECONDS_PER_RUN"
      read -r lat_med lat_p99 cyc_med cyc_p99 dropped returns rss0 rssmax rsslast < <(summary "$name")
      say "$sensor $preset ${speed}x | $lat_med / $lat_p99 | $cyc_med / $cyc_p99 | $dropped | $returns | $rss0 / $rssmax / $rsslast"
      [[ $dropped -gt 0 ]] && break  # the highest sustained multiple is the last speed without drops
    done
  done
done
if [[ $SOAK_SECONDS -gt 0 ]]; then
  run_one soak mid360 objects-mid360 1 "$SOAK_SECONDS"
  read -r lat_med lat_p99 cyc_med cyc_p99 dropped returns rss0 rssmax rsslast < <(summary soak)
  say "soak mid360 objects-mid360 1x ${SOAK_SECONDS}s | $lat_med / $lat_p99 | $cyc_med / $cyc_p99 | $dropped | $returns | $rss0 / $rssmax / $rsslast"
fi
