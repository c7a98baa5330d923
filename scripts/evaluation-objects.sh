#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The objects evaluation of docs/evaluation.md (section "Objects"): builds the
# streamclust tool (Release, g++), runs `streamclust evaluate --objects` over
# sensors {mid360, avia} x scenes {office, forest, street, hills} x mounts
# {level, pitched 15 deg, pitched 30 deg, upside down} x {at rest, moving with
# poses, moving without poses} (3 s, seed 1, --verify), then rewrites the
# tables between the <!-- objects:NAME --> markers of docs/evaluation.md.
#
#   JOBS=2              runs in parallel (default 2)
#   BUILD_DIR=build/evaluation
#   TOOL=path           use this streamclust binary (Release) instead of building one
#   QUICK=1             a smoke run: Mid-360, office and hills, level and upside
#                       down, 1.5 s streams; no doc rewrite
#
# A run that fails (or whose --verify finds a difference: exit 3) is listed in
# failed.txt and in the doc. The committed run: 96 runs in 330 s with JOBS=2
# (plus the build), 4793 retrievals verified.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

JOBS=${JOBS:-2}
BUILD_DIR=${BUILD_DIR:-build/evaluation}
QUICK=${QUICK:-}
OUT="$BUILD_DIR/results-objects"
if [[ -z "${TOOL:-}" ]]; then
  TOOL="$BUILD_DIR/tools/streamclust"
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=g++ -DSTREAMCLUST_BUILD_TESTS=OFF \
    -DSTREAMCLUST_BUILD_EXAMPLES=OFF -DSTREAMCLUST_BUILD_BENCH=OFF -DSTREAMCLUST_BUILD_TOOLS=ON >&2
  cmake --build "$BUILD_DIR" --target streamclust_tool -j "$JOBS" >&2
fi
TOOL=$(realpath "$TOOL")

rm -rf "$OUT"
mkdir -p "$OUT"

SENSORS="mid360 avia"
SCENES="office forest street hills"
MOUNTS="level p15 p30 up"
MOTIONS="rest poses noposes"
DURATION=3
if [[ -n "$QUICK" ]]; then
  SENSORS="mid360"
  SCENES="office hills"
  MOUNTS="level up"
  DURATION=1.5
fi

mount_args() {
  case "$1" in
    level) echo "--mount 0,0,0" ;;
    p15) echo "--mount 0,15,0" ;;
    p30) echo "--mount 0,30,0" ;;
    up) echo "--mount 180,0,0" ;;  # 2.5 m above the ground (the tool's default upside down)
  esac
}
# Moving: 1.5 m/s forward while turning at 0.3 rad/s (4.5 m and 52 deg in 3 s).
motion_args() {
  case "$1" in
    rest) echo "" ;;
    poses) echo "--speed 1.5 --yaw-rate 0.3 --poses on" ;;
    noposes) echo "--speed 1.5 --yaw-rate 0.3 --poses off" ;;
  esac
}

JOBLIST="$OUT/jobs.txt"
: >"$JOBLIST"
for sensor in $SENSORS; do
  for scene in $SCENES; do
    for mount in $MOUNTS; do
      for motion in $MOTIONS; do
        name="obj_${sensor}_${scene}_${mount}_${motion}"
        echo "$name --objects --sensor $sensor --scene $scene $(mount_args "$mount") $(motion_args "$motion")" \
          "--duration $DURATION --seed 1 --verify --json $OUT/$name.json --quiet" >>"$JOBLIST"
      done
    done
  done
done

runs=$(wc -l <"$JOBLIST")
echo "evaluation-objects: $runs runs, $JOBS in parallel, results in $OUT" >&2
start=$(date +%s)
: >"$OUT/failed.txt"
xargs -P "$JOBS" -L 1 bash -c 'name=$0; msg=$("'"$TOOL"'" evaluate "$@" 2>&1) ||
  { echo "$name: $(echo "$msg" | head -1)" >>"'"$OUT"'/failed.txt"; echo "evaluation-objects: run $name failed: $msg" >&2; }' <"$JOBLIST"
elapsed=$(($(date +%s) - start))
echo "evaluation-objects: runs done in $elapsed s" >&2

if [[ -n "$QUICK" ]]; then
  echo "evaluation-objects: QUICK run, docs left unchanged" >&2
  exit 0
fi

python3 - "$OUT" docs/evaluation.md "$elapsed" <<'PY'
import glob, json, os, re, sys
out, doc_path, elapsed = sys.argv[1], sys.argv[2], int(sys.argv[3])

runs = {}
for path in glob.glob(os.path.join(out, "obj_*.json")):
    with open(path) as f:
        runs[os.path.basename(path)[:-5]] = json.load(f)

SENSORS = [("mid360", "Mid-360"), ("avia", "Avia")]
SCENES = ["office", "forest", "street", "hills"]
MOUNTS = [("level", "level"), ("p15", "pitch 15"), ("p30", "pitch 30"), ("up", "upside down")]
MOTIONS = [("rest", "at rest"), ("poses", "moving, poses"), ("noposes", "moving, no poses")]
PEERS = [("carc", "C-ARC (paper's preset)"), ("euclidean", "Euclidean 0.3 m"), ("frame", "RANSAC plane + Euclidean")]
TARGETS = {"ari": 0.85, "correct": 0.6, "object_point_coverage": 0.95, "ground_f1": 0.95}
TOL = 0.02

def mean(run, name):
    for m in run["methods"]:
        if m["name"] == name:
            return m["mean"]
    return None

def rated(run):
    return mean(run, "objects")["objects"] > 0

def targets(run):
    """Which targets the objects method meets in a run (None: no object rated)."""
    if not rated(run):
        return None
    o = mean(run, "objects")
    met = {k: o[k] >= v for k, v in TARGETS.items()}
    met["above_peers"] = all(o["correct"] > mean(run, p)["correct"] for p, _ in PEERS)
    return met

cells = [(s, sc, mo, mt) for s, _ in SENSORS for sc in SCENES for mo, _ in MOUNTS for mt, _ in MOTIONS]
def run_of(c):
    return runs.get("obj_%s_%s_%s_%s" % c)

tables = {}

# --- targets met, per motion
rows = ["| motion | cells with objects | ARI >= 0.85 | objects correct >= 0.6 | coverage >= 0.95 | ground F1 >= 0.95 | correct above every peer | all five |",
        "|---|---|---|---|---|---|---|---|"]
for mt, label in MOTIONS + [(None, "all")]:
    ts = [targets(run_of(c)) for c in cells if (mt is None or c[3] == mt) and run_of(c)]
    ts = [t for t in ts if t is not None]
    count = lambda k: sum(1 for t in ts if t[k])
    alls = sum(1 for t in ts if all(t.values()))
    rows.append(f"| {label} | {len(ts)} | {count('ari')} | {count('correct')} | {count('object_point_coverage')} | "
                f"{count('ground_f1')} | {count('above_peers')} | {alls} |")
tables["targets"] = "\n".join(rows)

# --- the objects preset against each peer
def verdict(a, b, higher_better=True):
    d = (a - b) if higher_better else (b - a)
    return "win" if d > TOL else ("loss" if d < -TOL else "tie")
rows = ["| peer | motion | cells | ARI (win/tie/loss) | objects correct | over-seg | under-seg | mean ARI objects / peer | mean correct objects / peer |",
        "|---|---|---|---|---|---|---|---|---|"]
for peer, plabel in PEERS:
    for mt, label in MOTIONS:
        cnt = {k: [0, 0, 0] for k in ["ari", "correct", "over_segmented", "under_segmented"]}
        sums = [0.0] * 4
        n = 0
        for c in cells:
            r = run_of(c)
            if c[3] != mt or r is None or not rated(r):
                continue
            o, p = mean(r, "objects"), mean(r, peer)
            n += 1
            for k, hb in [("ari", True), ("correct", True), ("over_segmented", False), ("under_segmented", False)]:
                cnt[k][["win", "tie", "loss"].index(verdict(o[k], p[k], hb))] += 1
            sums[0] += o["ari"]; sums[1] += p["ari"]; sums[2] += o["correct"]; sums[3] += p["correct"]
        if n == 0:
            continue
        w = lambda k: "/".join(str(x) for x in cnt[k])
        rows.append(f"| {plabel} | {label} | {n} | {w('ari')} | {w('correct')} | {w('over_segmented')} | "
                    f"{w('under_segmented')} | {sums[0]/n:.2f} / {sums[1]/n:.2f} | {sums[2]/n:.2f} / {sums[3]/n:.2f} |")
tables["peers"] = "\n".join(rows)

# --- per cell: two grids (scene rows, mount x motion columns)
def grid(fmt):
    head = "| sensor | scene | " + " | ".join(f"{ml}, {tl}" for _, ml in MOUNTS for _, tl in MOTIONS) + " |"
    rows = [head, "|---|---|" + "---|" * (len(MOUNTS) * len(MOTIONS))]
    for s, sl in SENSORS:
        for sc in SCENES:
            cellv = []
            for mo, _ in MOUNTS:
                for mt, _ in MOTIONS:
                    r = run_of((s, sc, mo, mt))
                    cellv.append("-" if r is None else fmt(r))
            rows.append(f"| {sl} | {sc} | " + " | ".join(cellv) + " |")
    return rows

def fmt_quality(r):
    if not rated(r):
        return "no object"
    o = mean(r, "objects")
    t = targets(r)
    text = f"{o['ari']:.2f} / {o['correct']:.2f}"
    return f"**{text}**" if all(t.values()) else text

def fmt_structure(r):
    o = mean(r, "objects")
    text = f"{o['object_point_coverage']:.2f} / {o['ground_f1']:.2f}"
    if r.get("scene_has_ceiling"):
        text += f" / {o['ceiling_f1']:.2f}"
    return text

tables["grid-quality"] = "\n".join(grid(fmt_quality))
tables["grid-structure"] = "\n".join(grid(fmt_structure))

# --- the objects method's cycle cost
rows = ["| sensor | cycle cost median, mean over cells [ms] | P99, worst cell [ms] | points per window |", "|---|---|---|---|"]
for s, sl in SENSORS:
    ms = [next(m for m in r["methods"] if m["name"] == "objects") for r in (run_of(c) for c in cells if c[0] == s) if r]
    if not ms:
        continue
    pts = [run_of(c)["window_points"] for c in cells if c[0] == s and run_of(c)]
    rows.append(f"| {sl} | {sum(m['cost_median_ms'] for m in ms)/len(ms):.2f} | {max(m['cost_p99_ms'] for m in ms):.2f} | "
                f"{sum(pts)/len(pts):.0f} |")
tables["cost"] = "\n".join(rows)

failed = [l.strip() for l in open(os.path.join(out, "failed.txt")) if l.strip()]
verified = sum(r["verify"]["retrievals"] for r in runs.values() if r.get("verify"))
tables["failed"] = (f"{len(runs)} runs in {elapsed} s; --verify: {verified} retrievals, "
                    + (f"{len(failed)} runs failed:\n\n" + "\n".join(f"- {l}" for l in sorted(failed)) if failed
                       else "every objects partition equal to the batch partition; no run failed."))

with open(doc_path) as f:
    doc = f.read()
for name, table in tables.items():
    pattern = re.compile(r"(<!-- objects:%s -->\n)(?:.*?\n)?(<!-- /objects:%s -->)" % (re.escape(name), re.escape(name)), re.S)
    if not pattern.search(doc):
        print(f"evaluation-objects: no marker for table '{name}' in {doc_path}", file=sys.stderr)
        continue
    doc = pattern.sub(lambda m: m.group(1) + table + "\n" + m.group(2), doc)
with open(doc_path, "w") as f:
    f.write(doc)
print(f"evaluation-objects: {len(runs)} results, tables written to {doc_path}", file=sys.stderr)
PY
