#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The objects evaluation of docs/evaluation.md (section "Objects"), in one
# command: builds the streamclust tool (Release, g++), then
#   1. SWEEP: the peers' settings. `streamclust evaluate --objects --method
#      euclidean,frame` over the matrix at rest and moving with poses (5 Hz
#      retrievals), Euclidean radii 0.3-0.7 m and, for the frame pipeline,
#      every (inlier tolerance 0.05-0.2 m, radius 0.3-0.7 m) pair; each peer's
#      setting with the best mean strict objects correct over those cells
#      is chosen (file chosen.txt);
#   2. MATRIX: `streamclust evaluate --objects --verify` with every method
#      (the peers at their chosen settings) over sensors {mid360, avia} x
#      scenes {office, forest, street, hills} x mounts {level, pitched 15
#      deg, pitched 30 deg, upside down} x {at rest, moving with poses}, and
#      the objects method alone moving without poses (the peers see the same
#      sensor-frame points as with poses: their scores are those of that run);
#   3. rewrites the tables between the <!-- objects:NAME --> markers of
#      docs/evaluation.md.
#
#   JOBS=2              runs in parallel (default 2)
#   BUILD_DIR=build/evaluation
#   TOOL=path           use this streamclust binary (Release) instead of building one
#   SWEEP=0             skip the sweep: the settings of the last one (BUILD_DIR/
#                       results-objects-sweep/chosen.txt), else EUCLIDEAN=0.3 FRAME=0.2/0.3
#   QUICK=1             a smoke run: Mid-360, office and hills, level and upside
#                       down, 1.5 s streams, a two-setting sweep; no doc rewrite
#
# A run that fails (or whose --verify finds a difference: exit 3) is listed in
# failed.txt and in the doc. The committed run's time is in the doc.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

JOBS=${JOBS:-2}
BUILD_DIR=${BUILD_DIR:-build/evaluation}
QUICK=${QUICK:-}
SWEEP=${SWEEP:-1}
OUT="$BUILD_DIR/results-objects"
SWEEP_OUT="$BUILD_DIR/results-objects-sweep"
source scripts/lib/evaluation-common.sh
evaluation_tool

SENSORS="mid360 avia"
SCENES="office forest street hills"
MOUNTS="level p15 p30 up"
DURATION=3
EUCLIDEAN_SWEEP="0.3,0.4,0.5,0.6,0.7"
FRAME_RADII_SWEEP="0.3,0.4,0.5,0.6,0.7"
PLANE_SWEEP="0.05,0.1,0.15,0.2"
if [[ -n "$QUICK" ]]; then
  SENSORS="mid360"
  SCENES="office hills"
  MOUNTS="level up"
  DURATION=1.5
  EUCLIDEAN_SWEEP="0.3,0.4"
  FRAME_RADII_SWEEP="0.3,0.4"
  PLANE_SWEEP="0.2"
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

start=$(date +%s)
# ---------------------------------------------------------------- 1. sweep
if [[ "$SWEEP" != 0 ]]; then
  rm -rf "$SWEEP_OUT"
  mkdir -p "$SWEEP_OUT"
  : >"$SWEEP_OUT/jobs.txt"
  for sensor in $SENSORS; do
    for scene in $SCENES; do
      for mount in $MOUNTS; do
        for motion in rest poses; do
          name="sweep_${sensor}_${scene}_${mount}_${motion}"
          echo "$name --objects --method euclidean,frame --sensor $sensor --scene $scene $(mount_args "$mount")" \
            "$(motion_args "$motion") --duration $DURATION --seed 1 --rate 5 --euclidean-distances $EUCLIDEAN_SWEEP" \
            "--frame-distances $FRAME_RADII_SWEEP --plane-distance $PLANE_SWEEP --json $SWEEP_OUT/$name.json --quiet" \
            >>"$SWEEP_OUT/jobs.txt"
        done
      done
    done
  done
  echo "evaluation-objects: sweep, $(wc -l <"$SWEEP_OUT/jobs.txt") runs, $JOBS in parallel, results in $SWEEP_OUT" >&2
  evaluation_run_jobs "$SWEEP_OUT/jobs.txt" "$SWEEP_OUT" evaluation-objects
  echo $(($(date +%s) - start)) >"$SWEEP_OUT/elapsed.txt"
  # The best mean strict objects correct per peer over the cells with objects.
  python3 - "$SWEEP_OUT" <<'PY'
import glob, json, os, sys
out = sys.argv[1]
sums = {}
for path in sorted(glob.glob(os.path.join(out, "sweep_*.json"))):
    with open(path) as f:
        run = json.load(f)
    for m in run["methods"]:
        if m["mean"]["objects"] <= 0:
            continue
        s = sums.setdefault(m["name"], [0.0, 0])
        s[0] += m["mean"]["correct"]
        s[1] += 1
best = {}
for name, (total, n) in sums.items():
    peer = name.split("@")[0]
    if peer not in best or total / n > best[peer][1] + 1e-12:
        best[peer] = (name, total / n)
euclidean = best["euclidean"][0].split("@")[1]
plane, radius = best["frame"][0].split("@")[1].split("/")
with open(os.path.join(out, "chosen.txt"), "w") as f:
    f.write(f"EUCLIDEAN={euclidean}\nFRAME={plane}/{radius}\n")
print(f"evaluation-objects: chosen euclidean {euclidean} m, frame {plane} m / {radius} m", file=sys.stderr)
PY
fi
EUCLIDEAN=${EUCLIDEAN:-0.3}
FRAME=${FRAME:-0.2/0.3}
if [[ -f "$SWEEP_OUT/chosen.txt" ]]; then
  # shellcheck disable=SC1091
  source "$SWEEP_OUT/chosen.txt"
fi
PLANE_DISTANCE=${FRAME%/*}
FRAME_DISTANCE=${FRAME#*/}
sweep_elapsed=$(cat "$SWEEP_OUT/elapsed.txt" 2>/dev/null || echo 0)

# ---------------------------------------------------------------- 2. matrix
rm -rf "$OUT"
mkdir -p "$OUT"
JOBLIST="$OUT/jobs.txt"
: >"$JOBLIST"
peers="--euclidean-distances $EUCLIDEAN --frame-distances $FRAME_DISTANCE --plane-distance $PLANE_DISTANCE"
for sensor in $SENSORS; do
  for scene in $SCENES; do
    for mount in $MOUNTS; do
      for motion in rest poses noposes; do
        name="obj_${sensor}_${scene}_${mount}_${motion}"
        methods="--method all $peers"
        [[ "$motion" == noposes ]] && methods="--method objects"
        echo "$name --objects $methods --sensor $sensor --scene $scene $(mount_args "$mount") $(motion_args "$motion")" \
          "--duration $DURATION --seed 1 --verify --json $OUT/$name.json --quiet" >>"$JOBLIST"
      done
    done
  done
done

runs=$(wc -l <"$JOBLIST")
echo "evaluation-objects: $runs runs, $JOBS in parallel, results in $OUT (euclidean $EUCLIDEAN m, frame $FRAME m)" >&2
matrix_start=$(date +%s)
evaluation_run_jobs "$JOBLIST" "$OUT" evaluation-objects
elapsed=$(($(date +%s) - matrix_start))
echo "evaluation-objects: runs done in $elapsed s (sweep $sweep_elapsed s)" >&2

if [[ -n "$QUICK" ]]; then
  echo "evaluation-objects: QUICK run, docs left unchanged" >&2
  exit 0
fi

python3 - "$OUT" "$SWEEP_OUT" docs/evaluation.md "$elapsed" "$sweep_elapsed" "$JOBS" <<'PY'
import glob, json, os, re, sys
out, sweep_out, doc_path = sys.argv[1], sys.argv[2], sys.argv[3]
elapsed, sweep_elapsed, jobs = int(sys.argv[4]), int(sys.argv[5]), sys.argv[6]

def load(directory, prefix):
    runs = {}
    for path in glob.glob(os.path.join(directory, prefix + "_*.json")):
        with open(path) as f:
            runs[os.path.basename(path)[len(prefix) + 1:-5]] = json.load(f)
    return runs
runs = load(out, "obj")
sweep = load(sweep_out, "sweep")

SENSORS = [("mid360", "Mid-360"), ("avia", "Avia")]
SCENES = ["office", "forest", "street", "hills"]
MOUNTS = [("level", "level"), ("p15", "pitch 15"), ("p30", "pitch 30"), ("up", "upside down")]
MOTIONS = [("rest", "at rest"), ("poses", "moving, poses")]  # the targets count these
EXTRA = ("noposes", "moving, no poses")                       # extra information
TARGETS = {"ari": 0.9, "correct": 0.7, "object_point_coverage": 0.95, "ground_f1": 0.9}
MEAN_CORRECT_TARGET = 0.8
TOL = 0.02  # a win: 0.02 or more

def method(run, name):
    for m in run["methods"]:
        if m["name"] == name:
            return m
    return None
def mean(run, name):
    m = method(run, name)
    return None if m is None else m["mean"]

cells = [(s, sc, mo) for s, _ in SENSORS for sc in SCENES for mo, _ in MOUNTS]
def run_of(c, motion):
    return runs.get("%s_%s_%s_%s" % (c[0], c[1], c[2], motion))
def peers_of(c, motion):
    """The run holding the peers of a cell: the poses run for the no-poses one (the same points)."""
    return run_of(c, "poses" if motion == "noposes" else motion)

some = next((r for r in runs.values() if method(r, "euclidean")), None)
setting = some["settings"] if some else {"euclidean_distances": ["?"], "frame_distances": ["?"], "plane_distances": ["?"]}
fmt_m = lambda v: ("%g" % v) if isinstance(v, (int, float)) else v
PEERS = [("carc", "C-ARC (paper's preset)"),
         ("euclidean", "Euclidean %s m" % fmt_m(setting["euclidean_distances"][0])),
         ("frame", "RANSAC + Euclidean %s / %s m" % (fmt_m(setting["plane_distances"][0]), fmt_m(setting["frame_distances"][0])))]

def rated(run):
    return run is not None and mean(run, "objects")["objects"] > 0

def targets(c, motion):
    """Which targets the objects method meets in a cell (None: no object rated)."""
    r, pr = run_of(c, motion), peers_of(c, motion)
    if not rated(r) or pr is None:
        return None
    o = mean(r, "objects")
    met = {k: o[k] >= v for k, v in TARGETS.items()}
    met["above_peers"] = all(o["correct"] - mean(pr, p)["correct"] >= TOL - 1e-12 for p, _ in PEERS)
    return met

tables = {}

# --- the sweep that chose the peers' settings
if sweep:
    sums = {}
    for key, r in sweep.items():
        motion = key.rsplit("_", 1)[1]
        for m in r["methods"]:
            if m["mean"]["objects"] <= 0:
                continue
            s = sums.setdefault(m["name"], {"rest": [0.0, 0], "poses": [0.0, 0], "ari": 0.0})
            s[motion][0] += m["mean"]["correct"]
            s[motion][1] += 1
            s["ari"] += m["mean"]["ari"]
    def order(name):
        peer, value = name.split("@")
        return (peer, [float(v) for v in value.split("/")])
    rows = ["| peer | setting [m] | cells | strict correct at rest | moving, poses | both (chooses) | ARI, both |",
            "|---|---|---|---|---|---|---|"]
    chosen = {"euclidean": "euclidean@%s" % fmt_m(setting["euclidean_distances"][0]),
              "frame": "frame@%s/%s" % (fmt_m(setting["plane_distances"][0]), fmt_m(setting["frame_distances"][0]))}
    for name in sorted(sums, key=order):
        s = sums[name]
        n = s["rest"][1] + s["poses"][1]
        peer, value = name.split("@")
        label = ("radius " if peer == "euclidean" else "tolerance / radius ") + value.replace("/", " / ")
        both = (s["rest"][0] + s["poses"][0]) / n
        cellv = [f"{s['rest'][0] / max(s['rest'][1], 1):.3f}", f"{s['poses'][0] / max(s['poses'][1], 1):.3f}", f"{both:.3f}"]
        if name == chosen.get(peer):
            cellv[2] = f"**{cellv[2]}**"
        rows.append(f"| {'Euclidean' if peer == 'euclidean' else 'RANSAC + Euclidean'} | {label} | {n} | " + " | ".join(cellv) +
                    f" | {s['ari'] / n:.3f} |")
    tables["sweep"] = "\n".join(rows)

# --- targets met, per motion, and the summary
head = ("| motion | cells with objects | mean strict correct (>= 0.8) | ARI >= 0.9 | strict correct >= 0.7 | "
        "coverage >= 0.95 | ground F1 >= 0.9 | above every peer | all five |")
rows = [head, "|---|---|---|---|---|---|---|---|---|"]
def target_row(label, keys):
    ts = [(targets(c, mt), mean(run_of(c, mt), "objects")) for c in cells for mt in keys if run_of(c, mt)]
    ts = [(t, o) for t, o in ts if t is not None]
    if not ts:
        return None
    count = lambda k: sum(1 for t, _ in ts if t[k])
    mc = sum(o["correct"] for _, o in ts) / len(ts)
    mark = "**%.2f**" % mc if mc >= MEAN_CORRECT_TARGET else "%.2f" % mc
    alls = sum(1 for t, _ in ts if all(t.values()))
    return (f"| {label} | {len(ts)} | {mark} | {count('ari')} | {count('correct')} | {count('object_point_coverage')} | "
            f"{count('ground_f1')} | {count('above_peers')} | {alls} |")
for keys, label in [(["rest"], "at rest"), (["poses"], "moving, poses"), (["rest", "poses"], "**both (the targets)**"),
                    (["noposes"], "moving, no poses (extra)")]:
    row = target_row(label, keys)
    if row:
        rows.append(row)
tables["targets"] = "\n".join(rows)

# --- per cell: which targets are missed
LETTERS = [("ari", "A"), ("correct", "S"), ("object_point_coverage", "C"), ("ground_f1", "G"), ("above_peers", "P")]
def grid(fmt, motions):
    headr = "| sensor | scene | " + " | ".join(f"{ml}, {tl}" for _, ml in MOUNTS for _, tl in motions) + " |"
    rows = [headr, "|---|---|" + "---|" * (len(MOUNTS) * len(motions))]
    for s, sl in SENSORS:
        for sc in SCENES:
            vals = []
            for mo, _ in MOUNTS:
                for mt, _ in motions:
                    r = run_of((s, sc, mo), mt)
                    vals.append("-" if r is None else fmt((s, sc, mo), mt, r))
            rows.append(f"| {sl} | {sc} | " + " | ".join(vals) + " |")
    return rows
def fmt_missed(c, mt, r):
    t = targets(c, mt)
    if t is None:
        return "no object"
    missed = "".join(letter for k, letter in LETTERS if not t[k])
    return "all met" if not missed else missed
tables["grid-targets"] = "\n".join(grid(fmt_missed, MOTIONS))

def fmt_quality(c, mt, r):
    if not rated(r):
        return "no object"
    o = mean(r, "objects")
    t = targets(c, mt)
    text = f"{o['ari']:.2f} / {o['correct']:.2f}"
    return f"**{text}**" if t and all(t.values()) else text
tables["grid-quality"] = "\n".join(grid(fmt_quality, MOTIONS + [EXTRA]))

def fmt_structure(c, mt, r):
    o = mean(r, "objects")
    text = f"{o['object_point_coverage']:.2f} / {o['ground_f1']:.2f}"
    if r.get("scene_has_wall"):
        text += f" / {o['wall_precision']:.2f} / {o['wall_recall']:.2f}"
    if r.get("scene_has_ceiling"):
        text += f" / {o['ceiling_f1']:.2f}"
    return text
tables["grid-structure"] = "\n".join(grid(fmt_structure, MOTIONS))

# --- object-point coverage per range band, pooled over the cells at rest and with poses
BANDS = ["0-10 m", "10-30 m", ">= 30 m"]
def pooled_bands(name, select):
    kept, total = [0, 0, 0], [0, 0, 0]
    for c in cells:
        if not select(c):
            continue
        for mt, _ in MOTIONS:
            r = run_of(c, mt)
            m = r and method(r, name)
            if not m:
                continue
            for b, band in enumerate(m["object_point_coverage_by_range"]):
                kept[b] += band["kept"]
                total[b] += band["object_points"]
    return " | ".join("-" if t == 0 else f"{k / t:.3f}" for k, t in zip(kept, total))
rows = ["| sensor | scene | objects " + " | objects ".join(BANDS) + " | frame " + " | frame ".join(BANDS) + " |",
        "|---|---|" + "---|" * 6]
for s, sl in SENSORS:
    for sc in SCENES:
        sel = lambda c, s=s, sc=sc: c[0] == s and c[1] == sc
        rows.append(f"| {sl} | {sc} | {pooled_bands('objects', sel)} | {pooled_bands('frame', sel)} |")
rows.append(f"| all | all | {pooled_bands('objects', lambda c: True)} | {pooled_bands('frame', lambda c: True)} |")
tables["range"] = "\n".join(rows)

# --- the objects preset against each peer
def verdict(a, b, higher_better=True):
    d = (a - b) if higher_better else (b - a)
    return "win" if d >= TOL - 1e-12 else ("loss" if d <= -TOL + 1e-12 else "tie")
rows = ["| peer | motion | cells | strict correct (win/tie/loss) | ARI | over-seg | under-seg | mean correct objects / peer | mean ARI objects / peer | peer's coverage / ground F1 |",
        "|---|---|---|---|---|---|---|---|---|---|"]
for peer, plabel in PEERS:
    for mt, label in MOTIONS + [EXTRA]:
        cnt = {k: [0, 0, 0] for k in ["ari", "correct", "over_segmented", "under_segmented"]}
        sums = [0.0] * 6
        n = 0
        for c in cells:
            r, pr = run_of(c, mt), peers_of(c, mt)
            if not rated(r) or pr is None or mean(pr, peer) is None:
                continue
            o, p = mean(r, "objects"), mean(pr, peer)
            n += 1
            for k, hb in [("ari", True), ("correct", True), ("over_segmented", False), ("under_segmented", False)]:
                cnt[k][["win", "tie", "loss"].index(verdict(o[k], p[k], hb))] += 1
            for i, v in enumerate([o["correct"], p["correct"], o["ari"], p["ari"], p["object_point_coverage"], p["ground_f1"]]):
                sums[i] += v
        if n == 0:
            continue
        w = lambda k: "/".join(str(x) for x in cnt[k])
        rows.append(f"| {plabel} | {label} | {n} | {w('correct')} | {w('ari')} | {w('over_segmented')} | "
                    f"{w('under_segmented')} | {sums[0]/n:.2f} / {sums[1]/n:.2f} | {sums[2]/n:.2f} / {sums[3]/n:.2f} | "
                    f"{sums[4]/n:.2f} / {sums[5]/n:.2f} |")
tables["peers"] = "\n".join(rows)

# --- cycle cost
rows = ["| sensor | objects: median, mean over cells [ms] | objects: P99, worst cell [ms] | C-ARC median [ms] | Euclidean median [ms] | RANSAC + Euclidean median [ms] | points per window |",
        "|---|---|---|---|---|---|---|"]
for s, sl in SENSORS:
    rs = [r for key, r in runs.items() if key.startswith(s + "_")]
    if not rs:
        continue
    def med(name):
        ms = [method(r, name) for r in rs if method(r, name)]
        return sum(m["cost_median_ms"] for m in ms) / len(ms) if ms else float("nan")
    worst = max(method(r, "objects")["cost_p99_ms"] for r in rs)
    pts = sum(r["window_points"] for r in rs) / len(rs)
    rows.append(f"| {sl} | {med('objects'):.2f} | {worst:.2f} | {med('carc'):.2f} | {med('euclidean'):.2f} | {med('frame'):.2f} | {pts:.0f} |")
tables["cost"] = "\n".join(rows)

failed = [l.strip() for l in open(os.path.join(out, "failed.txt")) if l.strip()]
if os.path.exists(os.path.join(sweep_out, "failed.txt")):
    failed += ["sweep " + l.strip() for l in open(os.path.join(sweep_out, "failed.txt")) if l.strip()]
verified = sum(r["verify"]["retrievals"] for r in runs.values() if r.get("verify"))
tables["failed"] = (f"{len(runs)} runs in {elapsed} s, after the sweep's {len(sweep)} runs in {sweep_elapsed} s "
                    f"(JOBS={jobs}); --verify: {verified} retrievals, "
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
