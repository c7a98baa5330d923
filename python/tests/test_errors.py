# SPDX-License-Identifier: MIT
"""Every bad argument is a ValueError that names it (never a crash, never a
silent copy or conversion)."""

import numpy as np
import pytest

import streamclust

XYZ = np.zeros((4, 3), dtype=np.float32) + np.array([1.0, 2.0, 0.5], dtype=np.float32)
T = np.arange(4, dtype=np.float64) * 1e-3

BAD_OPTIONS = [
    ({"window_time": -1.0}, "window_time"),
    ({"window_time": "0.1"}, "window_time"),
    ({"window_count": 0}, "window_count"),
    ({"window_time": 0.1, "window_count": 100}, "window_time and window_count"),
    ({"linkage": "nearest"}, "linkage"),
    ({"theta": 0.0}, "theta"),
    ({"theta": float("nan")}, "theta"),
    ({"min_ray_angle": "x"}, "min_ray_angle"),
    ({"distance": -0.5}, "distance"),
    ({"min_distance": 0}, "min_distance"),
    ({"range_factor": None}, "range_factor"),
    ({"mask": 4}, "mask"),
    ({"mask": 0}, "mask"),
    ({"mask": 2.5}, "mask"),
    ({"index": "kd-tree"}, "index"),
    ({"cap": 0}, "cap"),
    ({"cap": 300}, "cap"),
    ({"connectivity": "graph"}, "connectivity"),
    ({"projection": "planar"}, "projection"),
    ({"mode": "batch"}, "mode"),
    ({"mode": "frame", "connectivity": "forest"}, "connectivity"),  # the CLI: frame mode has no connectivity
    ({"mode": "frame", "mount": (0, 10, 0)}, "mount"),
    ({"fov_azimuth": (10,)}, "fov_azimuth"),
    ({"fov_elevation": ("a", "b")}, "fov_elevation"),
    ({"fov_z": 3}, "fov_z"),
    ({"min_range": "near"}, "min_range"),
    ({"grid": (0, 64)}, "grid"),
    ({"grid": "64x1024"}, "grid"),
    ({"grid": (1.5, 3)}, "grid"),
    ({"max_multiplicity": 0}, "max_multiplicity"),
    ({"mount": (0, 15)}, "mount"),
    ({"mount": (0, 400, 0)}, "mount"),
    ({"ground": "yes"}, "ground"),
    ({"ceiling": 1}, "ceiling"),
    ({"sensor_height": -1.0}, "sensor_height"),
    ({"ground_tolerance": 5.0}, "ground_tolerance"),
    ({"ground_cell": 0.01}, "ground_cell"),
    ({"max_slope": 90}, "max_slope"),
    ({"poses": 3}, "poses"),
    ({"poses": "/nonexistent/poses.tum"}, "poses"),
    ({"ground": True}, "ground"),  # a Clusterer cannot estimate the mount: it names what to give
    ({"colour": "red"}, "colour"),
    ({"rate": 20}, "rate"),  # a Clusterer has no schedule: cluster_stream takes rate
    ({"labels": "out.csv"}, "labels"),  # CLI outputs are not keywords
]


@pytest.mark.parametrize("options,name", BAD_OPTIONS)
def test_bad_clusterer_option(options, name):
    with pytest.raises(ValueError, match=name):
        streamclust.Clusterer(preset="carc", **options)


def test_bad_first_window():
    with pytest.raises(ValueError, match="first_window"):
        streamclust.Clusterer(preset="objects", first_window=XYZ)
    with pytest.raises(ValueError, match="first_window t: 3 times for 4 points"):
        streamclust.Clusterer(preset="objects", first_window=(XYZ, T[:3]))
    with pytest.raises(ValueError, match="first_window xyz: expected dtype"):
        streamclust.Clusterer(preset="objects", first_window=(XYZ.astype(np.int16), T))


@pytest.mark.parametrize("preset", ["nope", "Carc", 3, None])
def test_bad_preset(preset):
    with pytest.raises(ValueError, match="preset"):
        streamclust.Clusterer(preset=preset)


def test_every_preset_builds():
    for preset in streamclust.PRESETS:
        kw = {"mount": (0, 0, 0), "sensor_height": 1.5} if preset.startswith("objects") else {}
        streamclust.Clusterer(preset=preset, **kw)


BAD_INSERTS = [
    (dict(xyz=XYZ.tolist(), t=T), "xyz: expected a numpy.ndarray"),
    (dict(xyz=XYZ[:, :2].copy(), t=T), r"xyz: expected shape \(N, 3\)"),
    (dict(xyz=XYZ.reshape(-1), t=np.zeros(12)), r"xyz: expected shape \(N, 3\)"),
    (dict(xyz=XYZ.astype(np.int32), t=T), "xyz: expected dtype float32 or float64"),
    (dict(xyz=XYZ.astype(np.float16), t=T), "xyz: expected dtype"),
    (dict(xyz=XYZ.astype(">f4"), t=T), "xyz: expected dtype"),
    (dict(xyz=np.zeros((4, 6), dtype=np.float32)[:, ::2], t=T), "xyz: the array is not C-contiguous"),
    (dict(xyz=np.asfortranarray(np.zeros((4, 3))), t=T), "xyz: the array is not C-contiguous"),
    (dict(xyz=XYZ, t=T.astype(np.float32)), "t: expected dtype float64"),
    (dict(xyz=XYZ, t=T[:3]), "t: 3 times for 4 points"),
    (dict(xyz=XYZ, t=T.reshape(2, 2)), r"t: expected shape \(N,\)"),
    (dict(xyz=XYZ, t=np.zeros(8)[::2]), "t: the array is not C-contiguous"),
    (dict(xyz=XYZ, t=list(T)), "t: expected a numpy.ndarray"),
    (dict(xyz=XYZ, t=T, intensity=np.zeros(3, dtype=np.float32)), "intensity: 3 values for 4 points"),
    (dict(xyz=XYZ, t=T, intensity=np.zeros(4, dtype=np.int64)), "intensity: expected dtype"),
    (dict(xyz=XYZ, t=T, intensity=np.zeros((4, 1), dtype=np.float32)), "intensity: expected shape"),
]


@pytest.mark.parametrize("arguments,message", BAD_INSERTS)
def test_bad_insert(arguments, message):
    c = streamclust.Clusterer(preset="carc")
    with pytest.raises(ValueError, match=message):
        c.insert(**arguments)
    assert c.offered == 0, "nothing was inserted"


def test_nan_is_a_rejection_not_an_error():
    c = streamclust.Clusterer(preset="carc")
    xyz = XYZ.copy()
    xyz[1, 0] = np.nan
    t = T.copy()
    t[2] = np.inf
    accepted, reasons = c.insert(xyz, t, reasons=True)
    assert accepted == 2
    assert [streamclust.REJECT_REASONS[r] for r in reasons] == ["accepted", "non_finite", "non_finite", "accepted"]


@pytest.mark.parametrize("time", ["soon", float("nan"), float("inf"), [1.0]])
def test_bad_retrieve_and_advance_time(time):
    c = streamclust.Clusterer(preset="carc")
    with pytest.raises(ValueError, match="time"):
        c.retrieve(time)
    with pytest.raises(ValueError, match="time"):
        c.advance_to(time)
    with pytest.raises(ValueError, match="time"):
        c.advance_to(None)


@pytest.mark.parametrize("kw,name", [
    ({"rate": 0}, "rate"), ({"rate": -20}, "rate"), ({"rate": "fast"}, "rate"),
    ({"cycles": [-1]}, "cycles"), ({"cycles": "some"}, "cycles"), ({"cycles": 2.5}, "cycles"),
    ({"theta": -3}, "theta"), ({"window": 0.1}, "window"),
])
def test_bad_cluster_stream_argument(kw, name):
    with pytest.raises(ValueError, match=name):
        streamclust.cluster_stream(XYZ, T, preset="carc", **kw)


def test_cluster_stream_needs_points_and_a_preset():
    with pytest.raises(ValueError, match="xyz: no points"):
        streamclust.cluster_stream(np.zeros((0, 3), np.float32), np.zeros(0), preset="carc")
    with pytest.raises(TypeError):
        streamclust.cluster_stream(XYZ, T)  # preset is a required keyword


def test_bad_read(tmp_path):
    good = tmp_path / "p.csv"
    good.write_text("x,y,z,t\n1,2,3,0\n")
    with pytest.raises(FileNotFoundError):
        streamclust.read(tmp_path / "missing.csv")
    with pytest.raises(ValueError, match="format"):
        streamclust.read(good, format="las")
    with pytest.raises(ValueError, match="time_unit"):
        streamclust.read(good, time_unit="h")
    with pytest.raises(ValueError, match="point_rate"):
        streamclust.read(good, point_rate=-1)
    with pytest.raises(ValueError, match="colour"):
        streamclust.read(good, colour=1)
    with pytest.raises(ValueError, match="path"):
        streamclust.read(3)
    bad = tmp_path / "bad.csv"
    bad.write_text("x,y,z,t\n1,2,oops,0\n")
    with pytest.raises(ValueError, match="bad.csv"):
        streamclust.read(bad)


@pytest.mark.parametrize("kw,name", [
    ({"sensor": "velodyne"}, "sensor"), ({"scene": "moon"}, "scene"), ({"seconds": 0}, "seconds"),
    ({"seed": 0}, "seed"), ({"dropout": "x"}, "dropout"), ({"mount": (1, 2)}, "mount"),
    ({"burst": (1,)}, "burst"), ({"point_rate": 1000.0}, "point_rate"), ({"speeed": 1}, "speeed"),
])
def test_bad_simulate(kw, name):
    with pytest.raises(ValueError, match=name):
        streamclust.simulate(**{"seconds": 0.1, **kw})


def test_bad_evaluate():
    with pytest.raises(ValueError, match="labels: 3 labels for 4"):
        streamclust.evaluate(np.zeros(3, np.int32), np.zeros(4, np.int64))
    with pytest.raises(ValueError, match="labels: expected an integer dtype"):
        streamclust.evaluate(np.zeros(4), np.zeros(4, np.int64))
    with pytest.raises(ValueError, match="truth: expected a numpy.ndarray"):
        streamclust.evaluate(np.zeros(4, np.int64), [0, 0, 0, 0])
    with pytest.raises(ValueError, match="min_points"):
        streamclust.evaluate(np.zeros(4, np.int64), np.zeros(4, np.int64), min_points=0)
