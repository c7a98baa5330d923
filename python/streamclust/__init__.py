# SPDX-License-Identifier: MIT
"""streamclust: continuous clustering of LiDAR point streams (C-ARC), from numpy.

The engine is the C++ library's, configured exactly as the ``streamclust``
command-line tool configures it: the same presets, options, validation and
compiled fast paths. See docs/python.md.

>>> import streamclust
>>> sim = streamclust.simulate("mid360", "office", seconds=1.0, seed=7)
>>> cycles = streamclust.cluster_stream(sim.xyz, sim.t, preset="carc-mid360")
>>> streamclust.evaluate(labels_of_last_window, truth_of_last_window)["ari"]  # doctest: +SKIP
"""

import os
from collections import namedtuple
from numbers import Integral

import numpy as np

from . import _streamclust
from ._options import (POLICY_KEYWORDS, READ_KEYWORDS, SIMULATION_KEYWORDS, reraise_with_keywords,
                       to_arguments)
from ._retrieval import CEILING, COMPONENT_DTYPE, GROUND, TRACK_DTYPE, TRACK_STATES, UNLABELLED, Retrieval

__all__ = ["Clusterer", "Retrieval", "Simulation", "cluster_stream", "read", "simulate", "evaluate", "live",
           "LiveStream", "LiveRetrieval", "REJECT_REASONS", "COMPONENT_DTYPE", "TRACK_DTYPE", "TRACK_STATES", "PRESETS",
           "UNLABELLED", "GROUND", "CEILING"]

#: Names of the rejection reason codes returned by ``insert(..., reasons=True)``
#: (code i is REJECT_REASONS[i]; 0 is "accepted").
REJECT_REASONS = tuple(_streamclust.REJECT_REASONS)

#: The CLI's presets ("baseline" is the frame clusterer: each retrieval re-clusters the window).
PRESETS = ("carc", "carc-mid360", "carc-avia", "baseline", "objects", "objects-mid360", "objects-avia")


def _policy_arguments(preset, options):
    if not isinstance(preset, str):
        raise ValueError(f"preset: expected a preset name ({', '.join(PRESETS)}), got {preset!r}")
    return ["--preset", preset] + to_arguments(POLICY_KEYWORDS, options, "Clusterer")


def _call(function, *args):
    """Calls the extension, with the CLI's option names turned into keywords."""
    try:
        return function(*args)
    except ValueError as e:
        raise reraise_with_keywords(e) from None


class Clusterer:
    """The continuous engine, fed packet by packet from numpy.

    ``Clusterer(preset="carc-mid360", **options)``: every policy option of
    ``streamclust cluster`` is a keyword (``window_time``, ``window_count``,
    ``linkage``, ``theta``, ``min_ray_angle``, ``distance``, ``min_distance``,
    ``range_factor``, ``mask``, ``index``, ``cap``, ``connectivity``,
    ``projection``, ``mode``, ``fov_azimuth``, ``fov_elevation``, ``fov_z``,
    ``min_range``, ``grid``, ``max_multiplicity``, ``poses``, ``mount``,
    ``ground``, ``sensor_height``, ``ground_tolerance``, ``ground_cell``,
    ``max_slope``, ``ceiling``). ``mode="frame"`` (the ``baseline`` preset)
    runs the frame clusterer, as the CLI does. Unknown keywords and bad values raise
    ValueError naming the keyword. With ``ground=True`` (the objects presets)
    the CLI estimates the mount and sensor height not given from the first
    window of its input: give ``first_window=(xyz, t)``, the stream's
    beginning (at least T_B seconds of it; read, not kept), for the same
    estimate, or ``mount`` (or ``poses``) and ``sensor_height``.
    With ``tracks=True`` every retrieval also has ``tracks``: the objects'
    oriented boxes followed by a Kalman tracker, as ``cluster --tracks``
    (:data:`TRACK_DTYPE`; continuous mode only).

    Thread safety: calls from several threads are serialised (a mutex); the
    GIL is released while the engine works.

    Example (20 Hz retrievals over packets of a recorded stream)::

        import numpy as np
        import streamclust

        sim = streamclust.simulate("mid360", "office", seconds=1.0, seed=7)
        c = streamclust.Clusterer(preset="carc-mid360", window_time=0.1)
        for packet in np.array_split(np.arange(len(sim.t)), 20):  # 50 ms each
            c.insert(sim.xyz[packet], sim.t[packet], sim.intensity[packet])
            r = c.retrieve(sim.t[packet[-1]])
            big = r.components[r.components["size"] >= 20]
            print(r.cycle, r.time, len(big), big["centroid"][:3])

    Cost: ``insert`` is the engine's ``insert_batch`` (amortised
    O(w^2 k + e) per point, no copy of the arrays); ``retrieve`` is O(window)
    plus the copy of the rows.
    """

    def __init__(self, preset="carc-mid360", *, first_window=None, tracks=False, **options):
        first_xyz = first_t = None
        if first_window is not None:
            try:
                first_xyz, first_t = first_window
            except (TypeError, ValueError):
                raise ValueError(f"first_window: expected a pair (xyz, t) of numpy arrays, got {first_window!r}") from None
        if not isinstance(tracks, bool):
            raise ValueError(f"tracks: expected True or False, got {tracks!r}")
        self._engine = _call(_streamclust.Clusterer, _policy_arguments(preset, options), first_xyz, first_t, tracks)

    def insert(self, xyz, t, intensity=None, reasons=False):
        """Offers N points in stream order; returns the number accepted.

        xyz: (N, 3) float32 or float64 [m], C-contiguous; t: (N,) float64
        stream time [s]; intensity: None or (N,) float32/float64. The arrays
        are read in place (zero copy); a strided view, a wrong dtype or shape
        raises ValueError (never a silent copy). Points with NaN or infinite
        coordinates or time are rejected by the engine (reason "non_finite"),
        like every other rejected point. With ``reasons=True`` returns
        ``(accepted, reasons)``, reasons a uint8 array of codes into
        :data:`REJECT_REASONS`.
        """
        return self._engine.insert(xyz, t, intensity, bool(reasons))

    def advance_to(self, time):
        """Evicts the points that left the window at stream time `time` [s]."""
        self._engine.advance_to(time)

    def retrieve(self, time=None):
        """The window's labels and components as a :class:`Retrieval`.

        With `time` [s], first advances the window to it (as the CLI does at a
        scheduled retrieval). Empty while the first window is buffered for
        the adaptive grid (see :attr:`calibrating`). One copy of the rows.
        """
        return Retrieval(*self._engine.retrieve(time))

    def complete_calibration(self):
        """Ends the adaptive grid's calibration on the points buffered so far."""
        self._engine.complete_calibration()

    @property
    def calibrating(self):
        """True while the first window is buffered to choose the grid."""
        return self._engine.calibrating

    @property
    def offered(self):
        """Points offered so far (the next point's stream index)."""
        return self._engine.offered

    @property
    def size(self):
        """Points in the window."""
        return self._engine.size

    @property
    def grid(self):
        """(rows, cols, wraps) of the grid in use; (0, 0, False) while calibrating."""
        return self._engine.grid


def _cycle_list(cycles):
    if cycles is None or (isinstance(cycles, str) and cycles in ("all", "last")):
        return None
    if isinstance(cycles, Integral) and not isinstance(cycles, bool):
        cycles = [cycles]
    try:
        items = list(cycles)
    except TypeError:
        raise ValueError(f"cycles: expected None, 'all', 'last', a cycle number or a list of them, got {cycles!r}") from None
    for c in items:
        if isinstance(c, bool) or not isinstance(c, Integral) or c < 0:
            raise ValueError(f"cycles: expected cycle numbers >= 0, got {c!r}")
    return [int(c) for c in items]


def cluster_stream(xyz, t, intensity=None, *, preset, rate=20, cycles=None, tracks=False, **options):
    """Clusters a whole stream on the CLI's retrieval schedule.

    Retrieves at t0 + k / rate of stream time (t0 the first finite time) and
    once more after the last point, exactly as ``streamclust cluster --rate
    RATE`` does (no cycle while the adaptive grid calibrates), so cycle k of
    the result is the CLI's cycle k on the same stream. Options as for
    :class:`Clusterer`; with ``ground=True`` the mount and sensor height are
    estimated from the first window as the CLI does.

    cycles: None or "all" (every cycle), "last", a cycle number or a list of
    them. tracks: as :class:`Clusterer` (each retrieval's ``tracks``, the
    rows of ``streamclust cluster --tracks`` for its cycle). Returns a list
    of :class:`Retrieval` (each with ``.cycle``).
    """
    if not isinstance(tracks, bool):
        raise ValueError(f"tracks: expected True or False, got {tracks!r}")
    args = _policy_arguments(preset, options) + to_arguments({"rate": ("--rate", "number")}, {"rate": rate}, "rate")
    wanted = _cycle_list(cycles)
    out = _call(_streamclust.cluster_stream, args, xyz, t, intensity, wanted, tracks)
    result = [Retrieval(*r) for r in out]
    if cycles == "last":
        result = result[-1:]
    return result


def read(path, **read_options):
    """Reads a point file or a recording (CSV, PCD, PLY, KITTI, ROS 1 bag,
    rosbag2 folder or .db3, MCAP, LVX/LVX2: every format the CLI reads).

    read_options: ``format`` ("auto", "csv", "pcd", "ply", "kitti", "bag",
    "db3", "mcap", "lvx"), ``topic`` (a recording's point-cloud topic, needed
    when it has several; an LVX file's LiDAR by serial or index),
    ``time_unit`` ("s", "ms", "us", "ns"), ``point_rate`` [Hz] (times for an
    input without a time field), ``time_origin`` (whole seconds to count
    from; default: the first time's). Returns a dict: x, y, z, intensity
    (float32 arrays), t (float64 [s] since time_origin, exact for Unix
    times), time_origin (int [s]; absolute time = time_origin + t) and, when
    the file has one, label (int64). Pass ``time_origin`` on to a Clusterer
    or cluster_stream that reads ``poses`` in absolute time.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise ValueError(f"path: expected a file path, got {path!r}")
    path = os.fspath(path)
    if not os.path.exists(path):
        raise FileNotFoundError(f"{path}: no such file")
    args = to_arguments(READ_KEYWORDS, read_options, "read")
    return _call(_streamclust.read, path, args)


#: A simulated stream: xyz (N, 3) float32 [m, sensor frame], t (N,) float64 [s],
#: intensity (N,) float32, truth (N,) int64 instance ids (0: structure),
#: surface (N,) uint8 (0 object, 1 ground, 2 wall, 3 ceiling).
Simulation = namedtuple("Simulation", ["xyz", "t", "intensity", "truth", "surface"])


def simulate(sensor="mid360", scene="office", seconds=1.0, seed=1, **options):
    """Simulates a sensor in a scene with ground truth (``streamclust simulate``).

    sensor: mid360, mid40, mid70, avia, spinning32 or synthetic; scene:
    office, forest, street, hills (room with the synthetic sensor). Options:
    ``speed``, ``yaw_rate``, ``noise``, ``dropout``, ``max_range``, ``mount``
    (roll, pitch, yaw) [deg], ``burst`` (start, length) [s], ``burst_speed``,
    ``burst_yaw_rate``, ``point_rate`` (synthetic only). Returns a
    :data:`Simulation`.
    """
    keywords = dict(sensor=sensor, scene=scene, seconds=seconds, seed=seed, **options)
    args = to_arguments(SIMULATION_KEYWORDS, keywords, "simulate")
    return Simulation(*_call(_streamclust.simulate, args))


def evaluate(labels, truth, *, min_points=10):
    """The clustering metrics of one window (the CLI's ``evaluate`` fields).

    labels: predicted ids per point (< 0 unlabelled); truth: ground-truth
    instance ids (0 structure, > 0 object, < 0 ignored); integer arrays of the
    same length. min_points: smaller segments and objects are not counted as
    false positives / negatives. Returns a dict: points, object_points,
    objects, ari, ose, use, ose_mean, use_mean, precision, recall, sq, rq, pq,
    coverage, object_coverage, correct, over_segmented, under_segmented,
    missed.
    """
    if isinstance(min_points, bool) or not isinstance(min_points, Integral) or min_points < 1:
        raise ValueError(f"min_points: expected a whole number >= 1, got {min_points!r}")
    return _call(_streamclust.evaluate, labels, truth, int(min_points))


from ._live import LiveRetrieval, LiveStream, live  # noqa: E402 (uses _call above)
