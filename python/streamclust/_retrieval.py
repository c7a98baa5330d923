# SPDX-License-Identifier: MIT
"""Retrieval: one labelled window, as numpy arrays."""

import numpy as np

#: dtype of Retrieval.components (one row per connected component).
COMPONENT_DTYPE = np.dtype([
    ("id", np.int64),             # stable component id
    ("size", np.int64),           # points in the window
    ("centroid", np.float32, 3),  # mean position [m]
    ("min", np.float32, 3),       # box, lower corner [m]
    ("max", np.float32, 3),       # box, upper corner [m]
    ("t_min", np.float64),        # oldest point [s]
    ("t_max", np.float64),        # newest point [s]
], align=True)  # the C struct's layout: 4 bytes of padding before t_min, 72 bytes a row

#: dtype of Retrieval.tracks (one row per track; Clusterer(tracks=True)), the
#: columns of ``streamclust cluster --tracks`` (docs/tracking.md).
TRACK_DTYPE = np.dtype([
    ("track_id", np.int64),       # the track's own id (never reused)
    ("cluster_id", np.int64),     # the component seen this retrieval, -1 when none was
    ("position", np.float32, 3),  # box centre [m]
    ("velocity", np.float32, 3),  # [m/s]; 0 while the track is static
    ("length", np.float32),       # [m] along yaw
    ("width", np.float32),        # [m]
    ("height", np.float32),       # [m] from the ground under the object or its lowest point
    ("yaw", np.float32),          # [rad]
    ("points", np.int64),         # of the component seen (0 when none)
    ("state", np.int8),           # index into TRACK_STATES
    ("moving", np.bool_),         # the speed stands clear of zero
], align=True)

#: Retrieval.tracks["state"] values: 0 tentative, 1 confirmed, 2 coasting.
TRACK_STATES = ("tentative", "confirmed", "coasting")

#: Row labels that are not components (the CLI's --labels file, docs/cli.md).
UNLABELLED, GROUND, CEILING = -1, -2, -3


class Retrieval:
    """One retrieval: the window's rows by stream index, and its components.

    Attributes
    ----------
    cycle : int
        Retrievals before this one (0-based). In :func:`cluster_stream` it is
        the CLI's cycle number on the same stream.
    time : float
        Stream time of the retrieval [s]: the scheduled time in
        :func:`cluster_stream`, the time passed to :meth:`Clusterer.retrieve`,
        else the newest point's.
    index : numpy.ndarray, int64 (M,)
        Stream index of each row (0-based; rejected points counted), ascending:
        every window point and every rejected point inside the window's span,
        the rows of ``streamclust cluster --labels``.
    labels : numpy.ndarray, int32 (M,)
        Stable component id (>= 0), -1 unlabelled (rejected), -2 ground,
        -3 ceiling, -4 wall (with ``ground=True``).
    components : numpy.ndarray, structured (K,), :data:`COMPONENT_DTYPE`
        id, size, centroid, min, max, t_min, t_max per component, by id.
    tracks : numpy.ndarray, structured (T,), :data:`TRACK_DTYPE`, or None
        With ``Clusterer(tracks=True)``: the tracked objects after this
        retrieval (oriented boxes, velocities, states; docs/tracking.md),
        by track id; None otherwise.

    The arrays are new (one copy out of the engine, which reuses its buffers
    at the next retrieval); they belong to this object and stay valid.
    """

    __slots__ = ("cycle", "time", "index", "labels", "components", "tracks")

    def __init__(self, cycle, time, index, labels, components, tracks=None):
        self.cycle = int(cycle)
        self.time = float(time)
        self.index = index
        self.labels = labels
        self.components = components
        self.tracks = tracks

    def __len__(self):
        return len(self.index)

    def __repr__(self):
        return (f"Retrieval(cycle={self.cycle}, time={self.time:.6f}, rows={len(self.index)}, "
                f"components={len(self.components)})")
