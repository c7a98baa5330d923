#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The performance targets of the engine (docs/performance.md, "Targets"),
each marked met / missed with the measured value, from bench_latency's
summary.json (printed as markdown).

    python3 bench/latency/targets.py build/bench-run/results/latency/summary.json

Each target is evaluated for the best preset that was run and meets the
quality condition (mean ARI of the scenario within 0.02 of the paper preset's
on the same sensor, scene and T_B; the paper preset itself always qualifies);
the verdict is the best preset's. The paper preset's row (C-ARC: bucket grid,
lazy BFS; for target 2 the capped grid with the lazy BFS, for target 4 the
Euclidean preset) is printed as well, marked "paper", for comparison.

Target 5 (insertion throughput) uses the timed pass's insertion + eviction
phases; a scenario that was not run is reported as "not measured".

Targets 3 and 6 are the restated ones: the engine's median at most 1/3 of
batch re-clustering (BATCH_RATIO_BAR), and at most 128 bytes per window point
with zero steady allocations on the Mid-360 office at T_B = 0.5 s (the
scenario of TARGET6_SCENARIO; the other capped-grid scenarios are printed
for information, without a verdict).

Target 7 is the objects presets' (ObjectsConfig with ground removal and
PosedMotion): P99 at most 20 % of the period at T_B = 0.5 s on each of
OBJECTS_SCENES, at rest ("objects") and moving with poses ("objects-moving");
no quality condition (no other preset removes the ground).
"""
import json
import sys

BUDGET_MS = 50.0
ARI_TOLERANCE = 0.02
TB = ("0.1", "0.2", "0.3", "0.4", "0.5")
BATCH_RATIO_BAR = 3.0  # target 3: batch median / engine median >= 3
BYTES_PER_POINT_BAR = 128.0  # target 6
TARGET6_SCENARIO = ("mid360", "office", "0.5")
CAPPED_CONFIGS = ("capped", "capfast", "caprebuild")
OBJECTS_SCENES = (("mid360", "office"), ("mid360", "forest"), ("avia", "office"))
OBJECTS_CONFIGS = ("objects", "objects-moving")


def main(path):
    data = json.load(open(path))
    sc = {s["name"]: s for s in data["scenarios"]}
    rows = []

    def add(target, what, measured, bar, ok, role=""):
        verdict = "not measured" if ok is None else ("met" if ok else "MISSED")
        if role == "paper":
            verdict = f"({verdict.lower()} for the paper preset)"
        rows.append((target, what, measured, bar, verdict))

    def get(sensor, scene, config, tb):
        return sc.get(f"{sensor}-{scene}-{config}-tb{tb}")

    def quality_ok(s, reference):
        """ARI within ARI_TOLERANCE of the reference (paper) scenario."""
        if reference is None or s is reference:
            return True
        return s["ari_engine_mean"] >= reference["ari_engine_mean"] - ARI_TOLERANCE

    def best(sensor, scene, tb, configs, reference_config, key):
        """(config, scenario) minimising key among the configs that ran and meet quality."""
        ref = get(sensor, scene, reference_config, tb)
        found = [(c, get(sensor, scene, c, tb)) for c in configs]
        found = [(c, s) for c, s in found if s is not None and quality_ok(s, ref) and key(s) is not None]
        return min(found, key=lambda cs: key(cs[1])) if found else (None, None)

    p99 = lambda s: s["latency_ms"]["p99"]  # noqa: E731
    median = lambda s: s["latency_ms"]["median"]  # noqa: E731

    # 1. Mid-360, office and forest, T_B = 0.5: P99 <= 20 % of the cycle period.
    for scene in ("office", "forest"):
        paper = get("mid360", scene, "carc", "0.5")
        c, s = best("mid360", scene, "0.5", ("carc", "fast", "capfast", "rebuild"), "carc", p99)
        if s is None:
            add(1, f"Mid-360 {scene} T_B 0.5 P99", "-", "<= 20 % of 50 ms", None)
            continue
        for role, cfg, x in (("paper", "carc", paper), ("best", c, s)):
            if x is None or (role == "paper" and c == "carc"):
                continue
            r = p99(x) / BUDGET_MS
            add(1, f"Mid-360 {scene} T_B 0.5, {cfg}: P99 {p99(x):.2f} ms", f"{100 * r:.0f} %", "<= 20 %", r <= 0.2,
                role)

    # 2. Avia office, capped grid, every T_B <= 0.5: P99 <= 20 %, ARI within 0.02 of the bucket grid.
    for tb in TB:
        paper = get("avia", "office", "capped", tb)
        bucket = get("avia", "office", "carc", tb)
        c, s = best("avia", "office", tb, ("capped", "capfast", "caprebuild"), "carc", p99)
        if s is None:
            add(2, f"Avia office capped T_B {tb}", "-", "", None)
            continue
        for role, cfg, x in (("paper", "capped", paper), ("best", c, s)):
            if x is None or (role == "paper" and c == "capped"):
                continue
            r = p99(x) / BUDGET_MS
            add(2, f"Avia office T_B {tb}, {cfg}: P99 {p99(x):.2f} ms", f"{100 * r:.0f} %", "<= 20 %", r <= 0.2, role)
        if bucket is not None:
            d = s["ari_engine_mean"] - bucket["ari_engine_mean"]
            add(2, f"Avia office T_B {tb}: ARI {c} {s['ari_engine_mean']:.4f} vs bucket (carc) "
                   f"{bucket['ari_engine_mean']:.4f}", f"{d:+.4f}", ">= -0.02", d >= -ARI_TOLERANCE)

    # 3. Mid-360, T_B = 0.5: engine median <= 1/3 of batch re-clustering.
    def batch_ratio(s):
        return None if s["batch"] is None else s["batch"]["ms"]["median"] / median(s)

    for scene in ("office", "forest"):
        paper = get("mid360", scene, "carc", "0.5")
        c, s = best("mid360", scene, "0.5", ("carc", "fast", "capfast", "rebuild"), "carc",
                    lambda x: None if batch_ratio(x) is None else -batch_ratio(x))
        if s is None:
            add(3, f"Mid-360 {scene} T_B 0.5 batch/engine", "-", f">= {BATCH_RATIO_BAR:g}x", None)
            continue
        for role, cfg, x in (("paper", "carc", paper), ("best", c, s)):
            if x is None or batch_ratio(x) is None or (role == "paper" and c == "carc"):
                continue
            r = batch_ratio(x)
            add(3, f"Mid-360 {scene} T_B 0.5, {cfg}: batch median {x['batch']['ms']['median']:.2f} ms / engine "
                   f"{median(x):.2f} ms", f"{r:.2f}x", f">= {BATCH_RATIO_BAR:g}x", r >= BATCH_RATIO_BAR, role)

    # 4. >= 20x faster than PCL per window (median, T_B = 0.5): Euclidean scenarios (PCL runs only there).
    def pcl_ratio(s):
        return None if s["pcl"] is None else s["pcl"]["ms"]["median"] / median(s)

    for sensor in ("mid360", "avia"):
        for scene in ("office", "forest"):
            paper = get(sensor, scene, "euclid", "0.5")
            c, s = best(sensor, scene, "0.5", ("euclid", "euclidfast"), "euclid",
                        lambda x: None if pcl_ratio(x) is None else -pcl_ratio(x))
            if paper is None and s is None:
                continue
            if s is None:
                add(4, f"{sensor}-{scene} T_B 0.5: PCL / engine", "-", ">= 20x", None)
                continue
            for role, cfg, x in (("paper", "euclid", paper), ("best", c, s)):
                if x is None or pcl_ratio(x) is None or (role == "paper" and c == "euclid"):
                    continue
                r = pcl_ratio(x)
                add(4, f"{sensor}-{scene} T_B 0.5, {cfg}: PCL median {x['pcl']['ms']['median']:.1f} ms / engine "
                       f"{median(x):.2f} ms", f"{r:.2f}x", ">= 20x", r >= 20, role)

    # 5. Insertion throughput >= 2 M points/s, Mid-360 preset (timed pass).
    def throughput(s):
        if s["timed_cycles"] == 0 or s["phase_mean_ms"]["insertion"] <= 0:
            return None
        ins = s["phase_mean_ms"]["insertion"] + s["phase_mean_ms"]["eviction"]
        return s["points_per_cycle_mean"] / ins / 1e3

    for scene in ("office", "forest"):
        paper = get("mid360", scene, "carc", "0.5")
        c, s = best("mid360", scene, "0.5", ("carc", "fast", "capfast", "rebuild"), "carc",
                    lambda x: None if throughput(x) is None else -throughput(x))
        if s is None:
            add(5, f"Mid-360 {scene} insertion throughput", "-", ">= 2 M/s", None)
            continue
        for role, cfg, x in (("paper", "carc", paper), ("best", c, s)):
            if x is None or throughput(x) is None or (role == "paper" and c == "carc"):
                continue
            mps = throughput(x)
            ins = x["phase_mean_ms"]["insertion"] + x["phase_mean_ms"]["eviction"]
            add(5, f"Mid-360 {scene} T_B 0.5, {cfg}: {x['points_per_cycle_mean']:.0f} points per {ins:.2f} ms "
                   "(insertion + eviction phases)", f"{mps:.2f} M/s", ">= 2 M/s", mps >= 2, role)

    # 6. <= 128 bytes per windowed point and zero steady-state allocations, Mid-360 office at T_B = 0.5 s,
    #    best capped-grid preset (fewest bytes); the other capped-grid scenarios for information.
    sensor, scene, tb = TARGET6_SCENARIO
    bpp = lambda x: x["bytes_per_point"]["median"]  # noqa: E731
    c, s = best(sensor, scene, tb, CAPPED_CONFIGS, "carc", bpp)
    if s is None:
        add(6, f"{sensor}-{scene} T_B {tb}, capped grid: bytes per window point", "-",
            f"<= {BYTES_PER_POINT_BAR:g} B", None)
    else:
        name = s["name"]
        add(6, f"{name}: bytes per window point (median)", f"{bpp(s):.1f} B", f"<= {BYTES_PER_POINT_BAR:g} B",
            bpp(s) <= BYTES_PER_POINT_BAR)
        add(6, f"{name}: heap allocations after warm-up",
            f"{s['steady_allocations']} in {s['latency_ms']['count']} cycles", "0", s["steady_allocations"] == 0)
    for name, x in sorted(sc.items()):
        if x["config"] not in CAPPED_CONFIGS or (s is not None and x is s):
            continue
        rows.append((6, f"{name}: bytes per window point (median); heap allocations after warm-up",
                     f"{bpp(x):.1f} B; {x['steady_allocations']} in {x['latency_ms']['count']} cycles", "(information)",
                     "-"))

    # 7. Objects presets, T_B = 0.5 s, ground and pose work included: P99 <= 20 % of the period.
    for sensor, scene in OBJECTS_SCENES:
        for cfg in OBJECTS_CONFIGS:
            x = get(sensor, scene, cfg, "0.5")
            if x is None:
                add(7, f"{sensor}-{scene} T_B 0.5, {cfg}: P99", "-", "<= 20 %", None)
                continue
            r = p99(x) / BUDGET_MS
            ph = x["phase_mean_ms"]
            split = "" if x["timed_cycles"] == 0 else (
                f" (phases: placement {ph.get('placement', 0):.2f}, ground {ph.get('ground', 0):.2f}, "
                f"insertion {ph['insertion']:.2f}, component update {ph['component_update']:.2f} ms)")
            add(7, f"{sensor}-{scene} T_B 0.5, {cfg}: P99 {p99(x):.2f} ms{split}", f"{100 * r:.0f} %", "<= 20 %",
                r <= 0.2)

    print("| target | measurement | measured | bar | verdict |")
    print("|---|---|---|---|---|")
    for t, what, m, bar, verdict in rows:
        print(f"| {t} | {what} | {m} | {bar} | {verdict} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: targets.py summary.json")
    main(sys.argv[1])
