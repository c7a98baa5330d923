#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Compare two builds of a Google Benchmark program in the same session.

Runs OLD and NEW alternately (old, new, old, new, ...) `--rounds` times with
the same Google Benchmark arguments, then prints, per benchmark, the median
over the rounds of items_per_second (CPU time; the machine may be shared)
of each build and their ratio new / old. Benchmarks are matched by name
after applying `--rename PATTERN=REPLACEMENT` (Python regular expressions,
in order) to the NEW names.

  bench/compare_runs.py --old OLD_BINARY --new NEW_BINARY --rounds 5 \\
      --rename '/sample/mid360_office_back16$=' -- --benchmark_min_time=0.2
"""
import argparse
import json
import re
import statistics
import subprocess
import sys


def run(binary, args):
    out = subprocess.run([binary, "--benchmark_format=json", *args], check=True, capture_output=True, text=True)
    rates = {}
    for b in json.loads(out.stdout)["benchmarks"]:
        if "items_per_second" in b:
            rates[b["name"]] = b["items_per_second"]
    return rates


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--old", required=True)
    ap.add_argument("--new", required=True)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--rename", action="append", default=[], help="PATTERN=REPLACEMENT applied to NEW names")
    ap.add_argument("bench_args", nargs="*")
    a = ap.parse_args()
    renames = [tuple(r.split("=", 1)) for r in a.rename]
    old, new = {}, {}
    for i in range(a.rounds):
        for binary, store in ((a.old, old), (a.new, new)):
            for name, rate in run(binary, a.bench_args).items():
                if store is new:
                    for pattern, repl in renames:
                        name = re.sub(pattern, repl, name)
                store.setdefault(name, []).append(rate)
        print(f"round {i + 1}/{a.rounds} done", file=sys.stderr)
    common = [n for n in old if n in new]
    if not common:
        sys.exit("no benchmark name in common (see --rename)")
    width = max(len(n) for n in common)
    print(f"{'benchmark':<{width}}  {'old M/s':>9}  {'new M/s':>9}  {'new/old':>7}  (medians of {a.rounds} alternating runs)")
    ratios = []
    for n in common:
        o, w = statistics.median(old[n]), statistics.median(new[n])
        ratios.append(w / o)
        print(f"{n:<{width}}  {o / 1e6:9.2f}  {w / 1e6:9.2f}  {w / o:7.3f}")
    print(f"{'median ratio':<{width}}  {'':9}  {'':9}  {statistics.median(ratios):7.3f}")


if __name__ == "__main__":
    main()
