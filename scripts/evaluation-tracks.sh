#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The tracking evaluation of docs/evaluation.md (section "Tracks"), in one
# command: builds the streamclust tool (Release, g++), runs
# `streamclust evaluate --tracks` (the objects tracker, the same boxes into
# the centroid tracker, and the centroid peer) over sensors {mid360, avia} x
# scenes {office, forest, street, hills} x {at rest, moving 1.2 m/s while
# turning at 0.2 rad/s}, 4 s streams, T_B = 0.5 s, 20 Hz, and rewrites the
# tables between the <!-- tracks:NAME --> markers of docs/evaluation.md.
#
#   JOBS=2              runs in parallel (default 2)
#   BUILD_DIR=build/evaluation
#   TOOL=path           use this streamclust binary (Release) instead of building one
#   QUICK=1             a smoke run: Mid-360, office and street, 2 s; no doc rewrite
#
# A run that fails is listed in failed.txt and in the doc.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

JOBS=${JOBS:-2}
BUILD_DIR=${BUILD_DIR:-build/evaluation}
QUICK=${QUICK:-}
OUT="$BUILD_DIR/results-tracks"
source scripts/lib/evaluation-common.sh
evaluation_tool

SENSORS="mid360 avia"
SCENES="office forest street hills"
DURATION=4
if [[ -n "$QUICK" ]]; then
  SENSORS="mid360"
  SCENES="office street"
  DURATION=2
fi
motion_args() {
  case "$1" in
    rest) echo "" ;;
    moving) echo "--speed 1.2 --yaw-rate 0.2" ;;
  esac
}

rm -rf "$OUT"
mkdir -p "$OUT"
JOBLIST="$OUT/jobs.txt"
: >"$JOBLIST"
for sensor in $SENSORS; do
  for scene in $SCENES; do
    for motion in rest moving; do
      name="trk_${sensor}_${scene}_${motion}"
      echo "$name --tracks --sensor $sensor --scene $scene $(motion_args "$motion") --duration $DURATION --seed 1" \
        "--json $OUT/$name.json --quiet" >>"$JOBLIST"
    done
  done
done
echo "evaluation-tracks: $(wc -l <"$JOBLIST") runs, $JOBS in parallel, results in $OUT" >&2
start=$(date +%s)
evaluation_run_jobs "$JOBLIST" "$OUT" evaluation-tracks
elapsed=$(($(date +%s) - start))
echo "evaluation-tracks: runs done in $elapsed s" >&2

if [[ -n "$QUICK" ]]; then
  echo "evaluation-tracks: QUICK run, docs left unchanged" >&2
  exit 0
fi

python3 - "$OUT" docs/evaluation.md "$elapsed" "$JOBS" <<'PY'
import glob, json, os, re, sys
out, doc_path, elapsed, jobs = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
runs = {}
for path in glob.glob(os.path.join(out, "trk_*.json")):
    with open(path) as f:
        runs[os.path.basename(path)[4:-5]] = json.load(f)
SENSORS = [("mid360", "Mid-360"), ("avia", "Avia")]
SCENES = ["office", "forest", "street", "hills"]
MOTIONS = [("rest", "at rest"), ("moving", "moving 1.2 m/s")]
METHODS = ["objects", "objects-centroid", "centroid"]

def method(run, name):
    for m in run["methods"]:
        if m["method"] == name:
            return m
    return None

def cells():
    for sensor, sensor_name in SENSORS:
        for scene in SCENES:
            for motion, motion_name in MOTIONS:
                yield sensor_name, scene, motion_name, runs.get(f"{sensor}_{scene}_{motion}")

def f3(v):
    return f"{v:.3f}"

tables = {}
# 1. Per cell: MOTA / IDF1 of each method, bold where the objects tracker beats the peer.
rows = ["| sensor | scene | motion | rated objects | MOTA objects / objects-centroid / centroid | IDF1 objects / objects-centroid / centroid | above the peer |",
        "|---|---|---|---|---|---|---|"]
above = 0
total = 0
for sensor_name, scene, motion_name, run in cells():
    if run is None:
        rows.append(f"| {sensor_name} | {scene} | {motion_name} | run failed | | | |")
        continue
    ms = [method(run, n) for n in METHODS]
    beat = ms[0]["mota"] > ms[2]["mota"] and ms[0]["idf1"] > ms[2]["idf1"]
    total += 1
    above += 1 if beat else 0
    lose = []
    if ms[0]["mota"] <= ms[2]["mota"]:
        lose.append("MOTA")
    if ms[0]["idf1"] <= ms[2]["idf1"]:
        lose.append("IDF1")
    rows.append(f"| {sensor_name} | {scene} | {motion_name} | {ms[0]['objects']} | "
                + " / ".join(f3(m["mota"]) for m in ms) + " | " + " / ".join(f3(m["idf1"]) for m in ms)
                + " | " + ("yes" if beat else "no (" + ", ".join(lose) + ")") + " |")
tables["cells"] = "\n".join(rows)

# 2. The targets per cell, objects tracker.
rows = ["| sensor | scene | motion | velocity RMSE all / steady [m/s] (matches) | static still | id switches / object / 4 s | recall | precision | MOTP [m] | BEV IoU | P99 cost [ms] |",
        "|---|---|---|---|---|---|---|---|---|---|---|"]
for sensor_name, scene, motion_name, run in cells():
    if run is None:
        continue
    m = method(run, "objects")
    rows.append(f"| {sensor_name} | {scene} | {motion_name} | {m['velocity_rmse_mps']:.2f} / {m['steady_velocity_rmse_mps']:.2f} "
                f"({m['velocity_samples']} / {m['steady_velocity_samples']}) | {m['still_share']:.3f} | "
                f"{m['id_switches_per_object_4s']:.3f} | {m['recall']:.3f} | {m['precision']:.3f} | {m['motp_m']:.3f} | "
                f"{m['mean_bev_iou']:.3f} | {m['cost_p99_ms']:.2f} |")
tables["targets"] = "\n".join(rows)

# 3. Pooled over the cells, per method.
rows = ["| method | MOTA | IDF1 | recall | precision | id switches / object / 4 s | velocity RMSE all / steady [m/s] | static still | BEV IoU |",
        "|---|---|---|---|---|---|---|---|---|"]
for name in METHODS:
    ms = [method(r, name) for r in runs.values()]
    ms = [m for m in ms if m]
    if not ms:
        continue
    def mean(key):
        return sum(m[key] for m in ms) / len(ms)
    vel = sum(m["velocity_rmse_mps"] ** 2 * m["velocity_samples"] for m in ms) / max(1, sum(m["velocity_samples"] for m in ms))
    steady = sum(m["steady_velocity_rmse_mps"] ** 2 * m["steady_velocity_samples"] for m in ms) / max(1, sum(m["steady_velocity_samples"] for m in ms))
    still = sum(m["still_share"] * m["static_samples"] for m in ms) / max(1, sum(m["static_samples"] for m in ms))
    rows.append(f"| {name} | {mean('mota'):.3f} | {mean('idf1'):.3f} | {mean('recall'):.3f} | {mean('precision'):.3f} | "
                f"{mean('id_switches_per_object_4s'):.3f} | {vel ** 0.5:.2f} / {steady ** 0.5:.2f} | {still:.3f} | {mean('mean_bev_iou'):.3f} |")
failed = open(os.path.join(out, "failed.txt")).read().strip()
rows.append("")
rows.append(f"Means over {len(runs)} cells (velocity and stillness pooled over matches); the objects tracker is above "
            f"the peer in MOTA and IDF1 in {above} of {total} cells. Run time: {elapsed} s with {jobs} jobs."
            + (f" Failed runs: {failed}." if failed else ""))
tables["pooled"] = "\n".join(rows)

with open(doc_path) as f:
    doc = f.read()
for name, table in tables.items():
    pattern = re.compile(r"(<!-- tracks:%s -->\n)(?:.*?\n)?(<!-- /tracks:%s -->)" % (re.escape(name), re.escape(name)), re.S)
    if not pattern.search(doc):
        sys.exit(f"evaluation-tracks: marker tracks:{name} missing from {doc_path}")
    doc = pattern.sub(lambda m: m.group(1) + table + "\n" + m.group(2), doc)
with open(doc_path, "w") as f:
    f.write(doc)
print(f"evaluation-tracks: {doc_path} updated", file=sys.stderr)
PY
