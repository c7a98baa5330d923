#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The quality evaluation of docs/evaluation.md: builds the streamclust tool
# (Release, g++), runs `streamclust evaluate` over the whole matrix (sensors x
# scenes x grids x linkages, the theta sweep, the T_B study, the ego-motion
# recovery study), then rewrites the generated tables of docs/evaluation.md
# (between the <!-- evaluation:NAME --> markers) and, when gnuplot is
# installed (apt-get install gnuplot-nox), docs/evaluation-burst.png; without
# gnuplot the picture is left as it is and the script says so.
#
#   JOBS=2              evaluate runs in parallel (default 2)
#   BUILD_DIR=build/evaluation
#   TOOL=path           use this streamclust binary (Release) instead of building one
#   SECONDS_MAIN=3      simulated seconds per run of the matrix, the sweep and the T_B study
#   QUICK=1             a smoke run: 1 s streams, two sensors, no doc rewrite
#   TABLES_ONLY=1       no build and no runs: rewrite the tables and the picture
#                       from the results already in BUILD_DIR/results
#
# About 26 minutes on 2 cores with the defaults (533 runs: 1558 s of runs in
# the committed run, the cores shared with other builds, plus the build).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

JOBS=${JOBS:-2}
BUILD_DIR=${BUILD_DIR:-build/evaluation}
SECONDS_MAIN=${SECONDS_MAIN:-3}
QUICK=${QUICK:-}
TABLES_ONLY=${TABLES_ONLY:-}
OUT="$BUILD_DIR/results"

if [[ -n "$TABLES_ONLY" ]]; then
  if [[ ! -f "$OUT/jobs.txt" ]]; then
    echo "evaluation: TABLES_ONLY=1 needs the results of an earlier run in $OUT (no $OUT/jobs.txt)" >&2
    exit 1
  fi
else
  source scripts/lib/evaluation-common.sh
  evaluation_tool
  rm -rf "$OUT"
  mkdir -p "$OUT"
fi

SENSORS="mid360 avia mid40 mid70 spinning32"
SCENES="office forest street"
TB_LIST="0.1 0.2 0.3 0.4 0.5"
THETAS="5 10 20 30 45 60 80"
BURST_TB="0.1 0.2 0.3 0.5"
SEEDS="1 2 3"
if [[ -n "$QUICK" ]]; then
  SENSORS="mid360 avia"
  SECONDS_MAIN=1
  TB_LIST="0.1 0.3"
  THETAS="10 45"
  BURST_TB="0.1"
  SEEDS="1"
fi

# The paper's per-sensor theta (latency section): Mid-360 30 deg, Avia 80 deg.
sensor_theta() {
  case "$1" in
    mid360) echo 30 ;;
    avia) echo 80 ;;
    *) echo "" ;;
  esac
}

JOBLIST="$OUT/jobs.txt"
[[ -n "$TABLES_ONLY" ]] && JOBLIST=/dev/null  # the earlier run's list stays
: >"$JOBLIST"
job() {  # job NAME ARGS...: one evaluate run writing $OUT/NAME.json
  local name=$1
  shift
  echo "$name $* --json $OUT/$name.json --quiet" >>"$JOBLIST"
}

for sensor in $SENSORS; do
  for scene in $SCENES; do
    # 1. The comparative matrix: T_M x linkage x structure.
    for tm in 1.25 2; do
      for st in keep drop; do
        base="--sensor $sensor --scene $scene --duration $SECONDS_MAIN --multiplicity $tm --structure $st"
        job "main_${sensor}_${scene}_tm${tm}_${st}_ang10" $base --linkage angular --theta 10
        th=$(sensor_theta "$sensor")
        [[ -n "$th" ]] && job "main_${sensor}_${scene}_tm${tm}_${st}_ang${th}" $base --linkage angular --theta "$th"
        for d in 0.3 0.6; do
          job "main_${sensor}_${scene}_tm${tm}_${st}_euc${d}" $base --linkage euclidean --distance "$d"
        done
        # 2. The theta sweep (T_M 2).
        [[ $tm == 2 ]] && for th in $THETAS; do
          job "sweep_${sensor}_${scene}_${st}_th${th}" $base --theta "$th"
        done
      done
    done
    # 1b. The spinning sensor on its natural fixed grid (one row per beam, one
    # column per firing column: the classic range image), for both methods.
    if [[ $sensor == spinning32 ]]; then
      for st in keep drop; do
        base="--sensor $sensor --scene $scene --duration $SECONDS_MAIN --grid 32x1800 --structure $st"
        job "main_${sensor}_${scene}_tmnat_${st}_ang10" $base --linkage angular --theta 10
        for d in 0.3 0.6; do
          job "main_${sensor}_${scene}_tmnat_${st}_euc${d}" $base --linkage euclidean --distance "$d"
        done
      done
    fi
    # 3. Quality against T_B (the adaptive loop picks the grid for each T_B, T_M 2).
    for tb in $TB_LIST; do
      job "tb_${sensor}_${scene}_tb${tb}" --sensor "$sensor" --scene "$scene" --duration "$SECONDS_MAIN" \
        --multiplicity 2 --structure drop --theta 10 --window-time "$tb"
    done
  done
done

# 4. Ego-motion burst: Mid-360 in the forest (the paper's Fig. motion_blur),
# at rest, 0.35 s of turning at 3 rad/s while driving at 1 m/s from t = 1 s,
# at rest again; structure dropped (the merges of interest are between objects).
for tb in $BURST_TB; do
  duration=$(python3 -c "print(round(1.35 + 3 * $tb + 0.6, 3))")
  for seed in $SEEDS; do
    burst="--sensor mid360 --scene forest --structure drop --duration $duration --seed $seed --window-time $tb
           --multiplicity 2 --theta 10 --burst 1:0.35 --burst-yaw-rate 3 --burst-speed 1"
    job "burst_tb${tb}_s${seed}_sliding" $burst --method both --frames sliding
    job "burst_tb${tb}_s${seed}_tumbling" $burst --method baseline --frames tumbling
  done
done
# The time series of the first seed at T_B = 0.1 s, for the table and the plot.
first_tb=${BURST_TB%% *}
duration=$(python3 -c "print(round(1.35 + 3 * $first_tb + 0.6, 3))")
for frames in sliding tumbling; do
  method=both
  [[ $frames == tumbling ]] && method=baseline
  echo "series_$frames --sensor mid360 --scene forest --structure drop --duration $duration --seed 1 \
--window-time $first_tb --multiplicity 2 --theta 10 --burst 1:0.35 --burst-yaw-rate 3 --burst-speed 1 \
--method $method --frames $frames --series $OUT/series_$frames.csv --quiet" >>"$JOBLIST"
done

if [[ -z "$TABLES_ONLY" ]]; then
  runs=$(wc -l <"$JOBLIST")
  echo "evaluation: $runs runs, $JOBS in parallel, results in $OUT" >&2
  start=$(date +%s)
  # Each line: NAME ARGS...; a failing run (e.g. a narrow sensor that sees no
  # object once the structure is dropped) is listed in failed.txt and its
  # table cells stay empty.
  evaluation_run_jobs "$JOBLIST" "$OUT" evaluation
  echo "evaluation: runs done in $(($(date +%s) - start)) s" >&2
fi

if [[ -n "$QUICK" ]]; then
  echo "evaluation: QUICK run, docs left unchanged" >&2
  exit 0
fi

python3 - "$OUT" docs/evaluation.md "$SECONDS_MAIN" <<'PY'
import glob, json, os, re, sys
out, doc_path, seconds = sys.argv[1], sys.argv[2], sys.argv[3]

runs = {}
for path in glob.glob(os.path.join(out, "*.json")):
    with open(path) as f:
        runs[os.path.basename(path)[:-5]] = json.load(f)

def method(run, name):
    for m in run["methods"]:
        if m["name"] == name:
            return m
    return None

SENSORS = ["mid360", "avia", "mid40", "mid70", "spinning32"]
SCENES = ["office", "forest", "street"]
SENSOR_NAME = {"mid360": "Mid-360", "avia": "Avia", "mid40": "Mid-40", "mid70": "Mid-70", "spinning32": "spinning-32"}
SENSOR_THETA = {"mid360": 30, "avia": 80}

def f2(x):
    return "-" if x is None else f"{x:.2f}"

def f3(x):
    return "-" if x is None else f"{x:.3f}"

def pair(run, key, fmt=f2):
    c, b = method(run, "carc"), method(run, "baseline")
    return f"{fmt(c['mean'][key])} / {fmt(b['mean'][key])}"

def lab(m):
    # The method's mean on the points the baseline labelled.
    return m.get("mean_on_baseline_labelled") or {}

def pair_labelled(run, key, fmt=f2):
    c, b = lab(method(run, "carc")), lab(method(run, "baseline"))
    return f"{fmt(c.get(key))} / {fmt(b.get(key))}"

TMS = ["1.25", "2", "nat"]
TM_NAME = {"1.25": "1.25", "2": "2", "nat": "fixed"}

tables = {}

# --- the comparative matrix, one table per (linkage, structure)
def main_table(st, link):
    rows = ["| sensor | scene | T_M | grid | M_mu | ARI | PQ | OSE/obj | USE/cl | over-seg | under-seg | coverage | ARI, baseline-labelled | PQ, baseline-labelled |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for sensor in SENSORS:
        for scene in SCENES:
            for tm in TMS:
                lk = link if not link.startswith("angS") else f"ang{SENSOR_THETA.get(sensor, '')}"
                r = runs.get(f"main_{sensor}_{scene}_tm{tm}_{st}_{lk}")
                if r is None:
                    continue
                g = r["grid"]
                mmu = f"{g['mean_multiplicity']:.2f}" if g["adaptive"] else "-"
                rows.append(f"| {SENSOR_NAME[sensor]} | {scene} | {TM_NAME[tm]} | {g['rows']}x{g['cols']} | "
                            f"{mmu} | {pair(r, 'ari')} | {pair(r, 'pq')} | "
                            f"{pair(r, 'ose_mean')} | {pair(r, 'use_mean')} | {pair(r, 'over_segmented')} | "
                            f"{pair(r, 'under_segmented')} | {pair(r, 'coverage')} | {pair_labelled(r, 'ari')} | "
                            f"{pair_labelled(r, 'pq')} |")
    return "\n".join(rows)

# Per-cell tables for angular 10 deg only; the other linkages are counted in
# the summary below and kept in the runs' JSON.
tables["main-keep-ang10"] = main_table("keep", "ang10")
tables["main-drop-ang10"] = main_table("drop", "ang10")

# --- win / tie / loss summary over the matrix
TOL = 0.02
def verdict(c, b, higher_better=True):
    d = (c - b) if higher_better else (b - c)
    return "win" if d > TOL else ("loss" if d < -TOL else "tie")

summary = ["| linkage | structure | T_M | cells | ARI (win/tie/loss) | PQ | OSE/obj | USE/cl | under-seg rate | mean ARI C-ARC / baseline | mean PQ C-ARC / baseline | ARI, baseline-labelled (w/t/l) | PQ, baseline-labelled (w/t/l) | mean ARI, baseline-labelled | mean PQ, baseline-labelled |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
for link, label in [("ang10", "angular 10 deg"), ("angS", "angular, paper's theta (Mid-360 30, Avia 80)"),
                    ("euc0.3", "Euclidean 0.3 m"), ("euc0.6", "Euclidean 0.6 m")]:
    for st in ["keep", "drop"]:
        for tm in TMS:
            counts = {k: {"win": 0, "tie": 0, "loss": 0} for k in ["ari", "pq", "ose_mean", "use_mean", "under_segmented", "ari_l", "pq_l"]}
            n = 0
            sums = [0.0] * 8
            for sensor in SENSORS:
                for scene in SCENES:
                    lk = link if link != "angS" else (f"ang{SENSOR_THETA[sensor]}" if sensor in SENSOR_THETA else None)
                    if lk is None:
                        continue
                    r = runs.get(f"main_{sensor}_{scene}_tm{tm}_{st}_{lk}")
                    if r is None:
                        continue
                    c, b = method(r, "carc")["mean"], method(r, "baseline")["mean"]
                    n += 1
                    for k, hb in [("ari", True), ("pq", True), ("ose_mean", False), ("use_mean", False), ("under_segmented", False)]:
                        counts[k][verdict(c[k], b[k], hb)] += 1
                    sums[0] += c["ari"]; sums[1] += b["ari"]; sums[2] += c["pq"]; sums[3] += b["pq"]
                    cl, bl = lab(method(r, "carc")), lab(method(r, "baseline"))
                    counts["ari_l"][verdict(cl["ari"], bl["ari"])] += 1
                    counts["pq_l"][verdict(cl["pq"], bl["pq"])] += 1
                    sums[4] += cl["ari"]; sums[5] += bl["ari"]; sums[6] += cl["pq"]; sums[7] += bl["pq"]
            if n == 0:
                continue
            cell = lambda k: f"{counts[k]['win']}/{counts[k]['tie']}/{counts[k]['loss']}"
            summary.append(f"| {label} | {st} | {TM_NAME[tm]} | {n} | {cell('ari')} | {cell('pq')} | {cell('ose_mean')} | "
                           f"{cell('use_mean')} | {cell('under_segmented')} | {sums[0]/n:.2f} / {sums[1]/n:.2f} | "
                           f"{sums[2]/n:.2f} / {sums[3]/n:.2f} | {cell('ari_l')} | {cell('pq_l')} | "
                           f"{sums[4]/n:.2f} / {sums[5]/n:.2f} | {sums[6]/n:.2f} / {sums[7]/n:.2f} |")
tables["summary"] = "\n".join(summary)

# --- theta sweep: mean over scenes per sensor
def sweep_table(st, key):
    thetas = sorted({int(k.split("_th")[1]) for k in runs if k.startswith("sweep_")})
    rows = ["| theta [deg] | " + " | ".join(SENSOR_NAME[s] for s in SENSORS) + " |",
            "|---|" + "---|" * len(SENSORS)]
    for th in thetas:
        cells = []
        for sensor in SENSORS:
            cs, bs = [], []
            for scene in SCENES:
                r = runs.get(f"sweep_{sensor}_{scene}_{st}_th{th}")
                if r:
                    cs.append(method(r, "carc")["mean"][key]); bs.append(method(r, "baseline")["mean"][key])
            cells.append(f"{sum(cs)/len(cs):.2f} / {sum(bs)/len(bs):.2f}" if cs else "-")
        rows.append(f"| {th} | " + " | ".join(cells) + " |")
    return "\n".join(rows)

# ARI with and without the structure, and the under-segmented rate with it
# (PQ and the over-segmented rate stay in the runs' JSON).
for st, key in [("keep", "ari"), ("drop", "ari"), ("keep", "under_segmented")]:
    tables[f"sweep-{st}-{key}"] = sweep_table(st, key)

# --- T_B study: per sensor (mean over scenes)
tbs = sorted({k.split("_tb")[1] for k in runs if k.startswith("tb_")}, key=float)
rows = ["| sensor | T_B [s] | grid (office) | points / window (mean) | ARI | PQ | over-seg | under-seg | baseline coverage |",
        "|---|---|---|---|---|---|---|---|---|"]
for sensor in SENSORS:
    for tb in tbs:
        rs = [runs.get(f"tb_{sensor}_{scene}_tb{tb}") for scene in SCENES]
        rs = [r for r in rs if r]
        if not rs:
            continue
        mean = lambda name, key: sum(method(r, name)["mean"][key] for r in rs) / len(rs)
        g = rs[0]["grid"]
        rows.append(f"| {SENSOR_NAME[sensor]} | {tb} | {g['rows']}x{g['cols']} | {mean('carc', 'points'):.0f} | "
                    f"{mean('carc', 'ari'):.2f} / {mean('baseline', 'ari'):.2f} | {mean('carc', 'pq'):.2f} / {mean('baseline', 'pq'):.2f} | "
                    f"{mean('carc', 'over_segmented'):.2f} / {mean('baseline', 'over_segmented'):.2f} | "
                    f"{mean('carc', 'under_segmented'):.2f} / {mean('baseline', 'under_segmented'):.2f} | "
                    f"{mean('baseline', 'coverage'):.2f} |")
tables["tb"] = "\n".join(rows)

# --- ego-motion recovery
btbs = sorted({k.split("_")[1][2:] for k in runs if k.startswith("burst_")}, key=float)
rows = ["| T_B [s] | seeds | method | USE before | USE peak | USE settled | recovery [s] (per seed) | recovery / T_B (mean) | under-seg peak / settled |",
        "|---|---|---|---|---|---|---|---|---|"]
for tb in btbs:
    for label, kind, name in [("C-ARC", "sliding", "carc"), ("baseline, sliding window", "sliding", "baseline"),
                              ("baseline, tumbling frames", "tumbling", "baseline")]:
        rs = [r for k, r in sorted(runs.items()) if k.startswith(f"burst_tb{tb}_") and k.endswith(kind)]
        ms = [method(r, name) for r in rs]
        ms = [m for m in ms if m and m["recovery"]]
        if not ms:
            continue
        rec = [m["recovery"]["use"] for m in ms]
        und = [m["recovery"]["under_segmented"] for m in ms]
        times = [x["time"] for x in rec]
        shown = ", ".join("never" if t is None else f"{t:.2f}" for t in times)
        valid = [t for t in times if t is not None]
        ratio = f"{sum(valid)/len(valid)/float(tb):.2f}" if valid else "-"
        avg = lambda xs, k: sum(x[k] for x in xs) / len(xs)
        rows.append(f"| {tb} | {len(ms)} | {label} | {avg(rec, 'before'):.1f} | {avg(rec, 'peak'):.1f} | "
                    f"{avg(rec, 'settled'):.1f} | {shown} | {ratio} | {avg(und, 'peak'):.2f} / {avg(und, 'settled'):.2f} |")
tables["burst"] = "\n".join(rows)

# (the time series around the burst goes to docs/evaluation-burst.png below;
# its CSV stays in $OUT/series_*.csv)

failed = [l.strip() for l in open(os.path.join(out, "failed.txt")) if l.strip()] if os.path.exists(os.path.join(out, "failed.txt")) else []
tables["failed"] = "\n".join(["| run | message |", "|---|---|"] + [
    "| " + l.split(": ", 1)[0] + " | " + (l.split(": ", 1)[1] if ": " in l else "") + " |" for l in sorted(failed)]) if failed else "(none)"

with open(doc_path) as f:
    doc = f.read()
for name, table in tables.items():
    pattern = re.compile(r"(<!-- evaluation:%s -->\n).*?(\n<!-- /evaluation:%s -->)" % (re.escape(name), re.escape(name)), re.S)
    if not pattern.search(doc):
        print(f"evaluation: no marker for table '{name}' in {doc_path}", file=sys.stderr)
        continue
    doc = pattern.sub(lambda m: m.group(1) + table + m.group(2), doc)
with open(doc_path, "w") as f:
    f.write(doc)
print(f"evaluation: {len(runs)} results, tables written to {doc_path}", file=sys.stderr)
PY

# The burst time series as a PNG (optional: gnuplot, e.g. apt-get install gnuplot-nox).
if command -v gnuplot >/dev/null 2>&1; then
  awk -F, 'NR>1 && $1=="carc" {print $2, $9}' "$OUT/series_sliding.csv" >"$OUT/carc.dat"
  awk -F, 'NR>1 && $1=="baseline" {print $2, $9}' "$OUT/series_sliding.csv" >"$OUT/base.dat"
  awk -F, 'NR>1 && $1=="baseline" {print $2, $9}' "$OUT/series_tumbling.csv" >"$OUT/tumb.dat"
  gnuplot <<GP
set terminal pngcairo size 900,420 noenhanced
set output "docs/evaluation-burst.png"
set xlabel "stream time [s]"
set ylabel "under-segmentation entropy (USE)"
set title "Mid-360, forest, structure dropped, T_B = $first_tb s: 3 rad/s turn + 1 m/s over [1.0, 1.35) s"
set object 1 rect from 1.0, graph 0 to 1.35, graph 1 fc rgb "#eeeeee" behind
set key top left
plot "$OUT/carc.dat" with linespoints title "C-ARC", \
     "$OUT/base.dat" with linespoints title "baseline, sliding window", \
     "$OUT/tumb.dat" with steps title "baseline, tumbling frames (held)"
GP
  echo "evaluation: docs/evaluation-burst.png written" >&2
else
  echo "evaluation: gnuplot not installed (apt-get install gnuplot-nox), docs/evaluation-burst.png left as it is" >&2
fi
