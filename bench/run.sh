#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# One command for every benchmark figure of docs/performance.md:
#   bench/run.sh
# 1. installs what it needs with apt-get when missing (libpcl-dev for the PCL
#    peer, gnuplot-nox for the plots; idempotent, needs root only if missing);
# 2. configures a Release build in build/bench-run and builds every benchmark;
# 3. runs the Google Benchmark microbenchmarks (bench_policies, and any other
#    bench/*.cpp such as bench_engine) and the full latency program;
# 4. writes the results to build/bench-run/results/ and the CDF plots to
#    docs/img/, and prints where everything went.
#
# Knobs (environment):
#   BENCH_CYCLES        measured cycles per latency scenario   (default 1000)
#   BENCH_PEER_EVERY    batch/frame peers + ARI every k cycles (default 20)
#   BENCH_PCL_EVERY     PCL peer every k cycles                (default 100)
#   BENCH_TIMED_CYCLES  cycles of the phase-split pass          (default 200)
#   BENCH_FILTER        only latency scenarios containing this  (default all)
#   BENCH_MIN_TIME      Google Benchmark min time per case [s] (default 0.5)
#   BENCH_SKIP_MICRO=1  skip the microbenchmarks (and their build)
#   BENCH_JOBS          build parallelism                       (default 2)
#   BENCH_LATENCY_JOBS  latency scenarios run side by side      (default 2)
#   BENCH_BUILD_DIR     build directory                (default build/bench-run)
#   BENCH_IMG_DIR       where the CDF plots go             (default docs/img)
#
# Latency: every scenario of `bench_latency --list` runs as its own process
# (`--scenario NAME`, so each has its own peak RSS), BENCH_LATENCY_JOBS at a
# time, longest expected first (xargs -P); the per-scenario outputs in
# results/latency-parts/ are merged into results/latency/ by
# bench/latency/merge_summaries.py. With 2 jobs on a 2-core machine the two
# processes share the memory bus and L3: set BENCH_LATENCY_JOBS=1 for a
# strictly sequential record.
#
# Expected duration of the latency part with the defaults (86 scenarios,
# 1000 cycles) on the 2-core reference VM: about 20-25 min with 2 jobs on a
# quiet machine (19 min 26 s for the 78 of the record in docs/performance.md), about
# twice that with BENCH_LATENCY_JOBS=1, about 1 h 45 min at a load average of
# 6; plus the build (a few minutes) and the microbenchmarks.
# bench/latency/estimate_duration.py projects it from a short run. A faster
# engine shortens it; PCL (10 windows of 7-22 s per Euclidean scenario) does not.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BENCH_BUILD_DIR:-${root}/build/bench-run}"
results="${build}/results"
img="${BENCH_IMG_DIR:-${root}/docs/img}"
cycles="${BENCH_CYCLES:-1000}"
peer_every="${BENCH_PEER_EVERY:-20}"
pcl_every="${BENCH_PCL_EVERY:-100}"
timed_cycles="${BENCH_TIMED_CYCLES:-200}"
filter="${BENCH_FILTER:-}"
min_time="${BENCH_MIN_TIME:-0.5}"
jobs="${BENCH_JOBS:-2}"
latency_jobs="${BENCH_LATENCY_JOBS:-2}"

# ------------------------------------------------------------- dependencies
need=()
for pkg in libpcl-dev gnuplot-nox; do
  dpkg -s "${pkg}" >/dev/null 2>&1 || need+=("${pkg}")
done
if ((${#need[@]})); then
  echo "== installing ${need[*]}"
  apt_get="apt-get"
  [[ $(id -u) -eq 0 ]] || apt_get="sudo apt-get"
  DEBIAN_FRONTEND=noninteractive ${apt_get} install -y --no-install-recommends "${need[@]}"
fi

# -------------------------------------------------------------------- build
echo "== configuring ${build}"
cmake -S "${root}" -B "${build}" -DCMAKE_BUILD_TYPE=Release -DSTREAMCLUST_BUILD_BENCH=ON >/dev/null
micro_targets=()
if [[ "${BENCH_SKIP_MICRO:-0}" != 1 ]]; then
  for src in "${root}"/bench/*.cpp; do
    stem="$(basename "${src}" .cpp)"
    micro_targets+=("bench_${stem#bench_}")
  done
fi
echo "== building ${micro_targets[*]} bench_latency"
cmake --build "${build}" -j"${jobs}" --target "${micro_targets[@]}" bench_latency

mkdir -p "${results}" "${img}"
{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "commit: $(git -C "${root}" rev-parse HEAD 2>/dev/null || echo unknown)$(git -C "${root}" diff --quiet 2>/dev/null || echo ' (+ local changes)')"
  echo "cpu: $(lscpu | sed -n 's/^Model name: *//p' | head -1)"
  echo "cores: $(nproc) (lscpu: $(lscpu | sed -n 's/^CPU(s): *//p' | head -1))"
  echo "memory: $(free -h | awk '/^Mem:/ {print $2}')"
  echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "compiler: $(c++ --version | head -1)"
  echo "latency: cycles=${cycles} peer_every=${peer_every} pcl_every=${pcl_every} timed_cycles=${timed_cycles} filter='${filter}' jobs=${latency_jobs}"
} | tee "${results}/machine.txt"

# ------------------------------------------------------- microbenchmarks
if [[ "${BENCH_SKIP_MICRO:-0}" != 1 ]]; then
  for t in "${micro_targets[@]}"; do
    echo "== ${t}"
    "${build}/bench/${t}" --benchmark_min_time="${min_time}" \
      --benchmark_out="${results}/${t}.json" --benchmark_out_format=json | tee "${results}/${t}.txt"
  done
fi

# ----------------------------------------------------------------- latency
latency_bin="${build}/bench/bench_latency"
parts="${results}/latency-parts"
rm -rf "${parts}" "${results}/latency"
mkdir -p "${parts}"
list_args=()
[[ -n "${filter}" ]] && list_args+=(--filter "${filter}")
mapfile -t scenarios < <("${latency_bin}" --list "${list_args[@]}")
((${#scenarios[@]})) || { echo "no latency scenario matches '${filter}'" >&2; exit 1; }
echo "== bench_latency: ${#scenarios[@]} scenarios, ${latency_jobs} at a time"
# Longest expected first (the T_B 0.5 s, paper-strategy and Euclidean + PCL
# scenarios), so that the last scenarios running alone are short ones.
order() {
  local s w
  for s in "$@"; do
    w=0
    [[ ${s} == *tb0.5 ]] && w=$((w + 4))
    [[ ${s} == *tb0.4 ]] && w=$((w + 3))
    [[ ${s} == *tb0.3 ]] && w=$((w + 2))
    [[ ${s} == *-euclid-* || ${s} == *-carc-* || ${s} == *-capped-* ]] && w=$((w + 3))
    [[ ${s} == *office* ]] && w=$((w + 1))
    echo "${w} ${s}"
  done | sort -k1,1nr -s | cut -d' ' -f2
}
run_one() {
  "${latency_bin}" --scenario "$1" --cycles "${cycles}" --peer-every "${peer_every}" --pcl-every "${pcl_every}" \
    --timed-cycles "${timed_cycles}" --out "${parts}/$1" > "${parts}/$1.txt" 2>&1 \
    || { echo "bench_latency --scenario $1 FAILED (see ${parts}/$1.txt)" >&2; return 1; }
  grep -F "$1 " "${parts}/$1.txt"
}
export -f run_one
export latency_bin parts cycles peer_every pcl_every timed_cycles
latency_start=${SECONDS}
order "${scenarios[@]}" | xargs -P "${latency_jobs}" -I{} bash -c 'run_one "$1"' _ {} | tee "${results}/latency.txt"
echo "bench_latency: $(( (SECONDS - latency_start) / 60 )) min $(( (SECONDS - latency_start) % 60 )) s wall" \
  | tee -a "${results}/latency.txt" "${results}/machine.txt"
part_dirs=()
for s in "${scenarios[@]}"; do part_dirs+=("${parts}/${s}"); done
python3 "${root}/bench/latency/merge_summaries.py" "${results}/latency" "${part_dirs[@]}"
python3 "${root}/bench/latency/targets.py" "${results}/latency/summary.json" | tee "${results}/latency/targets.md"

# ------------------------------------------------------------------- plots
plots=()
plot() {  # sensor config title file
  local out="${img}/$4"
  if ls "${results}/latency/cdf/$1-"*"-$2-tb"*.dat >/dev/null 2>&1; then
    gnuplot -e "dir='${results}/latency'; sensor='$1'; config='$2'; title='$3'; out='${out}'" \
      "${root}/bench/latency/plot_cdf.gp" 2>/dev/null
    plots+=("${out}")
  fi
}
plot mid360 carc "Livox Mid-360, C-ARC (bucket grid, theta = 30 deg): 20 Hz cycle latency" latency_cdf_mid360_carc.png
plot mid360 fast "Livox Mid-360, CArcFastConfig (bucket grid, spanning forest): 20 Hz cycle latency" latency_cdf_mid360_fast.png
plot avia capfast "Livox Avia, CArcCappedFastConfig (capped grid K = 4, spanning forest): 20 Hz cycle latency" latency_cdf_avia_capfast.png

echo
echo "== results"
echo "machine and settings:   ${results}/machine.txt"
[[ "${BENCH_SKIP_MICRO:-0}" != 1 ]] && echo "microbenchmarks:        ${results}/bench_*.{txt,json}"
echo "latency summary:        ${results}/latency/summary.md (and summary.json)"
echo "per-cycle latencies:    ${results}/latency/cycles.csv"
echo "targets:                ${results}/latency/targets.md"
for p in "${plots[@]}"; do echo "plot:                   ${p}"; done
echo "Record the figures in docs/performance.md."
