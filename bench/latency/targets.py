#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The six performance targets of issue 5, each marked met / missed with the
measured ratio, from bench_latency's summary.json (printed as markdown).

    python3 bench/latency/targets.py build/bench-run/results/latency/summary.json

Target 5 (insertion throughput) uses the timed pass's insertion phase; a
scenario that was not run is reported as "not measured".
"""
import json
import sys

BUDGET_MS = 50.0


def main(path):
    data = json.load(open(path))
    sc = {s["name"]: s for s in data["scenarios"]}
    rows = []

    def add(target, what, measured, bar, ok):
        rows.append((target, what, measured, bar, "not measured" if ok is None else ("met" if ok else "MISSED")))

    # 1. Mid-360, office and forest, T_B = 0.5: P99 <= 20 % of the cycle period.
    for scene in ("office", "forest"):
        s = sc.get(f"mid360-{scene}-carc-tb0.5")
        if s is None:
            add(1, f"Mid-360 {scene} T_B 0.5 P99", "-", "<= 20 % of 50 ms", None)
            continue
        r = s["latency_ms"]["p99"] / BUDGET_MS
        add(1, f"Mid-360 {scene} T_B 0.5: P99 {s['latency_ms']['p99']:.2f} ms", f"{100 * r:.0f} %", "<= 20 %", r <= 0.2)

    # 2. Avia office, capped grid, every T_B <= 0.5: P99 <= 20 %, ARI within 0.02 of the bucket grid.
    for tb in ("0.1", "0.2", "0.3", "0.4", "0.5"):
        c = sc.get(f"avia-office-capped-tb{tb}")
        b = sc.get(f"avia-office-carc-tb{tb}")
        if c is None:
            add(2, f"Avia office capped T_B {tb}", "-", "", None)
            continue
        r = c["latency_ms"]["p99"] / BUDGET_MS
        add(2, f"Avia office capped T_B {tb}: P99 {c['latency_ms']['p99']:.2f} ms", f"{100 * r:.0f} %", "<= 20 %",
            r <= 0.2)
        if b is not None:
            d = c["ari_engine_mean"] - b["ari_engine_mean"]
            add(2, f"Avia office T_B {tb}: ARI capped {c['ari_engine_mean']:.4f} vs bucket {b['ari_engine_mean']:.4f}",
                f"{d:+.4f}", ">= -0.02", d >= -0.02)

    # 3. Mid-360, T_B = 0.5: engine median <= 1/5 of batch re-clustering.
    for scene in ("office", "forest"):
        s = sc.get(f"mid360-{scene}-carc-tb0.5")
        if s is None or s["batch"] is None:
            add(3, f"Mid-360 {scene} T_B 0.5 batch/engine", "-", ">= 5x", None)
            continue
        r = s["batch"]["ms"]["median"] / s["latency_ms"]["median"]
        add(3, f"Mid-360 {scene} T_B 0.5: batch median {s['batch']['ms']['median']:.2f} ms / engine "
               f"{s['latency_ms']['median']:.2f} ms", f"{r:.2f}x", ">= 5x", r >= 5)

    # 4. >= 20x faster than PCL per window (median, T_B = 0.5): Euclidean scenarios.
    for name, s in sc.items():
        if s["config"] != "euclid" or abs(s["window_s"] - 0.5) > 1e-9:
            continue
        if s["pcl"] is None:
            add(4, f"{name}: PCL / engine", "-", ">= 20x", None)
            continue
        r = s["pcl"]["ms"]["median"] / s["latency_ms"]["median"]
        add(4, f"{name}: PCL median {s['pcl']['ms']['median']:.1f} ms / engine {s['latency_ms']['median']:.2f} ms",
            f"{r:.2f}x", ">= 20x", r >= 20)

    # 5. Insertion throughput >= 2 M points/s, Mid-360 preset.
    for scene in ("office", "forest"):
        s = sc.get(f"mid360-{scene}-carc-tb0.5")
        if s is None or s["timed_cycles"] == 0 or s["phase_mean_ms"]["insertion"] <= 0:
            add(5, f"Mid-360 {scene} insertion throughput", "-", ">= 2 M/s", None)
            continue
        ins = s["phase_mean_ms"]["insertion"] + s["phase_mean_ms"]["eviction"]
        mps = s["points_per_cycle_mean"] / ins / 1e3
        add(5, f"Mid-360 {scene} T_B 0.5: {s['points_per_cycle_mean']:.0f} points per {ins:.2f} ms "
               "(insertion + eviction phases)", f"{mps:.2f} M/s", ">= 2 M/s", mps >= 2)

    # 6. <= 128 bytes per windowed point and zero steady-state allocations, capped grid.
    for name, s in sorted(sc.items()):
        if s["config"] != "capped":
            continue
        bpp = s["bytes_per_point"]["median"]
        add(6, f"{name}: bytes per window point (median)", f"{bpp:.0f} B", "<= 128 B", bpp <= 128)
        add(6, f"{name}: heap allocations after warm-up", f"{s['steady_allocations']} in {s['latency_ms']['count']} cycles",
            "0", s["steady_allocations"] == 0)

    print("| target | measurement | measured | bar | verdict |")
    print("|---|---|---|---|---|")
    for t, what, m, bar, verdict in rows:
        print(f"| {t} | {what} | {m} | {bar} | {verdict} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: targets.py summary.json")
    main(sys.argv[1])
