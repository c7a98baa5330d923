# SPDX-License-Identifier: MIT
"""Clusterer(tracks=True): every retrieval's tracks, tied to its components;
standing objects reported still and walkers moving (the simulator's truth)."""

import numpy as np
import pytest

import streamclust


def walking_instances(sim, segment=0.25, path=1.0):
    """Instances whose points' centroid travels more than `path` metres over
    the stream, from segment to segment (walkers; a cabinet coming into view
    moves its centroid by a few decimetres)."""
    moving = set()
    bins = (sim.t // segment).astype(np.int64)
    for instance in np.unique(sim.truth[sim.truth > 0]):
        mask = sim.truth == instance
        centres = [sim.xyz[mask & (bins == b)].mean(axis=0) for b in np.unique(bins[mask])
                   if np.count_nonzero(mask & (bins == b)) >= 5]
        travelled = sum(np.linalg.norm(b[:2] - a[:2]) for a, b in zip(centres, centres[1:]))
        if travelled > path:
            moving.add(int(instance))
    return moving


def test_tracks_follow_the_retrievals():
    sim = streamclust.simulate("mid360", "office", seconds=2.5, seed=1)
    walking = walking_instances(sim)
    assert walking
    c = streamclust.Clusterer(preset="objects-mid360", sensor_height=1.0, tracks=True)
    static_rows = still = 0
    seen_moving = set()
    retrievals = 0
    for k in range(50):
        sel = (sim.t >= k * 0.05) & (sim.t < (k + 1) * 0.05)
        c.insert(np.ascontiguousarray(sim.xyz[sel]), np.ascontiguousarray(sim.t[sel]))
        r = c.retrieve((k + 1) * 0.05)
        assert r.tracks is not None
        assert r.tracks.dtype == streamclust.TRACK_DTYPE
        if c.calibrating:
            continue
        retrievals += 1
        assert len(np.unique(r.tracks["track_id"])) == len(r.tracks)
        sizes = dict(zip(r.components["id"].tolist(), r.components["size"].tolist()))
        truth = sim.truth[r.index]
        for track in r.tracks:
            state = streamclust.TRACK_STATES[track["state"]]
            if track["cluster_id"] < 0:
                assert state != "confirmed" and track["points"] == 0
                continue
            assert sizes[int(track["cluster_id"])] == track["points"] >= 10
            if state != "confirmed":
                continue
            members = truth[r.labels == track["cluster_id"]]
            instance = np.bincount(members[members >= 0]).argmax()
            speed = float(np.hypot(*track["velocity"][:2]))
            if instance in walking:
                if speed >= 0.4:
                    seen_moving.add(int(instance))
            elif instance > 0:
                static_rows += 1
                still += speed < 0.2 and not track["moving"]
    assert retrievals >= 30
    assert static_rows >= 100
    assert still >= 0.95 * static_rows
    assert seen_moving == walking


def test_tracks_are_off_by_default_and_need_the_continuous_mode():
    sim = streamclust.simulate("mid360", "office", seconds=0.6, seed=1)
    c = streamclust.Clusterer(preset="objects-mid360", sensor_height=1.0)
    c.insert(np.ascontiguousarray(sim.xyz), np.ascontiguousarray(sim.t))
    assert c.retrieve().tracks is None
    with pytest.raises(ValueError, match="tracks"):
        streamclust.Clusterer(preset="baseline", tracks=True)
    with pytest.raises(ValueError, match="tracks"):
        streamclust.Clusterer(preset="objects-mid360", tracks="yes")
