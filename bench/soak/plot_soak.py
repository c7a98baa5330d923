#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Draws bench_soak's CSV files as one PNG: the resident set's growth over
the end of the first window (top) and the P99 cycle latency (bottom) over
stream time, one colour per preset.

    python3 bench/soak/plot_soak.py build/soak/record -o docs/img/soak.png

Reads DIR/soak_<preset>.csv (one row per second) and, when present,
DIR/soak_<preset>_cycles.csv (one row per cycle) for the presets found.
The P99 is nearest rank over 10 s of steady cycles (200 cycles) and over
each minute; without the cycles file, the per-second maximum is drawn.
Needs matplotlib (Debian: python3-matplotlib).
"""
import argparse
import csv
import math
import os
import sys

PRESETS = [("carc", "carc (default)", "tab:blue"), ("objects-mid360", "objects-mid360", "tab:orange")]


def read_rows(path):
    with open(path, newline="") as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def nearest_rank(values, p):
    """Nearest-rank percentile (the project's definition, percentiles.hpp)."""
    v = sorted(values)
    if not v:
        return float("nan")
    rank = max(1, math.ceil(p / 100.0 * len(v)))
    return v[min(rank, len(v)) - 1]


def p99_by(cycles, span, warmup, column="latency_us"):
    """[(start, end, p99_ms)] of `column` over consecutive spans of stream time [s], steady cycles only."""
    groups = {}
    for c in cycles:
        if c["retrieved"] and c["time_s"] > warmup + 1e-9:
            groups.setdefault(int((c["time_s"] - 1e-9) // span), []).append(c[column] / 1000.0)
    return [(k * span, (k + 1) * span, nearest_rank(v, 99.0)) for k, v in sorted(groups.items())]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("dir", help="bench_soak's --out-dir")
    ap.add_argument("-o", "--output", default="soak.png", help="PNG to write (default soak.png)")
    ap.add_argument("--warmup", type=float, default=10.0, help="stream time before the steady state [s] (default 10)")
    ap.add_argument("--window", type=float, default=1.0,
                    help="stream second whose RSS is the baseline (the end of the first window; default 1)")
    args = ap.parse_args()

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_rss, ax_p99) = plt.subplots(2, 1, figsize=(8.0, 6.0), sharex=True, dpi=100)
    found = 0
    for preset, label, colour in PRESETS:
        seconds_csv = os.path.join(args.dir, f"soak_{preset}.csv")
        if not os.path.exists(seconds_csv):
            continue
        found += 1
        seconds = read_rows(seconds_csv)
        base = next((s["rss_kib"] for s in seconds if s["second"] == args.window), seconds[0]["rss_kib"])
        minutes = [s["second"] / 60.0 for s in seconds]
        growth = [100.0 * (s["rss_kib"] - base) / base for s in seconds]
        ax_rss.step(minutes, growth, where="post", color=colour, lw=1.4,
                    label=f"{label}: over {base / 1024.0:.1f} MiB at {args.window:.0f} s (the first window), "
                          f"max {max(growth[1:] or [0]):+.2f} %")

        cycles_csv = os.path.join(args.dir, f"soak_{preset}_cycles.csv")
        if os.path.exists(cycles_csv):
            cycles = read_rows(cycles_csv)
            fine = p99_by(cycles, 10.0, args.warmup)
            ax_p99.plot([(a + b) / 120.0 for a, b, _ in fine], [p for _, _, p in fine], color=colour, lw=0.7,
                        alpha=0.6, label=f"{label}: P99 per 10 s")
            for i, (a, b, p) in enumerate(p99_by(cycles, 60.0, args.warmup)):
                ax_p99.hlines(p, max(a, args.warmup) / 60.0, b / 60.0, color=colour, lw=2.4,
                              label=f"{label}: P99 per minute" if i == 0 else None)
            for i, (a, b, p) in enumerate(p99_by(cycles, 60.0, args.warmup, "cpu_us")):
                ax_p99.hlines(p, max(a, args.warmup) / 60.0, b / 60.0, color=colour, lw=1.2, ls=(0, (3, 2)),
                              label=f"{label}: CPU-time P99 per minute" if i == 0 else None)
        else:
            steady = [s for s in seconds if s["second"] > args.warmup]
            ax_p99.plot([s["second"] / 60.0 for s in steady], [s["p99_ms"] for s in steady], color=colour, lw=0.7,
                        label=f"{label}: max per second")
    if found == 0:
        sys.exit(f"plot_soak: no soak_<preset>.csv in {args.dir}")

    ax_rss.axhline(1.0, color="tab:red", ls="--", lw=1.0, label="target: growth under 1 %")
    ax_rss.set_ylabel("RSS growth [%]")
    ax_rss.set_ylim(min(-0.25, ax_rss.get_ylim()[0]), max(1.5, ax_rss.get_ylim()[1]))
    ax_rss.legend(loc="upper left", fontsize=8, frameon=False)
    ax_rss.grid(alpha=0.3)
    ax_rss.set_title("Soak: simulated Mid-360 office, 20 Hz retrievals, as fast as it goes", fontsize=10)
    for ax in (ax_rss, ax_p99):
        ax.axvspan(0, args.warmup / 60.0, color="0.85", lw=0)
    ax_p99.set_ylabel("cycle latency P99 [ms]")
    ax_p99.set_xlabel("stream time [min] (grey: warm-up)")
    ax_p99.set_ylim(0, 1.5 * ax_p99.get_ylim()[1])  # room for the legend above the lines
    ax_p99.legend(loc="upper left", fontsize=7, frameon=False, ncol=2)
    ax_p99.set_xlim(0, max(ax_p99.get_xlim()[1], 0.1))
    ax_p99.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.output, dpi=100, bbox_inches="tight", pad_inches=0.1)
    print(f"plot_soak: wrote {args.output}")


if __name__ == "__main__":
    main()
