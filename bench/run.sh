#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# One command for every benchmark figure of docs/benchmarks.md:
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
#   BENCH_SKIP_MICRO=1  skip the microbenchmarks
#   BENCH_JOBS          build parallelism                       (default 2)
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${root}/build/bench-run"
results="${build}/results"
img="${root}/docs/img"
cycles="${BENCH_CYCLES:-1000}"
peer_every="${BENCH_PEER_EVERY:-20}"
pcl_every="${BENCH_PCL_EVERY:-100}"
timed_cycles="${BENCH_TIMED_CYCLES:-200}"
filter="${BENCH_FILTER:-}"
min_time="${BENCH_MIN_TIME:-0.5}"
jobs="${BENCH_JOBS:-2}"

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
for src in "${root}"/bench/*.cpp; do
  stem="$(basename "${src}" .cpp)"
  micro_targets+=("bench_${stem#bench_}")
done
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
  echo "latency: cycles=${cycles} peer_every=${peer_every} pcl_every=${pcl_every} timed_cycles=${timed_cycles} filter='${filter}'"
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
echo "== bench_latency"
latency_args=(--cycles "${cycles}" --peer-every "${peer_every}" --pcl-every "${pcl_every}"
              --timed-cycles "${timed_cycles}" --out "${results}/latency")
[[ -n "${filter}" ]] && latency_args+=(--filter "${filter}")
"${build}/bench/bench_latency" "${latency_args[@]}" | tee "${results}/latency.txt"
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
plot avia carc "Livox Avia, C-ARC (bucket grid, theta = 80 deg): 20 Hz cycle latency" latency_cdf_avia_carc.png
plot avia capped "Livox Avia, capped grid (K = 4, theta = 80 deg): 20 Hz cycle latency" latency_cdf_avia_capped.png
plot mid360 fast "Livox Mid-360, CArcFastConfig (bucket grid, union-find rebuild): 20 Hz cycle latency" latency_cdf_mid360_fast.png
plot avia fast "Livox Avia, CArcFastConfig (bucket grid, union-find rebuild): 20 Hz cycle latency" latency_cdf_avia_fast.png
plot avia capfast "Livox Avia, CArcCappedFastConfig (capped grid K = 4, rebuild): 20 Hz cycle latency" latency_cdf_avia_capfast.png

echo
echo "== results"
echo "machine and settings:   ${results}/machine.txt"
[[ "${BENCH_SKIP_MICRO:-0}" != 1 ]] && echo "microbenchmarks:        ${results}/bench_*.{txt,json}"
echo "latency summary:        ${results}/latency/summary.md (and summary.json)"
echo "per-cycle latencies:    ${results}/latency/cycles.csv"
echo "targets:                ${results}/latency/targets.md"
for p in "${plots[@]}"; do echo "plot:                   ${p}"; done
echo "Record the figures in docs/benchmarks.md."
