# SPDX-License-Identifier: MIT
"""cluster_stream's cycle k is the CLI's cycle k: the same rows, the same partition.

The stream is simulated by the tool (``streamclust simulate``), read from the
same CSV by both (``streamclust.read`` and ``streamclust cluster``), and the
CLI's ``--labels FILE --cycles all`` rows are compared with every Retrieval.
"""

import csv
import subprocess

import numpy as np
import pytest

import streamclust
from conftest import same_partition

CONFIGURATIONS = [
    ("carc-mid360", {}),
    ("carc", {"linkage": "euclidean", "distance": 0.4, "index": "capped", "cap": 3, "window_count": 15000}),
    ("carc-mid360", {"projection": "cylindrical", "connectivity": "lazy-bfs", "mask": 3}),
    ("carc", {"linkage": "range-adaptive", "grid": (32, 512), "window_time": 0.2, "fov_elevation": (-10, 60)}),
    ("objects-mid360", {}),
    ("baseline", {"index": "bucket", "window_count": 12000}),
]


def cli_arguments(options):
    from streamclust._options import POLICY_KEYWORDS, to_arguments
    return to_arguments(POLICY_KEYWORDS, options, "test")


@pytest.fixture(scope="module")
def stream_csv(tool, tmp_path_factory):
    path = tmp_path_factory.mktemp("stream") / "office.csv"
    subprocess.run([tool, "simulate", "--sensor", "mid360", "--scene", "office", "--seconds", "1.2",
                    "--seed", "11", "--mount", "0,20,0", "--dropout", "0.02", "--out", str(path), "--quiet"],
                   check=True)
    return path


@pytest.fixture(scope="module")
def rough_stream_csv(tool, tmp_path_factory):
    """The simulated stream with 1 % NaN coordinates, a 0.35 s pause and
    points too close to the sensor: rejected rows (-1) and skipped retrievals."""
    d = tmp_path_factory.mktemp("rough")
    clean = d / "clean.csv"
    subprocess.run([tool, "simulate", "--sensor", "mid360", "--scene", "office", "--seconds", "1.0",
                    "--seed", "4", "--out", str(clean), "--quiet"], check=True)
    data = streamclust.read(clean)
    rng = np.random.default_rng(4)
    x, y, z, t = (data[k].astype(np.float64) for k in ("x", "y", "z", "t"))
    x[rng.random(len(t)) < 0.01] = np.nan
    near = rng.random(len(t)) < 0.005
    x[near], y[near], z[near] = 0.01, 0.0, 0.0
    t[t > 0.5] += 0.35
    path = d / "rough.csv"
    with open(path, "w") as f:
        f.write("x,y,z,intensity,t\n")
        np.savetxt(f, np.column_stack([x, y, z, data["intensity"], t]),
                   fmt=["%.9g", "%.9g", "%.9g", "%.9g", "%.17g"], delimiter=",")
    return path


@pytest.mark.parametrize("preset,options", [CONFIGURATIONS[0], CONFIGURATIONS[1], CONFIGURATIONS[-1]])
def test_every_cycle_equals_the_cli_with_rejections_and_a_pause(tool, rough_stream_csv, tmp_path, preset, options):
    data = streamclust.read(rough_stream_csv)
    xyz = np.column_stack([data["x"], data["y"], data["z"]])
    ours = streamclust.cluster_stream(xyz, data["t"], data["intensity"], preset=preset, rate=20, **options)
    theirs = cli_cycles(tool, rough_stream_csv, preset, options, 20, tmp_path)
    assert [r.cycle for r in ours] == sorted(theirs)
    assert any((r.labels == streamclust.UNLABELLED).any() for r in ours), "rejected rows were compared"
    gaps = np.diff([r.time for r in ours])
    assert gaps.max() > 0.3, "the pause skipped retrievals"
    for r in ours:
        c = theirs[r.cycle]
        assert r.time == pytest.approx(c["time"], rel=1e-8, abs=1e-8), f"cycle {r.cycle}: time"
        assert np.array_equal(r.index, np.asarray(c["index"], dtype=np.int64)), f"cycle {r.cycle}: rows"
        assert same_partition(r.labels, c["label"]), f"cycle {r.cycle}: partition"


def cli_cycles(tool, path, preset, options, rate, tmp_path):
    labels = tmp_path / "labels.csv"
    subprocess.run([tool, "cluster", str(path), "--preset", preset, "--rate", repr(float(rate)),
                    "--labels", str(labels), "--cycles", "all", "--quiet"] + cli_arguments(options), check=True)
    cycles = {}
    with open(labels, newline="") as f:
        for row in csv.DictReader(f):
            c = cycles.setdefault(int(row["cycle"]), {"time": float(row["time"]), "index": [], "label": []})
            c["index"].append(int(row["index"]))
            c["label"].append(int(row["label"]))
    return cycles


@pytest.mark.parametrize("preset,options", CONFIGURATIONS)
def test_every_cycle_equals_the_cli(tool, stream_csv, tmp_path, preset, options):
    rate = 20.0
    data = streamclust.read(stream_csv)
    xyz = np.column_stack([data["x"], data["y"], data["z"]])
    ours = streamclust.cluster_stream(xyz, data["t"], data["intensity"], preset=preset, rate=rate, **options)
    theirs = cli_cycles(tool, stream_csv, preset, options, rate, tmp_path)
    assert [r.cycle for r in ours] == sorted(theirs), "the same cycles"
    assert len(ours) >= 10
    for r in ours:
        c = theirs[r.cycle]
        assert r.time == pytest.approx(c["time"], rel=1e-8, abs=1e-8), f"cycle {r.cycle}: time"
        assert np.array_equal(r.index, np.asarray(c["index"], dtype=np.int64)), f"cycle {r.cycle}: rows"
        assert same_partition(r.labels, c["label"]), f"cycle {r.cycle}: partition"
    if preset.startswith("objects"):
        assert any((r.labels == streamclust.GROUND).any() for r in ours), "ground rows were compared"


# Every preset; those that place the sensor with an explicit mount and height
# (the frame-mode baseline takes neither).
PLACED = {"mount": (0, 20, 0), "sensor_height": 1.0}
EVERY_PRESET = [("carc", {"mount": (0, 20, 0)}), ("carc-mid360", {"mount": (0, 20, 0)}),
                ("carc-avia", {"mount": (0, 20, 0)}), ("baseline", {}), ("objects", PLACED),
                ("objects-mid360", PLACED), ("objects-avia", PLACED)]


@pytest.mark.parametrize("preset,options", EVERY_PRESET)
def test_every_preset_gives_the_cli_labels(tool, stream_csv, tmp_path, preset, options):
    """The module's presets are the CLI's, which are the library's
    (tests/test_cli_objects.cpp compares the CLI with the library's engine):
    the same label values, row for row, not only the same partition."""
    data = streamclust.read(stream_csv)
    xyz = np.column_stack([data["x"], data["y"], data["z"]])
    ours = streamclust.cluster_stream(xyz, data["t"], data["intensity"], preset=preset, rate=20, **options)
    theirs = cli_cycles(tool, stream_csv, preset, options, 20, tmp_path)
    assert [r.cycle for r in ours] == sorted(theirs)
    assert len(ours) >= 10
    for r in ours:
        c = theirs[r.cycle]
        assert np.array_equal(r.index, np.asarray(c["index"], dtype=np.int64)), f"cycle {r.cycle}: rows"
        assert np.array_equal(r.labels, np.asarray(c["label"], dtype=np.int64)), f"cycle {r.cycle}: labels"
    assert any((r.labels >= 0).sum() > 1000 for r in ours), "object rows were compared"
    if preset.startswith("objects"):
        assert any((r.labels == streamclust.GROUND).sum() > 1000 for r in ours), "ground rows were compared"


@pytest.mark.parametrize("preset", ["carc-mid360", "objects-mid360", "baseline"])
def test_packets_and_schedule_by_hand_equal_cluster_stream(stream_csv, preset):
    """Clusterer.insert in packets + retrieve(time) on the schedule == cluster_stream
    (objects-mid360: the mount and sensor height estimated from first_window)."""
    data = streamclust.read(stream_csv)
    xyz = np.column_stack([data["x"], data["y"], data["z"]]).astype(np.float64)
    t = data["t"]
    reference = streamclust.cluster_stream(xyz, t, preset=preset, rate=10)
    c = streamclust.Clusterer(preset=preset, first_window=(xyz, t))
    got = []
    period = 1.0 / 10.0
    t0, k, start = t[0], 1.0, 0  # RetrievalSchedule: retrieval k due at t0 + k * period
    for i in range(1, len(t)):
        due = t0 + k * period
        if not t[i] >= due:
            continue
        k = max(k + 1.0, np.floor((t[i] - t0) / period) + 1.0)
        c.insert(xyz[start:i], t[start:i])
        start = i
        c.advance_to(due)
        if not c.calibrating:
            got.append(c.retrieve(due))
    c.insert(xyz[start:], t[start:])
    c.complete_calibration()
    got.append(c.retrieve(float(t[-1])))
    assert len(got) == len(reference)
    for a, b in zip(got, reference):
        assert a.time == pytest.approx(b.time)
        assert np.array_equal(a.index, b.index)
        assert np.array_equal(a.labels, b.labels)
        assert np.array_equal(a.components, b.components)


def test_epoch_times_keep_their_nanoseconds_and_the_cli_partitions(tool, tmp_path):
    """A recording in Unix time: read() counts from its whole-second origin,
    exactly, and cluster_stream on it gives the CLI's cycles, whose times
    are the origin plus ours."""
    path = tmp_path / "epoch.csv"
    subprocess.run([tool, "simulate", "--sensor", "mid360", "--scene", "office", "--seconds", "0.8", "--seed", "5",
                    "--start-time", "1700000000", "--out", str(path), "--quiet"], check=True)
    data = streamclust.read(path)
    assert data["time_origin"] == 1700000000
    assert data["t"][0] == 0.0 and data["t"][-1] < 1.0
    xyz = np.column_stack([data["x"], data["y"], data["z"]])
    ours = streamclust.cluster_stream(xyz, data["t"], data["intensity"], preset="carc-mid360", rate=20)
    labels = tmp_path / "labels.csv"
    subprocess.run([tool, "cluster", str(path), "--preset", "carc-mid360", "--labels", str(labels), "--cycles", "all",
                    "--quiet"], check=True)
    theirs = {}
    with open(labels, newline="") as f:
        for row in csv.DictReader(f):
            c = theirs.setdefault(int(row["cycle"]), {"time": row["time"], "label": []})
            c["label"].append(int(row["label"]))
    assert [r.cycle for r in ours] == sorted(theirs)
    for r in ours:
        c = theirs[r.cycle]
        assert c["time"] == f"{1700000000 + int(r.time)}.{round((r.time % 1) * 1e9):09d}", f"cycle {r.cycle}: time"
        assert same_partition(r.labels, c["label"]), f"cycle {r.cycle}: partition"


def test_epoch_poses_meet_times_read_from_the_recording(tool, tmp_path):
    """Poses in Unix time with times from read(): time_origin puts them on one
    time base, and the objects preset with poses gives the CLI's partitions."""
    path = tmp_path / "moving.csv"
    subprocess.run([tool, "simulate", "--sensor", "mid360", "--scene", "street", "--speed", "1.5", "--seconds", "0.9",
                    "--start-time", "1700000000", "--out", str(path), "--quiet"], check=True)
    tum = tmp_path / "moving.tum"
    data = streamclust.read(path)
    xyz = np.column_stack([data["x"], data["y"], data["z"]])
    options = {"sensor_height": 1.0, "poses": str(tum)}
    ours = streamclust.cluster_stream(xyz, data["t"], data["intensity"], preset="objects-mid360", rate=20,
                                      time_origin=data["time_origin"], **options)
    theirs = cli_cycles(tool, path, "objects-mid360", options, 20.0, tmp_path)
    assert [r.cycle for r in ours] == sorted(theirs)
    assert len(ours) >= 5
    for r in ours:
        assert (r.labels >= 0).sum() > 1000, f"cycle {r.cycle}: placed and clustered"
        assert same_partition(r.labels, theirs[r.cycle]["label"]), f"cycle {r.cycle}: partition"
    # Without the origin the poses (Unix time) miss the times (from 0): nothing is placed.
    lost = streamclust.cluster_stream(xyz, data["t"], data["intensity"], preset="objects-mid360", rate=20, **options)
    assert all((r.labels >= 0).sum() == 0 for r in lost)
