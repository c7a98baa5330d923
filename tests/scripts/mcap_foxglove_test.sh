#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# CTest mcap_foxglove: `streamclust cluster --mcap --tracks` read by an
# independent MCAP reader (tests/scripts/check_mcap.mjs: @mcap/core with CRCs,
# indexes, and every message decoded from its schema); the track boxes and
# arrows checked against the tracks CSV. Skipped (exit 77) without node
# or without the npm packages: install them with scripts/install-npm-tools.sh
# (npm registry needed) or point STREAMCLUST_NPM_PREFIX at them.
# Usage: mcap_foxglove_test.sh TOOL SOURCE_DIR WORK_DIR
set -euo pipefail
tool=$1 src=$2 work=$3
prefix=${STREAMCLUST_NPM_PREFIX:-$src/build/npm}
if ! command -v node >/dev/null || [[ ! -d "$prefix/node_modules/@mcap/core" ]]; then
  echo "skipped: needs node and @mcap/core in $prefix (scripts/install-npm-tools.sh)"
  exit 77
fi
mkdir -p "$work"
out="$work/clusters.mcap"
"$tool" cluster "$src/tests/data/recordings/ros2_custom_lz4.mcap" --preset carc-mid360 --window-time 0.2 \
  --quiet --mcap "$out" --labels "$work/labels.csv" --cycles all --tracks "$work/tracks.csv"
json=$(node "$src/tests/scripts/check_mcap.mjs" "$prefix" "$out")
echo "$json"
cycles=$(tail -n +2 "$work/labels.csv" | cut -d, -f1 | sort -u | wc -l)
python3 - "$json" "$cycles" "$work/tracks.csv" <<'PY'
import csv, json, sys
r, cycles = json.loads(sys.argv[1]), int(sys.argv[2])
rows = list(csv.DictReader(open(sys.argv[3])))
def need(ok, what):
    if not ok:
        sys.exit("mcap_foxglove: " + what)
need(r["profile"] == "ros2", "profile ros2")
need(r["topics"]["/streamclust/points"]["schema"] == "foxglove_msgs/msg/PointCloud", "PointCloud schema")
need(r["topics"]["/streamclust/clusters"]["schema"] == "foxglove_msgs/msg/SceneUpdate", "SceneUpdate schema")
need(r["topics"]["/streamclust/points"]["messages"] == cycles, "one PointCloud per cycle (%d)" % cycles)
need(r["indexed"] == r["messages"] == 3 * cycles, "the indexed reader finds every message")
tracks = r["topics"]["/streamclust/tracks"]
need(tracks["schema"] == "foxglove_msgs/msg/SceneUpdate" and tracks["messages"] == cycles, "one track update per cycle")
shown = [sum(1 for row in rows if int(row["cycle"]) == c and row["state"] != "tentative") for c in range(cycles)]
need(tracks["entities"] == shown, "one entity per confirmed or coasting track of the CSV, every cycle")
need(sum(shown) > 0 and tracks["cubes_turned"] > 0, "tracks shown, as boxes turned by their yaw")
moving = sum(1 for row in rows if row["state"] != "tentative" and (float(row["vx"]) != 0 or float(row["vy"]) != 0))
need(tracks["arrows"] == moving, "an arrow per moving track (%d)" % moving)
need(all(n > 0 for n in r["points"]) and all(e > 0 for e in r["entities"]), "points and cluster boxes in every cycle")
need(int(r["first_log_time"]) >= 1700000000 * 10**9, "log times in the stream's Unix time")
print("mcap_foxglove: ok,", cycles, "cycles")
PY

# Walkers in the simulated office: moving tracks, so arrows are written and decoded.
"$tool" simulate --sensor mid360 --scene office --seconds 2 --out "$work/office.csv" --quiet
"$tool" cluster "$work/office.csv" --preset objects-mid360 --sensor-height 1.0 --quiet \
  --mcap "$work/office.mcap" --tracks "$work/office_tracks.csv"
json=$(node "$src/tests/scripts/check_mcap.mjs" "$prefix" "$work/office.mcap")
python3 - "$json" "$work/office_tracks.csv" <<'PY'
import csv, json, sys
r = json.loads(sys.argv[1])
rows = list(csv.DictReader(open(sys.argv[2])))
def need(ok, what):
    if not ok:
        sys.exit("mcap_foxglove (office): " + what)
tracks = r["topics"]["/streamclust/tracks"]
moving = sum(1 for row in rows if row["state"] != "tentative" and (float(row["vx"]) != 0 or float(row["vy"]) != 0))
need(moving > 0, "walkers tracked as moving")
need(tracks["arrows"] == moving, "an arrow per moving track (%d, found %d)" % (moving, tracks["arrows"]))
print("mcap_foxglove: office ok,", moving, "moving track rows with arrows")
PY
