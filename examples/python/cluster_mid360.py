#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Simulate a Livox Mid-360 in an office, cluster the stream continuously,
print the scores of every retrieval and save a picture of the last window.

  PYTHONPATH=build/gcc/python python3 examples/python/cluster_mid360.py [--out mid360.png] [--seconds 2]
"""

import argparse

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import streamclust  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default="mid360.png", help="picture of the last window (PNG)")
    p.add_argument("--seconds", type=float, default=2.0, help="stream length [s]")
    p.add_argument("--seed", type=int, default=7)
    p.add_argument("--preset", default="objects-mid360",
                   help="objects-mid360 (ground and ceiling removed) or carc-mid360")
    a = p.parse_args()

    # 1. A simulated stream with ground truth: instance ids, 0 = structure.
    sim = streamclust.simulate("mid360", "office", seconds=a.seconds, seed=a.seed)
    print(f"simulated {len(sim.t)} points over {sim.t[-1] - sim.t[0]:.2f} s")

    # 2. The CLI's retrieval schedule (20 Hz); objects-mid360 takes ground and ceiling out
    #    (mount and sensor height estimated from the first window, as the CLI does).
    retrievals = streamclust.cluster_stream(sim.xyz, sim.t, sim.intensity, preset=a.preset, rate=20)

    # 3. Scores per retrieval on the window's rows.
    print(f"{'cycle':>5} {'time':>7} {'points':>7} {'comps':>6} {'ARI':>6} {'PQ':>6} {'USE':>6}")
    for r in retrievals:
        m = streamclust.evaluate(r.labels, sim.truth[r.index])
        print(f"{r.cycle:5d} {r.time:7.3f} {len(r):7d} {len(r.components):6d} {m['ari']:6.3f} {m['pq']:6.3f} "
              f"{m['use']:6.3f}")

    # 4. The last window from above, coloured by component (grey: unlabelled, ground, ceiling).
    last = retrievals[-1]
    xyz = sim.xyz[last.index]
    big = last.components["id"][last.components["size"] >= 20]
    keep = np.isin(last.labels, big)
    fig, ax = plt.subplots(figsize=(7, 7))
    ax.scatter(xyz[~keep, 0], xyz[~keep, 1], s=0.2, c="0.8")
    ax.scatter(xyz[keep, 0], xyz[keep, 1], s=0.4, c=last.labels[keep] % 20, cmap="tab20")
    # (components["centroid"] is in the engine's frame: the world, levelled by the
    # estimated mount; the picture is in the sensor frame, so label at the points' mean)
    for cid in big:
        ax.annotate(str(cid), xyz[last.labels == cid, :2].mean(axis=0), fontsize=6)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"Mid-360 office, {a.preset}, cycle {last.cycle} at t = {last.time:.2f} s: "
                 f"{len(big)} components >= 20 points", fontsize=9)
    fig.savefig(a.out, dpi=120)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
