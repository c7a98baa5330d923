#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# measure_memory.sh -- peak RSS and wall time of `streamclust info` and `streamclust cluster` on the
# CSV and the recordings make_long_recordings.sh wrote.
#
#   bash bench/recordings/measure_memory.sh OUTDIR [OUTDIR...]
#
# For every input in each OUTDIR (STEM.csv, STEM.bag, STEM_db3/, STEM.mcap), one run each, in turn
# (never two at once), under /usr/bin/time -v:
#   info      streamclust info INPUT
#   cluster   streamclust cluster INPUT --preset carc-mid360 --quiet
#   +labels   streamclust cluster INPUT --preset carc-mid360 --quiet --labels /dev/null --cycles all
#             (set LABELS=0 to skip: it writes every cycle's labels, 12 M lines per 30 s of stream)
# and prints a markdown table: input, length, file size, points (from info), wall time and peak
# RSS ("Maximum resident set size") of each run.  Give a short and a long OUTDIR (e.g. 30 s and
# 180 s) to see whether peak RSS grows with the recording's length.  The raw /usr/bin/time -v
# outputs are kept in OUTDIR/measure/.  STREAMCLUST=path overrides build/dev/tools/streamclust.
# MMAP_THRESHOLD=131072 runs the tool with glibc's MALLOC_MMAP_THRESHOLD_ fixed at that many bytes
# (glibc's default threshold adapts upwards after the first large free(), so buffers of ~1 MB --
# decompressed chunks -- then come from the heap and fragment it; fixing it shows the tool's own
# memory without that effect).
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
STREAMCLUST="${STREAMCLUST:-$ROOT/build/dev/tools/streamclust}"
LABELS="${LABELS:-1}"
MMAP_THRESHOLD="${MMAP_THRESHOLD:-}"
if [ -n "$MMAP_THRESHOLD" ]; then export MALLOC_MMAP_THRESHOLD_="$MMAP_THRESHOLD"; fi
[ $# -ge 1 ] || { echo "usage: measure_memory.sh OUTDIR [OUTDIR...]" >&2; exit 2; }
[ -x "$STREAMCLUST" ] || { echo "measure_memory.sh: $STREAMCLUST not found (build streamclust_tool)" >&2; exit 1; }

# run LOG CMD...: CMD under /usr/bin/time -v (its output to /dev/null); prints "WALL_S RSS_KB"
run() {
  local log="$1"; shift
  /usr/bin/time -v -o "$log" "$@" >/dev/null
  awk -F': ' '
    /Elapsed \(wall clock\) time/ { n = split($NF, p, ":"); w = 0; for (i = 1; i <= n; i++) w = w * 60 + p[i] }
    /Maximum resident set size/   { r = $NF }
    END { printf "%.2f %d\n", w, r }' "$log"
}
mib() { awk -v k="$1" 'BEGIN { printf "%.1f", k / 1024 }'; }
human() { awk -v b="$1" 'BEGIN { if (b >= 1e9) printf "%.2f GB", b / 1e9; else printf "%.0f MB", b / 1e6 }'; }

rows=()
for dir in "$@"; do
  dir="$(cd "$dir" && pwd)"
  mkdir -p "$dir/measure"
  inputs=()
  for f in "$dir"/*.csv "$dir"/*.bag "$dir"/*_db3 "$dir"/*.mcap; do [ -e "$f" ] && inputs+=("$f"); done
  [ ${#inputs[@]} -gt 0 ] || { echo "measure_memory.sh: no inputs in $dir" >&2; exit 1; }
  for f in "${inputs[@]}"; do
    name="$(basename "$f")"
    size="$(du -sb "$f" | cut -f1)"
    echo "== $name: info" >&2
    read -r iw ir < <(run "$dir/measure/$name.info.time" "$STREAMCLUST" info "$f")
    "$STREAMCLUST" info "$f" > "$dir/measure/$name.info.txt"
    points="$(awk '$1 == "points:" {print $2; exit}' "$dir/measure/$name.info.txt")"
    span="$(awk '$1 == "time:" {for (i = 1; i <= NF; i++) if ($i == "(span") {printf "%.1f\n", $(i + 1); exit}}' "$dir/measure/$name.info.txt")"
    echo "== $name: cluster" >&2
    read -r cw cr < <(run "$dir/measure/$name.cluster.time" "$STREAMCLUST" cluster "$f" --preset carc-mid360 --quiet)
    lw="-"; lr="-"
    if [ "$LABELS" = 1 ]; then
      echo "== $name: cluster --labels /dev/null --cycles all" >&2
      read -r lw lrk < <(run "$dir/measure/$name.labels.time" "$STREAMCLUST" cluster "$f" --preset carc-mid360 --quiet \
        --labels /dev/null --cycles all)
      lr="$(mib "$lrk")"
    fi
    rows+=("| $name | ${span} s | $(human "$size") | $points | $iw | $(mib "$ir") | $cw | $(mib "$cr") | $lw | $lr |")
  done
done

rev="$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
git -C "$ROOT" diff --quiet HEAD 2>/dev/null || rev="$rev + uncommitted changes"
echo "$STREAMCLUST (built $(date -u -r "$STREAMCLUST" '+%Y-%m-%d %H:%M UTC'); repository at $rev); $(nproc) cores, $(awk -F': ' '/model name/ {print $2; exit}' /proc/cpuinfo)${MMAP_THRESHOLD:+; MALLOC_MMAP_THRESHOLD_=$MMAP_THRESHOLD}"
echo
echo "| input | length | size | points | info wall (s) | info peak RSS (MiB) | cluster wall (s) | cluster peak RSS (MiB) | +labels wall (s) | +labels peak RSS (MiB) |"
echo "|---|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
