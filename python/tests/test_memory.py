# SPDX-License-Identifier: MIT
"""No leak over 1,000 retrieve calls: reference counts and resident memory."""

import gc
import sys
import weakref

import numpy as np

import streamclust


def rss_kib():
    with open("/proc/self/statm") as f:
        pages = int(f.read().split()[1])
    import resource
    return pages * resource.getpagesize() // 1024


def filled_clusterer():
    sim = streamclust.simulate("mid360", "office", seconds=0.3, seed=5)
    c = streamclust.Clusterer(preset="carc-mid360")
    c.insert(sim.xyz, sim.t, sim.intensity)
    c.complete_calibration()
    return c, sim


def test_retrieve_references_are_released():
    c, sim = filled_clusterer()
    r = c.retrieve()
    assert len(r.index) > 1000 and len(r.components) > 3
    refs = [weakref.ref(a) for a in (r.index, r.labels, r.components)]
    # getrefcount's own argument + the Retrieval's attribute (counted outside
    # the assert: pytest's rewriting holds its operands)
    counts = [sys.getrefcount(r.index), sys.getrefcount(r.labels), sys.getrefcount(r.components)]
    assert counts == [2, 2, 2]
    assert all(a.base is None for a in (r.index, r.labels, r.components)), "each owns its data"
    del r
    gc.collect()
    assert all(ref() is None for ref in refs), "the arrays die with the Retrieval"
    # The input arrays are not held by the clusterer either.
    before = [sys.getrefcount(a) for a in (sim.xyz, sim.t)]
    for _ in range(100):
        c.insert(sim.xyz[:10], sim.t[-10:] + 1.0)
    assert [sys.getrefcount(a) for a in (sim.xyz, sim.t)] == before


def test_no_leak_over_1000_retrievals():
    c, sim = filled_clusterer()
    owner = sys.getrefcount(c._engine)
    for _ in range(100):  # warm up: the engine's result buffers reach their size
        c.retrieve()
    gc.collect()
    objects_before = len(gc.get_objects())
    rss_before = rss_kib()
    for _ in range(1000):
        r = c.retrieve()
        assert r.labels.dtype == np.int32
    del r
    gc.collect()
    grown_kib = rss_kib() - rss_before
    owner_after = sys.getrefcount(c._engine)  # outside the assert: pytest's rewriting holds its operands
    assert owner_after == owner
    assert len(gc.get_objects()) - objects_before < 50
    # One retrieval holds ~20,000 rows (12 bytes each, ~0.24 MB): a leak of
    # one per call would be ~240 MB over 1,000 calls.
    assert grown_kib < 4096, f"resident memory grew by {grown_kib} KiB over 1,000 retrievals"
