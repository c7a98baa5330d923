# SPDX-License-Identifier: MIT
"""Clusterer(tracks=True): every retrieval's tracks, tied to its components;
standing objects reported still and walkers moving (the simulator's truth)."""

import numpy as np
import pytest

import streamclust


def walking_instances(sim, segment=0.25, margin=0.8):
    """Instances whose points over the whole stream spread more than `margin`
    metres wider than within a `segment` (walkers, circling ones too; a
    standing object spreads as wide in a segment as in the stream, give or
    take the sides coming into view)."""
    moving = set()
    bins = (sim.t // segment).astype(np.int64)
    for instance in np.unique(sim.truth[sim.truth > 0]):
        mask = sim.truth == instance
        xy = sim.xyz[mask][:, :2]
        whole = np.linalg.norm(xy.max(axis=0) - xy.min(axis=0))
        spans = []
        for b in np.unique(bins[mask]):
            part = sim.xyz[mask & (bins == b)][:, :2]
            if len(part) >= 5:
                spans.append(np.linalg.norm(part.max(axis=0) - part.min(axis=0)))
        if spans and whole - np.median(spans) > margin:
            moving.add(int(instance))
    return moving


def test_tracks_follow_the_retrievals():
    sim = streamclust.simulate("mid360", "office", seconds=2.5, seed=1)
    walking = walking_instances(sim)
    assert walking
    c = streamclust.Clusterer(preset="objects-mid360", mount=(0, 0, 0), sensor_height=1.0, tracks=True)
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
    c = streamclust.Clusterer(preset="objects-mid360", mount=(0, 0, 0), sensor_height=1.0)
    c.insert(np.ascontiguousarray(sim.xyz), np.ascontiguousarray(sim.t))
    assert c.retrieve().tracks is None
    with pytest.raises(ValueError, match="tracks"):
        streamclust.Clusterer(preset="baseline", tracks=True)
    with pytest.raises(ValueError, match="tracks"):
        streamclust.Clusterer(preset="objects-mid360", tracks="yes")


def test_cluster_stream_tracks_are_the_cli_tracks(tool, tmp_path):
    """cluster_stream(tracks=True) cycle k carries the rows of
    `streamclust cluster --tracks` for cycle k: the same ids, states and numbers."""
    import csv
    import subprocess
    stream = tmp_path / "office.csv"
    subprocess.run([tool, "simulate", "--sensor", "mid360", "--scene", "office", "--seconds", "1.5", "--seed", "1",
                    "--out", str(stream), "--quiet"], check=True)
    rows = tmp_path / "tracks.csv"
    subprocess.run([tool, "cluster", str(stream), "--preset", "objects-mid360", "--mount", "0,0,0",
                    "--sensor-height", "1.0", "--rate", "20", "--tracks", str(rows), "--quiet"], check=True)
    cli = {}
    with open(rows) as f:
        for row in csv.DictReader(f):
            cli.setdefault(int(row["cycle"]), []).append(row)
    data = streamclust.read(stream)
    xyz = np.column_stack([data["x"], data["y"], data["z"]])
    ours = streamclust.cluster_stream(xyz, data["t"], data["intensity"], preset="objects-mid360", rate=20,
                                      mount=(0, 0, 0), sensor_height=1.0, tracks=True)
    compared = 0
    for r in ours:
        theirs = cli.get(r.cycle, [])
        assert len(r.tracks) == len(theirs), f"cycle {r.cycle}"
        for track, row in zip(r.tracks, theirs):
            assert int(track["track_id"]) == int(row["track_id"])
            assert int(track["cluster_id"]) == int(row["cluster_id"])
            assert streamclust.TRACK_STATES[track["state"]] == row["state"]
            assert int(track["points"]) == int(row["points"])
            for k, column in enumerate(("x", "y", "z")):
                assert float(track["position"][k]) == pytest.approx(float(row[column]), abs=1e-4)
            for k, column in enumerate(("vx", "vy", "vz")):
                assert float(track["velocity"][k]) == pytest.approx(float(row[column]), abs=1e-4)
            compared += 1
    assert compared > 200
    assert sum(len(v) for v in cli.values()) == compared
    with pytest.raises(ValueError, match="tracks"):
        streamclust.cluster_stream(xyz, data["t"], preset="baseline", tracks=True)
    with pytest.raises(ValueError, match="tracks"):
        streamclust.cluster_stream(xyz, data["t"], preset="objects-mid360", tracks=1)
