#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Projects the duration of a bench_latency record (e.g. the full 1,000-cycle
run of bench/run.sh) from a short run of the same scenarios (e.g.
BENCH_CYCLES=50), per scenario and for N scenarios run side by side.

    python3 bench/latency/estimate_duration.py SUMMARY_JSON [--cycles 1000]
        [--peer-every 20] [--pcl-every 100] [--timed-cycles 200] [--jobs 2]

Model, per scenario (W = warm-up cycles = ceil(2 T_B / 50 ms) + 10):
    wall = (W + C) (E + O) + Np (B + F) + Nq P + [T_B 0.5: (W + Ct) (Et + O)]
with E the engine's mean cycle, B / F / P the batch, frame and PCL peers'
mean times, Et the timed pass's median cycle, Np = ceil(C / peer_every),
Nq = ceil(C / pcl_every) (PCL scenarios only), and O the per-cycle rest
(simulating the slice, memory_usage(), bookkeeping) solved from the short
run's measured wall time. The projection is printed as measured (the short
run's load) and "unloaded": scaled by the engine's CPU / wall ratio of the
short run (the thread's CPU time is not inflated by other processes; the
peers and the simulator are assumed to be slowed down alike). The side-by-side
total simulates run.sh's scheduler (longest expected first, N workers).
"""
import argparse
import json
import math


def warmup(tb):
    return math.ceil(2.0 * tb / 0.05 - 1e-9) + 10


def ms(block, key="mean"):
    return 0.0 if block is None else block["ms"][key] * 1e-3


def runsh_weight(name):
    """The order of bench/run.sh (keep in sync): longest expected first."""
    w = {"tb0.5": 4, "tb0.4": 3, "tb0.3": 2}.get(name[-5:], 0)
    if any(f"-{c}-" in name for c in ("euclid", "carc", "capped")):
        w += 3
    if "office" in name:
        w += 1
    return w


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("summary")
    ap.add_argument("--cycles", type=int, default=1000)
    ap.add_argument("--peer-every", type=int, default=20)
    ap.add_argument("--pcl-every", type=int, default=100)
    ap.add_argument("--timed-cycles", type=int, default=200)
    ap.add_argument("--jobs", type=int, default=2)
    a = ap.parse_args()
    data = json.load(open(a.summary))
    c0, pe0, pc0, t0 = data["cycles"], data["peer_every"], data["pcl_every"], data["timed_cycles"]
    rows = []
    for s in data["scenarios"]:
        tb = s["window_s"]
        w = warmup(tb)
        e = s["latency_ms"]["mean"] * 1e-3
        load = s["cpu_ms"]["mean"] / s["latency_ms"]["mean"] if s["latency_ms"]["mean"] > 0 else 1.0
        b, f, p = ms(s["batch"]), ms(s["frame"]), ms(s["pcl"])
        timed = s["timed_cycles"] > 0
        et = s["timed_median_ms"] * 1e-3
        np0 = s["batch"]["ms"]["count"] if s["batch"] else 0
        nq0 = s["pcl"]["ms"]["count"] if s["pcl"] else 0
        known = (w + c0) * e + np0 * (b + f) + nq0 * p + ((w + t0) * et if timed else 0.0)
        rest_cycles = (w + c0) + ((w + t0) if timed else 0)
        o = max(0.0, (s["wall_seconds"] - known) / rest_cycles)
        np1 = math.ceil(a.cycles / a.peer_every) if np0 else 0
        nq1 = math.ceil(a.cycles / a.pcl_every) if nq0 else 0
        t1 = a.timed_cycles if timed else 0
        wall = (w + a.cycles) * (e + o) + np1 * (b + f) + nq1 * p + ((w + t1) * (et + o) if timed else 0.0)
        rows.append((s["name"], s["wall_seconds"], wall, wall * load, load))
    print(f"short run: {c0} cycles, peers every {pe0}, PCL every {pc0}, {t0} timed cycles; projection: "
          f"{a.cycles} cycles, peers every {a.peer_every}, PCL every {a.pcl_every}, {a.timed_cycles} timed cycles\n")
    print("| scenario | short run [s] | projected [s] | engine CPU / wall | projected unloaded [s] |")
    print("|---|---|---|---|---|")
    for name, short, wall, unloaded, load in rows:
        print(f"| {name} | {short:.0f} | {wall:.0f} | {load:.2f} | {unloaded:.0f} |")

    def schedule(durations):
        order = sorted(durations, key=lambda x: -runsh_weight(x[0]))  # stable, as sort -s
        workers = [0.0] * a.jobs
        for _, d in order:
            i = workers.index(min(workers))
            workers[i] += d
        return max(workers)

    for label, k in (("as measured", 2), ("unloaded", 3)):
        total = sum(r[k] for r in rows)
        side = schedule([(r[0], r[k]) for r in rows])
        print(f"\n{label}: sequential {total / 60:.0f} min; {a.jobs} side by side {side / 60:.0f} min")


if __name__ == "__main__":
    main()
