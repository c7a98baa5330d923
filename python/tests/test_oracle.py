# SPDX-License-Identifier: MIT
"""The oracle from Python: at every retrieval the continuous partition is the
batch partition of the window.

With the Euclidean linkage on a one-cell grid (every window point is a
candidate neighbour of every other), the batch partition is the connected
components of the graph "distance <= d" over the window's points, computed
here by brute force in numpy, independently of the C++ code.
"""

import numpy as np
import pytest

import streamclust
from conftest import same_partition


def batch_components(points, d):
    """Connected components of |p - q| <= d (union-find over all pairs)."""
    n = len(points)
    parent = np.arange(n)

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    p = points.astype(np.float64)
    for i in range(n):
        dist2 = ((p[i + 1:] - p[i]) ** 2).sum(axis=1)
        for j in np.nonzero(dist2 <= d * d)[0] + i + 1:
            a, b = find(i), find(j)
            if a != b:
                parent[a] = b
    return np.array([find(i) for i in range(n)])


def random_stream(rng, n, seconds):
    """Blobs around the sensor, some points far, a few NaN and too-close points."""
    centres = rng.uniform(-8, 8, size=(12, 3))
    centres[:, 2] = rng.uniform(-1, 2, size=12)
    which = rng.integers(0, len(centres), size=n)
    xyz = centres[which] + rng.normal(scale=0.35, size=(n, 3))
    xyz[rng.random(n) < 0.01] = np.nan
    xyz[rng.random(n) < 0.005] = 0.01
    t = np.sort(rng.uniform(0, seconds, size=n))
    return np.ascontiguousarray(xyz, dtype=np.float32), t


@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_continuous_partition_is_the_batch_partition(seed):
    rng = np.random.default_rng(seed)
    xyz, t = random_stream(rng, 3000, 1.0)
    d = 0.3
    c = streamclust.Clusterer(preset="carc", linkage="euclidean", distance=d, grid=(1, 1), mask=1,
                              window_time=0.15)
    retrievals = 0
    for start in range(0, len(t), 250):
        stop = start + 250
        c.insert(xyz[start:stop], t[start:stop])
        r = c.retrieve()
        window = r.labels >= 0
        assert (r.labels[~window] == streamclust.UNLABELLED).all()
        points = xyz[r.index[window]]
        assert np.isfinite(points).all()
        assert same_partition(r.labels[window], batch_components(points, d)), f"retrieval at t = {r.time}"
        assert len(r.components) == len(np.unique(r.labels[window]))
        assert r.components["size"].sum() == window.sum()
        assert r.components.dtype == streamclust.COMPONENT_DTYPE
        assert r.index.dtype == np.int64 and r.labels.dtype == np.int32
        retrievals += 1
    assert retrievals == 12


def test_rejected_points_have_reasons_and_rows():
    rng = np.random.default_rng(9)
    xyz, t = random_stream(rng, 2000, 0.5)
    c = streamclust.Clusterer(preset="carc", grid=(8, 64))
    accepted, reasons = c.insert(xyz, t, reasons=True)
    names = np.array(streamclust.REJECT_REASONS)[reasons]
    nan_rows = np.isnan(xyz).any(axis=1)
    assert (names[nan_rows] == "non_finite").all()
    assert accepted == (reasons == 0).sum()
    assert accepted < len(t)
    r = c.retrieve()
    rejected_in_rows = r.index[r.labels == streamclust.UNLABELLED]
    assert set(rejected_in_rows) <= set(np.nonzero(reasons != 0)[0])
