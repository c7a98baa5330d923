#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Insertion throughput from numpy vs the C++ insert_batch on the same stream.

Simulates a stream (or takes FILE), writes it as CSV, then times, R times each
(interleaved, C++ then Python in each repetition):
  C++:    streamclust_py_insert_rate FILE  (insert_batch over std::vector<Point>, packets of P)
  Python: Clusterer.insert(xyz, t, intensity) over numpy packets of P (the same points, read
          back from the same CSV with streamclust.read)
and prints the medians and the ratio (target: Python >= 90 % of C++).

  PYTHONPATH=build/gcc/python python3 python/bench/throughput.py \\
      --insert-rate build/gcc/python/streamclust_py_insert_rate [--seconds 5] [--packet 10000] [--repeat 5]
"""

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import streamclust


def python_seconds(xyz, t, intensity, preset, packet):
    c = streamclust.Clusterer(preset=preset)
    total = 0.0
    for start in range(0, len(t), packet):
        stop = start + packet
        x, tt, i = xyz[start:stop], t[start:stop], intensity[start:stop]
        t0 = time.perf_counter()
        c.insert(x, tt, i)
        total += time.perf_counter() - t0
    return total


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--insert-rate", required=True, help="the built streamclust_py_insert_rate program")
    p.add_argument("--file", help="a point file (default: a simulated Mid-360 office stream)")
    p.add_argument("--seconds", type=float, default=5.0, help="simulated stream length [s]")
    p.add_argument("--preset", default="carc-mid360")
    p.add_argument("--packet", type=int, default=10000)
    p.add_argument("--repeat", type=int, default=5)
    a = p.parse_args()

    with tempfile.TemporaryDirectory() as tmp:
        path = a.file
        if path is None:
            sim = streamclust.simulate("mid360", "office", seconds=a.seconds, seed=7)
            path = str(Path(tmp) / "stream.csv")
            with open(path, "w") as f:
                f.write("x,y,z,intensity,t\n")
                rows = np.column_stack([sim.xyz.astype(np.float64), sim.intensity, sim.t])
                np.savetxt(f, rows, fmt=["%.9g", "%.9g", "%.9g", "%.9g", "%.17g"], delimiter=",")
        data = streamclust.read(path)
        xyz = np.column_stack([data["x"], data["y"], data["z"]])  # (N, 3) float32, C-contiguous
        t, intensity = data["t"], data["intensity"]

        # Interleaved, one run of each per repetition, so a load change on a
        # shared machine hits both sides alike.
        cpp_seconds, py = [], []
        for _ in range(a.repeat):
            run = subprocess.run([a.insert_rate, path, "--preset", a.preset, "--packet", str(a.packet),
                                  "--repeat", "1"], check=True, capture_output=True, text=True)
            cpp_seconds.extend(json.loads(run.stdout)["seconds"])
            py.append(python_seconds(xyz, t, intensity, a.preset, a.packet))
    py_rate = len(t) / statistics.median(py)
    cpp_rate = len(t) / statistics.median(cpp_seconds)
    result = {
        "points": len(t), "packet": a.packet, "repeat": a.repeat, "preset": a.preset,
        "cpp_seconds": cpp_seconds, "python_seconds": [round(s, 6) for s in py],
        "cpp_median_points_per_second": round(cpp_rate), "python_median_points_per_second": round(py_rate),
        "ratio": round(py_rate / cpp_rate, 4),
    }
    print(json.dumps(result))
    return 0 if result["ratio"] >= 0.9 else 1


if __name__ == "__main__":
    sys.exit(main())
